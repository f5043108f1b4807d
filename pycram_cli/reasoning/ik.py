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

Only the requested joints move (by default the seven joints of the arm that owns the tool
link); the torso, head and base keep their current values.
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..robots import description_for
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

    def forward(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Tool poses (S,4,4) for configurations q (S,n), with the world origin and axis of every joint (S,n,3)."""
        count, n = q.shape
        origins = np.empty((count, n, 3))
        axes = np.empty((count, n, 3))
        eye3 = np.eye(3)
        t = np.broadcast_to(self.segments[0] if n else np.eye(4), (count, 4, 4))
        for i in range(n):
            if i:
                t = t @ self.segments[i]
            origins[:, i] = t[:, :3, 3]
            axes[:, i] = t[:, :3, :3] @ self.axes[i]
            motion = np.zeros((count, 4, 4))
            motion[:, 3, 3] = 1.0
            if self.revolute[i]:
                sin, cos = np.sin(q[:, i]), np.cos(q[:, i])
                motion[:, :3, :3] = eye3 + sin[:, None, None] * self.K[i] + (1.0 - cos)[:, None, None] * self.K2[i]
            else:
                motion[:, :3, :3] = eye3
                motion[:, :3, 3] = q[:, i:i + 1] * self.axes[i]
            t = t @ motion
        return t @ self.tail, origins, axes

    def jacobian(self, tool: np.ndarray, origins: np.ndarray, axes: np.ndarray) -> np.ndarray:
        """(S,6,n): linear rows, then angular rows, in the world frame."""
        count, n, _ = origins.shape
        jac = np.zeros((count, 6, n))
        lever = tool[:, None, :3, 3] - origins
        linear = np.where(self.rev[None, :, None], np.cross(axes, lever), axes)
        jac[:, :3, :] = linear.transpose(0, 2, 1)
        jac[:, 3:, :] = (axes * self.rev[None, :, None]).transpose(0, 2, 1)
        return jac


def _rotation_errors(target: np.ndarray, current: np.ndarray) -> np.ndarray:
    """Rotation vectors (S,3), world frame, that turn each `current` (S,3,3) into `target` (3,3)."""
    r = target @ current.transpose(0, 2, 1)
    cos = np.clip((np.trace(r, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(cos)
    v = np.stack([r[:, 2, 1] - r[:, 1, 2], r[:, 0, 2] - r[:, 2, 0], r[:, 1, 0] - r[:, 0, 1]], axis=1)
    sin = np.sin(angle)
    out = np.empty_like(v)
    for k in range(len(v)):
        if angle[k] < 1e-9:
            out[k] = v[k] / 2.0
        elif sin[k] > 1e-6:
            out[k] = v[k] * (angle[k] / (2.0 * sin[k]))
        else:  # angle close to pi: the axis is the column of (r + I) with the largest norm
            m = r[k] + np.eye(3)
            col = m[:, int(np.argmax(np.linalg.norm(m, axis=0)))]
            out[k] = col / np.linalg.norm(col) * angle[k]
    return out


def _angle(target: np.ndarray, current: np.ndarray) -> float:
    r = target @ current.T
    return math.acos(max(-1.0, min(1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0)))


def _seeds(problem: _Problem, count: int) -> np.ndarray:
    """Deterministic starting points: where the arm is, the middle of its range, then fixed pseudo-random ones."""
    lo = np.where(np.isfinite(problem.lo), problem.lo, -math.pi)
    hi = np.where(np.isfinite(problem.hi), problem.hi, math.pi)
    seeds = [problem.current.copy(), (lo + hi) / 2.0]
    rng = np.random.default_rng(SEED)
    while len(seeds) < count:
        seeds.append(lo + rng.random(len(lo)) * (hi - lo))
    return np.clip(np.array(seeds[:count]), problem.lo, problem.hi)


def _search(problem: _Problem, seeds: np.ndarray, target_pos: np.ndarray, target_rot: np.ndarray | None,
            threshold: float, angle_threshold: float, iterations: int) -> tuple[np.ndarray, float, float | None]:
    """Levenberg–Marquardt from every seed at once; stops when one converged or all stalled.

    Returns the best configuration: the first seed (in seed order) that is within the
    thresholds once converged, or the one with the smallest weighted error.
    """
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
    for _ in range(iterations + 1):
        tool, origins, axes = problem.forward(q)
        dp = target_pos[None, :] - tool[:, :3, 3]
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
        if converged.any():
            break
        history.append(best_cost.copy())
        if len(history) > 8:
            active &= best_cost < 0.98 * history[-9]
            # a seed already within the thresholds that stopped improving is good enough
            good = (best_pos <= threshold * 0.5) & (best_ang <= angle_threshold * 0.5) & ~active
            if good.any() or not active.any():
                break
        jac = problem.jacobian(tool, origins, axes)[:, :rows]
        if target_rot is not None:
            jac[:, 3:] *= ORIENTATION_WEIGHT
        jt = jac.transpose(0, 2, 1)
        damping = 0.5 * cost + 1e-4
        lhs = jt @ jac + damping[:, None, None] * eye
        step = np.linalg.solve(lhs, (jt @ e[:, :, None]))[:, :, 0]
        q = np.clip(q + step, problem.lo, problem.hi)
    converged = (best_pos < CONVERGED_POSITION) & (best_ang < CONVERGED_ANGLE)
    within = (best_pos <= threshold) & (best_ang <= (angle_threshold if target_rot is not None else np.inf))
    if converged.any():
        pick = int(np.argmax(converged))
    else:
        pick = int(np.argmin(np.where(within, best_cost, np.inf))) if within.any() else int(np.argmin(best_cost))
    return best_q[pick], float(best_pos[pick]), (float(best_ang[pick]) if target_rot is not None else None)


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
    target = np.asarray(check_position(position, "IK target position"))
    target_rot = None
    if orientation is not None:
        target_rot = _transform((0, 0, 0), check_quaternion(orientation, "IK target orientation"))[:3, :3]
    link_index = robot.get_link_id(tool_link)
    names = list(joints) if joints is not None else _arm_joints(robot, tool_link)
    for name in names:
        robot.get_joint_id(name)  # unknown names raise KeyError with a suggestion
    with robot.world.lock:
        problem = _Problem(robot, chain_for(robot, link_index), names)
        if not problem.names:
            pos, orn = robot.get_link_position_and_orientation(link_index)
            return _verdict({}, pos, orn, target, target_rot, threshold, angle_threshold)
        q, _, _ = _search(problem, _seeds(problem, max(1, seeds)), target, target_rot, threshold,
                          angle_threshold, max_iterations)
        solution = {name: float(v) for name, v in zip(problem.names, q)}
        pos, orn = forward_pose(robot, tool_link, solution)
    return _verdict(solution, pos, orn, target, target_rot, threshold, angle_threshold)


def _verdict(solution: dict[str, float], pos: Sequence[float], orn: Sequence[float], target: np.ndarray,
             target_rot: np.ndarray | None, threshold: float, angle_threshold: float) -> IKSolution:
    pos_err = float(np.linalg.norm(target - np.asarray(pos)))
    ang_err = None
    if target_rot is not None:
        ang_err = _angle(target_rot, _transform((0, 0, 0), orn)[:3, :3])
    ok = pos_err <= threshold and (ang_err is None or ang_err <= angle_threshold)
    return IKSolution(ok, solution, pos_err, ang_err)
