"""The neighbourhood of an object: the bodies that touch it or could touch it while `stable` simulates.

Only these need simulating to tell whether the object stays put; the rest of the world is
parked (world/parking.py) for the check. Found from collision shapes and velocities, without
a simulation step:

* the object and everything attached to it (what it holds, what holds it);
* touching, transitively: free bodies within `TOUCH` of a member — its support, what rests on
  it, what leans on it, stacks — and theirs. Fixed bodies (the kitchen, the floor) are always
  simulated but do not pass touching on: a counter does not make the milk a neighbour of
  every cup on it;
* coming: a free body whose reach within the simulated time overlaps the box of one of those
  (grown by `TOUCH`). Resting on something, a body can slide until friction stops it and turn —
  spin in place or topple over an edge, whatever it rests on — which carries its points at most
  its radius or its height further (`reaches`); with nothing under it, it flies on with its
  velocity, tumbling, and falls. It comes with what it touches, so that it rests on its real
  support;
* fixed bodies are simulated (the kitchen and the floor reach everything), except those with joint
  motors that are not environments (robots): only when a member's reach comes within `TOUCH` of
  their box (their motors cost more per step than anything else). Of an environment that stays,
  the joints whose moving parts no member can reach are not held during the check (`loose`).

What this leaves out — a body at rest far away that is knocked over by another one that is not
a member either — cannot reach the object unless something of the neighbourhood moves towards
it, and `stable` watches that: when a member comes within reach of a parked body, that body is
put back (see stable.py). `TOUCH` is 5 mm: resting contacts sit at about -1e-5 m and objects
are spawned up to 1 mm above their support; a stable object moves less than 1 mm.
"""
from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..world import BulletWorld, Object

#: closer than this (m) counts as touching
TOUCH = 0.005
#: the least friction coefficient assumed between a sliding body and its support (PyBullet's default is 0.5)
FRICTION = 0.1
#: turning faster than this (rad/s) a body may sweep its whole radius
SPIN = 0.02


@dataclass
class Neighbourhood:
    """`members`: the bodies to simulate and watch (the object, what touches it or may come; with what is
    attached to them); `kept`: the fixed bodies simulated too; `parked`: everything else. `boxes`: each
    free or parked body's box as it stood, (2, 3) arrays of the min and max corner, by object id."""

    members: list[Object]
    kept: list[Object]
    parked: list[Object]
    boxes: dict[int, np.ndarray]
    #: joints (by index) of kept fixed bodies that nothing simulated comes near: they need not be held
    loose: dict[int, list[int]] = field(default_factory=dict)


def attached_closure(objects: Iterable[Object]) -> list[Object]:
    """`objects` with everything attached to them, transitively (parents and children), in a stable order."""
    found: dict[int, Object] = {}
    frontier = list(objects)
    while frontier:
        obj = frontier.pop(0)
        if obj.id in found:
            continue
        found[obj.id] = obj
        frontier.extend(sorted(obj.attachments, key=lambda o: o.id))
    return list(found.values())


def box_of(obj: Object) -> np.ndarray:
    """The object's box (2, 3): min and max corner of its collision shapes."""
    lo, hi = obj.get_aabb(-1) if not obj.joints else obj.get_aabb()
    return np.array([lo, hi], dtype=float)


def overlapping(box: np.ndarray, boxes: np.ndarray, grow: float = 0.0) -> np.ndarray:
    """Which of `boxes` (n, 2, 3) overlap `box` grown by `grow` on every side."""
    if not len(boxes):
        return np.zeros(0, dtype=bool)
    return np.all((boxes[:, 0] <= box[1] + grow) & (boxes[:, 1] >= box[0] - grow), axis=1)


def reaches(objects: list[Object], boxes: np.ndarray, seconds: float, supported: np.ndarray,
            gravity: float = 9.81) -> np.ndarray:
    """How far each object's box can grow in `seconds` (m), falling aside (see the module's text).

    Supported (something within TOUCH): friction stops a slide within v² / (2 μ g) (μ at least
    `FRICTION`), and turning — spinning in place or toppling over an edge — carries its points at
    most its radius or its height further. Unsupported: it flies on with its velocity, tumbling.
    """
    if not objects:
        return np.zeros(0)
    velocities = np.array([[*v[0], *v[1]] for v in (o.get_velocity() for o in objects)], dtype=float)
    size = boxes[:, 1] - boxes[:, 0]
    radius = 0.5 * np.linalg.norm(size, axis=1)
    speed = np.linalg.norm(velocities[:, :3], axis=1)
    spinning = np.linalg.norm(velocities[:, 3:], axis=1) > SPIN
    slide = np.minimum(speed * seconds, speed ** 2 / (2.0 * FRICTION * max(gravity, 1e-9)))
    resting = slide + np.maximum(size[:, 2], np.where(spinning, radius, 0.0))
    flying = speed * seconds + radius
    return np.where(supported, resting, flying)


def find(world: BulletWorld, obj: Object, seconds: float) -> Neighbourhood:
    """The neighbourhood of `obj` in `world` for a check that simulates `seconds` (see the module's text)."""
    free = [o for o in world.objects if not o.fixed]
    free_boxes = np.array([box_of(o) for o in free]).reshape(-1, 2, 3)
    boxes = {o.id: box for o, box in zip(free, free_boxes)}
    members = {o.id: o for o in attached_closure([obj])}
    _touching_closure(world, members, free, boxes)
    # the free bodies that could come to touch those within the time: first all at once as if nothing held
    # them up (their boxes grown by their reach and a fall below them); those near enough then as they are
    core = np.array([boxes[o.id] for o in members.values() if o.id in boxes] or [box_of(obj)])
    gravity = float(np.linalg.norm(world.gravity))
    flying = reaches(free, free_boxes, seconds, np.zeros(len(free), dtype=bool), gravity)
    resting = reaches(free, free_boxes, seconds, np.ones(len(free), dtype=bool), gravity)
    widest = np.maximum(flying, resting)[:, None] + TOUCH
    fall = np.array([0.0, 0.0, 0.5 * gravity * seconds ** 2])
    maybe = _hits(free_boxes[:, 0] - widest - fall, free_boxes[:, 1] + widest, core)
    comers = []
    for index, other in enumerate(free):
        if other.id in members or not maybe[index]:
            continue
        supported = _supported(world, other, boxes)
        grow = (resting if supported else flying)[index] + TOUCH
        below = 0.0 if supported else fall
        if _hits(free_boxes[index:index + 1, 0] - grow - below, free_boxes[index:index + 1, 1] + grow, core)[0]:
            comers.append(other)
    for other in attached_closure(comers):
        members.setdefault(other.id, other)
    _touching_closure(world, members, free, boxes)
    # fixed bodies: kept, except those with motors (robots) that nothing of the neighbourhood can reach
    moving = [o for o in members.values() if not o.fixed]
    moving_boxes = np.array([boxes[o.id] for o in moving]).reshape(-1, 2, 3)
    moving_reach = np.maximum(reaches(moving, moving_boxes, seconds, np.zeros(len(moving), dtype=bool), gravity),
                              reaches(moving, moving_boxes, seconds, np.ones(len(moving), dtype=bool), gravity))
    reach_boxes = np.stack([moving_boxes[:, 0] - (moving_reach + TOUCH)[:, None],
                            moving_boxes[:, 1] + (moving_reach + TOUCH)[:, None]], axis=1)
    kept, parked = [], []
    loose: dict[int, list[int]] = {}
    for other in world.objects:
        if other.id in members:
            continue
        if not other.fixed:
            parked.append(other)
        elif other.type == "environment" or not other.movable_joints:
            kept.append(other)
            far = [j for j, box in _joint_boxes(other).items() if not _hits(box[None, 0], box[None, 1], reach_boxes)[0]]
            if far:
                loose[other.id] = far
        else:
            box = boxes[other.id] = box_of(other)
            (kept if _hits(box[None, 0], box[None, 1], reach_boxes)[0] else parked).append(other)
    ordered = [o for o in world.objects if o.id in members]
    return Neighbourhood(ordered, kept, parked, boxes, loose)


def _joint_boxes(obj: Object) -> dict[int, np.ndarray]:
    """For each movable joint of `obj` (by index): the box of everything it moves (its child link's subtree),
    kept (in the world's cache) while the object's pose and joint positions stay."""
    key = (obj.get_com_pose(), tuple(obj.get_joint_positions().values()))
    return obj.world.cache.kept("joint boxes", obj, key, lambda: _build_joint_boxes(obj))


def _build_joint_boxes(obj: Object) -> dict[int, np.ndarray]:
    links = {j.index: np.array(obj.get_aabb(j.index), dtype=float) for j in obj.joints}
    boxes = {}
    for joint in obj.movable_joints:
        moved = [box for index, box in links.items() if obj.hangs_below(index, joint.index)]
        stacked = np.array(moved)
        boxes[joint.index] = np.array([stacked[:, 0].min(axis=0), stacked[:, 1].max(axis=0)])
    return boxes


def _hits(lo: np.ndarray, hi: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """For each box (lo[i], hi[i]) of (n, 3) corners: does it overlap any of `boxes` (k, 2, 3)?"""
    if not len(lo):
        return np.zeros(0, dtype=bool)
    inside = (lo[:, None, :] <= boxes[None, :, 1, :]) & (hi[:, None, :] >= boxes[None, :, 0, :])
    return np.all(inside, axis=2).any(axis=1)


def _supported(world: BulletWorld, obj: Object, boxes: dict[int, np.ndarray]) -> bool:
    """Whether anything is within TOUCH of `obj` (else it falls freely)."""
    box = boxes[obj.id]
    for other in world.objects:
        if other is obj or (not other.fixed and not overlapping(box, boxes[other.id][None], TOUCH)[0]):
            continue
        if world.distance(obj, other, TOUCH) <= TOUCH:
            return True
    return False


def _touching_closure(world: BulletWorld, members: dict[int, Object], free: list[Object],
                      boxes: dict[int, np.ndarray]) -> None:
    """Add to `members` every free body within TOUCH of a free member, transitively (with its attachments)."""
    candidates = [o for o in free if o.id not in members]
    frontier = [o for o in members.values() if not o.fixed]
    while frontier and candidates:
        member = frontier.pop(0)
        near = overlapping(boxes[member.id], np.array([boxes[o.id] for o in candidates]), TOUCH)
        joined = [o for o, hit in zip(candidates, near) if hit and world.distance(member, o, TOUCH) <= TOUCH]
        for other in attached_closure(joined):
            if other.id not in members:
                members[other.id] = other
                if not other.fixed:
                    frontier.append(other)
        candidates = [o for o in candidates if o.id not in members]


def near_parked(box: np.ndarray, grow: float, parked: list[Object], boxes: dict[int, np.ndarray]) -> list[Object]:
    """The parked objects whose box (as it stood) overlaps `box` grown by `grow`."""
    if not parked:
        return []
    hits = overlapping(box, np.array([boxes[o.id] for o in parked]), grow)
    return [o for o, hit in zip(parked, hits) if hit]
