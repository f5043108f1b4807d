"""Arm motion: inverse kinematics for the tool frame, joint poses, grippers."""
from __future__ import annotations

import math
from typing import Any, Mapping, Sequence

from ..errors import did_you_mean
from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..reasoning.ik import IKSolution, solve
from ..world import JointLimitError
from .base import ProcessModule, Robot
from .registry import process_module

def reach(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None) -> IKSolution:
    tool = robot.description.arm(arm).tool_frame
    return solve(robot.body, tool, position, orientation)


def move_tool(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None,
              what: str) -> IKSolution:
    """Bring the arm's tool frame to a pose, or raise ReachabilityFailure saying how far off it stays."""
    solution = reach(robot, arm, position, orientation)
    if not solution.success:
        angle = "" if solution.orientation_error is None else f", {math.degrees(solution.orientation_error):.0f}° off in orientation"
        raise ReachabilityFailure(
            f"{arm} arm cannot reach {what}: the tool frame stays {solution.position_error * 100:.1f} cm away{angle}",
            arm=arm, position_error=solution.position_error)
    robot.body.set_joint_positions(solution.joint_positions)
    return solution


def set_gripper(robot: Robot, arm: str, opening: str) -> None:
    gripper = robot.description.arm(arm).gripper
    value = gripper.open if opening == "open" else gripper.closed
    robot.body.set_joint_positions({joint: value for joint in gripper.joints})


def arm_configuration(robot: Robot, arm: str, config: Any) -> dict[str, float]:
    """Joint values by name for a named pose, a list in joint order, or a mapping."""
    desc = robot.description.arm(arm)
    if isinstance(config, str):
        if config not in desc.poses:
            hint = did_you_mean(config, desc.poses)
            raise ManipulationFailure(f"{arm} arm has no pose '{config}'" + (f" ({hint})" if hint else "")
                                      + f"; poses: {', '.join(desc.poses)}")
        values: Sequence[float] = desc.poses[config]
        return dict(zip(desc.joints, values))
    if isinstance(config, Mapping):
        unknown = [j for j in config if j not in desc.joints]
        if unknown:
            hint = did_you_mean(unknown[0], desc.joints)
            raise ManipulationFailure(f"'{unknown[0]}' is not a joint of the {arm} arm" + (f" ({hint})" if hint else ""))
        return {str(k): float(v) for k, v in config.items()}
    if len(config) != len(desc.joints):
        raise ManipulationFailure(f"{arm} arm has {len(desc.joints)} joints ({', '.join(desc.joints)}), got {len(config)} values")
    return dict(zip(desc.joints, (float(v) for v in config)))


def arm_configs(slots: Mapping[str, Any]) -> dict[str, Any]:
    """Configuration by arm name from `arms: {arm: config}` and the design's `<arm>-arm: config` slots."""
    configs: dict[str, Any] = dict(slots.get("arms") or {})
    for key, config in slots.items():
        if key.endswith("-arm") and config is not None:
            configs[key[: -len("-arm")]] = config
    return configs


@process_module("arm-joints")
class MoveArmJoints(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        values: dict[str, float] = {}
        for arm, config in arm_configs(slots).items():
            if arm not in robot.description.arms:
                raise ManipulationFailure(f"robot '{robot.description.name}' has no arm '{arm}' "
                                          f"(arms: {', '.join(robot.description.arms)})")
            values.update(arm_configuration(robot, arm, config))
        try:
            robot.body.set_joint_positions(values)
        except JointLimitError as exc:
            raise ManipulationFailure(str(exc)) from None


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
