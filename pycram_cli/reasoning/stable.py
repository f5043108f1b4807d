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
* It says what an unstable object does. Past the limits, the object is watched OBSERVE (1 s)
  longer: it `settled` (came to rest elsewhere), is still `moving` (falls, tips, slides, rolls),
  or `rocks` — its offset from where it stood keeps turning back without growing and its centre
  of mass stays up — with the amplitude of the swing, rather than a misleading "moved N mm" for
  an object that goes nowhere (a half cylinder on its round side; the design's open spoon). The
  verdict and `simulated` are the same watched or not (`displacement` and `rotation` then cover
  the watch too); `observe=0` skips the watch (location search only needs the verdict).

The tolerance (1 mm, 1°): objects at rest in a plain simulation of the bundled world drift at
most 0.103 mm and tilt at most 0.208° over 5 s (bench/stable_tolerance.py; README's stable section).

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
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..signature import Param
from ..world.parking import Parking
from ..world.pose import angle_between
from . import neighbourhood
from ._common import world_of
from .query import AN_OBJECT, Call, QueryAnswer, QuerySpec, declare_query, degrees, mm, parameters

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


#: after an object has gone past the limits it is watched this much longer (s), so that the answer says what it does:
#: comes to rest elsewhere, keeps moving away, or rocks (a 5° rocker on the island swings with a period of 0.55 s)
OBSERVE = 1.0
#: a rock is counted when the object's offset from where it stood turns back by more than this fraction of the limits
SWING = 0.5
#: and it rocks when its offset turned back at least this often while watched, grew no larger in the second half
#: of the watch than this many times its largest in the first half (a tipping or falling object's keeps growing),
#: and its centre of mass never sank more than DROP (m) below where it stood: rocking about a rest lifts it (a
#: tumbling or fallen object bounces too, but centimetres lower; the design's spoon shifts about 2 mm as it settles)
TURNS = 2
GROWTH = 1.5
DROP = 0.005

#: what an object does (`StableAnswer.motion`): stays put; went past the limits (not watched further); came to rest
#: elsewhere; keeps moving away (falls, tips, slides, rolls); keeps rocking back and forth about where it stood
AT_REST, MOVED, SETTLED, MOVING, ROCKS = "at rest", "moved", "settled", "moving", "rocks"


@dataclass(frozen=True)
class StableAnswer:
    """Truthy when stable. `displacement` (m) and `rotation` (rad): the largest reached while simulating;
    `simulated`: seconds simulated before the verdict was certain. An unstable object is watched OBSERVE s
    longer (`observed`: how long) and `motion` says what it does then (SETTLED, MOVING or ROCKS; MOVED when
    it was not watched); `amplitude` (m, rad): how far a rocking object's offset from where it stood swings
    (largest minus smallest over the second half of the watch)."""

    stable: bool
    displacement: float
    rotation: float
    simulated: float = 0.0
    motion: str = AT_REST
    amplitude: tuple[float, float] | None = None
    observed: float = 0.0

    def __bool__(self) -> bool:
        return self.stable


def _moved(a: tuple, b: tuple) -> tuple[float, float]:
    return math.dist(a[0], b[0]), angle_between(a[1], b[1])


def stable(obj: Object, world: BulletWorld | None = None, seconds: float = SECONDS,
           distance: float = DISTANCE, angle: float = ANGLE, observe: float = OBSERVE) -> StableAnswer:
    """Whether `obj` moves less than `distance` (m) and `angle` (rad) while the world runs for `seconds`; an object
    that does not is watched `observe` s longer to say what it does (0: the verdict only, as fast as it comes)."""
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
            return _Watch(copy, target, hood, parking, distance, angle).run(total, int(round(observe * STEP_HZ)))
        finally:
            parking.put_back()


class _Watch:
    """One check: steps the copy, watches the object and judges the neighbourhood's rest."""

    def __init__(self, world: BulletWorld, obj: Object, hood: neighbourhood.Neighbourhood, parking: Parking,
                 distance: float, angle: float) -> None:
        self.world, self.obj, self.hood, self.parking = world, obj, hood, parking
        self.distance, self.angle = distance, angle
        self.watched = [o for o in hood.members if _loose(o)]
        self.last = {o.id: o.get_com_pose() for o in self.watched}

    def run(self, total: int, observe: int = 0) -> StableAnswer:
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
                verdict = StableAnswer(False, worst_d, worst_a, step / STEP_HZ, MOVED)
                return self._observe(verdict, start, observe) if observe > 0 else verdict
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

    def _observe(self, verdict: StableAnswer, start: tuple, steps: int) -> StableAnswer:
        """Watch an object that went past the limits `steps` steps longer: SETTLED when it moves slower than the
        rest speeds for CALM_WINDOWS windows, ROCKS when its offset from `start` keeps turning back without
        growing, else MOVING."""
        obj, window_time = self.obj, WINDOW / STEP_HZ
        self._window(window_time)  # the windows count from here
        offsets: list[tuple[float, float]] = []
        worst_d, worst_a, lowest = verdict.displacement, verdict.rotation, start[0][2]
        calm = 0
        for step in range(1, steps + 1):
            self.world.step()
            pose = obj.get_com_pose()
            d, a = _moved(start, pose)
            worst_d, worst_a, lowest = max(worst_d, d), max(worst_a, a), min(lowest, pose[0][2])
            if step % WINDOW and step != steps:
                continue
            offsets.append((d, a))
            _, (md, ma) = self._window(window_time)
            calm = calm + 1 if md <= REST_SPEED * window_time and ma <= REST_SPIN * window_time else 0
            if calm >= CALM_WINDOWS:
                return replace(verdict, displacement=worst_d, rotation=worst_a, motion=SETTLED,
                               observed=step / STEP_HZ)
        watched = replace(verdict, displacement=worst_d, rotation=worst_a, observed=steps / STEP_HZ)
        half = len(offsets) // 2
        if half and lowest >= start[0][2] - DROP:
            for limit, series in ((self.distance, [o[0] for o in offsets]), (self.angle, [o[1] for o in offsets])):
                if _turns(series, SWING * limit) >= TURNS and max(series[half:]) <= GROWTH * max(series[:half]):
                    tail_d, tail_a = [o[0] for o in offsets[half:]], [o[1] for o in offsets[half:]]
                    return replace(watched, motion=ROCKS,
                                   amplitude=(max(tail_d) - min(tail_d), max(tail_a) - min(tail_a)))
        return replace(watched, motion=MOVING)

    def _window(self, window_time: float) -> tuple[bool, tuple[float, float]]:
        """Whether every watched body moved less than the creep speed over the last window, and the object's
        own motion; a body that moved is checked against the parked ones, which come back when it nears them."""
        at_rest = True
        motion = (0.0, 0.0)
        gravity = float(np.linalg.norm(self.world.gravity))
        returning: list[Object] = []
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

    def _put_back(self, objects: list[Object]) -> None:
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


def _turns(series: list[float], swing: float) -> int:
    """How often `series` turns back by more than `swing` from its last extreme (a rock to one side and back)."""
    turns, rising, extreme = 0, True, series[0] if series else 0.0
    for value in series[1:]:
        if (value > extreme) == rising:
            extreme = value
        elif abs(value - extreme) > swing:
            turns, rising, extreme = turns + 1, not rising, value
    return turns


def _loose(obj: Object) -> bool:
    """A free object that nothing holds (what is attached to a parent just follows it)."""
    return not obj.fixed and not any(a.child is obj for a in obj.attachments.values())


# -- the query, by name (plans, `pycram query`, docs) --------------------------------------------------


def _stable(call: Call) -> QueryAnswer:
    answer = stable(call.object("object"))
    details: dict[str, Any] = {"displacement": answer.displacement, "rotation": answer.rotation,
                               "simulated": answer.simulated}
    if not answer.stable:  # what it does once past the limits (a stable answer's is "at rest")
        details.update(motion=answer.motion, observed=answer.observed)
        if answer.amplitude is not None:
            details["amplitude"] = {"displacement": answer.amplitude[0], "rotation": answer.amplitude[1]}
    return QueryAnswer("stable", call.resolved, answer.stable, details, answer.stable)


def _say_stable(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    moved = f"moved {mm(d['displacement'])} and {degrees(d['rotation'])}"
    if answer.result:
        return f"{a['object']} is stable ({moved} in {d['simulated']:.2f} s simulated)"
    total = f"{d['simulated'] + d.get('observed', 0.0):.2f} s simulated"
    motion = d.get("motion")
    if motion == "rocks":
        swing = d["amplitude"]
        return (f"{a['object']} is NOT stable: it is not at rest, it rocks back and forth by {degrees(swing['rotation'])} "
                f"and {mm(swing['displacement'])} and is still moving ({total})")
    if motion == "settled":
        return f"{a['object']} is NOT stable: it {moved}, then came to rest ({total})"
    if motion == "moving":
        return f"{a['object']} is NOT stable: it {moved} and is still moving ({total})"
    return f"{a['object']} is NOT stable: it {moved} in {total}"


declare_query(QuerySpec(
    "stable", "Does the object stay put (within 1 mm and 1°) while the world is simulated for 2 s? When not, it is "
              f"watched {OBSERVE:g} s longer: it came to rest elsewhere, is still moving, or rocks (and by how much).",
    parameters(Param("object", "object", True, AN_OBJECT, positional=True)), _stable, _say_stable))
