"""Inverse kinematics for a robot's tool frame: damped least squares on our own kinematic chain.

PyBullet's `calculateInverseKinematics` often stops short of the target and its SDLS solver
crashes, so the chain from the robot's base to the tool link is read from the robot's joints once
(joint frames, axes, inertial offsets — PyBullet expresses every joint frame relative to
the parent's centre of mass) and solved with a Levenberg–Marquardt loop (ik_search.py) with joint limits enforced
by clamping and a few deterministic restarts. The kinematics never touch the world; only the final answer is checked
against PyBullet's own forward kinematics (joints set, link pose read, joints put back with their saved positions and
velocities), so the errors reported are PyBullet's. An answer is a function of the chain's joint values and the
question asked in the chain's own frame (`Problem.in_chain_frame`: wherever the base stands): it is kept (per robot,
the latest `MEMO_SIZE`, in the world's cache table `ANSWERS`), and the same question asked again is answered without
a search (forget the table for a benchmark of first questions). A location's candidate poses ask the arm's ways from
where it is again at each pose: those are answered once.

Only the requested joints move (by default the joints of the arm); the torso, head and base keep
their current values. `solve(robot, arm, ...)` is the front door: the robot (robots/robot.py) says
which joints the arm has and where its tool frame is; `solve_link(body, link, ...)` solves for any
link of a body (the design's `reachable(target, robot, gripper_link)`, a robot without a description).
Several targets are asked at once with `solutions`/`link_solutions`: iterators of the answers as they are found,
which the caller stops (break) once it has the one it needs. How an answer is searched for (thresholds, seeds,
iterations, whether the nearest configuration is wanted for a target out of reach) is one `Settings`.
"""
from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import BadValue
from ..robots import Robot, description_for
from ..world.cache import Memo
from ..world.pose import Quat, Vec3, check_position, check_quaternion
from .ik_search import REACH_SLACK, Found, Problem, initial_seeds, rotation_angle, search_groups
from .kinematics import chain_for, transform

if TYPE_CHECKING:
    from ..world import Object

MAX_ITERATIONS = 60
RESTARTS = 6
#: the seeds of an oriented target for a chain with no more joints than a pose has numbers (six or fewer): its
#: solutions are a few isolated configurations, whose basins six seeds miss (a pan, pitches, a telescope and a roll
#: holding a handle level found it only with the arm nearly stretched; over 80 level targets of two such arms, 6
#: seeds found 13 and 23, 12 found 63 and 62, 20 found 64 and 62); the seeds beyond RESTARTS are searched only when
#: the first find nothing (`_Batch.search`), which doubles what a target out of reach costs such an arm
FEW_JOINT_SEEDS = 12
#: how many answers each robot keeps (the latest used), and the world's cache table that keeps them (world/cache.py)
MEMO_SIZE = 512
ANSWERS = "ik answers"
#: the world's cache table of each robot's fixed seeds (`ik_search.initial_seeds`)
SEEDS = "ik seeds"


@dataclass(frozen=True)
class IKSolution:
    """The outcome of an IK query; truthy when the tool frame reached the target within the thresholds."""

    success: bool
    joint_positions: dict[str, float] = field(default_factory=dict)
    position_error: float = math.inf
    orientation_error: float | None = None

    def __bool__(self) -> bool:
        return self.success



@dataclass(frozen=True)
class Settings:
    """How an IK query is answered: success within `threshold` m and `angle_threshold` rad of the target, searched
    from `seeds` starting points (None: RESTARTS, or FEW_JOINT_SEEDS for an oriented target of a chain of six or
    fewer joints) for at most `max_iterations` steps. `best_effort=False`, for a caller that needs only
    the verdict: a target that a distance bound puts out of reach (`Problem.beyond_reach`) fails at once, without the
    search for the configuration nearest it (its `joint_positions` empty, its `position_error` how far beyond the
    bound it lies, no `orientation_error`)."""

    threshold: float = 0.01
    angle_threshold: float = 0.1
    seeds: int | None = None
    max_iterations: int = MAX_ITERATIONS
    best_effort: bool = True

    def seed_count(self, joints: int, oriented: bool) -> int:
        """How many starting points a search of a chain of `joints` joints makes."""
        if self.seeds is not None:
            return max(1, self.seeds)
        return FEW_JOINT_SEEDS if oriented and joints <= 6 else RESTARTS

    def asked(self) -> tuple[float, float, int | None, int]:
        """What of the settings an answer depends on (a verdict-only answer is never kept)."""
        return self.threshold, self.angle_threshold, self.seeds, self.max_iterations


DEFAULT = Settings()

#: one query of `solutions`: the target's position and orientation (None: any), and where the joints start from
Query = tuple[Sequence[float], "Sequence[float] | None", "Mapping[str, float] | None"]


def _recall(memo: Memo, key: tuple) -> IKSolution | None:
    found = memo.recall(key)
    if found is None:
        return None
    return IKSolution(found.success, dict(found.joint_positions), found.position_error, found.orientation_error)


def _remember(memo: Memo, key: tuple, answer: IKSolution) -> None:
    memo.remember(key, IKSolution(answer.success, dict(answer.joint_positions), answer.position_error,
                                  answer.orientation_error))


def _arm_joints(robot: Object, tool_link: str) -> list[str]:
    desc = description_for(robot)
    if desc is not None:
        arm = desc.arm_of_link(tool_link)
        if arm is not None:
            return list(desc.arm(arm).joints)
        torso = {desc.torso_joint} if desc.torso_joint else set()
    else:
        torso = set()
    # no description: every movable joint between the base and the link, but the torso
    chain = chain_for(robot, robot.get_link_id(tool_link))
    return [j.name for j in chain.joints if j.movable and j.name not in torso]


def forward_pose(robot: Object, tool_link: str, joint_positions: dict[str, float]) -> tuple[Vec3, Quat]:
    """PyBullet's pose of `tool_link` with `joint_positions` applied, computed on the world's prospection copy of
    the robot: the robot itself is only read (see world/prospection.py)."""
    twin = robot.world.prospection([robot], velocities=False)
    copy = twin.copy_of(robot)
    copy.reset_joints(joint_positions)
    return copy.get_link_position_and_orientation(tool_link)



def solve(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None = None,
          frame: str | None = None, joints: Sequence[str] | None = None, settings: Settings = DEFAULT) -> IKSolution:
    """Joint positions of `arm` (or `joints`) that bring its tool frame (or `frame`, a link the arm moves: a camera on
    its wrist) to `position` (and `orientation`, a world quaternion): `solve_link` for the arm."""
    return solve_link(robot.body, frame or robot.arm(arm).tool_frame, position, orientation,
                      list(robot.arm(arm).joints) if joints is None else joints, settings)


def solutions(robot: Robot, arm: str, queries: Sequence[Query],
              settings: Settings = DEFAULT) -> Iterator[tuple[int, IKSolution]]:
    """`link_solutions` for the arm's tool frame and joints."""
    return link_solutions(robot.body, robot.arm(arm).tool_frame, queries, list(robot.arm(arm).joints), settings)


def solve_link(robot: Object, tool_link: str, position: Sequence[float], orientation: Sequence[float] | None = None,
               joints: Sequence[str] | None = None, settings: Settings = DEFAULT) -> IKSolution:
    """Joint positions that bring `tool_link` of `robot` to `position` (and `orientation`, a world quaternion).

    `joints` (default: the arm owning the link) are the only joints that move; limits are respected.
    The world is left untouched. Deterministic: the same world and inputs give the same answer, bitwise.
    A failed search returns the best configuration found and its remaining errors (unless `settings.best_effort` is
    False: see `Settings`).
    """
    for _, answer in link_solutions(robot, tool_link, [(position, orientation, None)], joints, settings):
        return answer
    raise AssertionError("one IK query gives one answer")


def beyond_reach(robot: Robot, arm: str, targets: Sequence[tuple[Sequence[float], Sequence[float] | None]],
                 settings: Settings = DEFAULT) -> int | None:
    """The index of the first target (position, orientation) that the distance bound puts out of the arm's reach within
    the settings' thresholds (`Problem.beyond_reach`: no search, a necessary condition only), or None when each may be
    reachable. A walk of many poses asks this first, so that its last pose out of reach fails it before the walk."""
    body = robot.body
    asked = _Asked(body, robot.arm(arm).tool_frame, [(p, o, None) for p, o in targets], list(robot.arm(arm).joints),
                   settings)
    problem = Problem(body, chain_for(body, asked.link_index), asked.names)
    for k, (target, rotation) in enumerate(zip(asked.targets, asked.rotations)):
        if problem.beyond_reach(target, rotation, settings.threshold, settings.angle_threshold) > 0.0:
            return k
    return None


def link_solutions(robot: Object, tool_link: str, queries: Sequence[Query], joints: Sequence[str] | None = None,
                   settings: Settings = DEFAULT) -> Iterator[tuple[int, IKSolution]]:
    """`solve_link` for several queries (target position, orientation, start configuration: None for where the joints
    are, else values of the joints that move), yielding `(k, answer)` as each is found: those already known first (in
    query order), then those of one batched search as they come. Answer `k` is exactly what `solve_link` gives for
    query `k` with the joints first set to its start, for not much more than the price of one (the pre-grasp poses
    of the ways to hold an object, tried in turn, cost one search when none is reachable). The caller stops the
    search when it has what it needs (break). Either every query has an orientation or none has. The world's lock
    is held while the answers are searched for, between them too: stop (break, or close the iterator) or exhaust it."""
    if not queries:
        return
    asked = _Asked(robot, tool_link, queries, joints, settings)
    with robot.world.lock:
        problem = Problem(robot, chain_for(robot, asked.link_index), asked.names)
        if not problem.names:
            pos, orn = robot.get_link_position_and_orientation(asked.link_index)
            for k, (target, rotation) in enumerate(zip(asked.targets, asked.rotations)):
                yield k, _verdict({}, pos, orn, target, rotation, settings)
            return
        batch = _Batch(asked, problem)
        searched: list[int] = []
        for k in range(len(queries)):
            answer = batch.known(k)
            if answer is None:
                searched.append(k)
            else:
                yield k, answer
        if searched:
            yield from batch.search(searched)


class _Asked:
    """The queries of one `link_solutions` call, checked: targets as arrays, orientations as rotation matrices, the
    link's index and the names of the joints that move."""

    def __init__(self, robot: Object, tool_link: str, queries: Sequence[Query], joints: Sequence[str] | None,
                 settings: Settings) -> None:
        if len({orientation is not None for _, orientation, _ in queries}) > 1:
            raise BadValue("IK queries: expected an orientation for every target or for none")
        self.robot, self.tool_link, self.queries, self.settings = robot, tool_link, queries, settings
        self.targets = [np.asarray(check_position(position, "IK target position")) for position, _, _ in queries]
        self.rotations = [None if orientation is None else
                          transform((0, 0, 0), check_quaternion(orientation, "IK target orientation"))[:3, :3]
                          for _, orientation, _ in queries]
        self.link_index = robot.get_link_id(tool_link)
        self.names = list(joints) if joints is not None else _arm_joints(robot, tool_link)
        for name in self.names:
            robot.get_joint_id(name)  # unknown names raise KeyError with a suggestion


class _Batch:
    """The queries of one `link_solutions` call against the robot's chain: where each starts, what it is kept under
    (the robot's state, the link, joints, settings and the query: the same question in the same state has the same
    answer), the answers known without a search, and the one batched search for the others."""

    def __init__(self, asked: _Asked, problem: Problem) -> None:
        self.asked, self.problem = asked, problem
        robot, settings = asked.robot, asked.settings
        self.memo = robot.world.cache.memo(ANSWERS, robot, MEMO_SIZE)
        self.fixed_seeds: dict[tuple, np.ndarray] = robot.world.cache.table(SEEDS, robot)
        state = (problem.state, asked.link_index, tuple(problem.names), *settings.asked())
        self.starts = [self._start(start) for _, _, start in asked.queries]
        self.keys = [(state, *problem.in_chain_frame(target, rotation), None if start is None else start.tobytes())
                     for target, rotation, start in zip(asked.targets, asked.rotations, self.starts)]

    def _start(self, start: Mapping[str, float] | None) -> np.ndarray | None:
        """A query's start configuration over the joints that move (None: where they are)."""
        if start is None:
            return None
        problem = self.problem
        unknown = sorted(set(start) - set(problem.names))
        if unknown:
            raise BadValue(f"IK start: expected values of the joints that move ({', '.join(problem.names)}), "
                           f"got {', '.join(unknown)}")
        return np.array([start.get(n, c) for n, c in zip(problem.names, problem.current)], dtype=float)

    def known(self, k: int) -> IKSolution | None:
        """Query k's answer without a search: kept from before, or (verdict only) out of reach by the distance bound."""
        answer = _recall(self.memo, self.keys[k])
        settings = self.asked.settings
        if answer is None and not settings.best_effort:
            beyond = self.problem.beyond_reach(self.asked.targets[k], self.asked.rotations[k], settings.threshold,
                                               settings.angle_threshold)
            if beyond > 0.0:
                answer = IKSolution(False, {}, beyond + settings.threshold + REACH_SLACK, None)
        return answer

    def search(self, searched: list[int]) -> Iterator[tuple[int, IKSolution]]:
        """The searched queries' answers, each judged by PyBullet's forward kinematics and kept, as they are found.
        A query that asks for more seeds than RESTARTS (`Settings.seed_count`) is searched from the first RESTARTS
        and, only when those find no answer, from the others: what the first find stays the answer (a pull's next
        step stays on the branch the arm is on), and what they miss is found."""
        counts = {k: self._seeds(k) for k in searched}
        firsts = {k: c if self.asked.settings.seeds is not None else min(c, RESTARTS) for k, c in counts.items()}
        second: dict[int, IKSolution] = {}
        for k, verdict in self._round(searched, firsts, 0):
            if verdict.success or firsts[k] == counts[k]:
                _remember(self.memo, self.keys[k], verdict)
                yield k, verdict
            else:
                second[k] = verdict
        if second:
            for k, verdict in self._round(list(second), {k: counts[k] for k in second}, RESTARTS):
                answer = verdict if verdict.success else second[k]
                _remember(self.memo, self.keys[k], answer)
                yield k, answer

    def _seeds(self, k: int) -> int:
        return self.asked.settings.seed_count(len(self.problem.names), self.asked.rotations[k] is not None)

    def _round(self, searched: list[int], counts: dict[int, int], skip: int) -> Iterator[tuple[int, IKSolution]]:
        """One batched search of the queries `searched`, each from its seeds `skip` to `counts[k]`, judged (not kept)."""
        asked, settings = self.asked, self.asked.settings
        rows: dict[tuple, int] = {}  # the same seed towards the same target in two queries is searched once
        union: list[np.ndarray] = []
        row_target: list[int] = []
        groups: list[np.ndarray] = []
        for k in searched:
            rotation = asked.rotations[k]
            aim = (asked.targets[k].tobytes(), None if rotation is None else rotation.tobytes())
            group = []
            for seed in initial_seeds(self.problem, counts[k], self.starts[k], self.fixed_seeds)[skip:]:
                key = (seed.tobytes(), aim)
                if key not in rows:
                    rows[key] = len(union)
                    union.append(seed)
                    row_target.append(k)
                group.append(rows[key])
            groups.append(np.array(group))
        if len(set(row_target)) == 1:  # one target for all: broadcast it
            target_pos, target_rot = asked.targets[row_target[0]], asked.rotations[row_target[0]]
        else:
            target_pos = np.array([asked.targets[k] for k in row_target])
            target_rot = None if asked.rotations[0] is None else np.array([asked.rotations[k] for k in row_target])
        for g, found in search_groups(self.problem, np.array(union), groups, target_pos, target_rot,
                                      settings.threshold, settings.angle_threshold, settings.max_iterations):
            yield searched[g], self._judged(searched[g], found)

    def _judged(self, k: int, found: Found) -> IKSolution:
        """PyBullet's verdict on a found configuration for query k."""
        asked = self.asked
        solution = {name: float(v) for name, v in zip(self.problem.names, found[0])}
        pos, orn = forward_pose(asked.robot, asked.tool_link, solution)
        return _verdict(solution, pos, orn, asked.targets[k], asked.rotations[k], asked.settings)


def _verdict(solution: dict[str, float], pos: Sequence[float], orn: Sequence[float], target: np.ndarray,
             target_rot: np.ndarray | None, settings: Settings) -> IKSolution:
    pos_err = float(np.linalg.norm(target - np.asarray(pos)))
    ang_err = None
    if target_rot is not None:
        ang_err = rotation_angle(target_rot, transform((0, 0, 0), orn)[:3, :3])
    ok = pos_err <= settings.threshold and (ang_err is None or ang_err <= settings.angle_threshold)
    return IKSolution(ok, solution, pos_err, ang_err)
