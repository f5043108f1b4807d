"""Grasps from the object's own frame: which side the tool approaches, across what the fingers close, and how wide.

A grasp of the robot (`front`, `top`, ... in its description) is a tool orientation relative to
the robot's base: it says from where the robot means to take an object. The object has its own
frame and its own box (the box of its collision shapes in that frame, `Object.get_local_aabb`),
so the tool is aligned with the object, not with the robot:

* the tool approaches (its x axis) along the object's box axis nearest the grasp's approach
  direction, i.e. through the side of the object that best faces the way the robot reaches;
* the fingers close (the tool's y axis) along one of the two box axes across that side, the one
  nearest the grasp's closing direction first, the other when the first is wider than the
  gripper opens (a handle bar is taken across its thickness, a spoon across its width);
* the width between the fingers is the object's box measured along that axis, in the object's
  own frame — a carton turned 20° is as wide as a square one.

Round objects (`symmetry: revolution` in `grasps.yaml`) have no sides: the tool keeps the grasp's
own direction, turned into the plane across the object's axis. Special grasp points (a bowl by
its rim) are given in the object's box (see `grasps.yaml`); an object without them is held at the
middle of its box, no deeper along the approach than the gripper's palm allows (an arm without a
gripper goes to the side of the object it touches).

Everything robot-specific comes from the description (the grasp orientations, the gripper's
opening and finger height, the palm link) and from the robot's model: which axis of the tool
frame points out of the gripper (the axis of the arm's last joint, the wrist's roll, pointing
away from the arm: x on the PR2 and the Fetch, z on a KUKA flange; a palm-first hand's is the palm's
normal) and which one the fingers close along (the one the finger links are spread along: y on the PR2).
A hand with a grasp point of its own (a palm-first hand's: the palm's face) holds the object there: the
tool frame goes where that puts the grasp point.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..robots import Robot
from ..robots.objects import object_knowledge
from ..robots.tool import hand
from ..robots.tool import tool_axes as model_tool_axes
from ..world import Object
from ..world.pose import Quat, Vec3, compose, invert, matrix_to_quat, quat_to_matrix

#: a box axis within this of the wanted direction counts as equally good (ties keep the box's axis order)
TIE = 1e-6


@dataclass(frozen=True)
class Grasp:
    """One way to hold a thing: the tool frame's pose, what is between the fingers, and the grasp it realises."""

    position: Vec3
    orientation: Quat
    width: float  # the object's extent between the fingers (m)
    height: float  # the object's extent along the fingers (across approach and closing), for the finger pads (m)
    name: str | Sequence[float]  # the robot's grasp (or the quaternion) this realises
    approach: np.ndarray  # the direction the tool moves in to take the object (world frame)
    depth: float = 0.0  # how far the tool frame is in from the side of the object's box it comes through (m)


def tool_axes(robot: Robot, arm: str) -> np.ndarray:
    """The arm's tool frame as a grasp sees it: columns (approach, closing, the third), in the tool frame
    (robots/tool.py reads them from the model), kept per robot body in the world's cache."""
    cache: dict[str, np.ndarray] = robot.body.world.cache.table("tool axes", robot.body)
    if arm not in cache:
        cache[arm] = model_tool_axes(robot.body, robot.description.arm(arm))
    return cache[arm]


def gripper_values(robot: Robot, arm: str, which: str) -> dict[str, float]:
    """The arm's gripper joints `open` or `closed`, each turned by its coupling (robots/tool.py `hand`)."""
    gripper = robot.description.arm(arm).gripper
    return hand(robot.body, robot.description.arm(arm)).values(gripper, getattr(gripper, which))


def grasp_offset(robot: Robot, arm: str) -> np.ndarray:
    """The grasp point in the tool frame: where an object is held (zero for a hand without a grasp point of its own,
    or without a gripper)."""
    desc = robot.description.arm(arm)
    if not desc.gripper.joints:
        return np.zeros(3)
    return np.asarray(hand(robot.body, desc).grasp_offset, dtype=float)


def wanted_orientation(robot: Robot, grasp: str | Sequence[float], base: Quat | None = None) -> Quat:
    """The tool orientation a grasp asks for: a robot grasp turned with the base (as it stands, or turned to `base`),
    or a world quaternion."""
    return robot.description.grasp_orientation(grasp, robot.body.get_orientation() if base is None else base)


def _frame(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    x = x / np.linalg.norm(x)
    y = y - x * float(x @ y)
    y = y / np.linalg.norm(y)
    return np.column_stack([x, y, np.cross(x, y)])


def _unit(v: np.ndarray) -> np.ndarray | None:
    n = float(np.linalg.norm(v))
    return v / n if n > 1e-9 else None


def _box_orientations(frame: np.ndarray, wanted: np.ndarray) -> list[np.ndarray]:
    """Tool frames aligned with a box (axes `frame` columns): approach along the box axis nearest the wanted approach,
    the fingers closing along each axis across it, the nearest the wanted closing direction first."""
    axes = [sign * frame[:, k] for k in range(3) for sign in (1.0, -1.0)]
    best = max(range(6), key=lambda i: float(axes[i] @ wanted[:, 0]) - TIE * i)
    approach = axes[best]
    across = [i for i in range(6) if abs(float(axes[i] @ approach)) < 0.5]
    across.sort(key=lambda i: -float(axes[i] @ wanted[:, 1]) + TIE * i)
    return [_frame(approach, axes[i]) for i in across]


def _round_orientations(axis: np.ndarray, wanted: np.ndarray) -> list[np.ndarray]:
    """Tool frames for an object round about `axis`: along the axis when the grasp points nearly along it, else the
    grasp's approach turned into the plane across the axis; the fingers closing across the axis first."""
    a, c = wanted[:, 0], wanted[:, 1]
    if abs(float(a @ axis)) >= math.cos(math.radians(45)):
        approach = axis if float(a @ axis) > 0 else -axis
        closing = _unit(c - axis * float(c @ axis))
        if closing is None:  # the grasp closes along the axis: any direction across it
            closing = _unit(np.cross(approach, np.array([0.0, 1.0, 0.0]))) if abs(approach[1]) < 0.9 else \
                _unit(np.cross(approach, np.array([1.0, 0.0, 0.0])))
        assert closing is not None
        return [_frame(approach, closing), _frame(approach, -closing)]
    across = _unit(a - axis * float(a @ axis))
    assert across is not None
    approach = across
    across = np.cross(axis, approach)
    options = [across, -across, axis, -axis]
    options.sort(key=lambda v: -float(v @ c))
    return [_frame(approach, v) for v in options]


def _extent(half: np.ndarray, frame: np.ndarray, direction: np.ndarray) -> float:
    """The length of a box (half extents `half` along the columns of `frame`) measured along `direction`."""
    return float(2.0 * np.sum(np.abs(frame.T @ direction) * half))


def palm_clearance(robot: Robot, arm: str) -> float:
    """How deep the grasp point can go into an object before the palm meets it (inf without a palm link): the distance
    from the grasp point (the tool frame, for most hands) back to the front of the palm's box, along the tool's
    approach axis."""
    desc = robot.description.arm(arm)
    if not desc.palm_link or desc.palm_link == desc.tool_frame:
        return math.inf
    body = robot.body
    tool = body.get_link_position_and_orientation(desc.tool_frame)
    lo, hi = body.get_aabb(desc.palm_link)
    inverse = invert(tool)
    approach = tool_axes(robot, arm)[:, 0]
    front = max(float(np.asarray(compose(inverse, ((x, y, z), (0, 0, 0, 1)))[0]) @ approach)
                for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2]))
    offset = grasp_offset(robot, arm)
    if offset.any():
        front -= float(offset @ approach)
    return max(0.0, -front)


def grasps(robot: Robot, arm: str, obj: Object, grasp: str | Sequence[float], base: Quat | None = None) -> list[Grasp]:
    """Every way to hold `obj` with `grasp`, the one that best matches the grasp first (special grasp points: the
    nearest the robot first); not yet checked against the gripper (see `holdable`). `base`: the grasp as the robot
    would ask it with its base turned so (a location weighing headings), not as it stands."""
    pose = obj.get_pose()
    lo, hi = (np.asarray(v, dtype=float) for v in obj.get_local_aabb())
    return grasps_of_box(robot, arm, pose, lo, hi, grasp, obj.type, base)


def grasps_of_box(robot: Robot, arm: str, pose: tuple[Sequence[float], Sequence[float]], lo: np.ndarray, hi: np.ndarray,
                  grasp: str | Sequence[float], object_type: str = "", base: Quat | None = None) -> list[Grasp]:
    """`grasps` for a box `lo`..`hi` in the frame `pose` (an object's, or a link's such as a drawer handle)."""
    knowledge = object_knowledge(object_type)
    rotation = quat_to_matrix(pose[1])
    origin = np.asarray(pose[0], dtype=float)
    centre, half = (lo + hi) / 2.0, (hi - lo) / 2.0
    axes = tool_axes(robot, arm)  # the tool's (approach, closing, third) axes in its own frame
    wanted = quat_to_matrix(wanted_orientation(robot, grasp, base)) @ axes  # as world directions
    round_ = knowledge.symmetry == "revolution"
    if not isinstance(grasp, str):  # a world quaternion is taken as given
        frames = [wanted]
    elif round_:
        frames = _round_orientations(rotation[:, 2], wanted)
    else:
        frames = _box_orientations(rotation, wanted)
    points = knowledge.grasps.get(grasp, ()) if isinstance(grasp, str) else ()
    if knowledge.grasps and not points:  # a type with special grasps is held only those ways
        return []
    # how deep the tool frame goes into the object: up to the palm; an arm without a gripper only touches it
    depth_limit = palm_clearance(robot, arm) if robot.description.arm(arm).gripper.joints else 0.0
    offset = grasp_offset(robot, arm)
    found: list[Grasp] = []
    for tool in frames:
        approach, closing, along = tool[:, 0], tool[:, 1], tool[:, 2]
        height = _extent(half, rotation, along)
        if round_:  # round about z: across the axis it is as wide as the box is in x or y
            diameter = 2.0 * float(max(half[0], half[1]))
            axis = rotation[:, 2]
            width = 2.0 * half[2] if abs(float(closing @ axis)) > 0.5 else diameter
            height = 2.0 * half[2] if abs(float(along @ axis)) > 0.5 else diameter
        else:
            width = _extent(half, rotation, closing)
        orientation = matrix_to_quat(tool @ axes.T)  # the tool frame whose approach and closing axes are these
        if points:
            frame = _grasp_frame(rotation, tool, round_)
            local_half = np.abs(frame.T @ rotation) @ half if not round_ else np.array(
                [max(half[0], half[1]), max(half[0], half[1]), half[2]])
            world_centre = origin + rotation @ centre
            reach = _extent(half, rotation, approach) / 2.0
            for point in points:
                position = world_centre + frame @ (np.asarray(point.at) * local_half + np.asarray(point.offset))
                depth = reach + float((position - world_centre) @ approach)
                found.append(Grasp(_vec(_tool_at(position, tool, axes, offset)), orientation, point.width, height,
                                   grasp, approach, depth))
            continue
        # the middle of the box, no deeper along the approach than the palm allows
        world_centre = origin + rotation @ centre
        reach = _extent(half, rotation, approach) / 2.0
        depth = min(reach, depth_limit)
        position = world_centre - approach * (reach - depth)
        found.append(Grasp(_vec(_tool_at(position, tool, axes, offset)), orientation, width, height, grasp, approach,
                           depth))
    if points:
        here = np.asarray(robot.body.get_position())
        found.sort(key=lambda g: float(np.hypot(g.position[0] - here[0], g.position[1] - here[1])))
    return found


def _tool_at(point: np.ndarray, tool: np.ndarray, axes: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """Where the tool frame goes for its grasp point (`offset` in the tool frame) to be at `point`, the tool's grasp
    axes being `tool` (world) and `axes` (its own frame)."""
    if not offset.any():
        return point
    return point - (tool @ axes.T) @ offset


def _grasp_frame(rotation: np.ndarray, tool: np.ndarray, round_: bool) -> np.ndarray:
    """The object frame grasp points are given in: the object's own, or for a round object its axis as z and the
    fingers' closing direction (turned across the axis) as y."""
    if not round_:
        return rotation
    z = rotation[:, 2]
    y = _unit(tool[:, 1] - z * float(tool[:, 1] @ z))
    if y is None:
        return rotation
    return np.column_stack([np.cross(y, z), y, z])


def _vec(v: np.ndarray) -> Vec3:
    return (float(v[0]), float(v[1]), float(v[2]))


def holdable(robot: Robot, arm: str, candidate: Grasp) -> str | None:
    """Why the arm's gripper cannot hold a grasp candidate (None: it can): too wide, or too low for the finger pads."""
    gripper = robot.description.arm(arm).gripper
    if candidate.width > gripper.max_width:
        return (f"it is {candidate.width * 100:.1f} cm wide between the fingers; the gripper opens "
                f"{gripper.max_width * 100:.1f} cm")
    if candidate.height < gripper.finger_height:
        return (f"it is {candidate.height * 100:.1f} cm across the finger pads, less than they are tall "
                f"({gripper.finger_height * 100:.0f} cm)")
    return None


def holdable_grasps(robot: Robot, arm: str, obj: Object, grasp: str | Sequence[float]) -> tuple[list[Grasp], str | None]:
    """The candidates the gripper can hold (best first), and why none can when the list is empty."""
    candidates = grasps(robot, arm, obj, grasp)
    fitting = [c for c in candidates if holdable(robot, arm, c) is None]
    if fitting or not candidates:
        return fitting, (None if fitting else f"{obj.type} objects are not held that way")
    return [], holdable(robot, arm, min(candidates, key=lambda c: c.width))

