"""The tool frame as the model has it: which of its axes a hand approaches along and which its fingers close along,
and the four named grasps (front, top, left, right) of a robot whose description names none.

The approach is the axis of the arm's last joint (the wrist's roll on every arm we know of), pointing away from the
arm towards the tool's own links; the fingers close along the tool axis across it that the gripper's links are most
spread along (y when the gripper has fewer than two finger links). A description without `grasps:` gets the grasps
the bundled robots write by hand, computed for its own tool frame: front approaches along the base's +x with the
fingers closing along +y, top approaches downwards, left along -y and right along +y.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..world import Object
from ..world.pose import Quat, matrix_to_quat, quat_to_matrix

if TYPE_CHECKING:
    from .description import ArmDescription

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


def tool_axes(body: Object, arm: "ArmDescription") -> np.ndarray:
    """The arm's tool frame as a grasp sees it: columns (approach, closing, the third), in the tool frame."""
    _, tool_orientation = body.get_link_position_and_orientation(arm.tool_frame)
    to_tool = quat_to_matrix(tool_orientation).T
    last = body.joint(arm.joints[-1])
    joint_position, joint_orientation = body.get_link_position_and_orientation(last.index)
    axis = quat_to_matrix(joint_orientation) @ quat_to_matrix(last.inertial_frame[1]) @ np.asarray(last.axis, dtype=float)
    below = sorted(body.links_below([last.name]))
    boxes = [body.get_aabb(index) for index in below] or [body.get_aabb(arm.tool_frame)]
    centre = (np.min([b[0] for b in boxes], axis=0) + np.max([b[1] for b in boxes], axis=0)) / 2.0
    outward = centre - np.asarray(joint_position)
    if float(outward @ axis) < 0:
        axis = -axis
    approach = _nearest_axis(to_tool @ axis)
    fingers = [body.get_aabb(body.joint(name).index) for name in arm.gripper.joints]
    spread = np.zeros(3)
    if len(fingers) >= 2:
        centres = [to_tool @ ((np.asarray(lo) + np.asarray(hi)) / 2.0) for lo, hi in fingers]
        spread = np.max(centres, axis=0) - np.min(centres, axis=0)
    closing = _nearest_axis(spread + np.array([0.0, 1e-6, 0.0]), avoid=approach)
    return np.column_stack([approach, closing, np.cross(approach, closing)])


def model_grasps(body: Object, arm: "ArmDescription") -> dict[str, Quat]:
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


def astray_grasps(body: Object, arm: "ArmDescription", grasps: dict[str, Quat]) -> list[tuple[str, str, Quat]]:
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
