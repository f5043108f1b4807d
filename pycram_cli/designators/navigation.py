"""`moving`: drive (teleport) the robot base."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..robots import Robot
from ..signature import Param, Signature
from .declaration import Designator, declare_designator, drives


def _resolve(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {"target": [float(v) for v in slots["target"]],
            "orientation": list(slots.get("orientation") or robot.body.get_orientation())}


declare_designator(Designator(
    "moving", "Drive (teleport) the robot base to a pose; fails if the robot then collides with anything but the floor.",
    Signature((
        Param("target", "position", True, "where the base goes (z is ignored: the base stays on the floor)"),
        Param("orientation", "quaternion", False, "base orientation", default_doc="the current orientation"),
    )),
    resolve=_resolve, module="navigation", uses=drives("base"), needs=("mobile base",), resource="base"))
