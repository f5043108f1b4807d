"""Performing one designator on a world: check its slots once, resolve them, run its process module."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..errors import InputError, Location, raise_if_any
from ..jsonable import jsonable
from ..kinds import Robots
from ..process_modules import choose
from ..robots import Robot
from ..world import BulletWorld, Object
from .declaration import DESIGNATORS, check_designator
from .result import Performed


def perform(world: BulletWorld, designator: str, slots: Mapping[str, Any]) -> Performed:
    """Perform one motion designator with the world's robot; raises a Failure when the motion fails.

        perform(world, "pick-up", {"object": "milk", "arm": "right"})

    Bad slot values (checked against the robot's description) raise InputError(s).
    """
    robot = Robot.of(world)
    problems = check_designator(designator, slots, is_reference=lambda v: isinstance(v, Object),
                                robots=Robots((robot.description,), True))
    raise_if_any([InputError(p.message, Location(f"designator {designator}"), key=p.param, suggestion=p.suggestion)
                  for p in problems])
    spec = DESIGNATORS[designator]
    with world.lock:
        resolved = spec.resolve(robot, spec.signature.bind(slots))
        module = choose(designator, spec.module, robot.description)
        result = module.execute(robot, resolved)
    return Performed(designator, jsonable(resolved, drop_none=True), result)
