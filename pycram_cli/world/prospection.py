"""Prospection: a private copy of a world in a PyBullet client of its own, where queries try things out.

Reasoning queries that simulate (stable) or try joint values (reachable's forward check,
blocking's contacts at the solution) must leave the world exactly as they found it —
including what PyBullet does not let us read or put back: the broadphase's pairs and their
order, contact manifolds and the solver's warm starts. saveState/restoreState puts poses,
velocities and joints back bitwise but not these, so a world that was queried and then
simulated drifts away from an identical world that was never queried.

So those queries never write to the world: they run on its prospection copy, which is
brought in sync first (every object's base pose and velocity, its joints' positions and
velocities, the attachments, gravity). The world itself is only read. A world makes its
prospection on first use (loading a copy of every object, about as long as loading the
world) and closes it when it exits; syncing costs a few PyBullet calls per object.
"""
from __future__ import annotations

import warnings

import pybullet as p

from .bullet_world import BulletWorld
from .object import Attachment, Object


class Prospection:
    """The copy of one world (`copy`), with each object's copy in the same order."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self.copy = BulletWorld(mode="direct", gravity=world.gravity, _hidden=True)
        p.setPhysicsEngineParameter(deterministicOverlappingPairs=1, physicsClientId=self.copy.client_id)
        self._pairs: list[tuple[Object, Object]] = []  # (object, its copy), in the world's order
        self._copies: dict[int, Object] = {}  # by id() of the object (the pairs keep both alive)
        self._originals: dict[int, Object] = {}

    # -- the copies -----------------------------------------------------------------------------------
    def copy_of(self, obj: Object) -> Object:
        """The copy of `obj` (the world must be in sync: see `sync`)."""
        try:
            return self._copies[id(obj)]
        except KeyError:
            raise KeyError(f"object '{obj.name}' has no copy in the prospection world") from None

    def original_of(self, copy: Object) -> Object:
        try:
            return self._originals[id(copy)]
        except KeyError:
            raise KeyError(f"'{copy.name}' is not a copy in this prospection world") from None

    def _rebuild(self) -> None:
        """Copies of exactly the world's objects, in its order (made again when objects came or went)."""
        for _, copy in self._pairs:
            copy.remove()
        self._pairs, self._copies, self._originals = [], {}, {}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the world warned about its models already
            for obj in self.world.objects:
                position, orientation = obj.get_pose()
                copy = Object(obj.name, obj.type, obj.path, position, orientation, world=self.copy,
                              color=obj._color, fixed=obj.fixed, mass=obj._mass)
                self._pairs.append((obj, copy))
        self._copies = {id(obj): copy for obj, copy in self._pairs}
        self._originals = {id(copy): obj for obj, copy in self._pairs}

    # -- keeping in sync -----------------------------------------------------------------------------
    def sync(self, objects: "list[Object] | None" = None, velocities: bool = True) -> None:
        """Give the copies the world's state: base poses (and velocities), joint positions (and velocities),
        attachments and gravity. `objects`: only these (their copies must exist), e.g. only the robot."""
        world = self.world
        if len(self._pairs) != len(world.objects) or any(a is not b for (a, _), b in zip(self._pairs, world.objects)):
            self._rebuild()
            objects = None
        source, target = world.client_id, self.copy.client_id
        if objects is None:
            self._forget_contacts()
        if tuple(self.copy.gravity) != tuple(world.gravity):
            self.copy.set_gravity(world.gravity)
        chosen = set(map(id, objects)) if objects is not None else None
        for original, copy in self._pairs:
            if chosen is not None and id(original) not in chosen:
                continue
            position, orientation = p.getBasePositionAndOrientation(original.id, physicsClientId=source)
            p.resetBasePositionAndOrientation(copy.id, position, orientation, physicsClientId=target)
            if velocities:
                linear, angular = p.getBaseVelocity(original.id, physicsClientId=source)
                p.resetBaseVelocity(copy.id, linear, angular, physicsClientId=target)
            movable = [j.index for j in original.movable_joints]
            if movable:
                states = p.getJointStates(original.id, movable, physicsClientId=source)
                for index, state in zip(movable, states):
                    p.resetJointState(copy.id, index, state[0], state[1] if velocities else 0.0,
                                      physicsClientId=target)
        if objects is None:
            self._sync_attachments()

    def _forget_contacts(self) -> None:
        """Drop every contact the copy remembers from earlier queries (points, warm starts, pair order).

        Each copy is moved far from every other and collision detection runs: no pair overlaps, so
        the broadphase drops them all with their contact manifolds. With the copy's overlapping pairs
        kept sorted (`deterministicOverlappingPairs`), the next step finds the pairs of the synced
        state in the same order whatever came before: an answer depends on the world's state only.
        """
        client = self.copy.client_id
        for index, (_, copy) in enumerate(self._pairs):
            p.resetBasePositionAndOrientation(copy.id, (0.0, 0.0, -1000.0 - 100.0 * index), (0, 0, 0, 1),
                                              physicsClientId=client)
        p.performCollisionDetection(physicsClientId=client)

    def _sync_attachments(self) -> None:
        copies = self._copies
        for _, copy in self._pairs:
            copy.attachments.clear()
        for original, _ in self._pairs:
            for att in original.attachments.values():
                if att.parent is not original:
                    continue
                parent, child = copies.get(id(att.parent)), copies.get(id(att.child))
                if parent is None or child is None:
                    continue
                twin = Attachment(parent, child, att.parent_link, att.child_link, att.transform)
                parent.attachments[child] = twin
                child.attachments[parent] = twin

    def close(self) -> None:
        self.copy.exit()
        self._pairs, self._copies, self._originals = [], {}, {}
