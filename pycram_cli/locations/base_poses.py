"""Base poses: where the robot should stand to reach, see or open something, a ranked, deterministic sequence.

A base-pose location (reachable-for, visible-for, both, accessing) starts from candidate base poses
(`lattice.py`) ranked by cheap geometry (`scoring.py`), and tries them best first. Each one goes through the tests,
cheapest first, and the first to pass them all is the answer; the resolution is lazy, so asking again continues
where it stopped:

1. geometry: the target within the arm's length of the shoulder, the camera's distance
   in range (vectorised over every candidate) — `out of reach`, `out of view`;
2. the floor map (`floor.py`): the robot's footprint on occupied cells — `collide`;
3. the robot's collision shapes at the pose, as navigation tests them — `collide`;
4. reachable-for: inverse kinematics for each arm and grasp (the object's grasp points,
   `cannot hold` when the gripper cannot) and the arm's final configuration touching nothing
   but the target and what it stands on — `out of reach`, `blocked` (`reaching.py`);
   accessing: accessing's own plan: the handle's grasp and pre-grasp pose reached, the pull followed step
   by step holding it so (the drawer inside nothing of the robot but the hand), the way to the handle
   free, the robot clear of the opened drawer (`accessing.py`);
5. visible-for: the head turned to the object and the `visible` query — `not visible`.

Only `EXPENSIVE_LIMIT` candidates get tests 4 and 5; the rest count as `not tried`. A location where
an arm reaches (taking, placing, opening or closing) whose candidates all fail with nothing in the way tries them again with
the torso at other heights of its range (`_next_torso`); the pose found says the height. When no
candidate passes, `LocationFailure` says what ruled them out: "412 candidates: 380 collide,
32 out of reach". Everything is computed from the world and the robot's description: no
randomness, no clock; the same world gives the same answer.
"""
from __future__ import annotations

from collections import Counter
from typing import Any

import numpy as np

from ..failures import LocationFailure, ReachabilityFailure
from ..kinds import arm_phrase
from ..planning.head import Mount, camera_mount, look_at
from ..reasoning import visible
from ..reasoning.reachability import TakeAnswer, register_take_check
from ..robots import Robot
from ..world import Object
from ..world.pose import yaw_quaternion
from . import accessing, floor
from .candidates import CODE, OUTCOMES, BasePose, Candidates
from .geometry import ArmGeometry, arm_geometry, camera_offset, centre, yaw_of
from .lattice import DEFERRED, FIRST, candidate_poses
from .ranked import Resolution
from .reaching import ArmTests, Miss
from .scoring import add_pull_heading, add_reach, add_view, here_arm_order, travel_scores
from .spec import LocationSpec
from .touching import allowed_contacts

#: candidates that get the expensive tests (inverse kinematics, rendering) before the resolution gives up
EXPENSIVE_LIMIT = 40
#: ... times this many while none of them was blocked by something (see BasePoseResolution._patience)
REACH_PATIENCE = 3
#: a reachable-for location that finds no pose with the torso where it is tries at most this many other heights, first
#: those that put the shoulder nearest this fraction of the arm's length above the target (an arm reaches down onto a
#: counter best), none nearer than TORSO_MIN_CHANGE (m) to where the torso is
TORSO_PASSES = 2
TORSO_SHOULDER = 0.25
TORSO_MIN_CHANGE = 0.02
#: the map test runs on this many candidates at a time
CHUNK = 48
#: once this many candidates failed only for want of a joint-space search for the arm's way, they are tried again with
#: one before any further candidate is tried without (`_search`): an arm that needs a search at every pose (a short
#: arm carrying a thing over the counter's edge) tried 40 poses without one, 6-13 s per place, before the first with
SEARCH_AFTER = 4


def usable_arms(robot: Robot, spec: LocationSpec) -> dict[str, ArmGeometry]:
    """The arms a location may use: the one it names, the one holding what it places, else those with a free hand
    (a full hand takes nothing, opens nothing); LocationFailure when a location that reaches has none."""
    arms = arm_geometry(robot)
    if spec.arm is not None:
        arms = {spec.arm: arms[spec.arm]}
    if spec.placing is not None:
        holding = robot.arm_holding(spec.placing)
        arms = {name: geo for name, geo in arms.items() if name == holding}
    elif spec.reachable_for is not None or spec.accessing is not None:
        arms = {name: geo for name, geo in arms.items() if not robot.held_objects(name)}
    if not arms and (spec.reachable_for is not None or spec.accessing is not None):
        if spec.placing is not None:
            why = f"the robot does not hold {spec.placing.name}" + (f" in {arm_phrase(spec.arm)}" if spec.arm else "")
        elif spec.arm is not None:
            why = f"{arm_phrase(spec.arm)} holds {', '.join(o.name for o in robot.held_objects(spec.arm))}"
        else:
            why = "every gripper holds something"
        raise LocationFailure(f"no pose for {spec.describe()}: {why}", location=spec.describe())
    return arms


class BasePoseResolution(Resolution):
    """The base poses of one location, best first, found lazily (`next()`; iterate for all)."""

    def __init__(self, robot: Robot, spec: LocationSpec, limit: int = EXPENSIVE_LIMIT) -> None:
        super().__init__(robot, spec, limit)
        self.map: floor.FloorMap | None = None
        self.open_map: floor.FloorMap | None = None
        self.target: np.ndarray | None = None  # the point the candidates face
        self.view_target: np.ndarray | None = None
        self.arm_names: list[str] = []
        self.arm_order = np.zeros((0, 0), dtype=np.int8)
        self.arm_tests: ArmTests | None = None
        self._handle_path: list[np.ndarray] = []
        #: candidates tried only once all the others failed (with their arm orders): see `_prepare`
        self._deferred: tuple[Candidates, np.ndarray] | None = None
        #: candidates whose arm tests failed only for want of a joint-space search for the arm's way: the tests make
        #: none at first (`ArmTests.searching`), so that a pose whose ways need none is found without paying for the
        #: searches at the poses before it (about 0.4 s each where no way exists); these are tried again with searches
        #: once SEARCH_AFTER of them are waiting or no other candidate is left (`_search_again`), in the order they
        #: were tried
        self._unsearched: list[int] = []
        #: whether the robot's current pose is the first candidate (an action asks: no need to drive when it will do)
        self.here = False
        self.here_index: int | None = None
        #: the torso height the candidates are tried with (None: where it is), the heights still to try, and what the
        #: passes with earlier heights found
        self.torso: float | None = None
        self._torso_todo: list[float] | None = None
        self._passes: list[str] = []

    def take_here(self) -> TakeAnswer:
        """Only the pose the robot stands at, for an object to take: the arm and grasp pick-up itself would take it
        with (its own planning, `ArmTests`), or why none does. The base's own contacts where it stands do not count."""
        world = self.robot.world
        self.here = True
        with world.lock, world.snapshot():
            self._prepare_here()
            i = self.here_index
            assert i is not None and self.arm_tests is not None
            self.arm_tests.searching = True  # the only pose there is
            found = self._reach(i)
        tests = self.arm_tests
        if found is not None:
            solution = tests.taken
            return TakeAnswer(True, found[0], found[1], joint_positions=dict(solution.joint_positions),
                              position_error=solution.position_error, orientation_error=solution.orientation_error)
        arm = self.arm_names[int(self.arm_order[i][0])] if len(self.arm_order) and self.arm_names else None
        return TakeAnswer(False, arm, reason=OUTCOMES[self.candidates.outcome[i]],
                          detail=self.candidates.detail.get(i, ""), tried=tuple(tests.attempts),
                          position_error=tests.shortfall)

    # -- the candidates ---------------------------------------------------------------------------------------
    def _prepare(self) -> None:
        """The candidates, ranked and through the cheap tests (geometry, the floor map's core), and what the arm
        tests need (allowed contacts, the handle's path)."""
        robot, spec = self.robot, self.spec
        self.held = robot.held_objects()
        self.map = floor_map = floor.floor_map(robot, self.held, saved=True)
        self.floor_z = floor_map.floor_z
        arms = usable_arms(robot, spec)
        self.arm_names = list(arms)
        camera = camera_offset(robot)
        reach_target, handle_ends = self._reach_target()
        view_target = centre(spec.visible_for) if spec.visible_for is not None else None
        self.view_target = view_target
        primary = reach_target if reach_target is not None else view_target
        assert primary is not None
        self.target = primary
        fixed_camera = view_target is not None and camera_mount(robot).kind is Mount.BODY
        poses = candidate_poses(robot, spec, arms, primary, reach_target, fixed_camera, camera, handle_ends)
        xs, ys, yaws, kind = poses.xs, poses.ys, poses.yaws, poses.kind
        scores = travel_scores(xs, ys, poses.turns, np.asarray(robot.body.get_position()[:2]))
        outcome = np.zeros(len(xs), dtype=np.int8)
        self.arm_order = np.zeros((len(xs), len(arms)), dtype=np.int8)
        if reach_target is not None:
            pulled_to = self._handle_path[-1] if spec.accessing is not None and self._handle_path else None
            scores, self.arm_order = add_reach(scores, outcome, xs, ys, yaws, arms, reach_target, self.floor_z,
                                               pulled_to, poses.level())
            if handle_ends is not None:
                scores = add_pull_heading(scores, yaws, *handle_ends)
        if view_target is not None:
            scores = add_view(robot, scores, outcome, xs, ys, yaws, camera, view_target, self.floor_z, fixed_camera)
        todo = outcome == 0
        core = floor_map.core_collides(xs[todo], ys[todo], yaws[todo])
        outcome[np.flatnonzero(todo)[core]] = CODE["collides"]
        if not robot.description.mobile:  # a base that cannot drive: only where it stands
            xs, ys, yaws, scores = (np.zeros(0) for _ in range(4))
            outcome, self.arm_order = np.zeros(0, dtype=np.int8), np.zeros((0, len(arms)), dtype=np.int8)
            kind = np.zeros(0, dtype=np.int8)
            self.here = True
        first = kind == FIRST
        if (kind != 0).any():  # the in-line poses of arms that need them go first; the others wait until the lattice fails
            later = kind == DEFERRED
            kept = ~later
            self._deferred = (Candidates(xs[later], ys[later], yaws[later], scores[later], outcome[later],
                                         np.ones(int(later.sum()), dtype=bool)), self.arm_order[later])
            xs, ys, yaws, scores, outcome, first = xs[kept], ys[kept], yaws[kept], scores[kept], outcome[kept], first[kept]
            self.arm_order = self.arm_order[kept]
        if self.here:  # the pose the robot stands at, tried first (its map test is skipped: it stands there)
            row, here_arms = self._here_row(arms, reach_target)
            xs, ys, yaws, scores, outcome, first = (np.append(column, value) for column, value in
                                                    zip((xs, ys, yaws, scores, outcome, first), row))
            self.arm_order = np.concatenate([self.arm_order, here_arms])
            self.here_index = len(xs) - 1
        self.candidates = Candidates(xs, ys, yaws, scores, outcome, first)
        self.arm_tests = ArmTests(robot, spec, self.held, allowed_contacts(robot.world, spec), self._handle_path)
        self.arm_tests.searching = False
        self._unsearched = []

    def _here_row(self, arms: dict[str, Any], reach_target: np.ndarray | None) -> tuple[tuple, np.ndarray]:
        """The pose the robot stands at as a candidate (x, y, yaw, score: first, outcome, not `first`) and its arms;
        out of reach when no arm is long enough for the target (or the handle's pulled end), as `add_reach` rules
        out the others."""
        robot, spec = self.robot, self.spec
        rx, ry = robot.body.get_position()[:2]
        ryaw = yaw_of(robot.body.get_orientation())
        pulled = self._handle_path[-1] if spec.accessing is not None and self._handle_path else None
        here_arms = here_arm_order(arms, reach_target, rx, ry, ryaw, self.floor_z, pulled, bounded=True)
        beyond = reach_target is not None and bool(len(arms)) and bool((here_arms < 0).all())
        return (rx, ry, ryaw, -1.0, CODE["out of reach"] if beyond else 0, False), here_arms

    def _prepare_here(self) -> None:
        """What `take_here` needs of `_prepare`, for the one pose the robot stands at: its arms, nearest first, and the
        arm tests. The lattice, its scores and the floor map are left out: none of them decides a test at that pose
        (its map test is skipped, and the floor height is where the robot stands, as the map would say), and building
        them cost about 15 ms of every pick-up."""
        robot, spec = self.robot, self.spec
        self.held = robot.held_objects()
        rx, ry, rz = robot.body.get_position()
        self.floor_z = float(rz)
        arms = usable_arms(robot, spec)
        self.arm_names = list(arms)
        reach_target, _ = self._reach_target()
        assert reach_target is not None  # take_here is asked of an object to take
        self.target = reach_target
        ryaw = yaw_of(robot.body.get_orientation())
        self.arm_order = here_arm_order(arms, reach_target, rx, ry, ryaw, self.floor_z)
        self.candidates = Candidates(np.array([rx]), np.array([ry]), np.array([ryaw]), np.array([-1.0]),
                                     np.zeros(1, dtype=np.int8), np.zeros(1, dtype=bool))
        self.here_index = 0
        self.arm_tests = ArmTests(robot, spec, self.held, allowed_contacts(robot.world, spec), self._handle_path)
        self._unsearched = []
        self._prepared = True

    def _reach_target(self) -> tuple[np.ndarray | None, tuple[np.ndarray, np.ndarray] | None]:
        """The point an arm reaches (None: nothing to reach) and, for accessing on a mobile base, the handle's closed
        and opened ends (facing into the drawer, opening it or closing it: the closed end is the path's end nearer
        the joint's lower limit, where `accessing.goal` counts the distance from). Keeps the handle's path and the
        floor map with the drawer opened."""
        spec = self.spec
        reach_target = None
        if spec.reachable_for is not None:
            reach_target = (centre(spec.reachable_for) if isinstance(spec.reachable_for, Object)
                            else np.asarray(spec.reachable_for, dtype=float))
        if spec.accessing is None:
            return reach_target, None
        handle = spec.accessing
        reach_target = np.asarray(handle.obj.get_link_position(handle.link))
        self._handle_path = accessing.handle_positions(spec)
        self.open_map = accessing.opened_map(self.robot, spec, self.held)
        if not self.robot.description.mobile:
            return reach_target, None
        closed, opened = self._handle_path[0], self._handle_path[-1]
        if accessing.closing(spec):
            closed, opened = opened, closed
        return reach_target, (closed, opened)

    # -- the tests ----------------------------------------------------------------------------------------------
    def next(self) -> BasePose:
        """The next base pose (best first); LocationFailure when none is left. A reachable-for location that finds
        none with the torso where it is tries other torso heights (`_next_torso`)."""
        world = self.robot.world
        with world.lock, world.snapshot():
            self._prepared_inside()
            self._set_torso()
            while True:
                pose = self._search()
                if pose is not None:
                    return pose
                if not self._next_torso():
                    break
        raise self._fail(self.failure_message())

    def _search(self) -> BasePose | None:
        """The next candidate that passes every test, or None when none is left (or patience has run out)."""
        order = self.candidates.order
        while self.cursor < len(order) and self.expensive < self._patience():
            chunk = order[self.cursor:self.cursor + CHUNK]
            self._map_test(chunk)
            for i in chunk:
                self.cursor += 1
                if self.candidates.outcome[i] != 0:
                    continue
                pose = self._test(int(i))
                if pose is not None:
                    self.candidates.outcome[i] = CODE["ok"]
                    self.found.append(pose)
                    return pose
                if len(self._unsearched) >= SEARCH_AFTER:  # (marks what it finds)
                    pose = self._search_again()
                    if pose is not None:
                        return pose
                if self.expensive >= self._patience():
                    break
            if self.cursor >= len(order) or self.expensive >= self._patience():
                pose = self._search_again()
                if pose is not None:
                    return pose
                if not self._take_deferred():
                    break
                order = self.candidates.order
        return self._search_again()

    def _search_again(self) -> BasePose | None:
        """The first of the candidates that failed only for want of a search (`_unsearched`) that passes with one, or
        None. The pose found is the one the tests would have found with searches from the start, unless a later
        candidate passed without one (then that one was found first)."""
        tests = self.arm_tests
        assert tests is not None
        while self._unsearched:
            i = self._unsearched.pop(0)
            tests.searching = True
            counted = self.expensive  # the candidate was counted against patience when first tested
            try:
                pose = self._test(i)
            finally:
                tests.searching = False
                self.expensive = counted
            if pose is not None:
                self.candidates.outcome[i] = CODE["ok"]
                self.found.append(pose)
                return pose
        return None

    # -- the torso ----------------------------------------------------------------------------------------------
    def _set_torso(self) -> None:
        """The torso at the height this pass tries (nothing while it stays where it is); what the robot holds follows."""
        joint = self.robot.description.torso_joint
        if self.torso is not None and joint is not None:
            self.robot.body.reset_joints({joint: self.torso})
            self.robot.body.move_attached()

    def _torso_heights(self) -> list[float]:
        """The torso heights to try besides where it is: the bottom, middle and top of its range, those putting some
        arm's shoulder nearest TORSO_SHOULDER (of the arm's length) above the target first, at most TORSO_PASSES."""
        robot, body = self.robot, self.robot.body
        joint = robot.description.torso_joint
        if joint is None or self.target is None or not body.joint(joint).limited:
            return []
        torso = body.joint(joint)
        current = body.get_joint_positions([joint])[joint]
        heights = [h for h in (torso.lower, (torso.lower + torso.upper) / 2.0, torso.upper)
                   if abs(h - current) > TORSO_MIN_CHANGE]
        target_z = float(self.target[2])

        def off(height: float) -> float:
            with body.joints_kept([joint]):
                body.reset_joints({joint: height})
                arms = arm_geometry(robot)
            return min(abs(self.floor_z + arms[name].shoulder[2] - target_z - TORSO_SHOULDER * arms[name].length)
                       for name in self.arm_names)

        return sorted(heights, key=lambda h: (off(h), h))[:TORSO_PASSES]

    def _next_torso(self) -> bool:
        """When no pose reached the target with the torso where it is (and nothing was in the way: that is the plan's
        to move), the candidates anew with the torso at the next height (`_torso_heights`): whether there is one. Only
        locations where an arm reaches (taking, placing, opening or closing) do this; the pose found says the height
        (`torso`)."""
        robot, spec = self.robot, self.spec
        if (robot.description.torso_joint is None or (spec.reachable_for is None and spec.accessing is None)
                or CODE["blocked"] in self.candidates.outcome):
            return False
        if self._torso_todo is None:
            self._torso_todo = self._torso_heights()
        if not self._torso_todo:
            return False
        self._passes.append(self._pass_text())
        self.torso = self._torso_todo.pop(0)
        self._set_torso()
        self._deferred = None
        self._prepare()
        self.cursor, self.expensive = 0, 0
        return True

    def _take_deferred(self) -> bool:
        """Add the deferred candidates when all the others failed (tried anew, with patience anew): whether there were."""
        if self._deferred is None or not len(self._deferred[0]):
            return False
        more, arm_order = self._deferred
        self._deferred = None
        self.candidates = self.candidates.extended(more)
        self.arm_order = np.concatenate([self.arm_order, arm_order])
        self.cursor, self.expensive = 0, 0
        return True

    def _map_test(self, chunk: np.ndarray) -> None:
        todo = chunk[(self.candidates.outcome[chunk] == 0) & (chunk != (self.here_index if self.here_index is not None else -1))]
        if not len(todo):
            return
        cand = self.candidates
        assert self.map is not None
        hit = self.map.collides(cand.xs[todo], cand.ys[todo], cand.yaws[todo])
        if self.open_map is not None:
            hit |= self.open_map.collides(cand.xs[todo], cand.ys[todo], cand.yaws[todo])
        cand.outcome[todo[hit]] = CODE["collides"]

    def _test(self, i: int) -> BasePose | None:
        robot, spec, cand = self.robot, self.spec, self.candidates
        x, y, yaw = float(cand.xs[i]), float(cand.ys[i]), float(cand.yaws[i])
        hits = floor.exact_collisions(robot.body, self.held, x, y, yaw)
        if hits:
            cand.mark(i, "collides", ", ".join(hits))
            return None
        if spec.accessing is not None:
            hits = accessing.opened_collisions(robot, spec, self.held, x, y, yaw)
            if hits:
                cand.mark(i, "collides", f"{', '.join(hits)} (opened)")
                return None
        self.expensive += 1
        arm, grasp = None, None
        if spec.reachable_for is not None or spec.accessing is not None:
            found = self._reach(i)
            if found is None:
                return None
            arm, grasp = found
        look = None
        if spec.visible_for is not None:
            look = self._view(i)
            if look is None:
                return None
        return BasePose((x, y, self.floor_z), yaw_quaternion(yaw), yaw, float(cand.scores[i]), arm, grasp, look,
                        len(self.found), self.torso)

    def _patience(self) -> int:
        """How many candidates get the expensive tests: the limit, or REACH_PATIENCE times it while nothing was found
        blocked (an arm that is merely short of the geometric estimate, as a user's weaker arm is, finds its pose
        farther down the list; something in the way is the plan's to move, and waits for no more tries)."""
        if self.spec.patience is not None:
            return self.spec.patience
        if CODE["blocked"] in self.candidates.outcome:
            return self.limit
        return self.limit * REACH_PATIENCE

    def _reach(self, i: int) -> tuple[str, Any] | None:
        """The first arm and grasp (arms nearest first) that reach untouched from candidate `i` (`ArmTests`), or None
        with the candidate marked with why not."""
        spec = self.spec
        assert self.arm_tests is not None
        if spec.placing is not None and self.robot.arm_holding(spec.placing) is None:
            # let go since the resolution began (a step after the place failed)
            raise self._fail(f"no pose for {spec.describe()}: the robot no longer holds {spec.placing.name}")
        arms = [self.arm_names[k] for k in self.arm_order[i] if k >= 0] if len(self.arm_order) else self.arm_names
        found = self.arm_tests.reach(arms)
        if isinstance(found, Miss):
            self.candidates.mark(i, found.reason, found.detail)
            if found.unsearched and not self.arm_tests.searching:
                self._unsearched.append(i)
            return None
        return found

    def _view(self, i: int) -> tuple[float, float, float] | None:
        obj = self.spec.visible_for
        assert obj is not None
        target = tuple(float(v) for v in centre(obj))
        try:
            look_at(self.robot, target, turn_base=False)
        except ReachabilityFailure:  # the camera cannot be pointed there: not from this pose
            self.candidates.mark(i, "out of view", "the camera cannot point at it")
            return None
        answer = visible(obj, world=self.robot.world)
        if not answer.visible:
            self.candidates.mark(i, "not visible", f"{answer.fraction:.0%} seen")
            return None
        return target  # type: ignore[return-value]

    # -- reporting --------------------------------------------------------------------------------------------
    def _pass_text(self) -> str:
        """What this pass's candidates ran into: `412 candidates: 380 collide, 32 out of reach (blocked by cereal)`."""
        text = self.summary()
        blockers = Counter(name for detail in self.candidates.details("blocked") for name in detail.split(", "))
        if blockers:
            text += " (blocked by " + ", ".join(name for name, _ in blockers.most_common()) + ")"
        if self.torso is not None:
            text = f"with the torso at {self.torso:.3f} m, {text}"
        return text

    def failure_message(self) -> str:
        return f"no pose for {self.spec.describe()}: " + "; ".join([*self._passes, self._pass_text()])


def take_from_here(body: Object, obj: Object, arm: str | None = None, grasp: Any = None) -> TakeAnswer:
    """Whether pick-up would take `obj` from where the robot stands (see `BasePoseResolution.take_here`)."""
    robot = Robot.of(body.world)
    return BasePoseResolution(robot, LocationSpec(reachable_for=obj, arm=arm, grasp=grasp)).take_here()


register_take_check(take_from_here)
