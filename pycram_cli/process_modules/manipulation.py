"""Pick-up and place: grasp with inverse kinematics, attach to the tool frame, put down, let go."""
from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..world import Object
from ..world.pose import compose, invert, quat_multiply, yaw_quaternion
from .arms import move_tool, reach, set_gripper
from .base import ProcessModule, Robot
from .registry import process_module


def grasp_point(obj: Object, grasp: str | Sequence[float]) -> tuple[float, float, float]:
    """Where the tool frame goes to hold `obj`: its middle, or just below its top for a top grasp."""
    lo, hi = obj.get_aabb()
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    if grasp == "top":
        centre[2] = hi[2] - min(0.03, (hi[2] - lo[2]) / 2)
    return (centre[0], centre[1], centre[2])


def grasp_orientation(robot: Robot, grasp: str | Sequence[float]) -> tuple[float, float, float, float]:
    return robot.description.grasp_orientation(grasp, robot.body.get_orientation())  # type: ignore[arg-type]


@process_module("pick-up")
class PickUp(ProcessModule):
    resource = "arm"

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        obj: Object = slots["object"]
        arm, grasp = slots["arm"], slots["grasp"]
        holder = next((a.parent for a in obj.attachments.values() if a.child is obj), None)
        if holder is not None:
            raise ManipulationFailure(f"{obj.name} is already held by {holder.name}", object=obj.name)
        held = robot.held_objects(arm)
        if held:
            raise GripperFailure(f"the {arm} gripper already holds {held[0].name}", arm=arm)
        set_gripper(robot, arm, "open")
        move_tool(robot, arm, grasp_point(obj, grasp), grasp_orientation(robot, grasp), f"{obj.name} with a {grasp} grasp"
                  if isinstance(grasp, str) else obj.name)
        set_gripper(robot, arm, "closed")
        robot.body.attach(obj, parent_link=robot.description.arm(arm).tool_frame)


@process_module("place")
class Place(ProcessModule):
    resource = "arm"

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        obj: Object = slots["object"]
        arm: str = slots["arm"]
        target = tuple(float(v) for v in slots["target"])
        if robot.arm_holding(obj) != arm:
            raise ManipulationFailure(f"{obj.name} is not held by the {arm} gripper", object=obj.name, arm=arm)
        att = robot.body.attachments[obj]
        held = invert(att.transform)  # the tool frame seen from the object
        upright = obj.get_orientation()
        best = None
        # keep the object's current orientation, turned about the vertical if that is what it takes
        for turn in (0.0, math.pi / 2, -math.pi / 2, math.pi, math.pi / 4, -math.pi / 4, 3 * math.pi / 4, -3 * math.pi / 4):
            orientation = quat_multiply(yaw_quaternion(turn), upright)
            tool = compose((target, orientation), held)
            solution = reach(robot, arm, tool[0], tool[1])
            if solution.success:
                best = tool
                break
            if best is None or solution.position_error < best[2]:
                best = (tool[0], tool[1], solution.position_error)
        if best is None or len(best) == 3:
            error = best[2] if best is not None else math.inf
            raise ReachabilityFailure(
                f"{arm} arm cannot place {obj.name} at ({', '.join(f'{v:.3f}' for v in target)}): "
                f"the tool frame stays {error * 100:.1f} cm away", arm=arm, object=obj.name)
        move_tool(robot, arm, best[0], best[1], f"the place pose for {obj.name}")
        robot.body.detach(obj)
        set_gripper(robot, arm, "open")
