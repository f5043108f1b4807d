"""Inverse kinematics for a robot's tool frame: damped least squares on our own kinematic chain.

PyBullet's `calculateInverseKinematics` often stops short of the target and its SDLS solver
crashes, so the chain from the robot's base to the tool link is read from the robot's joints once
(joint frames, axes, inertial offsets — PyBullet expresses every joint frame relative to
the parent's centre of mass) and solved here with a Levenberg–Marquardt loop:

    (JᵀJ + (½‖e‖² + λ₀) I) Δq = Jᵀe

with joint limits enforced by clamping and a few deterministic restarts. The kinematics
never touch the world; only the final answer is checked against PyBullet's own forward
kinematics (joints set, link pose read, joints put back with their saved positions and
velocities), so the errors reported are PyBullet's.

Only the requested joints move (by default the joints of the arm); the torso, head and base keep
their current values. `solve(robot, arm, ...)` is the front door: the robot (robots/robot.py) says
which joints the arm has and where its tool frame is; `solve_link(body, link, ...)` solves for any
link of a body (the design's `reachable(target, robot, gripper_link)`, a robot without a description).
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Callable, Mapping, Sequence

import numpy as np

from ..robots import Robot, description_for
from ..world.pose import Quat, Vec3, check_position, check_quaternion

if TYPE_CHECKING:
    from ..world import Object

#: weight of one radian of orientation error against one metre of position error
ORIENTATION_WEIGHT = 0.25
#: stop iterating once the tool is this close (much tighter than any success threshold)
CONVERGED_POSITION = 2e-5
CONVERGED_ANGLE = 2e-4
MAX_ITERATIONS = 60
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


def _transform(position: Sequence[float], orientation: Sequence[float]) -> np.ndarray:
    x, y, z, w = orientation
    t = np.eye(4)
    t[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    t[:3, 3] = position
    return t


def _inverse(t: np.ndarray) -> np.ndarray:
    inv = np.eye(4)
    inv[:3, :3] = t[:3, :3].T
    inv[:3, 3] = -t[:3, :3].T @ t[:3, 3]
    return inv


@dataclass
class _ChainJoint:
    index: int
    name: str
    kind: str  # the Joint's type: revolute, continuous, prismatic, fixed, ...
    parent_to_joint: np.ndarray  # parent centre of mass -> joint (child link) frame
    axis: np.ndarray  # unit axis in the joint frame
    link_to_com: np.ndarray  # child link frame -> child centre of mass
    lower: float
    upper: float

    @property
    def revolute(self) -> bool:
        return self.kind in ("revolute", "continuous")

    @property
    def movable(self) -> bool:
        return self.revolute or self.kind == "prismatic"


@dataclass
class Chain:
    """The joints from the base to a link, with everything constant read once from the robot's joints."""

    body: int
    joints: list[_ChainJoint]
    tool_com_to_link: np.ndarray  # tool centre of mass -> tool link frame

    @classmethod
    def build(cls, robot: "Object", link_index: int) -> "Chain":
        joints: list[_ChainJoint] = []
        index = link_index
        while index != -1:
            joint = robot.joints[index]
            axis = np.asarray(joint.axis, dtype=float)
            norm = float(np.linalg.norm(axis))
            joints.append(_ChainJoint(
                index=index, name=joint.name, kind=joint.type,
                parent_to_joint=_transform(*joint.parent_frame),
                axis=axis / norm if norm > 0 else axis,
                link_to_com=_transform(*joint.inertial_frame),
                lower=joint.lower if joint.limited else -math.inf,
                upper=joint.upper if joint.limited else math.inf,
            ))
            index = joint.parent_index
        joints.reverse()
        return cls(robot.id, joints, _inverse(joints[-1].link_to_com) if joints else np.eye(4))


#: chains already built, per robot and tool link (forgotten with the robot)
_CHAINS: "weakref.WeakKeyDictionary[Object, dict[int, Chain]]" = weakref.WeakKeyDictionary()


def chain_for(robot: "Object", link_index: int) -> Chain:
    cache = _CHAINS.setdefault(robot, {})
    chain = cache.get(link_index)
    if chain is None:
        chain = cache[link_index] = Chain.build(robot, link_index)
    return chain


def _axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    C = 1.0 - c
    t = np.eye(4)
    t[:3, :3] = [
        [c + x * x * C, x * y * C - z * s, x * z * C + y * s],
        [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
        [z * x * C - y * s, z * y * C + x * s, c + z * z * C],
    ]
    return t


def _motion(joint: _ChainJoint, q: float) -> np.ndarray:
    axis = joint.axis
    if joint.revolute:
        return _axis_rotation(axis, q)
    if joint.kind == "prismatic":
        t = np.eye(4)
        t[:3, 3] = axis * q
        return t
    return np.eye(4)


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


class _Problem:
    """Forward kinematics and Jacobian of the tool frame over the variable joints only.

    Everything is batched over a set of configurations (one per restart), so all the
    restarts advance together for the price of about one.
    """

    def __init__(self, robot: "Object", chain: Chain, variable: Sequence[str]) -> None:
        base_pos, base_orn = robot.get_com_pose()  # the chain starts at the base's centre of mass
        current = robot.get_joint_positions([j.name for j in chain.joints])
        wanted = set(variable)
        # Collapse everything between two variable joints into one constant transform.
        segments: list[np.ndarray] = []  # segments[i] precedes the motion of variable joint i
        axes: list[np.ndarray] = []
        self.revolute: list[bool] = []
        self.names: list[str] = []
        lower: list[float] = []
        upper: list[float] = []
        acc = _transform(base_pos, base_orn)
        for joint in chain.joints:
            acc = acc @ joint.parent_to_joint
            if joint.name in wanted and joint.movable:
                segments.append(acc)
                axes.append(joint.axis)
                self.revolute.append(joint.revolute)
                self.names.append(joint.name)
                lower.append(joint.lower)
                upper.append(joint.upper)
                acc = joint.link_to_com
            else:
                acc = acc @ _motion(joint, current[joint.name]) @ joint.link_to_com
        self.tail = acc @ chain.tool_com_to_link
        self.segments = segments
        self.axes = axes
        self.K = [_skew(a) for a in axes]
        self.K2 = [k @ k for k in self.K]
        self.current = np.array([current[n] for n in self.names])
        self.lo = np.array(lower)
        self.hi = np.array(upper)
        self.rev = np.array(self.revolute, dtype=bool)
        # the same, stacked over the variable joints, so that every joint's motion is computed at once
        n = len(self.names)
        self._axes = np.array(axes).reshape(n, 3)
        self._K = np.array(self.K).reshape(n, 3, 3)
        self._K2 = np.array(self.K2).reshape(n, 3, 3)
        self._prismatic = np.flatnonzero(~self.rev)
        self._all_revolute = bool(self.rev.all())
        self._buffers: dict[int, np.ndarray] = {}  # the joints' motions, per number of configurations

    def forward(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Tool poses (S,4,4) for configurations q (S,n), with the world origin and axis of every joint (S,n,3)."""
        count, n = q.shape
        # every joint's motion (S,n,4,4) at once: a rotation about its axis (Rodrigues), or a shift along it
        motions = self._buffers.get(count)
        if motions is None:
            motions = self._buffers[count] = np.zeros((count, n, 4, 4))
            motions[:, :, 3, 3] = 1.0
        if self._all_revolute:
            sin, versin = np.sin(q)[:, :, None, None], (1.0 - np.cos(q))[:, :, None, None]
        else:
            sin = np.where(self.rev, np.sin(q), 0.0)[:, :, None, None]
            versin = np.where(self.rev, 1.0 - np.cos(q), 0.0)[:, :, None, None]
        motions[:, :, :3, :3] = _EYE3 + sin * self._K + versin * self._K2
        for i in self._prismatic:
            motions[:, i, :3, 3] = q[:, i:i + 1] * self._axes[i]
        frames = np.empty((count, n, 4, 4))  # each joint's frame in the world, before its own motion
        t = np.broadcast_to(self.segments[0] if n else np.eye(4), (count, 4, 4))
        for i in range(n):
            if i:
                t = t @ self.segments[i]
            frames[:, i] = t
            t = t @ motions[:, i]
        origins = frames[:, :, :3, 3]
        axes = np.einsum("snij,nj->sni", frames[:, :, :3, :3], self._axes)
        return t @ self.tail, origins, axes

    def jacobian(self, tool: np.ndarray, origins: np.ndarray, axes: np.ndarray) -> np.ndarray:
        """(S,6,n): linear rows, then angular rows, in the world frame."""
        count, n, _ = origins.shape
        jac = np.zeros((count, 6, n))
        lever = tool[:, None, :3, 3] - origins
        a0, a1, a2 = axes[..., 0], axes[..., 1], axes[..., 2]
        l0, l1, l2 = lever[..., 0], lever[..., 1], lever[..., 2]
        rev = self.rev[None, :]
        jac[:, 0, :] = np.where(rev, a1 * l2 - a2 * l1, a0)  # axis x lever for revolute joints, the axis for prismatic
        jac[:, 1, :] = np.where(rev, a2 * l0 - a0 * l2, a1)
        jac[:, 2, :] = np.where(rev, a0 * l1 - a1 * l0, a2)
        jac[:, 3:, :] = (axes * self.rev[None, :, None]).transpose(0, 2, 1)
        return jac


_EYE3 = np.eye(3)
_ROWS = np.array([2, 0, 1])
_COLS = np.array([1, 2, 0])


def _rotation_errors(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """Rotation vectors (S,3), world frame, that turn each `current` (S,3,3) into `target` (3,3)."""
    r = target @ current.transpose(0, 2, 1)
    cos = np.minimum(np.maximum((r[:, 0, 0] + r[:, 1, 1] + r[:, 2, 2] - 1.0) / 2.0, -1.0), 1.0)  # the trace
    angle = np.arccos(cos)
    v = r[:, _ROWS, _COLS] - r[:, _COLS, _ROWS]  # (r21 - r12, r02 - r20, r10 - r01)
    sin = np.sin(angle)
    small = angle < 1e-9
    regular = ~small & (sin > 1e-6)
    scale = np.where(small, 0.5, angle / (2.0 * np.where(regular, sin, 1.0)))
    out = v * scale[:, None]
    for k in np.flatnonzero(~small & ~regular):  # angle close to pi: the axis is the column of (r + I) with the largest norm
        m = r[k] + np.eye(3)
        col = m[:, int(np.argmax(np.linalg.norm(m, axis=0)))]
        out[k] = col / np.linalg.norm(col) * angle[k]
    return out


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
                   enough: "Callable[[int, Found], bool] | None" = None) -> list[Found | None]:
    """Levenberg–Marquardt from every seed at once, for several groups of seeds (rows of `seeds`): a group stops when
    one of its seeds converged or all stalled, and its answer is the first of its seeds (in seed order) within the
    thresholds once converged, or the one with the smallest weighted error. Every seed's iterations are independent
    of the others' (only when to stop depends on the group), so each group's answer is exactly what a search of its
    seeds alone gives, for the price of about one search. The targets may be one for all (`target_pos` (3,),
    `target_rot` (3,3)) or one per seed ((S,3), (S,3,3)). `enough(g, found)`, called as each group finishes, may
    end the search early: the groups not finished yet are then None."""
    q = seeds.copy()
    count, n = q.shape
    rows = 6 if target_rot is not None else 3
    eye = np.eye(n)
    best_cost = np.full(count, np.inf)
    best_q = q.copy()
    best_pos = np.full(count, np.inf)
    best_ang = np.full(count, np.inf)
    history: list[np.ndarray] = []
    active = np.ones(count, dtype=bool)
    answers: list[Found | None] = [None] * len(groups)
    todo = list(range(len(groups)))
    groups = [np.asarray(idx) for idx in groups]  # renumbered as the seeds of finished groups are dropped
    member = np.zeros((len(groups), count), dtype=bool)  # member[g, s]: seed s is one of group g's
    for g, idx in enumerate(groups):
        member[g, idx] = True
    pending = np.ones(len(groups), dtype=bool)
    per_seed_target = target_pos.ndim == 2

    def finish(g: int) -> bool:
        idx = groups[g]
        pos, ang, cost = best_pos[idx], best_ang[idx], best_cost[idx]
        converged = (pos < CONVERGED_POSITION) & (ang < CONVERGED_ANGLE)
        within = (pos <= threshold) & (ang <= (angle_threshold if target_rot is not None else np.inf))
        if converged.any():
            pick = int(np.argmax(converged))
        else:
            pick = int(np.argmin(np.where(within, cost, np.inf))) if within.any() else int(np.argmin(cost))
        answers[g] = (best_q[idx[pick]].copy(), float(pos[pick]), float(ang[pick]) if target_rot is not None else None)
        todo.remove(g)
        pending[g] = False
        return enough is not None and enough(g, answers[g])

    for _ in range(iterations + 1):
        tool, origins, axes = problem.forward(q)
        dp = target_pos - tool[:, :3, 3]
        pos_err = np.sqrt(np.einsum("ij,ij->i", dp, dp))
        if target_rot is not None:
            dr = _rotation_errors(target_rot, tool[:, :3, :3])
            ang_err = np.sqrt(np.einsum("ij,ij->i", dr, dr))
            e = np.concatenate([dp, ORIENTATION_WEIGHT * dr], axis=1)
        else:
            ang_err = np.zeros(count)
            e = dp
        cost = np.einsum("ij,ij->i", e, e)
        better = cost < best_cost
        best_cost = np.where(better, cost, best_cost)
        best_q[better] = q[better]
        best_pos = np.where(better, pos_err, best_pos)
        best_ang = np.where(better, ang_err, best_ang)
        converged = (best_pos < CONVERGED_POSITION) & (best_ang < CONVERGED_ANGLE)
        history.append(best_cost)  # a new array every iteration (np.where): never changed in place
        stalled = len(history) > 8
        if stalled:
            active &= best_cost < 0.98 * history[-9]
            # a seed already within the thresholds that stopped improving is good enough
            good = (best_pos <= threshold * 0.5) & (best_ang <= angle_threshold * 0.5) & ~active
        done = (member & converged).any(axis=1)  # per group: a seed converged, or (stalled) one is good or none active
        if stalled:
            done |= (member & good).any(axis=1) | ~(member & active).any(axis=1)
        finished = np.flatnonzero(done & pending)
        for g in finished:
            if finish(int(g)):
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
                q, best_q, best_cost = q[keep], best_q[keep], best_cost[keep]
                best_pos, best_ang = best_pos[keep], best_ang[keep]
                active, cost, e = active[keep], cost[keep], e[keep]
                tool, origins, axes = tool[keep], origins[keep], axes[keep]
                history = [h[keep] for h in history]
                if per_seed_target:
                    target_pos = target_pos[keep]
                    target_rot = target_rot[keep] if target_rot is not None else None
                count = len(keep)
        jac = problem.jacobian(tool, origins, axes)[:, :rows]
        if target_rot is not None:
            jac[:, 3:] *= ORIENTATION_WEIGHT
        jt = jac.transpose(0, 2, 1)
        damping = 0.5 * cost + 1e-4
        lhs = jt @ jac + damping[:, None, None] * eye
        step = np.linalg.solve(lhs, (jt @ e[:, :, None]))[:, :, 0]
        q = np.minimum(np.maximum(q + step, problem.lo), problem.hi)
    for g in list(todo):
        if finish(g):
            break
    return answers


def _arm_joints(robot: "Object", tool_link: str) -> list[str]:
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


def forward_pose(robot: "Object", tool_link: str, joint_positions: dict[str, float]) -> tuple[Vec3, Quat]:
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
) -> IKSolution:
    """Joint positions of `arm` (or `joints`) that bring its tool frame (or `frame`, a link the arm moves: a camera on
    its wrist) to `position` (and `orientation`, a world quaternion): `solve_link` for the arm."""
    return solve_link(robot.body, frame or robot.arm(arm).tool_frame, position, orientation,
                      list(robot.arm(arm).joints) if joints is None else joints, threshold, angle_threshold, seeds,
                      max_iterations)


def solve_each(
    robot: Robot,
    arm: str,
    queries: "Sequence[Query]",
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    enough: "Callable[[int, IKSolution], bool] | None" = None,
) -> list[IKSolution | None]:
    """`solve` for several queries at once (`solve_link_each`), for the arm's tool frame and joints."""
    return solve_link_each(robot.body, robot.arm(arm).tool_frame, queries, list(robot.arm(arm).joints), threshold,
                           angle_threshold, enough=enough)


def solve_link(
    robot: "Object",
    tool_link: str,
    position: Sequence[float],
    orientation: Sequence[float] | None = None,
    joints: Sequence[str] | None = None,
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    seeds: int = RESTARTS,
    max_iterations: int = MAX_ITERATIONS,
) -> IKSolution:
    """Joint positions that bring `tool_link` of `robot` to `position` (and `orientation`, a world quaternion).

    `joints` (default: the arm owning the link) are the only joints that move; limits are respected.
    The world is left untouched. Deterministic: the same world and inputs give the same answer, bitwise.
    A failed search returns the best configuration found and its remaining errors.
    """
    found = solve_link_each(robot, tool_link, [(position, orientation, None)], joints, threshold, angle_threshold,
                            seeds, max_iterations)[0]
    assert found is not None
    return found


#: one query of `solve_each`: the target's position and orientation (None: any), and where the joints start from
Query = tuple[Sequence[float], "Sequence[float] | None", "Mapping[str, float] | None"]


def solve_link_each(
    robot: "Object",
    tool_link: str,
    queries: Sequence[Query],
    joints: Sequence[str] | None = None,
    threshold: float = 0.01,
    angle_threshold: float = 0.1,
    seeds: int = RESTARTS,
    max_iterations: int = MAX_ITERATIONS,
    enough: Callable[[int, IKSolution], bool] | None = None,
) -> list[IKSolution | None]:
    """`solve_link` for several queries (target position, orientation, start configuration: None for where the joints
    are, else values of the joints that move) in one batched search: answer `k` is exactly what `solve_link` gives for
    query `k` with the joints first set to its start, for not much more than the price of one (the pre-grasp poses
    of the ways to hold an object, tried in turn, cost one search when none is reachable). Either every query
    has an orientation or none has. `enough(k, answer)`, called as each answer is found, may end the search: the
    answers not found by then are None."""
    if not queries:
        return []
    oriented = {orientation is not None for _, orientation, _ in queries}
    if len(oriented) > 1:
        raise ValueError("IK queries: expected an orientation for every target or for none")
    targets = [np.asarray(check_position(position, "IK target position")) for position, _, _ in queries]
    rotations = [None if orientation is None else
                 _transform((0, 0, 0), check_quaternion(orientation, "IK target orientation"))[:3, :3]
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
        rows: dict[tuple, int] = {}  # the same seed towards the same target in two queries is searched once
        union: list[np.ndarray] = []
        row_target: list[int] = []
        groups: list[np.ndarray] = []
        for k, (position, orientation, start) in enumerate(queries):
            current = None
            if start is not None:
                unknown = sorted(set(start) - set(problem.names))
                if unknown:
                    raise ValueError(f"IK start: expected values of the joints that move ({', '.join(problem.names)}), "
                                     f"got {', '.join(unknown)}")
                current = np.array([start.get(n, c) for n, c in zip(problem.names, problem.current)], dtype=float)
            aim = (targets[k].tobytes(), None if rotations[k] is None else rotations[k].tobytes())
            group = []
            for seed in _seeds(problem, max(1, seeds), current):
                key = (seed.tobytes(), aim)
                if key not in rows:
                    rows[key] = len(union)
                    union.append(seed)
                    row_target.append(k)
                group.append(rows[key])
            groups.append(np.array(group))
        answers: list[IKSolution | None] = [None] * len(queries)

        def judged(k: int, found: Found) -> bool:
            solution = {name: float(v) for name, v in zip(problem.names, found[0])}
            pos, orn = forward_pose(robot, tool_link, solution)
            answers[k] = _verdict(solution, pos, orn, targets[k], rotations[k], threshold, angle_threshold)
            return enough is not None and enough(k, answers[k])

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
        ang_err = _angle(target_rot, _transform((0, 0, 0), orn)[:3, :3])
    ok = pos_err <= threshold and (ang_err is None or ang_err <= angle_threshold)
    return IKSolution(ok, solution, pos_err, ang_err)
