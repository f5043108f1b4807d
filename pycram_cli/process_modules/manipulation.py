"""The pick-up and place executors: they carry out what `planning/pick_place.py` plans (the grasp, the place, the
motions there), with physics where it matters (the object settles where it is let go)."""
from __future__ import annotations

import contextlib
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..kinds import arm_words, gripper_words
from ..planning import motion
from ..planning.paths import move_from_above
from ..planning.pick_place import LIFT, grip, offset_along, plan_grasp, plan_place, retreat, settle
from ..planning.reach import back_off, reach, set_gripper
from ..robots import Robot
from ..world import Object
from .base import ProcessModule
from .registry import process_module


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
            raise GripperFailure(f"the {gripper_words(arm)} already holds {held[0].name}", arm=arm)
        how = f"a {grasp} grasp" if isinstance(grasp, str) else "that grasp"
        candidate, pre, solution = plan_grasp(robot, arm, obj, grasp)
        move_from_above(robot, arm, pre, f"the {arm_words(arm)}'s motion to the pre-grasp pose for {obj.name}")
        set_gripper(robot, arm, "open")  # there, clear of what stands around the object
        # in until the fingers or the palm touch something, never into it
        motion.advance(robot, solution.joint_positions)
        if not grip(robot, arm, obj, pre.joint_positions):
            raise GripperFailure(f"the {gripper_words(arm)} closed on nothing: {obj.name} did not come between its fingers "
                                 f"with {how}", arm=arm, object=obj.name)
        robot.body.attach(obj, parent_link=robot.description.arm(arm).tool_frame)
        try:
            retreat(robot, arm, obj)
        except (ManipulationFailure, ReachabilityFailure):
            robot.body.detach(obj)
            raise


@process_module("place")
class Place(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        obj: Object = slots["object"]
        arm: str = slots["arm"]
        target = tuple(float(v) for v in slots["target"])
        position, orientation, solution, above, support = plan_place(robot, arm, obj, target)
        move_from_above(robot, arm, above, f"the {arm_words(arm)}'s motion above the place for {obj.name}")
        motion.advance(robot, solution.joint_positions)  # down until it touches the surface
        robot.body.detach(obj)
        set_gripper(robot, arm, "open")
        back_off(robot, arm, obj.name)
        tool = robot.body.get_link_position_and_orientation(robot.description.arm(arm).tool_frame)
        up = reach(robot, arm, offset_along(tool[0], np.array([0.0, 0.0, 1.0]), LIFT), tool[1])
        if up.success:  # and up, clear of what stands there, if the way is free
            with contextlib.suppress(ManipulationFailure):
                motion.move(robot, up.joint_positions, f"the {arm_words(arm)}'s retreat from {obj.name}")
        settle(obj)
