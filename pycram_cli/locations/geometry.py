"""The robot as geometry for ranking base poses: each arm's shoulder and length, its reach line, the camera.

Scoring thousands of candidate base poses cannot call inverse kinematics for each; it needs a few numbers read once
from the robot's description and its body as it stands (all in the base frame), and the poses that put an arm's
reach line through a point (an arm that cannot turn its tool freely reaches sideways only on that line).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..planning.grasps import grasps, holdable, tool_axes
from ..planning.pick_place import PLACE_TURNS, level
from ..robots import Robot
from ..world import Object
from ..world.pose import compose, invert, quat_multiply, quat_to_matrix, yaw_quaternion

#: candidate base positions: a lattice of the floor with this spacing (m); poses along a reach line are as far apart
STEP = 0.05
#: a point or direction: a sequence of floats or a numpy array
Point = Sequence[float] | np.ndarray


@dataclass(frozen=True)
class ArmGeometry:
    """An arm as the scores see it: where its shoulder is and how far it reaches."""

    name: str
    shoulder: np.ndarray  # (x, y, z) in the base frame, z above the floor
    length: float  # shoulder to tool frame, stretched out


def arm_geometry(robot: Robot) -> dict[str, ArmGeometry]:
    """Each arm's shoulder (its first joint) in the base frame and its length (the sum of its links)."""
    body = robot.body
    base_pos, base_orn = body.get_pose()
    to_base = invert((base_pos, base_orn))
    found = {}
    for arm in robot.description.arms.values():
        links = [body.joint(j).child_link for j in arm.joints] + [arm.tool_frame]
        points = [np.asarray(compose(to_base, (body.get_link_position(link), (0, 0, 0, 1)))[0]) for link in links]
        length = float(sum(np.linalg.norm(b - a) for a, b in zip(points, points[1:])))
        found[arm.name] = ArmGeometry(arm.name, points[0], length)
    return found


#: an arm with fewer rotating joints than this cannot turn its tool about every axis wherever it reaches
FREE_ORIENTATION_JOINTS = 6


def straight_reach_line(robot: Robot, arm: str) -> float:
    """The lateral offset (m, the base frame's y) of the arm's tool frame with every arm joint at zero: the line
    straight ahead of the robot on which the arm reaches with its tool pointing along the base's x."""
    body = robot.body
    names = list(robot.description.arm(arm).joints)
    tool = robot.description.arm(arm).tool_frame
    with body.joints_kept(names):
        body.reset_joints({n: 0.0 for n in names})
        offset = compose(invert(body.get_pose()), (body.get_link_position(tool), (0, 0, 0, 1)))[0]
    return float(offset[1])


def aligned_reach_line(robot: Robot, arm: str) -> float | None:
    """`straight_reach_line` for an arm that cannot orient its tool freely (fewer than FREE_ORIENTATION_JOINTS
    rotating joints: a pan, pitches and a wrist roll keep the tool in the vertical plane the pan turns, so a front
    grasp, pointing along the base's x, is reachable only on that line); None for an arm that can."""
    body = robot.body
    rotating = sum(1 for n in robot.description.arm(arm).joints if body.joint(n).type in ("revolute", "continuous"))
    return straight_reach_line(robot, arm) if rotating < FREE_ORIENTATION_JOINTS else None


def line_poses(point: Point, heading: float, arm: ArmGeometry, line: float,
               pan: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Base poses (xs, ys, yaws) from which the arm's reach line (`straight_reach_line`), turned by `pan` about the
    shoulder, runs through `point` along `heading` (rad), the shoulder STEP, 2 STEP, ... up to the arm's length short
    of it: from these an arm that keeps its tool in its pan's plane reaches `point` with its tool pointing along
    `heading` (the base turned to `heading - pan`). The lattice's candidates face the target from the base's centre
    and miss that line by the arm's mount offset."""
    into = np.array([math.cos(heading), math.sin(heading)])
    left = np.array([-into[1], into[0]])
    if pan == 0.0:
        ahead = arm.shoulder[0] + np.arange(1, int(arm.length / STEP) + 1) * STEP  # the point's x in the base frame
        xs = point[0] - ahead * into[0] - line * left[0]
        ys = point[1] - ahead * into[1] - line * left[1]
        return xs, ys, np.full(len(xs), heading)
    # the base at B, turned to h = heading - pan: B + R(h)·shoulder + R(heading)·(u, line - shoulder y) = point
    yaw = heading - pan
    c, s = math.cos(yaw), math.sin(yaw)
    sx, sy = float(arm.shoulder[0]), float(arm.shoulder[1])
    along = np.arange(1, int(arm.length / STEP) + 1) * STEP
    lateral = line - sy
    xs = point[0] - (c * sx - s * sy) - along * into[0] - lateral * left[0]
    ys = point[1] - (s * sx + c * sy) - along * into[1] - lateral * left[1]
    return xs, ys, np.full(len(xs), yaw)


def pull_aligned_poses(closed: Point, opened: Point, arm: ArmGeometry,
                       line: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """`line_poses` for a handle: facing along its pull (from `opened` towards `closed`), the line through the closed
    handle; from these the arm follows the handle all the way open with one front grasp."""
    into = np.asarray(closed[:2], dtype=float) - np.asarray(opened[:2], dtype=float)
    if float(np.hypot(*into)) < 1e-6:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    return line_poses(closed, math.atan2(into[1], into[0]), arm, line)


def place_headings(robot: Robot, obj: Object, target: Point) -> list[tuple[np.ndarray, float]]:
    """(tool position, tool heading) for each way place may stand the held `obj` at `target` (`PLACE_TURNS`), where
    the tool points sideways (a tool pointing down turns about the vertical with the wrist: none)."""
    held = invert(robot.body.attachments[obj].transform)
    upright = level(obj.get_orientation(), obj.upright)
    found = []
    for turn in PLACE_TURNS:
        position, orientation = compose((tuple(target), quat_multiply(yaw_quaternion(turn), upright)), held)
        x = quat_to_matrix(orientation)[:, 0]
        if abs(float(x[2])) < 0.7:
            found.append((np.asarray(position, dtype=float), math.atan2(float(x[1]), float(x[0]))))
    return found


#: base headings (rad) at which `pick_lines` asks which sideways grasps an object offers
PICK_HEADINGS = tuple(math.radians(d) for d in range(-180, 180, 30))


def pan_range(robot: Robot, arm: str) -> tuple[float, float] | None:
    """The turn of the arm's first joint when it pans about the vertical (its limits; a full turn either way when it
    has none), else None: an arm whose first joint does not pan reaches sideways only straight ahead."""
    body = robot.body
    joint = body.joint(robot.description.arm(arm).joints[0])
    if joint.type not in ("revolute", "continuous"):
        return None
    if abs(float((quat_to_matrix(body.get_orientation()).T @ body.joint_axis(joint.name))[2])) < 0.99:
        return None
    if joint.type == "continuous" or not joint.limited:
        return -math.pi, math.pi
    return float(joint.lower), float(joint.upper)


def hand_length(robot: Robot, arm: str) -> float:
    """How far the tool frame is from the arm's last joint that moves it off its approach axis (the wrist's pitch: the
    joints after it only roll the tool). A tool held level sticks out that far from the wrist, whatever the arm's
    bend: the rest of the arm reaches the wrist (`pick_lines`' poses are scored so)."""
    body = robot.body
    desc = robot.description.arm(arm)
    position, orientation = body.get_link_position_and_orientation(desc.tool_frame)
    approach = quat_to_matrix(orientation) @ tool_axes(robot, arm)[:, 0]
    for name in reversed(desc.joints):
        joint = body.joint(name)
        if joint.type in ("revolute", "continuous") and abs(float(body.joint_axis(name) @ approach)) < 0.99:
            return math.dist(position, body.get_link_position(joint.child_link))
    return 0.0


def pick_lines(robot: Robot, arm: str, obj: Object, grasp_names: Sequence[str]) -> list[tuple[np.ndarray, float, float]]:
    """(tool position, tool heading, pan) for each way the arm's gripper may take `obj` from the side (one of
    `grasp_names`, as the grasp would be asked with the base at each of PICK_HEADINGS): an arm that keeps its tool in
    its pan's plane takes it so only with its reach line, turned by the pan, through the tool position (`line_poses`).
    Pans beyond the first joint's range are left out."""
    turns = pan_range(robot, arm)
    approach = tool_axes(robot, arm)[:, 0]
    level = [n for n in grasp_names if abs(float((quat_to_matrix(robot.description.grasps[n]) @ approach)[2])) <= 0.7]
    found: dict[tuple[float, ...], tuple[np.ndarray, float, float]] = {}
    for base_yaw in PICK_HEADINGS:
        for name in level:  # a grasp pointing down turns about the vertical with the wrist: reached off the line too
            for grasp in grasps(robot, arm, obj, name, yaw_quaternion(base_yaw)):
                way = np.asarray(grasp.approach, dtype=float)
                if abs(float(way[2])) > 0.7 or holdable(robot, arm, grasp) is not None:
                    continue
                heading = math.atan2(float(way[1]), float(way[0]))
                pan = math.remainder(heading - base_yaw, 2 * math.pi)
                if turns is None and abs(pan) > 1e-6 or turns is not None and not turns[0] <= pan <= turns[1]:
                    continue
                position = np.asarray(grasp.position, dtype=float)
                key = (*np.round(position, 6), round(heading, 6), round(pan, 6))
                found.setdefault(key, (position, heading, pan))
    return list(found.values())


def camera_offset(robot: Robot) -> np.ndarray | None:
    """The camera frame in the base frame (None without a camera)."""
    camera = robot.description.camera
    if camera is None:
        return None
    body = robot.body
    to_base = invert(body.get_pose())
    return np.asarray(compose(to_base, (body.get_link_position(camera.frame), (0, 0, 0, 1)))[0])


def centre(obj: Object) -> np.ndarray:
    """The centre of the object's bounding box (what a location faces and a camera looks at)."""
    lo, hi = obj.get_aabb()
    return (np.asarray(lo) + np.asarray(hi)) / 2.0


def yaw_of(orientation: Sequence[float]) -> float:
    """The heading (rad) of a quaternion (x, y, z, w) turned about the vertical."""
    x, y, z, w = orientation
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
