"""The design's `pycram.bullet_world`: BulletWorld and Event are pycram's own (they keep the design's names and
argument orders); Object is pycram's, and a robot made with it takes its description's defaults (the torso height),
as a robot loaded from a world file does. See `pycram_cli.design` for the one difference, `get_pose`."""
from __future__ import annotations

from typing import Any

from ..robots import description_for
from ..world import BulletWorld, Event
from ..world import Object as _Object

__all__ = ["BulletWorld", "Object", "Event"]


class Object(_Object):
    """`Object(name, type, path, position, orientation, world, color)`, as in the design."""

    def __init__(self, name: str, type: str, path: Any, position: Any = (0.0, 0.0, 0.0),
                 orientation: Any = (0.0, 0.0, 0.0, 1.0), world: BulletWorld | None = None, color: Any = None,
                 **options: Any) -> None:
        super().__init__(name, type, path, position, orientation, world=world, color=color, **options)
        if type == "robot":
            description = description_for(self)
            if description is not None:
                self.set_joint_positions(description.default_joints())
