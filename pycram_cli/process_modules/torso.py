"""The torso: raise or lower it (its prismatic joint, named in the robot description)."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..failures import ManipulationFailure
from ..robots import Robot
from ..world import JointLimitError
from .base import ProcessModule
from .registry import process_module


@process_module("torso")
class MoveTorso(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        joint = robot.description.torso_joint
        if joint is None:
            raise ManipulationFailure(f"robot '{robot.description.name}' has no torso to move")
        try:
            robot.body.set_joint_positions({joint: float(slots["position"])})
        except JointLimitError as exc:
            raise ManipulationFailure(str(exc)) from None
