#!/usr/bin/env python3
"""What `stable`'s tolerance (1 mm, 1°) stands against: objects at rest in a plain simulation, and what moves.

    python bench/stable_tolerance.py            # about 40 s

Plain PyBullet: the bundled world (`worlds/kitchen.yaml`) stepped as a whole with `p.stepSimulation` at
240 Hz, nothing of `stable`'s machinery (no neighbourhood, no parking, no early stop). Rows:

* resting: each bundled object standing upright — milk, cereal, bowl and bottle where the world file
  puts them on the sink-area counter, and each again alone on the island, touching its top; the spoon
  lying in its drawer as loaded, and lying on the island. The largest drift (mm) and tilt (°) from where it stood over
  `SECONDS`, and where it is at the end. These must stay well inside the tolerance, or settling reads
  as instability.
* moving: the slowest thing that must read as unstable in the tests — the cereal box with its centre
  of mass 0.5 mm beyond the island's edge, tipping very slowly — and when it passes 1 mm or 1°.
* rocking: a half cylinder lying on its round side on the island, tilted 5° and let go (`rocker_mesh`),
  and the design's spoon (`../shared/models/objects/spoon.stl`, when present) lying in the real
  kitchen's drawer: an open surface whose hull rests on three points and does not come to rest; how far
  its tilt swings in each second, and what `stable` says about it.

Prints a Markdown table; README.md's stable section quotes it.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import pybullet as p  # noqa: E402

from pycram_cli import load_world  # noqa: E402
from pycram_cli.world.pose import angle_between  # noqa: E402

SECONDS = 5.0
STEP_HZ = 240
COUNTER = ("milk", "cereal", "bowl", "bottle")
ISLAND = (-1.1, 1.0)  # where each object is stood alone on the island (x, y); its top is at z 0.861
ISLAND_TOP = 0.861
ISLAND_EDGE = -0.67  # the island's +x edge


def _pose(world: Any, obj: Any) -> tuple:
    return p.getBasePositionAndOrientation(obj.id, physicsClientId=world.client_id)


def drift(world: Any, names: list[str], seconds: float = SECONDS) -> dict[str, tuple[float, float, float, float]]:
    """Plain simulation of the whole world: per object the largest drift (m) and tilt (rad) from where it stood,
    and both at the end."""
    objects = [world.get_object_by_name(name) for name in names]
    start = {obj.name: _pose(world, obj) for obj in objects}
    worst = {obj.name: [0.0, 0.0] for obj in objects}
    for _ in range(int(round(seconds * STEP_HZ))):
        p.stepSimulation(physicsClientId=world.client_id)
        for obj in objects:
            pose = _pose(world, obj)
            w = worst[obj.name]
            w[0] = max(w[0], math.dist(start[obj.name][0], pose[0]))
            w[1] = max(w[1], angle_between(start[obj.name][1], pose[1]))
    end = {obj.name: _pose(world, obj) for obj in objects}
    return {name: (worst[name][0], worst[name][1], math.dist(start[name][0], end[name][0]),
                   angle_between(start[name][1], end[name][1])) for name in names}


def _stand_on_island(world: Any, obj: Any, x: float, y: float) -> None:
    """Upright at (x, y) on the island, touching its top (the collision shapes' closest points 0 mm apart)."""
    kitchen = world.get_object_by_name("kitchen")
    obj.set_position_and_orientation([x, y, 1.2], [0, 0, 0, 1])
    lo = obj.get_aabb()[0][2]
    obj.set_position([x, y, 1.2 - lo + ISLAND_TOP + 0.01])
    obj.set_position([x, y, obj.get_position()[2] - world.distance(obj, kitchen, 1.0)])


def resting(seconds: float = SECONDS) -> list[tuple[str, tuple[float, float, float, float]]]:
    """(where, (largest drift, largest tilt, end drift, end tilt)) for every bundled object at rest."""
    rows = []
    world = load_world()
    try:
        for name, figures in drift(world, [*COUNTER, "spoon"], seconds).items():
            rows.append((f"{name} on the counter" if name != "spoon" else "spoon in its drawer", figures))
    finally:
        world.exit()
    for name in (*COUNTER, "spoon"):
        world = load_world()
        try:
            for other in (*COUNTER, "spoon"):  # alone on the island: the others far away on the floor
                if other != name:
                    world.get_object_by_name(other).set_position([-3.0 - 0.3 * len(other), -0.5, 0.05])
            _stand_on_island(world, world.get_object_by_name(name), *ISLAND)
            rows.append((f"{name} on the island", drift(world, [name], seconds)[name]))
        finally:
            world.exit()
    return rows


def tipping(seconds: float = SECONDS) -> float | None:
    """When the cereal box with its centre of mass 0.5 mm beyond the island's edge passes 1 mm or 1° (s)."""
    world = load_world()
    try:
        cereal = world.get_object_by_name("cereal")
        lo, hi = cereal.get_aabb()
        x, _, _ = cereal.get_position()
        centre = (lo[0] + hi[0]) / 2.0 - x  # the box's middle from its origin, along x
        _stand_on_island(world, cereal, ISLAND_EDGE + 0.0005 - centre, 1.5)
        start = _pose(world, cereal)
        for step in range(1, int(round(seconds * STEP_HZ)) + 1):
            p.stepSimulation(physicsClientId=world.client_id)
            pose = _pose(world, cereal)
            if math.dist(start[0], pose[0]) > 0.001 or angle_between(start[1], pose[1]) > math.radians(1.0):
                return step / STEP_HZ
        return None
    finally:
        world.exit()


def rocker_mesh(folder: Path, radius: float = 0.05, length: float = 0.1, segments: int = 48) -> Path:
    """An OBJ half cylinder lying on its round side, flat face up (axis along x, origin at the bottom): tilted about
    its axis and let go, it rocks back and forth about its lowest point and, on PyBullet's contacts, hardly stops."""
    vertices = [(x, radius * math.cos(t), radius + radius * math.sin(t))
                for x in (-length / 2, length / 2)
                for t in (math.pi + math.pi * k / segments for k in range(segments + 1))]
    n = segments + 1
    faces = []
    for k in range(segments):  # the round side
        faces += [(k + 1, k + 2, n + k + 2), (k + 1, n + k + 2, n + k + 1)]
    faces += [(1, n, 2 * n), (1, 2 * n, n + 1)]  # the flat top
    for k in range(1, segments):  # the two ends
        faces += [(1, k + 2, k + 1), (n + 1, n + k + 1, n + k + 2)]
    path = Path(folder) / f"rocker_{radius * 1000:.0f}x{length * 1000:.0f}mm.obj"
    path.write_text("".join(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in vertices)
                    + "".join(f"f {a} {b} {c}\n" for a, b, c in faces))
    return path


#: the rocker is tilted this much about its axis (rad) before it is let go
ROCKER_TILT = math.radians(5.0)


def stand_rocker(world: Any, folder: Path) -> Any:
    """The rocker on the island at ISLAND, tilted by ROCKER_TILT, touching the top."""
    from pycram_cli import Object

    rocker = Object("rocker", "rocker", rocker_mesh(folder), (ISLAND[0], ISLAND[1], 1.2), world=world, mass=0.2)
    tilt = (math.sin(ROCKER_TILT / 2), 0.0, 0.0, math.cos(ROCKER_TILT / 2))
    _stand_on_island(world, rocker, *ISLAND)
    rocker.set_orientation(tilt)
    kitchen = world.get_object_by_name("kitchen")
    x, y, z = rocker.get_position()
    rocker.set_position([x, y, z - world.distance(rocker, kitchen, 1.0)])
    return rocker


def swings(world: Any, obj: Any, seconds: float) -> list[float]:
    """Plain simulation: how far `obj`'s tilt from where it stood swings (largest minus smallest, rad) each second."""
    start = _pose(world, obj)
    found = []
    for _ in range(int(round(seconds))):
        tilts = []
        for _ in range(STEP_HZ):
            p.stepSimulation(physicsClientId=world.client_id)
            tilts.append(angle_between(start[1], _pose(world, obj)[1]))
        found.append(max(tilts) - min(tilts))
    return found


def rocker(seconds: float = SECONDS) -> tuple[list[float], Any]:
    """The rocker on the island: its tilt's swing in each second of plain simulation, and `stable`'s answer."""
    import tempfile

    from pycram_cli.reasoning import stable

    world = load_world()
    try:
        obj = stand_rocker(world, Path(tempfile.mkdtemp(prefix="pycram-bench-")))
        answer = stable(obj)
        return swings(world, obj, seconds), answer
    finally:
        world.exit()


def rocking(seconds: float = SECONDS) -> tuple[list[float], Any] | None:
    """The design's spoon in the real drawer: how far its tilt swings (rad) in each second of `seconds` of plain
    simulation, and `stable`'s answer before it; None without ../shared/models."""
    sys.path.insert(0, str(REPO / "bench"))
    from scenes import design_world  # noqa: E402

    from pycram_cli.reasoning import stable  # noqa: E402

    world = design_world()
    if world is None:
        return None
    try:
        spoon = world.get_object_by_name("spoon")
        answer = stable(spoon)
        return swings(world, spoon, seconds), answer
    finally:
        world.exit()


def main() -> None:
    rows = resting()
    print(f"Plain PyBullet, the whole bundled world at {STEP_HZ} Hz for {SECONDS:g} s\n")
    print("| object at rest | largest drift | largest tilt | drift at the end | tilt at the end |")
    print("|---|---|---|---|---|")
    for where, (d, a, end_d, end_a) in rows:
        print(f"| {where} | {d * 1000:.3f} mm | {math.degrees(a):.3f}° | {end_d * 1000:.3f} mm | "
              f"{math.degrees(end_a):.3f}° |")
    worst_d = max(r[1][0] for r in rows)
    worst_a = max(r[1][1] for r in rows)
    print(f"\nlargest drift {worst_d * 1000:.3f} mm ({0.001 / worst_d:.0f}x inside 1 mm), largest tilt "
          f"{math.degrees(worst_a):.3f}° ({math.radians(1.0) / worst_a:.0f}x inside 1°)")
    crossed = tipping()
    print("cereal, centre of mass 0.5 mm beyond the island's edge: "
          + (f"passes 1 mm or 1° after {crossed:.2f} s" if crossed is not None else f"still within after {SECONDS:g} s"))
    found, answer = rocker()
    amplitude = answer.amplitude or (0.0, 0.0)
    print(f"half-cylinder rocker on the island, tilted {math.degrees(ROCKER_TILT):g}°: its tilt swings by "
          + ", ".join(f"{math.degrees(s):.2f}°" for s in found) + " in each second; "
          f"stable says: {answer.motion}, by {math.degrees(amplitude[1]):.2f}° and {amplitude[0] * 1000:.2f} mm")
    rock = rocking()
    if rock is None:
        print("design's spoon: ../shared/models absent, skipped")
    else:
        found, answer = rock
        amplitude = answer.amplitude or (0.0, 0.0)
        print("design's spoon in the real drawer: its tilt swings by "
              + ", ".join(f"{math.degrees(s):.2f}°" for s in found) + " in each of its first seconds; "
              f"stable says: {answer.motion}, by {math.degrees(amplitude[1]):.2f}° and {amplitude[0] * 1000:.2f} mm")

if __name__ == "__main__":
    main()
