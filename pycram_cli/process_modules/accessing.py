"""The accessing executor: grasp a drawer handle and pull the drawer open, the gripper following the handle, what
rests in the drawer riding along (`planning/drawers.py` plans the grasp and checks the pull)."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..failures import ManipulationFailure, ReachabilityFailure
from ..kinds import arm_words
from ..planning import motion
from ..planning.drawers import contents_of, drawer_pushes_into, held_pose, plan_handle_grasp, pull_values
from ..planning.paths import move_from_above
from ..planning.reach import back_off, close_on, set_gripper, solve_tool
from ..robots import Robot
from ..world import Object
from ..world.pose import compose
from .base import ProcessModule
from .registry import process_module


@process_module("accessing")
class Accessing(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        part: Object = slots["part-of"]
        joint = part.joint(slots["drawer-joint"])
        handle = slots["drawer-handle"]
        arm = slots["arm"]
        start = part.get_joint_position(joint.name)
        goal = min(joint.upper, joint.lower + float(slots["distance"])) if joint.limited else start + float(slots["distance"])
        what = f"the handle {handle}"
        set_gripper(robot, arm, "open")
        grasp, pre, at = plan_handle_grasp(robot, arm, part, handle)
        move_from_above(robot, arm, pre, f"the {arm_words(arm)}'s motion to {what}")
        motion.advance(robot, at.joint_positions)
        close_on(robot, arm)
        # where the tool holds the handle, in the handle's frame: it follows the handle as the drawer moves
        held = held_pose(robot, arm, part, handle)
        riders = contents_of(part, joint.index)
        hand = motion.Motion(robot, robot.description.arm(arm).joints[-1:]).links  # what holds the handle
        # the hand holds the handle and moves with the drawer: the drawer's moving links are not in its way
        moving = [(part, link) for link in range(len(part.joints)) if part.hangs_below(link, joint.index)]
        for obj in riders:
            part.attach(obj, parent_link=part.get_link_name(joint.index))
        try:
            for value in pull_values(start, goal):
                previous = part.get_joint_position(joint.name)
                part.set_joint_position(joint.name, value)
                tool = compose(part.get_link_position_and_orientation(handle), held)
                try:
                    solution = solve_tool(robot, arm, tool[0], tool[1], what)
                    motion.move(robot, solution.joint_positions, f"the {arm_words(arm)} pulling {what}", ignore_links=moving)
                    drawer_pushes_into(robot, part, moving, hand)
                except (ReachabilityFailure, ManipulationFailure) as exc:
                    part.set_joint_position(joint.name, previous)
                    raise ManipulationFailure(
                        f"the {arm_words(arm)} cannot follow {handle} beyond {previous - start:.2f} m "
                        f"(asked to open {joint.name} to {goal:.2f} m): {exc}", arm=arm, joint=joint.name) from None
        finally:
            for obj in riders:
                part.detach(obj)
            set_gripper(robot, arm, "open")
        back_off(robot, arm, what)
