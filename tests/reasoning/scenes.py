"""Helpers for the reasoning tests: the kitchen world, exact fingerprints, placing objects, plain simulation."""
from __future__ import annotations

import math
from typing import Any, Sequence

import pybullet as p

from pycram_cli import load_world
from pycram_cli.paths import default_world
from pycram_cli.world.pose import angle_between

#: the demo's pose in front of the sink-area counter (thesis Listing 5.2)
COUNTER_POSE = ((0.65, 0.7, 0.0), (0.0, 0.0, 0.0, 1.0))
COUNTER_TOP = 0.851  # sink_area_surface
ISLAND_TOP = 0.861  # kitchen_island_surface: x -1.47..-0.67, y 0.49..2.94


def kitchen_world() -> Any:
    return load_world(default_world())


def wake(world: Any) -> None:
    """PyBullet's restoreState does not restore sleep: wake every free object."""
    for obj in world.objects:
        if not obj.fixed:
            p.changeDynamics(obj.id, -1, activationState=p.ACTIVATION_STATE_WAKE_UP, physicsClientId=world.client_id)


def fingerprint(world: Any) -> tuple:
    """Everything a query must leave as it found it, as raw PyBullet numbers (compared bitwise)."""
    cid = world.client_id
    bodies = []
    for obj in world.objects:
        joints = p.getJointStates(obj.id, list(range(len(obj.joints))), physicsClientId=cid) if obj.joints else []
        attachments = sorted((a.parent.name, a.child.name, a.parent_link, a.child_link, a.transform)
                             for a in obj.attachments.values())
        bodies.append((obj.name, p.getBasePositionAndOrientation(obj.id, physicsClientId=cid),
                       p.getBaseVelocity(obj.id, physicsClientId=cid),
                       tuple((s[0], s[1]) for s in joints), tuple(attachments)))
    return tuple(bodies)


def put_on(obj: Any, support: Any, x: float, y: float, orientation: Sequence[float] = (0, 0, 0, 1)) -> None:
    """Stand `obj` at (x, y) on whatever of `support` is below it, touching it exactly (collision shapes)."""
    world = obj.world
    obj.set_position_and_orientation([x, y, 3.0], orientation)
    lo, _ = obj.get_aabb()
    highest = max(support.get_aabb(link)[1][2] for link in support.link_names
                  if _under(support.get_aabb(link), x, y)) if support.joints else support.get_aabb()[1][2]
    z = obj.get_position()[2] - lo[2] + highest + 0.01
    obj.set_position_and_orientation([x, y, z], orientation)
    gap = min(pt[8] for pt in p.getClosestPoints(obj.id, support.id, 0.5, physicsClientId=world.client_id))
    obj.set_position_and_orientation([x, y, z - gap], orientation)


def _under(box: tuple, x: float, y: float) -> bool:
    (x0, y0, _), (x1, y1, _) = box
    return x0 - 0.2 <= x <= x1 + 0.2 and y0 - 0.2 <= y <= y1 + 0.2


def plain_stable(world: Any, obj: Any, seconds: float = 2.0) -> tuple[bool, float, float]:
    """The reference: simulate the whole world for 2 s and compare the object's pose (then restore)."""
    with world.snapshot():
        start = obj.get_pose()
        world.simulate(seconds)
        end = obj.get_pose()
    wake(world)
    moved, turned = math.dist(start[0], end[0]), angle_between(start[1], end[1])
    return moved <= 0.001 and turned <= math.radians(1.0), moved, turned


def tilt_about_x(angle: float) -> tuple[float, float, float, float]:
    return (math.sin(angle / 2.0), 0.0, 0.0, math.cos(angle / 2.0))


def box_mesh(folder: Any, size: Sequence[float]) -> Any:
    """An OBJ box of `size` (x, y, z) standing on its bottom face (origin at the bottom centre), in `folder`."""
    from pathlib import Path

    hx, hy, height = float(size[0]) / 2.0, float(size[1]) / 2.0, float(size[2])
    path = Path(folder) / f"box_{size[0]:g}x{size[1]:g}x{size[2]:g}.obj"
    corners = [(x, y, z) for z in (0.0, height) for x, y in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]
    faces = [(1, 3, 2), (1, 4, 3), (5, 6, 7), (5, 7, 8), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6),
             (3, 4, 8), (3, 8, 7), (4, 1, 5), (4, 5, 8)]
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners)
                    + "".join(f"f {a} {b} {c}\n" for a, b, c in faces))
    return path


def add_clutter(world: Any, folder: Any, n: int = 200) -> list:
    """`n` small cubes (4 cm, 50 g) standing on the floor and the back of the sink-area counter, 8 cm apart:
    a crowded world whose extra bodies have nothing to do with the objects the stability tests move."""
    from pycram_cli import Object

    cube = box_mesh(folder, (0.04, 0.04, 0.04))
    spots = [(1.56 + 0.08 * i, 0.26 + 0.08 * j, 0.851) for i in range(3) for j in range(13)]  # the counter
    spots += [(-0.6 + 0.08 * i, -0.9 + 0.08 * j, 0.0) for j in range(10) for i in range(22)]  # the floor
    added = []
    for index, (x, y, z) in enumerate(spots[:n]):
        added.append(Object(f"clutter{index}", "cube", cube, (x, y, z + 0.0002), world=world, mass=0.05))
    return added
