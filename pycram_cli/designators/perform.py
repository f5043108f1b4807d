"""Performing one designator on a world: check, resolve its slots, run its process module."""
from __future__ import annotations

from typing import Any, Mapping

from ..errors import InputError, InputErrors, Location
from ..world import BulletWorld, Object
from .resolve import RESOLVERS, jsonable
from .result import Performed
from .spec import check_designator


def perform(world: BulletWorld, designator: str, slots: Mapping[str, Any]) -> Performed:
    """Perform one motion designator with the world's robot; raises a Failure when the motion fails.

        perform(world, "pick-up", {"object": "milk", "arm": "right"})
    """
    from ..process_modules import Robot, choose

    problems = check_designator(designator, slots, is_reference=lambda v: isinstance(v, Object))
    if problems:
        raise InputErrors([InputError(p.message, Location(f"designator {designator}"), key=p.slot, suggestion=p.suggestion)
                           for p in problems])
    robot = Robot.of(world)
    with world.lock:
        resolved = RESOLVERS[designator](robot, slots)
        module = choose(designator, robot.description.name)
        result = module.execute(robot, resolved)
    return Performed(designator, jsonable(resolved), result)
