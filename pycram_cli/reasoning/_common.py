"""Helpers shared by the reasoning queries: finding the world, and undoing exactly what a query changed."""
from __future__ import annotations

from typing import TYPE_CHECKING, Iterable, Sequence

import pybullet as p

from ..world import BulletWorld, WorldError

if TYPE_CHECKING:
    from ..world import Object


def world_of(obj: "Object", world: BulletWorld | None = None) -> BulletWorld:
    """The world `obj` lives in (a `world` argument, if given, must be that world)."""
    if world is not None and obj.world is not world:
        raise WorldError(f"object '{obj.name}' is not in the given world")
    if not obj.world.alive:
        raise WorldError(f"object '{obj.name}': its world has exited")
    return obj.world


def same_world(*objects: "Object") -> BulletWorld:
    world = objects[0].world
    for obj in objects[1:]:
        if obj.world is not world:
            raise WorldError(f"'{objects[0].name}' and '{obj.name}' are in different worlds")
    if not world.alive:
        raise WorldError("the objects' world has exited")
    return world


class JointUndo:
    """Remembers joint positions and velocities; `restore()` puts them back bitwise (resetJointState)."""

    def __init__(self, obj: "Object", joint_ids: Sequence[int]) -> None:
        self.obj = obj
        self.ids = list(joint_ids)
        cid = obj.world.client_id
        self.states = [(s[0], s[1]) for s in p.getJointStates(obj.id, self.ids, physicsClientId=cid)] if self.ids else []

    def restore(self) -> None:
        cid = self.obj.world.client_id
        for jid, (pos, vel) in zip(self.ids, self.states):
            p.resetJointState(self.obj.id, jid, pos, vel, physicsClientId=cid)


class BaseUndo:
    """Remembers base poses and velocities of some objects; `restore()` puts them back bitwise."""

    def __init__(self, objects: Iterable["Object"]) -> None:
        self.saved = []
        for obj in objects:
            cid = obj.world.client_id
            pos, orn = p.getBasePositionAndOrientation(obj.id, physicsClientId=cid)
            lin, ang = p.getBaseVelocity(obj.id, physicsClientId=cid)
            self.saved.append((obj, pos, orn, lin, ang))

    def restore(self) -> None:
        for obj, pos, orn, lin, ang in self.saved:
            cid = obj.world.client_id
            p.resetBasePositionAndOrientation(obj.id, pos, orn, physicsClientId=cid)
            p.resetBaseVelocity(obj.id, lin, ang, physicsClientId=cid)


def attached_descendants(obj: "Object") -> list["Object"]:
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
