"""Inverse kinematics for a robot's tool frame: damped least squares on our own kinematic chain.

PyBullet's `calculateInverseKinematics` often stops short of the target and its SDLS solver
crashes, so the chain from the robot's base to the tool link is read from the robot's joints once
(joint frames, axes, inertial offsets — PyBullet expresses every joint frame relative to
the parent's centre of mass) and solved here with a Levenberg–Marquardt loop:

    (JᵀJ + (½‖e‖² + λ₀) I) Δq = Jᵀe

with joint limits enforced by clamping and a few deterministic restarts. The kinematics
never touch the world; only the final answer is checked against PyBullet's own forward
kinematics (joints set, link pose read, joints put back with their saved positions and
velocities), so the errors reported are PyBullet's. An answer is a function of the robot's state (its base's pose, the
chain's joint values) and the question: it is kept (per robot, the latest `MEMO_SIZE`), and the same question
asked in the same state is answered again without a search (`forget_answers` for a benchmark of first questions).

Only the requested joints move (by default the joints of the arm); the torso, head and base keep
their current values. `solve(robot, arm, ...)` is the front door: the robot (robots/robot.py) says
which joints the arm has and where its tool frame is; `solve_link(body, link, ...)` solves for any
link of a body (the design's `reachable(target, robot, gripper_link)`, a robot without a description).
"""
from __future__ import annotations

import math
import weakref
from collections import OrderedDict
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import BadValue
from ..robots import Robot, description_for
from ..world.pose import Quat, Vec3, check_position, check_quaternion
from .kinematics import Chain, chain_for, kinematics_of, transform

if TYPE_CHECKING:
    from ..world import Object

#: weight of one radian of orientation error against one metre of position error
ORIENTATION_WEIGHT = 0.25
#: stop iterating once the tool is this close (much tighter than any success threshold)
CONVERGED_POSITION = 2e-5
CONVERGED_ANGLE = 2e-4
MAX_ITERATIONS = 60
#: what the reach bound leaves to spare (m): PyBullet's forward kinematics, which judge an answer, and ours differ by
#: about 1e-7 m
REACH_SLACK = 1e-4
RESTARTS = 6
SEED = 20190923


@dataclass(frozen=True)
class IKSolution:
    """The outcome of an IK query; truthy when the tool frame reached the target within the thresholds."""

    success: bool
    joint_positions: dict[str, float] = field(default_factory=dict)
    position_error: float = math.inf
    orientation_error: float | None = None

    def __bool__(self) -> bool:
        return self.success


# -- the kinematic chain -------------------------------------------------------------------


class _Problem:
    """Forward kinematics and Jacobian of the tool frame over the variable joints only.

    Everything is batched over a set of configurations (one per restart), so all the
    restarts advance together for the price of about one. Arrays of every joint's frames
    are laid out joint-major ((n, S, ...)), so that each joint's slice is contiguous.
    """

    def __init__(self, robot: Object, chain: Chain, variable: Sequence[str]) -> None:
        kin = kinematics_of(chain, variable)
        base_pos, base_orn = robot.get_com_pose()  # the chain starts at the base's centre of mass
        current = robot.get_joint_positions(kin.read) if kin.read else {}
        layout = self.layout = kin.layout(current)
        lead, self._after, self._turned, self._turned2 = layout.lead, layout.after, layout.turned, layout.turned2
        #: everything of the robot's state the answers depend on: the base's pose and the chain's joint values
        self.state = (tuple(base_pos), tuple(base_orn), tuple(current[name] for name in kin.read))
        start = transform(base_pos, base_orn)
        for factor in lead:
            start = start @ factor
        self.start = start  # the first variable joint's frame in the world, before its motion
        self.names = kin.names
        self.revolute = [bool(r) for r in kin.rev]
        self.current = np.array([current[n] for n in self.names])
        self.lo, self.hi, self.rev = kin.lo, kin.hi, kin.rev
        self._axes = kin.axes
        self._axes_col = kin.axes[:, None, :, None]  # (n,1,3,1): each joint's axis, for every configuration
        self._prismatic = kin.prismatic
        self._all_revolute = kin.all_revolute
        self._buffers: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # per number of configurations

    def beyond_reach(self, target: np.ndarray, rotation: np.ndarray | None, threshold: float,
                     angle_threshold: float) -> float:
        """How far (m) the target lies beyond anything the joints can reach within the thresholds (≤ 0: it may be
        reachable). Without an orientation, the tool can come no nearer the first variable joint's origin than
        `reach`; with one, the tool's pose fixes where the last variable joint's origin must be (within the
        thresholds), which can be no farther from the first's than `wrist_reach`. A necessary condition only, with
        REACH_SLACK to spare for PyBullet's forward kinematics (which decide success) against ours."""
        origin = self.start[:3, 3]
        layout = self.layout
        if rotation is None:
            return float(np.linalg.norm(target - origin)) - layout.reach - threshold - REACH_SLACK
        wrist = target + rotation @ layout.wrist
        return float(np.linalg.norm(wrist - origin)) - layout.wrist_reach - threshold \
            - angle_threshold * layout.lever - REACH_SLACK

    def _buffers_for(self, count: int) -> tuple[np.ndarray, np.ndarray]:
        found = self._buffers.get(count)
        if found is None:
            n = len(self.names)
            steps = np.zeros((n, count, 4, 4))
            steps[:, :, 3, 3] = 1.0
            frames = np.empty((n + 1, count, 4, 4))
            frames[0] = self.start
            found = self._buffers[count] = (steps, frames)
        return found

    def forward(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Tool poses (S,4,4) for configurations q (S,n), with the world origin and axis of every joint (n,S,3)."""
        count, n = q.shape
        steps, frames = self._buffers_for(count)
        # each joint's motion times the constant transform after it, all at once: R·A = A + sin·K·A + (1 - cos)·K²·A
        qt = q.T[:, :, None, None]
        if self._all_revolute:
            sin, versin = np.sin(qt), 1.0 - np.cos(qt)
        else:
            rev = self.rev[:, None, None, None]
            sin, versin = np.where(rev, np.sin(qt), 0.0), np.where(rev, 1.0 - np.cos(qt), 0.0)
        top = steps[:, :, :3, :]
        np.multiply(sin, self._turned[:, None], out=top)
        top += versin * self._turned2[:, None]
        top += self._after[:, None, :3, :]
        for i in self._prismatic:  # a shift along the axis: the transform after it moves with it
            steps[i, :, :3, 3] += q[:, i:i + 1] * self._axes[i]
        for i in range(n):
            np.matmul(frames[i], steps[i], out=frames[i + 1])
        joints = frames[:n]
        axes = (joints[:, :, :3, :3] @ self._axes_col)[..., 0]
        return frames[n].copy(), joints[:, :, :3, 3], axes

    def jacobian_t(self, tool: np.ndarray, origins: np.ndarray, axes: np.ndarray, weight: float | None) -> np.ndarray:
        """The transposed Jacobian (S,n,3) or, with an orientation `weight`, (S,n,6): per joint, the tool's linear
        velocity (axis × lever for a revolute joint, the axis for a prismatic one), then its weighted angular one."""
        n, count, _ = origins.shape
        lever = tool[None, :, :3, 3] - origins
        out = np.empty((count, n, 3 if weight is None else 6))
        joint_major = out.transpose(1, 0, 2)
        linear = joint_major[:, :, :3]
        np.subtract(axes[:, :, _NEXT] * lever[:, :, _AFTER], axes[:, :, _AFTER] * lever[:, :, _NEXT], out=linear)
        if weight is not None:
            np.multiply(axes, weight, out=joint_major[:, :, 3:])
        for i in self._prismatic:
            linear[i] = axes[i]
            if weight is not None:
                joint_major[i, :, 3:] = 0.0
        return out


_NEXT = np.array([1, 2, 0])
_AFTER = np.array([2, 0, 1])
_V_PLUS = np.array([7, 2, 3])  # r21, r02, r10 of a flattened 3×3
_V_MINUS = np.array([5, 6, 1])  # r12, r20, r01
_DIAGONAL = np.array([0, 4, 8])


def _rotation_errors(target: np.ndarray, current: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotation vectors (S,3), world frame, that turn each `current` (S,3,3) into `target` (3,3) (or (S,3,3)), and
    their angles (S,): the vectors' lengths."""
    r = target @ current.transpose(0, 2, 1)
    flat = r.reshape(len(r), 9)
    cos = np.minimum(np.maximum((flat[:, _DIAGONAL].sum(axis=1) - 1.0) / 2.0, -1.0), 1.0)  # from the trace
    angle = np.arccos(cos)
    v = flat[:, _V_PLUS] - flat[:, _V_MINUS]  # (r21 - r12, r02 - r20, r10 - r01): 2 sin(angle) times the axis
    sin = np.sin(angle)
    if sin.min() > 1e-6:  # every angle well inside (0, pi)
        return v * (angle / (2.0 * sin))[:, None], angle
    small = angle < 1e-9
    regular = ~small & (sin > 1e-6)
    scale = np.where(small, 0.5, angle / (2.0 * np.where(regular, sin, 1.0)))
    out = v * scale[:, None]
    for k in np.flatnonzero(~small & ~regular):  # angle close to pi: the axis is the column of (r + I) with the largest norm
        m = r[k] + np.eye(3)
        col = m[:, int(np.argmax(np.linalg.norm(m, axis=0)))]
        out[k] = col / np.linalg.norm(col) * angle[k]
    return out, angle


def _angle(target: np.ndarray, current: np.ndarray) -> float:
    r = target @ current.T
    return math.acos(max(-1.0, min(1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0)))


#: the seeds after the first (the middle of the ranges, then the pseudo-random ones) by joint ranges and count: the
#: same for every search of the same joints, so made once (drawing them cost as much as an iteration of the search)
_FIXED_SEEDS: dict[tuple[bytes, bytes, int], np.ndarray] = {}


def _seeds(problem: _Problem, count: int, current: np.ndarray | None = None) -> np.ndarray:
    """Deterministic starting points: where the arm is (or `current`), the middle of its range, then fixed
    pseudo-random ones."""
    first = np.clip((problem.current if current is None else current)[None, :], problem.lo, problem.hi)
    if count <= 1:
        return first
    key = (problem.lo.tobytes(), problem.hi.tobytes(), count)
    rest = _FIXED_SEEDS.get(key)
    if rest is None:
        lo = np.where(np.isfinite(problem.lo), problem.lo, -math.pi)
        hi = np.where(np.isfinite(problem.hi), problem.hi, math.pi)
        seeds = [(lo + hi) / 2.0]
        rng = np.random.default_rng(SEED)
        while len(seeds) < count - 1:
            seeds.append(lo + rng.random(len(lo)) * (hi - lo))
        rest = _FIXED_SEEDS[key] = np.clip(np.array(seeds), problem.lo, problem.hi)
        rest.flags.writeable = False
    return np.concatenate([first, rest])


Found = tuple[np.ndarray, float, "float | None"]


def _search_groups(problem: _Problem, seeds: np.ndarray, groups: Sequence[np.ndarray], target_pos: np.ndarray,
                   target_rot: np.ndarray | None, threshold: float, angle_threshold: float, iterations: int,
                   enough: Callable[[int, Found], bool] | None = None) -> list[Found | None]:
    """Levenberg–Marquardt from every seed at once, for several groups of seeds (rows of `seeds`): a group stops when
    one of its seeds converged or all stalled, and its answer is the first of its seeds (in seed order) within the
    thresholds once converged, or the one with the smallest weighted error. Every seed's iterations are independent
    of the others' (only when to stop depends on the group), so each group's answer is exactly what a search of its
    seeds alone gives, for the price of about one search. The targets may be one for all (`target_pos` (3,),
    `target_rot` (3,3)) or one per seed ((S,3), (S,3,3)). `enough(g, found)`, called as each group finishes, may
    end the search early: the groups not finished yet are then None."""
    q = seeds.copy()
    count, n = q.shape
    best = np.full((count, 3), np.inf)  # per seed, the best so far: weighted cost, position error, angle error
    best_q = q.copy()
    history: list[np.ndarray] = []  # the best costs, per iteration
    active = np.ones(count, dtype=bool)
    answers: list[Found | None] = [None] * len(groups)
    todo = list(range(len(groups)))
    groups = [np.asarray(idx) for idx in groups]  # renumbered as the seeds of finished groups are dropped
    member = np.zeros((len(groups), count), dtype=bool)  # member[g, s]: seed s is one of group g's
    for g, idx in enumerate(groups):
        member[g, idx] = True
    pending = np.ones(len(groups), dtype=bool)
    per_seed_target = target_pos.ndim == 2
    oriented = target_rot is not None
    converged_below = np.array([CONVERGED_POSITION, CONVERGED_ANGLE])
    good_below = np.array([threshold * 0.5, angle_threshold * 0.5])

    def finish(g: int) -> bool:
        idx = groups[g]
        cost, pos, ang = best[idx, 0], best[idx, 1], best[idx, 2]
        converged = (pos < CONVERGED_POSITION) & (ang < CONVERGED_ANGLE)
        within = (pos <= threshold) & (ang <= (angle_threshold if oriented else np.inf))
        if converged.any():
            pick = int(np.argmax(converged))
        else:
            pick = int(np.argmin(np.where(within, cost, np.inf))) if within.any() else int(np.argmin(cost))
        found = (best_q[idx[pick]].copy(), float(pos[pick]), float(ang[pick]) if oriented else None)
        answers[g] = found
        todo.remove(g)
        pending[g] = False
        return enough is not None and enough(g, found)

    rows = 6 if oriented else 3
    diagonal = slice(None, None, n + 1)  # the diagonal of a flattened n×n matrix
    for _ in range(iterations + 1):
        tool, origins, axes = problem.forward(q)
        e = np.empty((count, rows))  # the weighted error: position, then ORIENTATION_WEIGHT × rotation vector
        dp = np.subtract(target_pos, tool[:, :3, 3], out=e[:, :3])
        now = np.zeros((count, 3))  # cost, position error, angle error
        np.sqrt(np.einsum("ij,ij->i", dp, dp), out=now[:, 1])
        if oriented:
            assert target_rot is not None
            dr, now[:, 2] = _rotation_errors(target_rot, tool[:, :3, :3])
            np.multiply(dr, ORIENTATION_WEIGHT, out=e[:, 3:])
        np.einsum("ij,ij->i", e, e, out=now[:, 0])
        better = now[:, 0] < best[:, 0]
        best = np.where(better[:, None], now, best)  # a new array every iteration: `history` keeps its costs
        np.copyto(best_q, q, where=better[:, None])
        converged = (best[:, 1:] < converged_below).all(axis=1)
        history.append(best[:, 0])
        stalled = len(history) > 8
        if stalled:
            active &= history[-1] < 0.98 * history[-9]
            # a seed already within the thresholds that stopped improving is good enough
            good = (best[:, 1:] <= good_below).all(axis=1) & ~active
        done = (member & converged).any(axis=1)  # per group: a seed converged, or (stalled) one is good or none active
        if stalled:
            done |= (member & good).any(axis=1) | ~(member & active).any(axis=1)
        finished = np.flatnonzero(done & pending)
        for row in finished:
            if finish(int(row)):
                return answers
        if not todo:
            return answers
        if len(finished):  # the seeds only finished groups had are searched no further (the others' steps are the same)
            keep = np.flatnonzero(member[pending].any(axis=0))
            if len(keep) < count:
                renumber = np.full(count, -1)
                renumber[keep] = np.arange(len(keep))
                groups = [renumber[idx] if pending[g] else idx for g, idx in enumerate(groups)]
                member = member[:, keep]
                q, best_q, best, active, now, e = q[keep], best_q[keep], best[keep], active[keep], now[keep], e[keep]
                tool, origins, axes = tool[keep], origins[:, keep], axes[:, keep]
                history = [h[keep] for h in history]
                if per_seed_target:
                    target_pos = target_pos[keep]
                    target_rot = target_rot[keep] if oriented and target_rot is not None else None
                count = len(keep)
        jt = problem.jacobian_t(tool, origins, axes, ORIENTATION_WEIGHT if oriented else None)  # (S,n,rows)
        lhs = jt @ jt.transpose(0, 2, 1)
        lhs.reshape(count, n * n)[:, diagonal] += (0.5 * now[:, 0] + 1e-4)[:, None]  # the damping
        step = np.linalg.solve(lhs, jt @ e[:, :, None])[:, :, 0]
        q = np.minimum(np.maximum(q + step, problem.lo), problem.hi)
    for g in list(todo):
        if finish(g):
            break
    return answers


#: how many answers `solve_link_each` keeps per robot (the latest used)
MEMO_SIZE = 512
#: answers already found, per robot: by the robot's state, the link, joints, settings and query (forgotten with the robot)
_MEMO: weakref.WeakKeyDictionary[Object, OrderedDict[tuple, IKSolution]] = weakref.WeakKeyDictionary()


def _recall(memo: OrderedDict[tuple, IKSolution], key: tuple) -> IKSolution | None:
    found = memo.get(key)
    if found is None:
        return None
    memo.move_to_end(key)
    return IKSolution(found.success, dict(found.joint_positions), found.position_error, found.orientation_error)


def _remember(memo: OrderedDict[tuple, IKSolution], key: tuple, answer: IKSolution) -> None:
    memo[key] = IKSolution(answer.success, dict(answer.joint_positions), answer.position_error, answer.orientation_error)
    if len(memo) > MEMO_SIZE:
        memo.popitem(last=False)


def forget_answers(robot: Object | None = None) -> None:
    """Forget the answers kept for `robot` (None: for every robot): what a benchmark of a first query needs."""
    if robot is None:
        _MEMO.clear()
    else:
        _MEMO.pop(robot, None)


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


def solve(
    robot: Robot,
    arm: str,
    position: Sequence[float],
    orientation: Sequence[float] | None = None,
    frame: str | None = None,
    joints: Sequence[str] | None = None,
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    seeds: int = RESTARTS,
    max_iterations: int = MAX_ITERATIONS,
    best_effort: bool = True,
) -> IKSolution:
    """Joint positions of `arm` (or `joints`) that bring its tool frame (or `frame`, a link the arm moves: a camera on
    its wrist) to `position` (and `orientation`, a world quaternion): `solve_link` for the arm."""
    return solve_link(robot.body, frame or robot.arm(arm).tool_frame, position, orientation,
                      list(robot.arm(arm).joints) if joints is None else joints, threshold, angle_threshold, seeds,
                      max_iterations, best_effort)


def solve_each(
    robot: Robot,
    arm: str,
    queries: Sequence[Query],
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    enough: Callable[[int, IKSolution], bool] | None = None,
    best_effort: bool = True,
) -> list[IKSolution | None]:
    """`solve` for several queries at once (`solve_link_each`), for the arm's tool frame and joints."""
    return solve_link_each(robot.body, robot.arm(arm).tool_frame, queries, list(robot.arm(arm).joints), threshold,
                           angle_threshold, enough=enough, best_effort=best_effort)


def solve_link(
    robot: Object,
    tool_link: str,
    position: Sequence[float],
    orientation: Sequence[float] | None = None,
    joints: Sequence[str] | None = None,
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    seeds: int = RESTARTS,
    max_iterations: int = MAX_ITERATIONS,
    best_effort: bool = True,
) -> IKSolution:
    """Joint positions that bring `tool_link` of `robot` to `position` (and `orientation`, a world quaternion).

    `joints` (default: the arm owning the link) are the only joints that move; limits are respected.
    The world is left untouched. Deterministic: the same world and inputs give the same answer, bitwise.
    A failed search returns the best configuration found and its remaining errors (`best_effort=False`: a target
    out of reach by a distance bound fails at once, see `solve_link_each`).
    """
    found = solve_link_each(robot, tool_link, [(position, orientation, None)], joints, threshold, angle_threshold,
                            seeds, max_iterations, best_effort=best_effort)[0]
    assert found is not None
    return found


#: one query of `solve_each`: the target's position and orientation (None: any), and where the joints start from
Query = tuple[Sequence[float], "Sequence[float] | None", "Mapping[str, float] | None"]


def solve_link_each(
    robot: Object,
    tool_link: str,
    queries: Sequence[Query],
    joints: Sequence[str] | None = None,
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    seeds: int = RESTARTS,
    max_iterations: int = MAX_ITERATIONS,
    enough: Callable[[int, IKSolution], bool] | None = None,
    best_effort: bool = True,
) -> list[IKSolution | None]:
    """`solve_link` for several queries (target position, orientation, start configuration: None for where the joints
    are, else values of the joints that move) in one batched search: answer `k` is exactly what `solve_link` gives for
    query `k` with the joints first set to its start, for not much more than the price of one (the pre-grasp poses
    of the ways to hold an object, tried in turn, cost one search when none is reachable). Either every query
    has an orientation or none has. `enough(k, answer)`, called as each answer is found, may end the search: the
    answers not found by then are None. `best_effort=False`, for a caller that needs only the verdict: a target
    that a distance bound puts out of reach (`_Problem.beyond_reach`) fails at once, without the search for the
    configuration nearest it (its `joint_positions` empty, its `position_error` how far beyond the bound it lies,
    no `orientation_error`); every other answer is the one a best-effort search gives."""
    if not queries:
        return []
    oriented = {orientation is not None for _, orientation, _ in queries}
    if len(oriented) > 1:
        raise BadValue("IK queries: expected an orientation for every target or for none")
    targets = [np.asarray(check_position(position, "IK target position")) for position, _, _ in queries]
    rotations = [None if orientation is None else
                 transform((0, 0, 0), check_quaternion(orientation, "IK target orientation"))[:3, :3]
                 for _, orientation, _ in queries]
    link_index = robot.get_link_id(tool_link)
    names = list(joints) if joints is not None else _arm_joints(robot, tool_link)
    for name in names:
        robot.get_joint_id(name)  # unknown names raise KeyError with a suggestion
    with robot.world.lock:
        problem = _Problem(robot, chain_for(robot, link_index), names)
        if not problem.names:
            pos, orn = robot.get_link_position_and_orientation(link_index)
            return [_verdict({}, pos, orn, t, r, threshold, angle_threshold) for t, r in zip(targets, rotations)]
        answers: list[IKSolution | None] = [None] * len(queries)
        # The answer to a query is a function of the robot's state (`problem.state`), the link, the joints, the
        # settings and the query: asked again, it is the one already found (the same question, the same answer)
        memo = _MEMO.setdefault(robot, OrderedDict())
        asked = (problem.state, link_index, tuple(problem.names), threshold, angle_threshold, seeds, max_iterations)
        keys: list[tuple] = []
        starts: list[np.ndarray | None] = []
        for k, (_, _, start) in enumerate(queries):
            current = None
            if start is not None:
                unknown = sorted(set(start) - set(problem.names))
                if unknown:
                    raise BadValue(f"IK start: expected values of the joints that move ({', '.join(problem.names)}), "
                                     f"got {', '.join(unknown)}")
                current = np.array([start.get(n, c) for n, c in zip(problem.names, problem.current)], dtype=float)
            starts.append(current)
            rotation = rotations[k]
            keys.append((asked, targets[k].tobytes(), None if rotation is None else rotation.tobytes(),
                         None if current is None else current.tobytes()))
        searched: list[int] = []
        for k, key in enumerate(keys):
            answers[k] = _recall(memo, key)
            if answers[k] is None and not best_effort:
                beyond = problem.beyond_reach(targets[k], rotations[k], threshold, angle_threshold)
                if beyond > 0.0:
                    answers[k] = IKSolution(False, {}, beyond + threshold + REACH_SLACK, None)
            answer = answers[k]
            if answer is None:
                searched.append(k)
            elif enough is not None and enough(k, answer):
                return answers
        if not searched:
            return answers
        rows: dict[tuple, int] = {}  # the same seed towards the same target in two queries is searched once
        union: list[np.ndarray] = []
        row_target: list[int] = []
        groups: list[np.ndarray] = []
        for k in searched:
            rotation = rotations[k]
            aim = (targets[k].tobytes(), None if rotation is None else rotation.tobytes())
            group = []
            for seed in _seeds(problem, max(1, seeds), starts[k]):
                key = (seed.tobytes(), aim)
                if key not in rows:
                    rows[key] = len(union)
                    union.append(seed)
                    row_target.append(k)
                group.append(rows[key])
            groups.append(np.array(group))

        def judged(g: int, found: Found) -> bool:
            k = searched[g]
            solution = {name: float(v) for name, v in zip(problem.names, found[0])}
            pos, orn = forward_pose(robot, tool_link, solution)
            verdict = _verdict(solution, pos, orn, targets[k], rotations[k], threshold, angle_threshold)
            answers[k] = verdict
            _remember(memo, keys[k], verdict)
            return enough is not None and enough(k, verdict)

        if len(set(row_target)) == 1:  # one target for all: broadcast it
            target_pos, target_rot = targets[row_target[0]], rotations[row_target[0]]
        else:
            target_pos = np.array([targets[k] for k in row_target])
            target_rot = None if rotations[0] is None else np.array([rotations[k] for k in row_target])
        _search_groups(problem, np.array(union), groups, target_pos, target_rot, threshold, angle_threshold,
                       max_iterations, judged)
    return answers


def _verdict(solution: dict[str, float], pos: Sequence[float], orn: Sequence[float], target: np.ndarray,
             target_rot: np.ndarray | None, threshold: float, angle_threshold: float) -> IKSolution:
    pos_err = float(np.linalg.norm(target - np.asarray(pos)))
    ang_err = None
    if target_rot is not None:
        ang_err = _angle(target_rot, transform((0, 0, 0), orn)[:3, :3])
    ok = pos_err <= threshold and (ang_err is None or ang_err <= angle_threshold)
    return IKSolution(ok, solution, pos_err, ang_err)
