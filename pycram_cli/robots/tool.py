"""The tool frame as the model has it: which of its axes a hand approaches along and which its fingers close along,
and the four named grasps (front, top, left, right) of a robot whose description names none.

The approach is the axis of the arm's last joint (the wrist's roll on every arm we know of), pointing away from the
arm towards the tool's own links; the fingers close along the tool axis across it that the gripper's links are most
spread along (y when the gripper has fewer than two finger links). A description without `grasps:` gets the grasps
the bundled robots write by hand, computed for its own tool frame: front approaches along the base's +x with the
fingers closing along +y, top approaches downwards, left along -y and right along +y.

A hand whose fingers curl towards its palm (a multi-finger hand) approaches palm-first instead: the approach is the
palm's normal, the side the fingers curl towards, and the object is held against the palm (`hand`). What the
description leaves out of the gripper (`approach`, `coupling`, `grasp_point`) is read from the model here.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..world import Object
from ..world.pose import Quat, matrix_to_quat, quat_to_matrix, vec3

if TYPE_CHECKING:
    from .description import ArmDescription, GripperDescription

#: the named grasps: (approach, closing) directions in the robot base's frame
NAMED_GRASPS: dict[str, tuple[tuple[float, float, float], tuple[float, float, float]]] = {
    "front": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "top": ((0.0, 0.0, -1.0), (0.0, 1.0, 0.0)),
    "left": ((0.0, -1.0, 0.0), (1.0, 0.0, 0.0)),
    "right": ((0.0, 1.0, 0.0), (-1.0, 0.0, 0.0)),
}


def _nearest_axis(v: np.ndarray, avoid: np.ndarray | None = None) -> np.ndarray:
    """The unit axis (±x, ±y, ±z) nearest `v` (and across `avoid`, if given)."""
    axes = [s * e for e in np.eye(3) for s in (1.0, -1.0)]
    if avoid is not None:
        axes = [a for a in axes if abs(float(a @ avoid)) < 0.5]
    return max(axes, key=lambda a: float(a @ v))


def _wrist_axes(body: Object, arm: ArmDescription) -> tuple[np.ndarray, np.ndarray]:
    """The wrist's roll axis pointing away from the arm (nearest tool axis), and the world-to-tool rotation."""
    _, tool_orientation = body.get_link_position_and_orientation(arm.tool_frame)
    to_tool = quat_to_matrix(tool_orientation).T
    last = body.joint(arm.joints[-1])
    joint_position = body.get_link_position(last.index)
    axis = body.joint_axis(last.name)
    below = sorted(body.links_below([last.name]))
    boxes = [body.get_aabb(index) for index in below] or [body.get_aabb(arm.tool_frame)]
    centre = (np.min([b[0] for b in boxes], axis=0) + np.max([b[1] for b in boxes], axis=0)) / 2.0
    outward = centre - np.asarray(joint_position)
    if float(outward @ axis) < 0:
        axis = -axis
    return _nearest_axis(to_tool @ axis), to_tool


def _closing_axis(body: Object, arm: ArmDescription, to_tool: np.ndarray, approach: np.ndarray) -> np.ndarray:
    """The tool axis across `approach` that the gripper joints' links are most spread along (y with fewer than two)."""
    fingers = [body.get_aabb(body.joint(name).index) for name in arm.gripper.joints]
    spread = np.zeros(3)
    if len(fingers) >= 2:
        centres = [to_tool @ ((np.asarray(lo) + np.asarray(hi)) / 2.0) for lo, hi in fingers]
        spread = np.max(centres, axis=0) - np.min(centres, axis=0)
    return _nearest_axis(spread + np.array([0.0, 1e-6, 0.0]), avoid=approach)


def tool_axes(body: Object, arm: ArmDescription) -> np.ndarray:
    """The arm's tool frame as a grasp sees it: columns (approach, closing, the third), in the tool frame. Fingers-first
    the approach is the wrist's roll axis; palm-first it is the palm's normal (`hand`)."""
    wrist, to_tool = _wrist_axes(body, arm)
    approach = wrist
    if arm.gripper.joints and hand(body, arm).approach == "palm":
        approach = np.asarray(hand(body, arm).palm_normal)
    closing = _closing_axis(body, arm, to_tool, approach)
    return np.column_stack([approach, closing, np.cross(approach, closing)])


# -- the hand as the model has it -------------------------------------------------------------------------------

#: a hand is palm-first when its fingers' links, closed, lie on average across the wrist axis from the palm's middle
#: by more than this share of their distance from it (fingers that close against each other lie ahead of the palm)
CURLING = 0.5


@dataclass(frozen=True)
class Hand:
    """How a gripper approaches and closes, resolved against the model: what the description says, else inferred."""

    approach: str  # "fingers" (along the wrist's roll axis) or "palm" (along the palm's normal)
    coupling: tuple[float, ...]  # per gripper joint: its value is this times the gripper's value
    palm_normal: tuple[float, float, float]  # the tool axis the fingers curl towards (palm-first: the approach)
    grasp_offset: tuple[float, float, float]  # the grasp point in the tool frame (where an object is held)

    def values(self, gripper: GripperDescription, value: float) -> dict[str, float]:
        """The gripper's joints at a gripper value (`open`, `closed`), each turned by its coupling."""
        return {joint: c * value for joint, c in zip(gripper.joints, self.coupling)}


def joint_coupling(gripper: GripperDescription, limits: Callable[[str], tuple[bool, float, float] | None]
                   ) -> tuple[float, ...]:
    """Each gripper joint's coupling: the description's, else 1, or -1 for a joint whose limits (`limits(name)`:
    limited, lower, upper) allow the gripper's open and closed values only negated (it curls the other way)."""
    if gripper.coupling:
        return gripper.coupling
    found = []
    for joint in gripper.joints:
        info = limits(joint)
        sign = 1.0
        if info is not None and info[0]:
            _, lo, hi = info
            if not _within((gripper.open, gripper.closed), lo, hi) and _within((-gripper.open, -gripper.closed), lo, hi):
                sign = -1.0
        found.append(sign)
    return tuple(found)


def _within(values: tuple[float, ...], lo: float, hi: float) -> bool:
    """Whether every value lies within [lo, hi] (give or take rounding)."""
    return all(lo - 1e-9 <= v <= hi + 1e-9 for v in values)


def hand(body: Object, arm: ArmDescription) -> Hand:
    """The arm's hand as the model has it (kept per body: it is first read when the robot is loaded, its fingers
    tried closed and put back; in the world's cache)."""
    key = (arm.name, arm.tool_frame, arm.palm_link, arm.joints[-1] if arm.joints else "", arm.gripper)
    cache: dict[tuple, Hand] = body.world.cache.table("hands", body)
    if key not in cache:
        cache[key] = _read_hand(body, arm)
    return cache[key]


def _read_hand(body: Object, arm: ArmDescription) -> Hand:
    """The hand as the description says and, where it says nothing, as the model shows: palm-first when its fingers
    (two or more chains of revolute joints), closed, lie to one side of the palm across the wrist axis (they curl
    towards that side: the palm's normal) rather than ahead of it, as fingers closing against each other do."""
    gripper = arm.gripper
    coupling = joint_coupling(gripper, lambda name: (body.joint(name).limited, body.joint(name).lower,
                                                     body.joint(name).upper))
    wrist, to_tool = _wrist_axes(body, arm)
    palm = arm.palm_link or arm.tool_frame
    where, roots = _closed_fingers(body, gripper, coupling, palm, to_tool)
    across = where - wrist * float(where @ wrist)
    curling = roots >= 2 and all(body.joint(j).type in ("revolute", "continuous") for j in gripper.joints) \
        and float(np.linalg.norm(across)) > CURLING * float(np.linalg.norm(where))
    approach = gripper.approach or ("palm" if curling else "fingers")
    if float(np.linalg.norm(across)) > 1e-6:
        normal = _nearest_axis(across, avoid=wrist)
    else:  # the fingers close ahead of the palm: its thinnest side across the wrist (its box along the tool's axes)
        lo, hi = (np.asarray(v) for v in body.get_link_local_aabb(palm))
        palm_to_tool = to_tool @ quat_to_matrix(body.get_link_orientation(palm))
        normal = min((a for a in np.eye(3) if abs(float(a @ wrist)) < 0.5),
                     key=lambda a: float(np.abs(palm_to_tool.T @ a) @ (hi - lo)))
    offset = _grasp_offset(body, arm, approach, normal)
    return Hand(approach, coupling, vec3(float(v) + 0.0 for v in normal), offset)


def _closed_fingers(body: Object, gripper: GripperDescription, coupling: tuple[float, ...], palm: str,
                    to_tool: np.ndarray) -> tuple[np.ndarray, int]:
    """Where the links the gripper's joints move lie, on average, with the gripper closed, seen from the middle of the
    palm (tool axes); and how many fingers there are (gripper joints not moved by another of them)."""
    if not gripper.joints:
        return np.zeros(3), 0
    links = sorted(body.links_below(gripper.joints))
    roots = sum(1 for j in gripper.joints if not (body.links_below([other for other in gripper.joints if other != j])
                                                   & {body.joint(j).index}))
    lo, hi = body.get_aabb(palm)
    middle = (np.asarray(lo) + np.asarray(hi)) / 2.0
    with body.joints_kept(gripper.joints):
        body.reset_joints({j: c * gripper.closed for j, c in zip(gripper.joints, coupling)})
        centres = [(np.asarray(a) + np.asarray(b)) / 2.0 for a, b in (body.get_aabb(i) for i in links)]
    return to_tool @ (np.mean(centres, axis=0) - middle), roots


def _grasp_offset(body: Object, arm: ArmDescription, approach: str, normal: np.ndarray) -> tuple[float, float, float]:
    """The grasp point in the tool frame: the description's (given in the palm's frame), else the tool frame itself
    (fingers-first) or the middle of the palm's face the fingers curl towards (palm-first)."""
    gripper = arm.gripper
    palm = arm.palm_link or arm.tool_frame
    if gripper.grasp_point is None and approach == "fingers":
        return (0.0, 0.0, 0.0)
    palm_pose = body.get_link_position_and_orientation(palm)
    tool_position, tool_orientation = body.get_link_position_and_orientation(arm.tool_frame)
    if gripper.grasp_point is not None:
        point = np.asarray(gripper.grasp_point, dtype=float)
        world = np.asarray(palm_pose[0]) + quat_to_matrix(palm_pose[1]) @ point
    else:
        world = _palm_face(body, palm, quat_to_matrix(tool_orientation) @ normal)
    local = quat_to_matrix(tool_orientation).T @ (world - np.asarray(tool_position))
    return vec3(float(v) + 0.0 for v in np.round(local, 6))


def _palm_face(body: Object, palm: str, normal: np.ndarray) -> np.ndarray:
    """The middle of the palm's face that `normal` (world) points out of: where a ray from outside towards the middle
    of the palm's box meets the palm (its box's face when something else of the robot is met first)."""
    lo, hi = (np.asarray(v) for v in body.get_aabb(palm))
    middle = (lo + hi) / 2.0
    reach = float(np.linalg.norm(hi - lo)) + 0.05
    others = [obj for obj in body.world.objects if obj is not body]
    hit = body.world.cast_rays([middle + normal * reach], [middle], others)[0]
    if hit is not None and hit.object is body and hit.link == body.get_link_id(palm):
        return np.asarray(hit.position, dtype=float)
    return middle + normal * float(np.abs(normal) @ ((hi - lo) / 2.0))


def model_grasps(body: Object, arm: ArmDescription) -> dict[str, Quat]:
    """The named grasps (tool orientations relative to the base) for this arm's tool frame as the model has it."""
    tool = tool_axes(body, arm)
    grasps: dict[str, Quat] = {}
    for name, (approach, closing) in NAMED_GRASPS.items():
        a, c = np.asarray(approach), np.asarray(closing)
        wanted = np.column_stack([a, c, np.cross(a, c)])
        grasps[name] = matrix_to_quat(wanted @ tool.T)
    return grasps


#: a hand-written named grasp whose approach is farther than this from its name's direction is reported (rad)
ASTRAY = 0.8


def astray_grasps(body: Object, arm: ArmDescription, grasps: dict[str, Quat]) -> list[tuple[str, str, Quat]]:
    """Hand-written named grasps (front, top, left, right) that do not approach from where their name says, for this
    arm's tool frame as the model has it: (name, where it approaches from, the orientation that would)."""
    tool = tool_axes(body, arm)
    computed = model_grasps(body, arm)
    astray = []
    for name, orientation in grasps.items():
        if name not in NAMED_GRASPS:
            continue
        approach = quat_to_matrix(orientation) @ tool[:, 0]
        wanted = np.asarray(NAMED_GRASPS[name][0])
        if float(np.arccos(np.clip(approach @ wanted, -1.0, 1.0))) > ASTRAY:
            direction = ", ".join(f"{v:.2g}" for v in np.round(approach, 2) + 0.0)
            astray.append((name, f"along ({direction}) in the base's frame", computed[name]))
    return astray
