"""The kinematic chain of a robot's link, read from its joints once, and its forward kinematics over some of the joints
in numpy (batched over configurations), for inverse kinematics (`ik.py`).

PyBullet expresses every joint frame relative to the parent's centre of mass: the chain keeps each joint's frame,
axis and inertial offset as PyBullet gives them, so that our forward kinematics agree with PyBullet's to about
1e-7 m. The transforms between the variable joints that do not change are cached per chain and per value of the
other joints (a torso), so that an iteration of the search multiplies only what moves.
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..world import Object


def transform(position: Sequence[float], orientation: Sequence[float]) -> np.ndarray:
    """The 4×4 homogeneous transform of a pose (position, quaternion x, y, z, w)."""
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
    #: what searches over its joints need, per tuple of variable joints (`kinematics_of`)
    kinematics: dict[tuple[str, ...], _Kinematics] = field(default_factory=dict, repr=False, compare=False)

    @classmethod
    def build(cls, robot: Object, link_index: int) -> Chain:
        joints: list[_ChainJoint] = []
        index = link_index
        while index != -1:
            joint = robot.joints[index]
            axis = np.asarray(joint.axis, dtype=float)
            norm = float(np.linalg.norm(axis))
            joints.append(_ChainJoint(
                index=index, name=joint.name, kind=joint.type,
                parent_to_joint=transform(*joint.parent_frame),
                axis=axis / norm if norm > 0 else axis,
                link_to_com=transform(*joint.inertial_frame),
                lower=joint.lower if joint.limited else -math.inf,
                upper=joint.upper if joint.limited else math.inf,
            ))
            index = joint.parent_index
        joints.reverse()
        return cls(robot.id, joints, _inverse(joints[-1].link_to_com) if joints else np.eye(4))


def chain_for(robot: Object, link_index: int) -> Chain:
    """The chain from the robot's base to a link: built once per robot and link, kept in the world's cache."""
    cache: dict[int, Chain] = robot.world.cache.table("kinematic chains", robot)
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


class _Kinematics:
    """What a search needs of a chain and its variable joints that does not depend on where the robot stands: made
    once per chain and joints (`kinematics_of`), the constant transforms between the variable joints once per value of
    the chain's other joints (a torso raised or lowered), so that a search only reads the base's pose."""

    def __init__(self, chain: Chain, variable: Sequence[str]) -> None:
        wanted = set(variable)
        self.chain = chain
        self.variable = [j for j in chain.joints if j.name in wanted and j.movable]
        self.names = [j.name for j in self.variable]
        self.read = [j.name for j in chain.joints if j.movable]  # the joints whose values the chain's pose needs
        self.fixed = [name for name in self.read if name not in wanted]  # those that keep their values
        n = len(self.variable)
        self.rev = np.array([j.revolute for j in self.variable], dtype=bool)
        self.lo = np.array([j.lower for j in self.variable])
        self.hi = np.array([j.upper for j in self.variable])
        self.axes = np.array([j.axis for j in self.variable]).reshape(n, 3)
        self.K = np.array([_skew(a) for a in self.axes]).reshape(n, 3, 3)
        self.K2 = self.K @ self.K
        self.prismatic = [int(i) for i in np.flatnonzero(~self.rev)]
        self.all_revolute = not self.prismatic
        self._layouts: dict[tuple[float, ...], _Layout] = {}

    def layout(self, current: Mapping[str, float]) -> _Layout:
        """The chain's constant parts for the other joints' values in `current` (`_Layout`)."""
        key = tuple(current[name] for name in self.fixed)
        found = self._layouts.get(key)
        if found is not None:
            return found
        wanted = set(self.names)
        lead: list[np.ndarray] = []
        segments: list[np.ndarray] = []
        acc: np.ndarray | None = None
        for joint in self.chain.joints:
            if acc is None:  # before the first variable joint: the factors themselves, multiplied onto the base's pose
                lead.append(joint.parent_to_joint)
                if joint.name in wanted and joint.movable:
                    acc = joint.link_to_com
                else:
                    lead.extend((_motion(joint, current.get(joint.name, 0.0)), joint.link_to_com))
                continue
            acc = acc @ joint.parent_to_joint
            if joint.name in wanted and joint.movable:
                segments.append(acc)
                acc = joint.link_to_com
            else:
                acc = acc @ _motion(joint, current.get(joint.name, 0.0)) @ joint.link_to_com
        if acc is not None:
            segments.append(acc @ self.chain.tool_com_to_link)
        after = np.array(segments).reshape(len(segments), 4, 4)  # none when no joint varies
        top = after[:, :3, :]
        # how far each variable joint's origin is from the next one's (the last: from the tool), a prismatic joint's
        # travel added: the chain's reach from its first variable joint, and the last joint's from the first's
        lengths = np.linalg.norm(after[:, :3, 3], axis=1) if len(after) else np.zeros(0)
        travel = np.where(self.rev, 0.0, np.maximum(np.abs(self.lo), np.abs(self.hi)))
        links = lengths + travel
        last = after[-1] if len(after) else np.eye(4)
        found = _Layout(lead, after, self.K @ top, self.K2 @ top, float(links.sum()),
                        float(links[:-1].sum() + travel[-1:].sum()), -(last[:3, :3].T @ last[:3, 3]),
                        float(lengths[-1]) if len(lengths) else 0.0)
        if len(self._layouts) >= 64:  # a torso at many heights: keep the latest few
            self._layouts.pop(next(iter(self._layouts)))
        self._layouts[key] = found
        return found


@dataclass
class _Layout:
    """A chain's constant parts, for given values of the joints that keep theirs.

    `lead`: the factors from the base's centre of mass to the first variable joint's frame (multiplied onto the base's
    pose in this order); `after` (n,4,4): per variable joint, the constant transform from its moved frame to the next
    variable joint's frame (the last: to the tool link), with its top rows turned by the joint's axis once and twice
    (`turned`, `turned2`: K·A, K²·A), so that each joint's motion and the transform after it are one sum (Rodrigues'
    formula applied to A). For the reach bound (`_Problem.beyond_reach`): `reach`, the longest the chain reaches from
    its first variable joint's origin (the distances between the variable joints' origins, each fixed by the rigid
    link between them, a prismatic joint's travel added); `wrist_reach`, the same to the last variable joint's origin;
    `wrist`, that origin seen from the tool frame (−Rᵀt of the last transform); `lever`, its distance from the tool."""

    lead: list[np.ndarray]
    after: np.ndarray
    turned: np.ndarray
    turned2: np.ndarray
    reach: float
    wrist_reach: float
    wrist: np.ndarray
    lever: float


def kinematics_of(chain: Chain, variable: Sequence[str]) -> _Kinematics:
    """The chain's forward kinematics over the `variable` joints (made once per chain and joints)."""
    key = tuple(variable)
    found = chain.kinematics.get(key)
    if found is None:
        found = chain.kinematics[key] = _Kinematics(chain, variable)
    return found
