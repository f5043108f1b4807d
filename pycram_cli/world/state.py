"""Saving and restoring a world exactly.

PyBullet's own saveState/restoreState puts poses, joint positions and velocities back
bitwise in about 0.1 ms; it knows nothing of our attachments, which live in Python and are
copied alongside. It does not put back everything the next simulation step depends on — the
broadphase's pairs and their order, contact manifolds and warm starts — so a world that was
saved, simulated and restored then simulates slightly differently from one that never was.
Queries therefore try things on a prospection copy instead (see prospection.py).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import pybullet as p

if TYPE_CHECKING:
    from .bullet_world import BulletWorld
    from .object import Attachment


class StateError(RuntimeError):
    """A saved state that cannot be restored (objects were added or removed since)."""


@dataclass(frozen=True)
class WorldState:
    state_id: int
    body_ids: tuple[int, ...]
    attachments: tuple["Attachment", ...]


def _all_attachments(world: "BulletWorld") -> tuple["Attachment", ...]:
    seen: dict[int, Attachment] = {}
    for obj in world.objects:
        for att in obj.attachments.values():
            seen[id(att)] = att
    return tuple(seen.values())


def capture(world: "BulletWorld") -> WorldState:
    state_id = p.saveState(physicsClientId=world.client_id)
    return WorldState(state_id, tuple(o.id for o in world.objects), _all_attachments(world))


def restore(world: "BulletWorld", state: WorldState) -> None:
    bodies = tuple(o.id for o in world.objects)
    if bodies != state.body_ids:
        raise StateError(
            f"cannot restore: the world had {len(state.body_ids)} objects when saved and has {len(bodies)} now "
            "(objects were added or removed since)"
        )
    p.restoreState(stateId=state.state_id, physicsClientId=world.client_id)
    for obj in world.objects:
        obj.attachments.clear()
    for att in state.attachments:
        att.parent.attachments[att.child] = att
        att.child.attachments[att.parent] = att


def release(world: "BulletWorld", state: WorldState) -> None:
    if world.alive:
        p.removeState(state.state_id, physicsClientId=world.client_id)
