"""Looking: point the camera's optical axis at a target, however the camera is mounted.

Where the camera sits is read from the model (`camera_mount`), not written down:
* on a **head** (the description has `head:`): pan and tilt turn, the rest of the robot stays;
* on the **wrist** (the camera frame moves with an arm's joints): the arm moves, collision-checked
  as every arm motion, to a viewpoint above and in front of the target;
* fixed on the **body** (neither): the base turns in place to face the target (a bolted-down robot
  only checks that the target is in view).
Every kind ends with the target inside the camera's field of view, or a ReachabilityFailure that
says why not.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from ..errors import InputError, Location
from ..failures import ManipulationFailure, ReachabilityFailure
from ..kinds import arm_words
from ..reasoning.ik import Settings, solve
from ..robots import Robot
from ..world.pose import compose, invert, matrix_to_quat, yaw_quaternion
from .contacts import collisions
from .motion import followers
from .paths import move_over

#: how close to the optical axis a look must end (rad)
AIM = math.radians(2.0)
#: a wrist camera's viewpoints: distances from the target (m) and elevations above it (rad), tried in order
WRIST_DISTANCES = (0.45, 0.35, 0.6)
WRIST_ELEVATIONS = (math.radians(60.0), math.radians(45.0), math.radians(75.0), math.radians(30.0))
#: how far from its orientation a wrist camera's viewpoint may be solved (rad): the target then is still well in view
WRIST_ANGLE = math.radians(8.0)


class Mount(StrEnum):
    """Where the camera is: what moves when the robot looks."""

    HEAD = "head"
    WRIST = "wrist"
    BODY = "body"


@dataclass(frozen=True)
class CameraMount:
    kind: Mount
    arm: str | None = None  # the arm that carries a wrist camera


def camera_mount(robot: Robot) -> CameraMount:
    """Where the robot's camera is mounted, from its description and its model's kinematic tree."""
    desc = robot.description
    if desc.head is not None:
        return CameraMount(Mount.HEAD)
    if desc.camera is not None:
        camera = robot.body.get_link_id(desc.camera.frame)
        for arm in desc.arms.values():
            if camera in robot.body.links_below(arm.joints):
                return CameraMount(Mount.WRIST, arm.name)
    return CameraMount(Mount.BODY)


def _angles_in_camera(robot: Robot, frame: str, target: Sequence[float]) -> np.ndarray:
    """Horizontal and vertical angle of the target off the optical axis (+z forward, +x right, +y down)."""
    camera = robot.body.get_link_position_and_orientation(frame)
    local = compose(invert(camera), (tuple(target), (0.0, 0.0, 0.0, 1.0)))[0]
    x, y, z = local
    return np.array([math.atan2(x, z), math.atan2(y, z)])


def in_view(robot: Robot, target: Sequence[float]) -> bool:
    """Whether the target is inside the camera's field of view as the robot stands (in front of the camera)."""
    camera = robot.description.camera
    assert camera is not None
    pose = robot.body.get_link_position_and_orientation(camera.frame)
    x, y, z = compose(invert(pose), (tuple(target), (0.0, 0.0, 0.0, 1.0)))[0]
    return z > 0 and abs(math.atan2(x, z)) <= camera.horizontal_fov / 2 and abs(math.atan2(y, z)) <= camera.vertical_fov / 2


def _where(target: Sequence[float]) -> str:
    return f"({', '.join(f'{v:.2f}' for v in target)})"


def look_at(robot: Robot, target: Sequence[float], turn_base: bool = True) -> None:
    """Point the camera at `target` (see the module docstring). `turn_base=False`: a camera fixed on the body is not
    turned, only checked (where to stand is being chosen: the pose's yaw already faces the target)."""
    camera = robot.description.camera
    if camera is None:
        raise InputError(f"robot '{robot.description.name}' cannot look: it has no camera in its description",
                         Location(str(robot.description.path)))
    mount = camera_mount(robot)
    if mount.kind is Mount.HEAD:
        _turn_head(robot, target)
    elif mount.kind is Mount.WRIST:
        assert mount.arm is not None
        _move_wrist(robot, mount.arm, target)
    elif turn_base and robot.description.mobile:
        _turn_base(robot, target)
    if not in_view(robot, target):
        off = np.degrees(np.abs(_angles_in_camera(robot, camera.frame, target)))
        how = {Mount.HEAD: "the head cannot turn far enough", Mount.WRIST: "the arm cannot hold its camera",
               Mount.BODY: "the camera is fixed on the body, and"}[mount.kind]
        raise ReachabilityFailure(
            f"{how} to look at {_where(target)}: it is {off[0]:.0f}° across and {off[1]:.0f}° up or down off the "
            f"camera's axis, which sees {math.degrees(camera.horizontal_fov) / 2:.0f}° and "
            f"{math.degrees(camera.vertical_fov) / 2:.0f}° either way", target=list(target))


def _turn_head(robot: Robot, target: Sequence[float]) -> None:
    """Newton steps on (pan, tilt) with a numeric Jacobian; joint limits respected."""
    head, camera = robot.description.head, robot.description.camera
    assert head is not None and camera is not None
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
    if np.max(np.abs(error)) > AIM:
        raise ReachabilityFailure(
            f"the head cannot turn far enough to look at {_where(target)}: "
            f"{math.degrees(float(np.max(np.abs(error)))):.0f}° off the camera axis at the joint limits",
            target=list(target))


def _optical_axis(robot: Robot) -> tuple[float, float, float]:
    """The camera's optical axis (+z of its frame) in the base's frame."""
    camera = robot.description.camera
    assert camera is not None
    relative = compose(invert(robot.body.get_pose()), robot.body.get_link_position_and_orientation(camera.frame))[1]
    x, y, z, w = relative
    return 2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)


def camera_yaw(robot: Robot) -> float:
    """How far the camera's optical axis, seen from above, is turned from the base's forward axis (rad)."""
    fx, fy, _ = _optical_axis(robot)
    return math.atan2(fy, fx) if math.hypot(fx, fy) > 1e-6 else 0.0


def camera_pitch(robot: Robot) -> float:
    """How far the camera's optical axis points above the base's horizontal plane (rad; negative: down)."""
    fx, fy, fz = _optical_axis(robot)
    return math.atan2(fz, math.hypot(fx, fy))


def _turn_base(robot: Robot, target: Sequence[float]) -> None:
    """Turn the base in place until the camera's axis, seen from above, points at the target (a few fixed-point
    steps: turning moves the camera too); NavigationFailure-like ReachabilityFailure if it would hit something."""
    camera = robot.description.camera
    assert camera is not None
    body = robot.body
    before = body.get_pose()
    position = before[0]
    x, y, z, w = before[1]
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    for _ in range(6):
        eye = body.get_link_position(camera.frame)
        wanted = math.atan2(target[1] - eye[1], target[0] - eye[0])
        error = math.remainder(wanted - (yaw + camera_yaw(robot)), 2 * math.pi)
        if abs(error) < 1e-4:
            break
        yaw += error
        body.set_position_and_orientation(position, yaw_quaternion(yaw))
    hits = collisions(body, held=followers(body))
    if hits:
        body.set_position_and_orientation(*before)
        raise ReachabilityFailure(f"the base cannot turn to look at {_where(target)}: it would hit "
                                  f"{', '.join(o.name for o in hits)}", target=list(target),
                                  colliding=[o.name for o in hits])


def _viewpoints(robot: Robot, arm: str, target: Sequence[float]) -> list[tuple[np.ndarray, tuple[float, ...]]]:
    """Camera poses looking at the target from above, on the side of the arm's shoulder, nearest first."""
    shoulder = np.asarray(robot.body.get_link_position(robot.body.joint(robot.description.arm(arm).joints[0]).child_link))
    goal = np.asarray(target, dtype=float)
    towards = shoulder[:2] - goal[:2]
    heading = math.atan2(towards[1], towards[0]) if np.hypot(*towards) > 1e-6 else 0.0
    poses: list[tuple[np.ndarray, tuple[float, ...]]] = []
    for distance in WRIST_DISTANCES:
        for elevation in WRIST_ELEVATIONS:
            eye = goal + distance * np.array([math.cos(elevation) * math.cos(heading),
                                              math.cos(elevation) * math.sin(heading), math.sin(elevation)])
            forward = (goal - eye) / np.linalg.norm(goal - eye)
            right = np.cross(forward, (0.0, 0.0, 1.0))
            right /= np.linalg.norm(right)
            down = np.cross(forward, right)
            poses.append((eye, matrix_to_quat(np.column_stack([right, down, forward]))))
    return poses


def _move_wrist(robot: Robot, arm: str, target: Sequence[float]) -> None:
    """Move the arm so that its camera looks at the target from a viewpoint above it (the first one it reaches and
    gets to along a free path)."""
    camera = robot.description.camera
    assert camera is not None
    body = robot.body
    joints = list(robot.description.arm(arm).joints)
    blocked: list[str] = []
    for eye, orientation in _viewpoints(robot, arm, target):
        solution = solve(robot, arm, tuple(eye), orientation, frame=camera.frame, joints=joints,
                         settings=Settings(threshold=0.03, angle_threshold=WRIST_ANGLE))
        if not solution.success:
            continue
        with body.joints_kept(joints):
            body.reset_joints(solution.joint_positions)
            seen = in_view(robot, target)
        if not seen:
            continue
        try:
            move_over(robot, arm, solution.joint_positions, f"the {arm_words(arm)}'s motion to look at {_where(target)}",
                      search=False)
            return
        except ManipulationFailure as failure:
            blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
    raise ReachabilityFailure(f"the {arm_words(arm)} cannot hold its camera to look at {_where(target)}"
                              + (f": the ways are blocked by {', '.join(blocked)}" if blocked else ""),
                              target=list(target), colliding=blocked)
