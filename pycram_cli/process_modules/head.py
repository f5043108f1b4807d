"""The head: turn pan and tilt so that the camera's optical axis points at a target."""
from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

import numpy as np

from ..errors import InputError, Location
from ..failures import ReachabilityFailure
from ..world.pose import invert, compose
from .base import ProcessModule, Robot
from .registry import process_module


def _angles_in_camera(robot: Robot, frame: str, target: Sequence[float]) -> np.ndarray:
    """Horizontal and vertical angle of the target off the optical axis (+z forward, +x right, +y down)."""
    camera = robot.body.get_link_position_and_orientation(frame)
    local = compose(invert(camera), (tuple(target), (0.0, 0.0, 0.0, 1.0)))[0]
    x, y, z = local
    return np.array([math.atan2(x, z), math.atan2(y, z)])


def look_at(robot: Robot, target: Sequence[float]) -> None:
    """Newton steps on (pan, tilt) with a numeric Jacobian; joint limits respected."""
    head, camera = robot.description.head, robot.description.camera
    if head is None or camera is None:
        raise InputError(f"robot '{robot.description.name}' cannot look: it has no "
                         f"{'head' if head is None else 'camera'} in its description", Location(str(robot.description.path)))
    body = robot.body
    pan, tilt = body.joint(head.pan_joint), body.joint(head.tilt_joint)
    q = np.array([body.get_joint_position(pan.name), body.get_joint_position(tilt.name)])
    lo = np.array([pan.lower if pan.limited else -math.inf, tilt.lower if tilt.limited else -math.inf])
    hi = np.array([pan.upper if pan.limited else math.inf, tilt.upper if tilt.limited else math.inf])
    # start from the straight-line guess for pan so that targets behind the robot converge
    base = body.get_link_position_and_orientation(head.pan_link or body.base_link_name)
    local = compose(invert(base), (tuple(target), (0.0, 0.0, 0.0, 1.0)))[0]
    q[0] = np.clip(q[0] + math.atan2(local[1], local[0]), lo[0], hi[0])

    def apply(values: np.ndarray) -> None:
        body.reset_joints({pan.name: float(values[0]), tilt.name: float(values[1])})

    error = np.zeros(2)
    for _ in range(8):
        apply(q)
        error = _angles_in_camera(robot, camera.frame, target)
        if np.max(np.abs(error)) < 1e-4:
            break
        jac = np.zeros((2, 2))
        for k in range(2):
            dq = q.copy()
            dq[k] += 1e-4
            apply(dq)
            jac[:, k] = (_angles_in_camera(robot, camera.frame, target) - error) / 1e-4
        step = np.linalg.lstsq(jac, -error, rcond=None)[0]
        q = np.clip(q + step, lo, hi)
    apply(q)
    body.set_joint_positions({pan.name: float(q[0]), tilt.name: float(q[1])})
    error = _angles_in_camera(robot, camera.frame, target)
    if np.max(np.abs(error)) > math.radians(2.0):
        raise ReachabilityFailure(
            f"the head cannot turn far enough to look at ({', '.join(f'{v:.2f}' for v in target)}): "
            f"{math.degrees(float(np.max(np.abs(error)))):.0f}° off the camera axis at the joint limits",
            target=list(target))


@process_module("head")
class MoveHead(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        look_at(robot, slots["target"])
