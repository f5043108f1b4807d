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
