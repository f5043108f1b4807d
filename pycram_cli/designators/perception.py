"""`looking`, `detecting` and `world-state-detecting`: the head, the camera and the belief state."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..robots import Robot
from ..signature import Param, Signature
from .declaration import Designator, declare_designator, drives
from .inference import the_object


def _looking(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    if slots.get("target") is not None:
        return {"target": [float(v) for v in slots["target"]]}
    obj = the_object(robot, slots["object"], "object")
    lo, hi = obj.get_aabb()
    return {"object": obj, "target": [(a + b) / 2 for a, b in zip(lo, hi)]}


declare_designator(Designator(
    "looking", "Point the camera at a position or an object: the head turns "
    "(a camera on the wrist: the arm moves; fixed on the body: the base turns).",
    Signature((
        Param("target", "position", False, "the point to look at"),
        Param("object", "object", False, "the object to look at", default_doc="looks at its position"),
    ), one_of=("target", "object")),
    resolve=_looking, module="head", uses=drives("head"), needs=("camera",), resource="head"))


def _object_type(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {"object-type": slots["object-type"]}


declare_designator(Designator(
    "detecting", "Find a visible object of a type with the robot's camera; fails with PerceptionFailure if none is seen.",
    Signature((
        Param("object-type", "object-type", True, "the type of object to find"),
    )),
    resolve=_object_type, module="perception", uses=drives("head"), needs=("camera",), resource="camera"))

declare_designator(Designator(
    "world-state-detecting", "Find an object of a type from the world state, whether visible or not.",
    Signature((
        Param("object-type", "object-type", True, "the type of object to find"),
    )),
    resolve=_object_type, module="world-state", uses=drives(), resource="belief"))
