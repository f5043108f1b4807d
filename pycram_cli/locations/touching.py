"""What the robot may touch and what it touches: the contact tests of the expensive base-pose tests.

An arm at its grasp may touch the object and what the object rests on (fingers closing around a flat thing graze
the counter), a hand at a handle the drawer it pulls, a hand placing the surface; anything else it touches blocks the
pose. These tests, and letting a held object go for a moment (to test a way back, or whether a spot is stable),
sit here so that the base-pose and the spot resolutions share them.
"""
from __future__ import annotations

import contextlib
import math
from collections.abc import Iterable, Iterator, Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..reasoning.supporting import support_points
from ..robots import Robot
from ..world import Object
from .spec import LocationSpec

if TYPE_CHECKING:
    from ..world import BulletWorld

#: the robot touches an object when their shapes are closer than this (m)
TOUCH = 0.001
#: links of what an object rests on that touch the supporting link's box (grown by this much, m) hold it up too
SUPPORT_NEIGHBOURS = 0.005


def supports_of(world: BulletWorld, obj: Object) -> set[tuple[int, str]]:
    """(object id, link) of everything `obj` rests on: the supporting links, and the links of the same object
    right against them (a counter top's carcass, under it), which fingers closing around a flat object graze."""
    found = set()
    for other in world.objects:
        if other is obj or other.type == "robot":
            continue
        if world.distance(other, obj, 0.005) == math.inf:
            continue
        for link, _ in support_points(other, obj):
            found.add((other.id, link))
            lo, hi = (np.asarray(v) for v in other.get_aabb(link))
            for index in [-1, *range(len(other.joints))]:
                blo, bhi = (np.asarray(v) for v in other.get_aabb(index))
                if np.all(blo <= hi + SUPPORT_NEIGHBOURS) and np.all(bhi >= lo - SUPPORT_NEIGHBOURS):
                    found.add((other.id, other.get_link_name(index)))
    return found


def touching(robot: Robot, held: Sequence[Object], allowed_objects: set[int], allowed_links: set[tuple[int, str]],
             joints: Iterable[str]) -> list[str]:
    """What the part of the robot that `joints` move (and what it holds) touches now, but the allowed objects and
    links (names, sorted). The base, the torso and the wheels on the floor do not move with an arm: not tested."""
    world = robot.world
    body = robot.body
    moving = body.links_below(joints)
    skip = {body.id, *(o.id for o in held)}
    found = set()
    for other in world.objects:
        if other.id in skip or other.id in allowed_objects:
            continue
        for mover in (body, *held):
            points = world.closest_points(mover, other, TOUCH)
            if any((mover is not body or p.link_a in moving)
                   and (other.id, other.get_link_name(p.link_b)) not in allowed_links for p in points):
                found.add(other.name)
                break
    return sorted(found)



def allowed_contacts(world: BulletWorld, spec: LocationSpec) -> tuple[set[int], set[tuple[int, str]]]:
    """What the arm may touch at its final configuration (object ids, (object id, link) pairs): the target and what
    the target rests on."""
    target = spec.reachable_for
    if spec.accessing is not None:  # the hand holds the handle: the drawer (or door) may be touched
        handle = spec.accessing
        obj = handle.obj
        moving = obj.joint(handle.joint).index
        parts = {obj.get_link_name(moving)} | {j.child_link for j in obj.joints if obj.hangs_below(j.index, moving)}
        return set(), {(obj.id, link) for link in parts}
    if spec.placing is not None and spec.onto is not None:
        surface = spec.onto
        if surface.link is None:
            return {surface.obj.id}, set()
        return set(), {(surface.obj.id, surface.link)}
    if isinstance(target, Object):
        return {target.id}, supports_of(world, target)
    return set(), set()


@contextlib.contextmanager
def let_go_for_now(obj: Object) -> Iterator[None]:
    """`with let_go_for_now(obj):` the object stops following what holds it (no events), and follows it again after,
    at exactly the same offset; where the object stands is put back too."""
    pose = obj.get_pose()
    held = {other: att for other, att in obj.attachments.items() if att.child is obj}
    for other in held:
        del obj.attachments[other]
        other.attachments.pop(obj, None)
    try:
        yield
    finally:
        obj.set_position_and_orientation(*pose)
        for other, att in held.items():
            obj.attachments[other] = att
            other.attachments[obj] = att


def quiet_let_go(obj: Object) -> None:
    """Inside a snapshot only: the object stops following what holds it, without a detachment event
    (the snapshot's restore brings the attachment back), so that physics can tell whether it stands."""
    for other in list(obj.attachments):
        if obj.attachments[other].child is obj:
            del obj.attachments[other]
            other.attachments.pop(obj, None)
