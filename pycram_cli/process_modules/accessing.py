"""Accessing: grasp a drawer handle and pull the drawer open, the gripper following the handle."""
from __future__ import annotations

from typing import Any, Mapping

from ..failures import ManipulationFailure, ReachabilityFailure
from ..world import Object
from .arms import move_tool, set_gripper
from .base import ProcessModule, Robot
from .manipulation import grasp_orientation
from .registry import process_module

STEPS = 6


def contents_of(part: Object, link: int) -> list[Object]:
    """Free objects resting on (touching, above) a link of `part` — they ride along when it moves."""
    link_top = part.get_aabb(link)[0][2]
    inside = []
    for obj in part.world.objects:
        if obj is part or obj.fixed or obj.attachments:
            continue
        points = part.world.closest_points(part, obj, 0.005, link_a=link)
        if points and obj.get_aabb()[0][2] >= link_top - 0.005:
            inside.append(obj)
    return inside


@process_module("accessing")
class Accessing(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        part: Object = slots["part-of"]
        joint = part.joint(slots["drawer-joint"])
        handle = slots["drawer-handle"]
        arm = slots["arm"]
        start = part.get_joint_position(joint.name)
        goal = min(joint.upper, joint.lower + float(slots["distance"])) if joint.limited else start + float(slots["distance"])
        orientation = grasp_orientation(robot, next(iter(robot.description.grasps)))  # the first grasp pulls handles
        set_gripper(robot, arm, "open")
        move_tool(robot, arm, part.get_link_position(handle), orientation, f"the handle {handle}")
        set_gripper(robot, arm, "closed")
        riders = contents_of(part, joint.index)
        for obj in riders:
            part.attach(obj, parent_link=part.get_link_name(joint.index))
        try:
            for k in range(1, STEPS + 1):
                value = start + (goal - start) * k / STEPS
                part.set_joint_position(joint.name, value)
                try:
                    move_tool(robot, arm, part.get_link_position(handle), orientation, f"the handle {handle}")
                except ReachabilityFailure as exc:
                    raise ManipulationFailure(
                        f"the {arm} arm cannot follow {handle} beyond {value - start:.2f} m "
                        f"(asked to open {joint.name} to {goal:.2f} m): {exc}", arm=arm, joint=joint.name) from None
        finally:
            for obj in riders:
                part.detach(obj)
            set_gripper(robot, arm, "open")
