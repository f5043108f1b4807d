"""Perception: detect a visible object of a type, or look it up in the world state."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..failures import PerceptionFailure
from ..reasoning import occluding, visible
from ..robots import Robot
from ..world import Object
from .base import ProcessModule
from .registry import process_module


def _of_type(robot: Robot, slots: Mapping[str, Any], missing: str) -> tuple[str, list[Object]]:
    """The slots' object type and the world's objects of it, by name: where both detectors start. When there are
    none, a `PerceptionFailure` whose message is `missing` with the type in its `{}` (each detector words it)."""
    object_type = slots["object-type"]
    found = sorted((o for o in robot.world.objects if o.type == object_type), key=lambda o: o.name)
    if not found:
        raise PerceptionFailure(missing.format(object_type), object_type=object_type)
    return object_type, found


@process_module("perception")
class Detecting(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> Object:
        object_type, candidates = _of_type(robot, slots, "there is no object of type '{}' to see")
        seen: list[tuple[float, str, Object | str]] = []  # (order, name, the object or why it is not seen)
        for obj in candidates:
            answer = visible(obj, world=robot.world)
            if answer.visible:
                seen.append((-answer.fraction, obj.name, obj))
            else:
                blockers = [o.name for o in occluding(obj, world=robot.world)]
                reason = f"{answer.fraction:.0%} visible" + (f", hidden by {', '.join(blockers)}" if blockers else "")
                seen.append((1.0, obj.name, reason))
        visible_ones = [(order, name, obj) for order, name, obj in seen if isinstance(obj, Object)]
        if visible_ones:
            return min(visible_ones)[2]
        details = "; ".join(f"{name}: {reason}" for _, name, reason in seen)
        raise PerceptionFailure(f"no {object_type} is visible from the robot's camera ({details})",
                                object_type=object_type)


@process_module("world-state")
class WorldStateDetecting(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> Object:
        return _of_type(robot, slots, "the world has no object of type '{}'")[1][0]
