"""Navigation: teleport the base; fail (and stay put) if the robot, or what it holds, would collide."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..failures import NavigationFailure
from ..planning.contacts import collisions
from ..planning.motion import followers
from ..robots import Robot
from .base import ProcessModule
from .registry import process_module


@process_module("navigation")
class Navigation(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        body = robot.body
        before = body.get_pose()
        target = (float(slots["target"][0]), float(slots["target"][1]), before[0][2])
        body.set_position_and_orientation(target, slots["orientation"])
        hits = collisions(body, held=followers(body))
        if hits:
            body.set_position_and_orientation(*before)
            what = "; ".join(f"{o.name} ({', '.join(f'{a}↔{b}' for a, b in pairs[:3])})" for o, pairs in hits.items())
            raise NavigationFailure(
                f"robot cannot stand at ({target[0]:.3f}, {target[1]:.3f}): it would collide with {what}",
                target=list(target), colliding=[o.name for o in hits])
