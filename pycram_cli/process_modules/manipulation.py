"""Pick-up and place: grasp with inverse kinematics, attach to the tool frame, put down, let go."""
from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..world import Object
from ..robots.objects import grasp_points, special_grasps
from ..world.pose import compose, invert, quat_multiply, quat_to_matrix, yaw_quaternion
from .arms import move_tool, reach, set_gripper
from .base import ProcessModule, Robot
from .registry import process_module


def grasp_orientation(robot: Robot, grasp: str | Sequence[float]) -> tuple[float, float, float, float]:
    return robot.description.grasp_orientation(grasp, robot.body.get_orientation())  # type: ignore[arg-type]


def _generic_point(obj: Object, grasp: str | Sequence[float]) -> tuple[float, float, float]:
    """The middle of the object's box, or just below its top for a top grasp."""
    lo, hi = obj.get_aabb()
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    if grasp == "top":
        centre[2] = hi[2] - min(0.03, (hi[2] - lo[2]) / 2)
    return (centre[0], centre[1], centre[2])


def grip_width(robot: Robot, obj: Object, grasp: str | Sequence[float]) -> float:
    """How wide `obj` is between the fingers for a grasp: its box measured along the tool frame's y axis."""
    closing = quat_to_matrix(grasp_orientation(robot, grasp))[:, 1]
    lo, hi = obj.get_aabb()
    return float(sum(abs(closing[k]) * (hi[k] - lo[k]) for k in range(3)))


def grasp_candidates(robot: Robot, obj: Object, grasp: str | Sequence[float]) -> list[tuple[tuple[float, float, float], float]]:
    """(tool position, width between the fingers) for each way to hold `obj` with `grasp`, nearest first."""
    if special_grasps(obj.type):
        points = grasp_points(obj.type, grasp) if isinstance(grasp, str) else ()
        pose = obj.get_pose()
        found = [(compose(pose, (point.offset, (0.0, 0.0, 0.0, 1.0)))[0], point.width) for point in points]
        base = robot.body.get_position()
        return sorted(found, key=lambda c: (c[0][0] - base[0]) ** 2 + (c[0][1] - base[1]) ** 2)
    return [(_generic_point(obj, grasp), grip_width(robot, obj, grasp))]


def grasp_target(robot: Robot, arm: str, obj: Object, grasp: str | Sequence[float]) -> tuple[tuple[float, float, float], float] | None:
    """Where the tool frame goes to hold `obj` with `grasp` and the width held, or None if the gripper cannot.

    A side grasp (the fingers closing horizontally) needs the object to be as tall as the finger pads;
    a spoon lying flat is taken from the top.
    """
    gripper = robot.description.arm(arm).gripper
    if grasp != "top" and not special_grasps(obj.type):
        lo, hi = obj.get_aabb()
        if hi[2] - lo[2] < gripper.finger_height:
            return None
    return next((c for c in grasp_candidates(robot, obj, grasp) if c[1] <= gripper.max_width), None)


def level(orientation: Sequence[float]) -> tuple[float, float, float, float]:
    """The object's orientation stood upright: its own z axis up, heading kept.

    Objects rest on their bottom (their origin is the bottom centre), so a placed object
    stands on it whatever the arm did to it on the way; its heading is that of its x axis
    (of its y axis when x points up or down).
    """
    rotation = quat_to_matrix(orientation)
    axis = rotation[:, 0] if math.hypot(rotation[0, 0], rotation[1, 0]) > 0.2 else rotation[:, 1]
    heading = math.atan2(axis[1], axis[0]) - (0.0 if axis is rotation[:, 0] else math.pi / 2)
    return yaw_quaternion(heading)


@process_module("pick-up")
class PickUp(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        obj: Object = slots["object"]
        arm, grasp = slots["arm"], slots["grasp"]
        holder = next((a.parent for a in obj.attachments.values() if a.child is obj), None)
        if holder is not None:
            raise ManipulationFailure(f"{obj.name} is already held by {holder.name}", object=obj.name)
        held = robot.held_objects(arm)
        if held:
            raise GripperFailure(f"the {arm} gripper already holds {held[0].name}", arm=arm)
        gripper = robot.description.arm(arm).gripper
        how = f"a {grasp} grasp" if isinstance(grasp, str) else "that grasp"
        target = grasp_target(robot, arm, obj, grasp)
        if target is None:
            widths = [w for _, w in grasp_candidates(robot, obj, grasp)]
            lo, hi = obj.get_aabb()
            if widths and min(widths) <= gripper.max_width:
                why = f"it is {(hi[2] - lo[2]) * 100:.1f} cm tall, lower than the fingers ({gripper.finger_height * 100:.0f} cm)"
            elif widths:
                why = (f"it is {min(widths) * 100:.1f} cm wide between the fingers; the gripper opens "
                       f"{gripper.max_width * 100:.1f} cm")
            else:
                why = f"{obj.type} objects are not held that way"
            raise GripperFailure(f"the {arm} gripper cannot hold {obj.name} with {how}: {why}", arm=arm, object=obj.name)
        position, width = target
        set_gripper(robot, arm, "open")
        move_tool(robot, arm, position, grasp_orientation(robot, grasp), f"{obj.name} with {how}")
        # close until the fingers touch the object
        robot.body.set_joint_positions({joint: gripper.angle_for_width(width) for joint in gripper.joints})
        robot.body.attach(obj, parent_link=robot.description.arm(arm).tool_frame)


@process_module("place")
class Place(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        obj: Object = slots["object"]
        arm: str = slots["arm"]
        target = tuple(float(v) for v in slots["target"])
        if robot.arm_holding(obj) != arm:
            raise ManipulationFailure(f"{obj.name} is not held by the {arm} gripper", object=obj.name, arm=arm)
        att = robot.body.attachments[obj]
        held = invert(att.transform)  # the tool frame seen from the object
        upright = level(obj.get_orientation())
        best = None
        # keep the object's current orientation, turned about the vertical if that is what it takes
        for turn in (0.0, math.pi / 2, -math.pi / 2, math.pi, math.pi / 4, -math.pi / 4, 3 * math.pi / 4, -3 * math.pi / 4):
            orientation = quat_multiply(yaw_quaternion(turn), upright)
            tool = compose((target, orientation), held)
            solution = reach(robot, arm, tool[0], tool[1])
            if solution.success:
                best = (tool[0], tool[1], orientation)
                break
            if best is None or solution.position_error < best[2]:
                best = (tool[0], tool[1], solution.position_error)
        if best is None or not isinstance(best[2], tuple):
            error = best[2] if best is not None else math.inf
            raise ReachabilityFailure(
                f"{arm} arm cannot place {obj.name} at ({', '.join(f'{v:.3f}' for v in target)}): "
                f"the tool frame stays {error * 100:.1f} cm away", arm=arm, object=obj.name)
        move_tool(robot, arm, best[0], best[1], f"the place pose for {obj.name}")
        robot.body.detach(obj)
        set_gripper(robot, arm, "open")
        # let go: the object settles exactly at the target, upright as it was held (the arm's
        # inverse kinematics is only accurate to its tolerance)
        obj.set_position_and_orientation(target, best[2])
