#!/usr/bin/env python3
"""Benchmark of the reasoning queries against the design's straightforward method.

    python bench/reasoning.py            # full run (about 15 s)
    python bench/reasoning.py --quick    # fewer repetitions

A full run keeps its table in bench/results.json (`tables.reasoning`, with the commit and the load average),
from which the README's table is written (bench/readme_figures.py).

Both run on the default kitchen world (`worlds/kitchen.yaml`), each in its own copy of it
loaded in the same process (the baseline hides bodies by changing their colours, which
must not disturb ours). Perception, contact and stability queries run on the world as
loaded (robot at its start pose, head tilted towards the counter); reachable and blocking
after the robot has driven to the demo's counter pose (0.65, 0.7), as in the demo. The
Fetch rows do the same on the kitchen with a Fetch (`worlds/kitchen_fetch.yaml`), with the
Fetch at the counter pose of `plans/fetch_milk.yaml` (0.8, 1.0) and the same targets.

The baseline is the design's method (thesis §4.4): visible/occluding render the whole
camera frame at 256×256 twice (scene, then the object alone with every other body made
transparent); contact steps the simulation once and reads contact points; supporting
compares heights and asks that contact; stable simulates the whole scene for 480 steps;
reachable makes one calculateInverseKinematics call; blocking applies it, steps once and
reads contacts; every query that changes the world saves and restores it.
"""
from __future__ import annotations

import argparse
import contextlib
import math
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any, Callable, Iterator

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from pycram_cli import load_world  # noqa: E402  (imports pybullet quietly)
import pybullet as p  # noqa: E402
from pycram_cli.reasoning import blocking, contact, occluding, reachable, stable, supporting, visible  # noqa: E402
from pycram_cli.reasoning.ik import ANSWERS  # noqa: E402
from pycram_cli.world.cache import forget_everywhere  # noqa: E402
from pycram_cli.robots import description_for  # noqa: E402
from pycram_cli.world.pose import quat_multiply  # noqa: E402

import results_file  # noqa: E402  (bench/results_file.py, beside this script)

WORLD = REPO / "worlds" / "kitchen.yaml"
COUNTER_POSE = ((0.65, 0.7, 0.0), (0.0, 0.0, 0.0, 1.0))
UNREACHABLE = (1.3, 0.6, 1.9)
FETCH_WORLD = REPO / "worlds" / "kitchen_fetch.yaml"
FETCH_COUNTER_POSE = ((0.8, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))
FETCH_UNREACHABLE = (1.3, 0.6, 2.4)  # the Fetch reaches higher than the PR2: 2.1 m with its torso up


# -- the design's straightforward method --------------------------------------------------


class Baseline:
    def __init__(self, world: Any) -> None:
        self.w = world
        self.cid = world.client_id
        self.robot = world.robot
        self.desc = description_for(self.robot)

    def _camera(self) -> tuple[list[float], list[float]]:
        cam = self.desc.camera
        pos, orn = self.robot.get_link_position_and_orientation(cam.frame)
        rot = np.array(p.getMatrixFromQuaternion(orn)).reshape(3, 3)
        forward, down = rot[:, 2], rot[:, 1]
        view = p.computeViewMatrix(pos, (np.array(pos) + forward).tolist(), (-down).tolist())
        proj = p.computeProjectionMatrixFOV(math.degrees(cam.vertical_fov),
                                            math.tan(cam.horizontal_fov / 2) / math.tan(cam.vertical_fov / 2),
                                            cam.near, cam.far)
        return view, proj

    def _render(self, view: list[float], proj: list[float]) -> np.ndarray:
        seg = p.getCameraImage(256, 256, view, proj, renderer=p.ER_TINY_RENDERER, physicsClientId=self.cid)[4]
        return np.asarray(seg).reshape(256, 256)

    def _two_renders(self, obj: Any) -> tuple[np.ndarray, np.ndarray]:
        view, proj = self._camera()
        scene = self._render(view, proj)
        colours = []
        for other in self.w.objects:
            if other is obj:
                continue
            for shape in p.getVisualShapeData(other.id, physicsClientId=self.cid):
                colours.append((other.id, shape[1], shape[7]))
                p.changeVisualShape(other.id, shape[1], rgbaColor=[1, 1, 1, 0], physicsClientId=self.cid)
        alone = self._render(view, proj)
        for body, link, rgba in colours:
            p.changeVisualShape(body, link, rgbaColor=rgba, physicsClientId=self.cid)
        return scene, alone

    def visible(self, obj: Any) -> bool:
        scene, alone = self._two_renders(obj)
        total = int((alone == obj.id).sum())
        return total > 0 and int((scene == obj.id).sum()) / total > 0.8

    def occluding(self, obj: Any) -> list[str]:
        scene, alone = self._two_renders(obj)
        ids = set(np.unique(scene[alone == obj.id]).tolist()) - {obj.id, -1}
        return sorted(self.w.get_object_by_id(i).name for i in ids)

    @contextlib.contextmanager
    def _saved(self) -> Iterator[None]:
        """Save the world and restore it afterwards, in full every time, as the design's code did (our worlds reuse a
        saved state while nothing changed: issue 15; the baseline does not get that)."""
        self.w.mark_changed()
        with self.w.snapshot():
            yield

    def contact(self, a: Any, b: Any) -> bool:
        with self._saved():
            p.stepSimulation(physicsClientId=self.cid)
            return bool(p.getContactPoints(a.id, b.id, physicsClientId=self.cid))

    def supporting(self, a: Any, b: Any) -> bool:
        return b.get_position()[2] > a.get_position()[2] and self.contact(a, b)

    def stable(self, obj: Any) -> bool:
        with self._saved():
            before = [round(v, 3) for v in obj.get_position()]
            self.w.simulate(2.0)
            return before == [round(v, 3) for v in obj.get_position()]

    def _ik(self, position: Any, tool: str, grasp: str | None) -> dict[str, float]:
        orientation = None
        if grasp is not None:
            orientation = quat_multiply(self.robot.get_orientation(), self.desc.grasps[grasp])
        link = self.robot.get_link_id(tool)
        if orientation is None:
            values = p.calculateInverseKinematics(self.robot.id, link, position, physicsClientId=self.cid)
        else:
            values = p.calculateInverseKinematics(self.robot.id, link, position, orientation, physicsClientId=self.cid)
        movable = [j for j in self.robot.joints if j.type in ("revolute", "prismatic", "continuous")]
        arm = set(self.desc.arm(self.desc.arm_of_link(tool)).joints)
        return {j.name: v for j, v in zip(movable, values) if j.name in arm}

    def reachable(self, target: Any, tool: str, grasp: str | None = None) -> bool:
        position = target.get_position() if hasattr(target, "get_position") else target
        with self._saved():
            for name, value in self._ik(position, tool, grasp).items():
                p.resetJointState(self.robot.id, self.robot.get_joint_id(name), value, physicsClientId=self.cid)
            return math.dist(self.robot.get_link_position(tool), position) <= 0.01

    def blocking(self, target: Any, tool: str, grasp: str | None = None) -> list[str]:
        position = target.get_position() if hasattr(target, "get_position") else target
        with self._saved():
            for name, value in self._ik(position, tool, grasp).items():
                p.resetJointState(self.robot.id, self.robot.get_joint_id(name), value, physicsClientId=self.cid)
            p.stepSimulation(physicsClientId=self.cid)
            return sorted(o.name for o in self.w.objects
                          if o is not self.robot and o is not target
                          and p.getContactPoints(self.robot.id, o.id, physicsClientId=self.cid))


# -- timing ------------------------------------------------------------------------------


def median_ms(func: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    answer = func()  # warm-up (first-use caches)
    times = []
    for _ in range(repeat):
        forget_everywhere(ANSWERS)  # each repetition a first question: IK answers are kept per robot state (reasoning/ik.py)
        start = time.perf_counter()
        answer = func()
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1000.0, answer


def fmt_ms(value: float) -> str:
    return f"{value:.3f} ms" if value < 0.1 else f"{value:.2f} ms" if value < 10 else f"{value:.0f} ms"


def short(answer: Any) -> str:
    if isinstance(answer, list):
        return "[" + ", ".join(getattr(o, "name", str(o)) for o in answer) + "]"
    return str(bool(answer))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    opts = parser.parse_args(argv)
    fast, slow = (15, 2) if opts.quick else (101, 7)

    ours_world = load_world(WORLD)
    base_world = load_world(WORLD)
    ow, bw = ours_world, base_world
    o = {x.name: x for x in ow.objects}
    b = {x.name: x for x in bw.objects}
    base = Baseline(bw)
    robot = ow.robot
    desc = description_for(robot)
    left, right = desc.arm("left").tool_frame, desc.arm("right").tool_frame

    def at_counter() -> None:
        for world in (ow, bw):
            world.robot.set_position_and_orientation(*COUNTER_POSE)

    rows: list[tuple[str, float, float, float, str, bool, str, str]] = []

    def run(label: str, ours: Callable[[], Any], baseline: Callable[[], Any], target: float, n_ours: int,
            n_base: int) -> None:
        ours_ms, ours_answer = median_ms(ours, n_ours)
        base_ms, base_answer = median_ms(baseline, n_base)
        rows.append((label, ours_ms, base_ms, base_ms / ours_ms, fmt_ms(target), ours_ms <= target,
                     short(ours_answer), short(base_answer)))
        print(f"  {label}: ours {fmt_ms(ours_ms)}, baseline {fmt_ms(base_ms)}", file=sys.stderr, flush=True)

    load_before = os.getloadavg()[0]
    print(f"benchmarking on {WORLD.relative_to(REPO)} ({'quick' if opts.quick else 'full'} run)", file=sys.stderr)
    run("visible bottle", lambda: visible(o["bottle"]), lambda: base.visible(b["bottle"]), 5.0, fast, slow * 3)
    run("occluding spoon", lambda: occluding(o["spoon"]), lambda: base.occluding(b["spoon"]), 5.0, fast, slow * 3)
    run("contact kitchen milk", lambda: contact(o["kitchen"], o["milk"]),
        lambda: base.contact(b["kitchen"], b["milk"]), 0.05, fast * 10, slow * 3)
    run("supporting kitchen milk", lambda: supporting(o["kitchen"], o["milk"]),
        lambda: base.supporting(b["kitchen"], b["milk"]), 0.05, fast * 10, slow * 3)
    run("stable milk", lambda: stable(o["milk"]), lambda: base.stable(b["milk"]), 200.0, max(5, fast // 4), slow)
    at_counter()
    run("reachable milk (right, front)", lambda: reachable(o["milk"], robot, right, grasp="front"),
        lambda: base.reachable(b["milk"], right, "front"), 5.0, fast, slow * 3)
    run("reachable unreachable (left)", lambda: reachable(UNREACHABLE, robot, left),
        lambda: base.reachable(UNREACHABLE, left), 30.0, fast, slow * 3)
    run("blocking milk (left)", lambda: blocking(o["milk"], robot, left),
        lambda: base.blocking(b["milk"], left), 5.0, fast, slow * 3)
    ow.exit()
    bw.exit()

    # the same questions for the Fetch (one arm, `arm`; head camera head_camera_rgb_optical_frame)
    ow, bw = load_world(FETCH_WORLD), load_world(FETCH_WORLD)
    o = {x.name: x for x in ow.objects}
    b = {x.name: x for x in bw.objects}
    base = Baseline(bw)
    robot = ow.robot
    tool = description_for(robot).arm("arm").tool_frame
    print(f"benchmarking on {FETCH_WORLD.relative_to(REPO)}", file=sys.stderr)
    run("fetch: visible milk", lambda: visible(o["milk"]), lambda: base.visible(b["milk"]), 5.0, fast, slow * 3)
    for world in (ow, bw):
        world.robot.set_position_and_orientation(*FETCH_COUNTER_POSE)
    run("fetch: reachable milk (arm, top)", lambda: reachable(o["milk"], robot, tool, grasp="top"),
        lambda: base.reachable(b["milk"], tool, "top"), 5.0, fast, slow * 3)
    run("fetch: reachable unreachable (arm)", lambda: reachable(FETCH_UNREACHABLE, robot, tool),
        lambda: base.reachable(FETCH_UNREACHABLE, tool), 30.0, fast, slow * 3)
    run("fetch: blocking milk (arm, top)", lambda: blocking(o["milk"], robot, tool, grasp="top"),
        lambda: base.blocking(b["milk"], tool, "top"), 5.0, fast, slow * 3)

    header = ("query", "ours (median)", "baseline (median)", "ratio", "target", "met?", "ours says", "baseline says")
    table = [header] + [(r[0], fmt_ms(r[1]), fmt_ms(r[2]), f"{r[3]:.0f}×", "≤ " + r[4], "yes" if r[5] else "NO",
                         r[6], r[7]) for r in rows]
    widths = [max(len(row[i]) for row in table) for i in range(len(header))]
    lines = ["| " + " | ".join(h.ljust(w) for h, w in zip(header, widths)) + " |",
             "|" + "|".join("-" * (w + 2) for w in widths) + "|"]
    lines += ["| " + " | ".join(c.ljust(w) for c, w in zip(row, widths)) + " |" for row in table[1:]]
    print("\n".join(lines))
    if not opts.quick:
        print(f"wrote {results_file.record_table('reasoning', chr(10).join(lines), load_before)}", file=sys.stderr)
    ow.exit()
    bw.exit()
    return 0 if all(r[5] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
