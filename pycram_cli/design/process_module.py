"""The design's `pycram.process_module.ProcessModule.perform(designator)`: performs a MotionDesignator with the robot
of the current BulletWorld (pycram's `designators.perform`: slots checked, resolved, the robot's process module run)
and returns what it yields (the object `detecting` found)."""
from __future__ import annotations

from typing import Any

from ..designators import perform as _perform
from ..world import BulletWorld, WorldError
from .designator import MotionDesignator


class ProcessModule:
    """The design's entry point; pycram's process modules are chosen by designator type and robot description."""

    @staticmethod
    def perform(designator: MotionDesignator, world: BulletWorld | None = None) -> Any:
        world = world if world is not None else BulletWorld.current_bullet_world
        if world is None or not world.alive:
            raise WorldError("no BulletWorld to perform the designator in (create one first)")
        return _perform(world, designator.type, designator.slots).result
