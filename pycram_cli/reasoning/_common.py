"""Helpers shared by the reasoning queries: finding the objects' world, and what follows an object."""
from __future__ import annotations

from typing import TYPE_CHECKING

from ..world import BulletWorld, WorldError

if TYPE_CHECKING:
    from ..world import Object


def world_of(obj: Object, world: BulletWorld | None = None) -> BulletWorld:
    """The world `obj` lives in (a `world` argument, if given, must be that world)."""
    if world is not None and obj.world is not world:
        raise WorldError(f"object '{obj.name}' is not in the given world")
    if not obj.world.alive:
        raise WorldError(f"object '{obj.name}': its world has exited")
    return obj.world


def same_world(*objects: Object) -> BulletWorld:
    world = objects[0].world
    for obj in objects[1:]:
        if obj.world is not world:
            raise WorldError(f"'{objects[0].name}' and '{obj.name}' are in different worlds")
    if not world.alive:
        raise WorldError("the objects' world has exited")
    return world


def attached_descendants(obj: Object) -> list[Object]:
    """Every object that follows `obj` (its attached children, theirs, ...), in a stable order."""
    found: list[Object] = []
    seen = {obj.id}
    frontier = [obj]
    while frontier:
        parent = frontier.pop(0)
        for child, att in sorted(parent.attachments.items(), key=lambda kv: kv[0].id):
            if att.parent is parent and child.id not in seen:
                seen.add(child.id)
                found.append(child)
                frontier.append(child)
    return found
