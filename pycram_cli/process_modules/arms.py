"""The arm executors: arms to joint poses, the tool to a pose, grippers open and closed; the planning they call
(inverse kinematics, ways around what is in the way, gripper values) is in `planning/`."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..failures import GripperFailure, ManipulationFailure
from ..planning import motion
from ..planning.paths import move_over, move_tool
from ..planning.reach import arm_configs, arm_configuration, set_gripper
from ..robots import Robot
from ..world import JointLimitError
from .base import ProcessModule
from .registry import process_module

#: the joint-space search's budget (legs checked) for a commanded arm configuration (`move-arm-joints`): it has no
#: other goal to fall back on, so it searches longer than a motion to a tool pose (`paths.SEARCH_EDGES`). Measured
#: once, for issue 23: of 22 random PR2 arm configurations beside the bundled kitchen's oven whose straight way to
#: park brushes the oven, the 6 that the ways `move_over` tries first did not clear needed 341 to 2416 legs (about
#: 4 to 28 s on the 2-core machine) with the search checking every leg it grew; the lazy search checks fewer (the one
#: tests/process_modules/test_arm_joints.py keeps: 147 legs instead of 341), so this budget is now generous
ARM_JOINTS_SEARCH_EDGES = 2500


@process_module("arm-joints")
class MoveArmJoints(ProcessModule):
    """Arms to joint values (a named pose of the description, a list in joint order, or a mapping): all at once
    along the straight path in joint space when it is free, else one arm after the other around what is in the way
    (`move_over`, then a longer joint-space search). A goal that is itself inside something fails at once, naming
    it; when no way is found the failure names what blocks the straight path. Either way nothing has moved."""

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        values: dict[str, float] = {}
        for arm, config in arm_configs(slots).items():
            if arm not in robot.description.arms:
                raise ManipulationFailure(f"robot '{robot.description.name}' has no arm '{arm}' "
                                          f"(arms: {', '.join(robot.description.arms)})")
            values.update(arm_configuration(robot, arm, config))
        for name, value in values.items():  # limits first: a pose out of range is said as such, not as a collision
            joint = robot.body.joint(name)
            if joint.limited and not (joint.lower - 1e-9 <= value <= joint.upper + 1e-9):
                raise ManipulationFailure(f"joint '{name}' of '{robot.body.name}': {value:g} is outside its limits "
                                          f"[{joint.lower:g}, {joint.upper:g}]")
        arms = list(arm_configs(slots))
        what = f"moving the {', '.join(arms)} arm{'s' if len(arms) > 1 else ''}"
        hits = motion.hits_at_goal(robot, values)
        if hits:  # no path ends there: said at once, not after a search
            raise motion.collision_failure(what, hits, 1.0, at_goal=True)
        try:
            motion.move(robot, values, what)
            return
        except JointLimitError as exc:
            raise ManipulationFailure(str(exc)) from None
        except ManipulationFailure:
            pass
        # one arm after the other, each around what is in its way if need be; all or nothing
        body = robot.body
        start = body.get_joint_positions(list(values))
        try:
            for arm in arms:
                goal = {name: values[name] for name in robot.description.arm(arm).joints if name in values}
                try:  # the failure names the arm that is blocked
                    move_over(robot, arm, goal, f"moving the {arm} arm", down_onto_goal=False,
                              edges=ARM_JOINTS_SEARCH_EDGES)
                except ManipulationFailure as exc:
                    raise ManipulationFailure(f"{exc}; no way around it was found", **exc.details) from None
        except BaseException:
            body.reset_joints(start)
            body.move_attached()
            raise


@process_module("tcp")
class MoveTCP(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        target = slots["target"]
        move_tool(robot, slots["arm"], target, slots.get("orientation"), f"({', '.join(f'{v:.3f}' for v in target)})")


class _Gripper(ProcessModule):
    opening = "open"

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        arm = slots["gripper"]
        if self.opening == "open":
            for obj in robot.held_objects(arm):  # an opened gripper lets go
                robot.body.detach(obj)
        set_gripper(robot, arm, self.opening)


@process_module("open-gripper")
class OpeningGripper(_Gripper):
    opening = "open"


@process_module("close-gripper")
class ClosingGripper(_Gripper):
    opening = "closed"

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        if not robot.description.arm(slots["gripper"]).gripper.joints:
            raise GripperFailure(f"the {slots['gripper']} arm has no gripper")
        super().execute(robot, slots)
