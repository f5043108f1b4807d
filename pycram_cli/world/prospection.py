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
world) and closes it when it exits; syncing costs a few PyBullet calls per object, and only
for objects that changed (versions, see BulletWorld.version): a run of queries on an unchanged
world reads the world once, and each query after the first only writes back the copies it
changed (after forgetting the contacts a simulation left in the copy).
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import pybullet as p

from .bullet_world import BulletWorld
from .object import Object
from .parts import Attachment


@dataclass(frozen=True)
class _State:
    """One object's state as read from its world (PyBullet's raw numbers, written back bitwise)."""

    version: int
    pose: tuple
    velocity: tuple
    joints: list[int]  # lists: resetJointStatesMultiDof crashes on tuples (pybullet 3.2.7)
    positions: list[list[float]]
    speeds: list[list[float]]


def _read(obj: Object, version: int) -> _State:
    client = obj.world.client_id
    pose = p.getBasePositionAndOrientation(obj.id, physicsClientId=client)
    velocity = p.getBaseVelocity(obj.id, physicsClientId=client)
    joints = [j.index for j in obj.movable_joints]
    states = p.getJointStates(obj.id, joints, physicsClientId=client) if joints else ()
    return _State(version, pose, velocity, joints, [[s[0]] for s in states], [[s[1]] for s in states])


def _write(copy: Object, state: _State) -> None:
    client = copy.world.client_id
    p.resetBasePositionAndOrientation(copy.id, *state.pose, physicsClientId=client)
    p.resetBaseVelocity(copy.id, *state.velocity, physicsClientId=client)
    if state.joints:
        p.resetJointStatesMultiDof(copy.id, state.joints, state.positions, state.speeds, physicsClientId=client)


class Prospection:
    """The copy of one world (`copy`), with each object's copy in the same order."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self.copy = BulletWorld(mode="direct", gravity=world.gravity, _hidden=True)
        self.copy._step_watchers = world._copy_watchers  # the world's watchers of its copy's steps (watch_steps)
        self._pairs: list[tuple[Object, Object]] = []  # (object, its copy), in the world's order
        self._copies: dict[int, Object] = {}  # by id() of the object (the pairs keep both alive)
        self._originals: dict[int, Object] = {}
        self._read: list[_State | None] = []  # each object's state as last read from the world
        self._written: list[int | None] = []  # each copy's version right after it was last written
        self._forgotten_at = -1  # the copy's last step when its contacts were last forgotten
        self._clean: tuple[int, int] | None = None  # (world, copy) versions right after the last full sync

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
        self._read = [None] * len(self._pairs)
        self._written = [None] * len(self._pairs)
        self._forgotten_at = -1
        self._clean = None

    # -- keeping in sync -----------------------------------------------------------------------------
    def sync(self, objects: list[Object] | None = None, velocities: bool = True) -> None:
        """Give the copies the world's state: base poses and velocities, joint positions and velocities,
        attachments and gravity. `objects`: only these (their copies must exist), e.g. only the robot.

        Once per world change: each object is read from the world only when its version changed since
        it was last read, and a copy is written only when it or its original changed since it was last
        written; a full sync of an unchanged world into an untouched copy costs nothing at all.
        `velocities` is kept for callers that do not need them; they are always copied (two calls).
        """
        world, copy = self.world, self.copy
        if len(self._pairs) != len(world.objects) or any(a is not b for (a, _), b in zip(self._pairs, world.objects)):
            self._rebuild()
            objects = None
        if objects is None:
            if self._clean == (world.version, copy.version):
                return  # nothing changed on either side since the last full sync
            if copy._stepped > self._forgotten_at:
                self._forget_contacts()
        if tuple(copy.gravity) != tuple(world.gravity):
            copy.set_gravity(world.gravity)
        chosen = set(map(id, objects)) if objects is not None else None
        for index, (original, twin) in enumerate(self._pairs):
            if chosen is not None and id(original) not in chosen:
                continue
            read = self._read[index]
            version = world.version_of(original)
            if read is None or read.version != version:
                read = self._read[index] = _read(original, version)
            elif self._written[index] == copy.version_of(twin):
                continue  # neither side changed since this copy was written
            _write(twin, read)
            self._written[index] = copy.version_of(twin)
        if objects is None:
            self._sync_attachments()
            self._clean = (world.version, copy.version)

    def _forget_contacts(self) -> None:
        """Drop every contact the copy remembers from earlier queries (points, warm starts, pair order).

        Each copy is moved far from every other and collision detection runs: no pair overlaps, so
        the broadphase drops them all with their contact manifolds. With the copy's overlapping pairs
        kept sorted (`deterministicOverlappingPairs`), the next step finds the pairs of the synced
        state in the same order whatever came before: an answer depends on the world's state only.
        """
        self.copy.drop_contacts()  # (the copy's objects are exactly the pairs' copies, in their order)
        self._written = [None] * len(self._pairs)  # every copy was moved: each must be written again
        self._forgotten_at = self.copy._stepped

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
