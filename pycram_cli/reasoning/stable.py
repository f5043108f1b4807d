"""stable(obj): does the object stay put (within 1 mm and 1°) while the world is simulated for 2 s?

The design saved the world, simulated it for 2 s, compared rounded coordinates and restored.
Two things differ here:

* Nothing else drifts. Robots and environments are fixed-base kinematic bodies whose joints
  are held, so the robot base cannot slide into the answer (the fault of the anchor
  implementations, which call the milk on the counter unstable).
* It stops early, both ways. The object is watched at every step: once it has moved more
  than the limits it is unstable at once. It is declared stable before the 2 s are up only
  when the whole scene has come to rest — every free object moved less than a creep speed
  over the last window — and the object's own motion, extrapolated with its current speed
  and acceleration to the end of the 2 s, stays under half the limits, and its motion is not
  growing (a slowly tipping object speeds up from window to window). Everything up to the
  early stop is the very same physics as a plain 2 s simulation of the world.

The simulation runs on the world's prospection copy (`world.prospection()`), brought in sync
with the world first: the world itself is only read, so everything it holds — poses,
velocities, joints, and the contact caches and broadphase order that PyBullet's restoreState
does not put back — is exactly as before, and simulating it afterwards gives what it would
have given without the query. Free objects of the copy are woken before simulating (a copy
put to sleep by an earlier query would otherwise hang).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ..world.pose import angle_between
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
        twin.copy.wake_free_objects()
        return _watch(twin.copy, twin.copy_of(obj), total, distance, angle)


def _watch(world: "BulletWorld", obj: "Object", total: int, distance: float, angle: float) -> StableAnswer:
    start = obj.get_com_pose()  # watched at the centre of mass: one cheap call per step
    free = [o for o in world.objects if not o.fixed and not any(a.child is o for a in o.attachments.values())]
    min_steps = int(MIN_SECONDS * STEP_HZ)
    window_time = WINDOW / STEP_HZ
    last = {o.id: o.get_com_pose() for o in free}
    previous_motion: tuple[float, float] | None = None
    calm = 0
    worst_d = worst_a = 0.0
    for step in range(1, total + 1):
        world.step()
        now = obj.get_com_pose()
        d, a = _moved(start, now)
        worst_d, worst_a = max(worst_d, d), max(worst_a, a)
        if d > distance or a > angle:
            return StableAnswer(False, worst_d, worst_a, step / STEP_HZ)
        if step % WINDOW:
            continue
        # -- a rest check every window --------------------------------------------------
        scene_at_rest = True
        motion = (0.0, 0.0)
        for other in free:
            pose = other.get_com_pose()
            md, ma = _moved(last[other.id], pose)
            last[other.id] = pose
            if other is obj:
                motion = (md, ma)
            if md > REST_SPEED * window_time or ma > REST_SPIN * window_time:
                scene_at_rest = False
        remaining = (total - step) / STEP_HZ
        settled = False
        if scene_at_rest and previous_motion is not None and step >= min_steps:
            settled = True
            for now_m, before_m, done, limit, noise in ((motion[0], previous_motion[0], d, distance, NOISE_DISTANCE),
                                                         (motion[1], previous_motion[1], a, angle, NOISE_ANGLE)):
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
