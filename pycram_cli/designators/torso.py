"""`moving-torso`: raise or lower the robot's torso."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..robots import Robot
from ..signature import Param, Signature
from .declaration import Designator, declare_designator, drives


def _resolve(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    position = slots.get("position")
    return {"position": float(robot.description.torso_default if position is None else position)}


declare_designator(Designator(
    "moving-torso", "Raise or lower the torso to a joint position (metres along its prismatic joint).",
    Signature((
        Param("position", "number", False, "the torso joint's position in metres",
              default_doc="the description's torso default"),
    )),
    resolve=_resolve, module="torso", uses=drives("torso"), needs=("torso",), resource="torso"))
