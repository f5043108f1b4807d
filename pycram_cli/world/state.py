"""Saving and restoring a world exactly.

PyBullet's own saveState/restoreState puts poses, joint positions and velocities back
bitwise in about 0.1 ms; it knows nothing of our attachments, which live in Python and are
copied alongside. It does not put back everything the next simulation step depends on — the
broadphase's pairs and their order, contact manifolds and warm starts — so a world that was
saved, simulated and restored then simulates slightly differently from one that never was.
Queries therefore try things on a prospection copy instead (see prospection.py).

saveState costs far more than restoreState (it serialises every collision shape: 4 ms on the
bundled kitchen, 11-20 ms with the real models), so a world saves once per change: while its
version (bullet_world.py) stays, `save_state` hands out the state it saved last, and restoring
a state gives the world that state's versions back, so a snapshot taken again right after a
restore costs nothing. A state is freed once every holder released it and it is not the one kept.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import pybullet as p

if TYPE_CHECKING:
    from .bullet_world import BulletWorld
    from .parts import Attachment


class StateError(RuntimeError):
    """A saved state that cannot be restored (objects were added or removed since)."""


@dataclass(frozen=True)
class WorldState:
    state_id: int
    body_ids: tuple[int, ...]
    attachments: tuple[Attachment, ...]
    #: the world's versions when saved: its own, its last step's, and each object's (in world order)
    version: int = 0
    stepped: int = 0
    object_versions: tuple[int, ...] = ()


def _all_attachments(world: BulletWorld) -> tuple[Attachment, ...]:
    seen: dict[int, Attachment] = {}
    for obj in world.objects:
        for att in obj.attachments.values():
            seen[id(att)] = att
    return tuple(seen.values())


def capture(world: BulletWorld) -> WorldState:
    state_id = p.saveState(physicsClientId=world.client_id)
    return WorldState(state_id, tuple(o.id for o in world.objects), _all_attachments(world), world._version,
                      world._stepped, tuple(o._version for o in world.objects))


def restore(world: BulletWorld, state: WorldState) -> None:
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
    # the world is as it was at those versions again (poses, velocities, joints, attachments)
    world._version, world._stepped = state.version, state.stepped
    for obj, version in zip(world.objects, state.object_versions):
        obj._version = version


def release(world: BulletWorld, state: WorldState) -> None:
    if world.alive:
        p.removeState(state.state_id, physicsClientId=world.client_id)


class StateCache:
    """A world's saved states: one saveState per world version, freed when nobody holds them."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self.kept: WorldState | None = None  # the newest state saved or restored
        self.holders: dict[int, int] = {}  # state id -> how many save_state calls hold it

    def save(self) -> WorldState:
        world = self.world
        kept = self.kept
        if kept is not None and world.tracks_changes and kept.version == world._version:
            self.holders[kept.state_id] = self.holders.get(kept.state_id, 0) + 1
            return kept
        state = capture(world)
        self.holders[state.state_id] = 1
        self._keep(state)
        return state

    def restore(self, state: WorldState) -> None:
        restore(self.world, state)
        if state.state_id in self.holders or state is self.kept:
            self._keep(state)

    def release(self, state: WorldState) -> None:
        count = self.holders.get(state.state_id, 0) - 1
        if count > 0:
            self.holders[state.state_id] = count
            return
        self.holders.pop(state.state_id, None)
        if state is not self.kept:
            release(self.world, state)

    def _keep(self, state: WorldState) -> None:
        old, self.kept = self.kept, state
        if old is not None and old is not state and old.state_id not in self.holders:
            release(self.world, old)
