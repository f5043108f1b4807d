"""The design's `pycram.bullet_world_reasoning` (thesis §4.4): the reasoning queries with the design's argument
orders and plain answers (True/False, lists of objects), over pycram's queries (`pycram_cli.reasoning`).

    btr.stable(bottle)                                   btr.contact(kitchen, bottle, world)
    btr.visible(bottle, robot.get_link_position("wide_stereo_optical_frame"))
    btr.occluding(bottle, camera_position)               btr.supporting(kitchen, bottle)
    btr.reachable(bottle, robot, "r_gripper_tool_frame") btr.reachable_pose([x, y, z], robot, "r_gripper_tool_frame")
    btr.blocking(bottle, robot, "r_gripper_tool_frame")  raise btr.ReasoningError
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ..failures import PerceptionError, ReasoningError
from ..reasoning import blocking as _blocking
from ..reasoning import contact as _contact
from ..reasoning import occluding as _occluding
from ..reasoning import reachable as _reachable
from ..reasoning import stable as _stable
from ..reasoning import supporting as _supporting
from ..reasoning import visible as _visible
from ..world import BulletWorld, Object

__all__ = ["stable", "contact", "visible", "occluding", "reachable", "reachable_pose", "blocking", "supporting",
           "ReasoningError", "PerceptionError"]


def _in(world: BulletWorld | None, *objects: Object) -> None:
    if world is not None:
        for obj in objects:
            if obj.world is not world:
                raise ValueError(f"object '{obj.name}' is not in the given world")


def stable(obj: Object, world: BulletWorld | None = None) -> bool:
    """Whether `obj` stays put (1 mm, 1°) while the world is simulated for 2 s."""
    return bool(_stable(obj, world, observe=0.0))  # the verdict only


def contact(object1: Object, object2: Object, world: BulletWorld | None = None) -> bool:
    """Whether the two objects touch (within 5 mm)."""
    _in(world, object1, object2)
    return bool(_contact(object1, object2))


def visible(obj: Object, camera_position: Sequence[float] | str | None = None, world: BulletWorld | None = None,
            threshold: float = 0.8) -> bool:
    """Whether at least 80 % of `obj` is seen from a camera position (default: the robot's camera)."""
    return bool(_visible(obj, camera_position, world, threshold))


def occluding(obj: Object, camera_position: Sequence[float] | str | None = None,
              world: BulletWorld | None = None) -> list[Object]:
    """The objects in front of `obj` seen from a camera position."""
    return _occluding(obj, camera_position, world)


def reachable(obj: Object, robot: Object, gripper_name: str, threshold: float = 0.01) -> bool:
    """Whether the robot's gripper (a link) reaches the object's position within `threshold` m."""
    return bool(_reachable(obj, robot, gripper_name, threshold=threshold))


def reachable_pose(pose: Any, robot: Object, gripper_name: str, threshold: float = 0.01) -> bool:
    """Whether the gripper reaches a position [x, y, z] (or a pose (position, orientation)) within `threshold` m."""
    return bool(_reachable(pose, robot, gripper_name, threshold=threshold))


def blocking(obj: Object, robot: Object, gripper_name: str, world: BulletWorld | None = None) -> list[Object]:
    """The objects the robot would touch reaching for the object (the design filters the environment afterwards)."""
    _in(world, obj, robot)
    return _blocking(obj, robot, gripper_name)


def supporting(object1: Object, object2: Object, world: BulletWorld | None = None) -> bool:
    """Whether `object1` carries `object2` (object2 on top, in contact)."""
    _in(world, object1, object2)
    return _supporting(object1, object2)
