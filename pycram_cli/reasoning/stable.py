"""stable(obj): does the object stay put (within 1 mm and 1°) while the world is simulated for 2 s?

The design saved the world, simulated it for 2 s, compared rounded coordinates and restored.
Three things differ here:

* Nothing else drifts. Robots and environments are fixed-base kinematic bodies whose joints
  are held, so the robot base cannot slide into the answer (the fault of the anchor
  implementations, which call the milk on the counter unstable).
* Only the object's neighbourhood is simulated (neighbourhood.py): the bodies that touch it or
  could touch it within the 2 s — its support, what rests on it or leans on it, stacks, what
  may topple or fall onto them — with the fixed scenery; every other body is parked for the
  check (world/parking.py: out of the way, asleep, costing nothing per step) and put back
  exactly afterwards. A parked body comes back as soon as a watched body moves near where it
  stood. So a cluttered world or a far object that never comes to rest (a rocking spoon in a
  drawer) costs a check nothing.
* It stops early, both ways. The object is watched at every step: once it has moved more
  than the limits it is unstable at once. It is declared stable before the 2 s are up only
  when its neighbourhood has come to rest — every watched body moved less than a creep speed
  over the last window — and the object's own motion, extrapolated with its current speed
  and acceleration to the end of the 2 s, stays under half the limits, and its motion is not
  growing (a slowly tipping object speeds up from window to window).

The simulation runs on the world's prospection copy (`world.prospection()`), brought in sync
with the world first: the world itself is only read, so everything it holds — poses,
velocities, joints, and the contact caches and broadphase order that PyBullet's restoreState
does not put back — is exactly as before, and simulating it afterwards gives what it would
have given without the query. The neighbourhood's bodies are woken before simulating (a copy
put to sleep by an earlier query would otherwise hang). Verdicts agree with a plain 2 s
simulation of the whole world (tests/reasoning/test_stable.py checks every case both ways);
the figures (displacement, rotation) can differ in the micrometres, as the solver's iterations
depend on every contact it solves together.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..world.parking import Parking
from ..world.pose import angle_between
from . import neighbourhood
from ._common import world_of

if TYPE_CHECKING:
    from ..world import BulletWorld, Object

STEP_HZ = 240
SECONDS = 2.0
DISTANCE = 0.001  # m
ANGLE = math.radians(1.0)
#: never stop early before this much simulated time (contacts settle in the first steps)
MIN_SECONDS = 0.25
#: steps between two rest checks (0.05 s)
WINDOW = 12
#: a free object moving slower than this (m/s, rad/s) counts as at rest
REST_SPEED = 2e-3
REST_SPIN = 2e-2
#: motion below these per window is noise, whatever its trend (m, rad)
NOISE_DISTANCE = 2e-7
NOISE_ANGLE = 2e-6
#: consecutive windows that must satisfy the rest test
CALM_WINDOWS = 2
#: a watched body that moved more than this in a window (m, rad) is checked against the parked ones
NEAR_MOTION = 1e-4
#: ... and counted as falling (it may speed up by g every second) beyond this (m in a window: 2 cm/s)
FALLING = 1e-3


@dataclass(frozen=True)
class StableAnswer:
    """Truthy when stable. `displacement` (m) and `rotation` (rad): the largest reached while
    simulating; `simulated`: seconds actually simulated before the answer was certain."""

    stable: bool
    displacement: float
    rotation: float
    simulated: float = 0.0

    def __bool__(self) -> bool:
        return self.stable


def _moved(a: tuple, b: tuple) -> tuple[float, float]:
    return math.dist(a[0], b[0]), angle_between(a[1], b[1])


def stable(obj: "Object", world: "BulletWorld | None" = None, seconds: float = SECONDS,
           distance: float = DISTANCE, angle: float = ANGLE) -> StableAnswer:
    """Whether `obj` moves less than `distance` (m) and `angle` (rad) while the world runs for `seconds`."""
    world = world_of(obj, world)
    if obj.fixed:
        return StableAnswer(True, 0.0, 0.0, 0.0)  # fixed objects are kinematic: simulation never moves them
    total = int(round(seconds * STEP_HZ))
    with world.lock:  # simulated on the world's prospection copy: the world itself is only read
        twin = world.prospection()
        copy, target = twin.copy, twin.copy_of(obj)
        hood = neighbourhood.find(copy, target, seconds)
        parking = Parking(copy)
        try:
            parking.park(hood.parked)
            for other in hood.kept:
                if other.id in hood.loose:
                    parking.loosen(other, hood.loose[other.id])
            copy.wake(hood.members + hood.kept)
            return _Watch(copy, target, hood, parking, distance, angle).run(total)
        finally:
            parking.put_back()


class _Watch:
    """One check: steps the copy, watches the object and judges the neighbourhood's rest."""

    def __init__(self, world: "BulletWorld", obj: "Object", hood: neighbourhood.Neighbourhood, parking: Parking,
                 distance: float, angle: float) -> None:
        self.world, self.obj, self.hood, self.parking = world, obj, hood, parking
        self.distance, self.angle = distance, angle
        self.watched = [o for o in hood.members if _loose(o)]
        self.last = {o.id: o.get_com_pose() for o in self.watched}

    def run(self, total: int) -> StableAnswer:
        obj, world = self.obj, self.world
        start = obj.get_com_pose()  # watched at the centre of mass: one cheap call per step
        min_steps = int(MIN_SECONDS * STEP_HZ)
        window_time = WINDOW / STEP_HZ
        previous_motion: tuple[float, float] | None = None
        calm = 0
        worst_d = worst_a = 0.0
        for step in range(1, total + 1):
            world.step()
            d, a = _moved(start, obj.get_com_pose())
            worst_d, worst_a = max(worst_d, d), max(worst_a, a)
            if d > self.distance or a > self.angle:
                return StableAnswer(False, worst_d, worst_a, step / STEP_HZ)
            if step % WINDOW:
                continue
            # -- a rest check every window, over the neighbourhood ---------------------------------------
            scene_at_rest, motion = self._window(window_time)
            remaining = (total - step) / STEP_HZ
            settled = False
            if scene_at_rest and previous_motion is not None and step >= min_steps:
                settled = True
                for now_m, before_m, done, limit, noise in (
                        (motion[0], previous_motion[0], d, self.distance, NOISE_DISTANCE),
                        (motion[1], previous_motion[1], a, self.angle, NOISE_ANGLE)):
                    if now_m <= noise:
                        continue
                    speed = now_m / window_time
                    accel = max(0.0, (now_m - before_m) / window_time ** 2)
                    growing = now_m > 1.2 * before_m
                    if growing or done + speed * remaining + 0.5 * accel * remaining ** 2 > 0.5 * limit:
                        settled = False
            previous_motion = motion
            calm = calm + 1 if settled else 0
            if calm >= CALM_WINDOWS:
                return StableAnswer(True, worst_d, worst_a, step / STEP_HZ)
        return StableAnswer(True, worst_d, worst_a, total / STEP_HZ)

    def _window(self, window_time: float) -> tuple[bool, tuple[float, float]]:
        """Whether every watched body moved less than the creep speed over the last window, and the object's
        own motion; a body that moved is checked against the parked ones, which come back when it nears them."""
        at_rest = True
        motion = (0.0, 0.0)
        gravity = float(np.linalg.norm(self.world.gravity))
        returning: list["Object"] = []
        for other in self.watched:
            pose = other.get_com_pose()
            md, ma = _moved(self.last[other.id], pose)
            self.last[other.id] = pose
            if other is self.obj:
                motion = (md, ma)
            if md > REST_SPEED * window_time or ma > REST_SPIN * window_time:
                at_rest = False
            if self.hood.parked and (md > NEAR_MOTION or ma > NEAR_MOTION):
                # where it may get by the next window: its motion again, and a falling body's speed-up
                grow = neighbourhood.TOUCH + 2.0 * md + (gravity * window_time ** 2 if md > FALLING else 0.0)
                returning += neighbourhood.near_parked(neighbourhood.box_of(other), grow, self.hood.parked,
                                                       self.hood.boxes)
        if returning:
            self._put_back(returning)
            at_rest = False
        return at_rest, motion

    def _put_back(self, objects: list["Object"]) -> None:
        """Bring parked bodies back into the check (with what touched them where they stood)."""
        hood = self.hood
        chosen = {o.id: o for o in neighbourhood.attached_closure(objects) if o in self.parking}
        frontier = list(chosen.values())
        while frontier:  # what they touch comes too: it holds them up
            other = frontier.pop()
            for near in neighbourhood.near_parked(hood.boxes[other.id], neighbourhood.TOUCH, hood.parked,
                                                  hood.boxes):
                if near.id not in chosen:
                    chosen[near.id] = near
                    frontier.append(near)
        back = self.parking.put_back(list(chosen.values()))
        hood.parked = [o for o in hood.parked if o.id not in chosen]
        for other in back:
            if _loose(other):
                self.watched.append(other)
                self.last[other.id] = other.get_com_pose()


def _loose(obj: "Object") -> bool:
    """A free object that nothing holds (what is attached to a parent just follows it)."""
    return not obj.fixed and not any(a.child is obj for a in obj.attachments.values())
