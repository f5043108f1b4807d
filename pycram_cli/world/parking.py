"""Parking: taking objects out of a simulation for a while and putting them back exactly.

A query that simulates one object's neighbourhood (stable) need not pay for the rest of the
world: every body a step simulates costs solver work — for a fixed robot or kitchen, its joint
motors and contacts cost more than everything else (0.5 ms per step for the real PR2's 45 held
joints). PyBullet cannot switch a body off, and putting it to sleep in place does not last:
a sleeping body that shares a simulation island with an awake one (everything resting on the
same kitchen does) is woken at the next step. So a parked body is moved to a spot of its own
far below the world, where it touches nothing, is put to sleep (alone in its island, it stays
asleep and costs nothing per step) and, if it holds joints with motors, has their force set to
zero. Putting it back writes its saved pose, velocity and joints back bitwise and gives the
motors their force again. The joints of a fixed object that stays (a kitchen's far drawers and
doors) can be loosened alike: their motors lose their force until put back. Meant for a world's private copy
(prospection.py): the world a user sees should never have bodies vanish, even briefly.
"""
from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import pybullet as p

from .object import HOLD_FORCE

if TYPE_CHECKING:
    from .bullet_world import BulletWorld
    from .object import Object

#: where the parked bodies go: each its own spot, 50 m from the next, 2 km below the world
SPOT_DEPTH = -2000.0
SPOT_SPACING = 50.0


@dataclass(frozen=True)
class _Saved:
    pose: tuple
    velocity: tuple
    joints: list[int]
    positions: list[list[float]]
    speeds: list[list[float]]


class Parking:
    """The objects of one world parked for a while (see the module's text)."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self._saved: dict[int, _Saved] = {}  # by object id
        self._objects: dict[int, Object] = {}
        self._loose: dict[tuple[int, int], tuple[Object, float, float]] = {}  # (body, joint): state

    @property
    def parked(self) -> list[Object]:
        return list(self._objects.values())

    def __contains__(self, obj: Object) -> bool:
        return obj.id in self._objects

    def park(self, objects: Iterable[Object]) -> None:
        """Take `objects` out of the simulation (their state is kept to put them back)."""
        client = self.world.client_id
        for obj in objects:
            if obj.id in self._objects:
                continue
            joints = [j.index for j in obj.movable_joints]
            states = p.getJointStates(obj.id, joints, physicsClientId=client) if joints else ()
            self._saved[obj.id] = _Saved(p.getBasePositionAndOrientation(obj.id, physicsClientId=client),
                                         p.getBaseVelocity(obj.id, physicsClientId=client), joints,
                                         [[s[0]] for s in states], [[s[1]] for s in states])
            self._objects[obj.id] = obj
            spot = (SPOT_SPACING * obj.id, 0.0, SPOT_DEPTH)
            p.resetBasePositionAndOrientation(obj.id, spot, (0.0, 0.0, 0.0, 1.0), physicsClientId=client)
            p.resetBaseVelocity(obj.id, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), physicsClientId=client)
            if obj.fixed and joints:
                p.setJointMotorControlArray(obj.id, joints, p.VELOCITY_CONTROL, targetVelocities=[0.0] * len(joints),
                                            forces=[0.0] * len(joints), physicsClientId=client)
            # bodies are loaded unable to sleep (URDF_ENABLE_SLEEPING not given): allow it, then sleep
            p.changeDynamics(obj.id, -1, activationState=p.ACTIVATION_STATE_ENABLE_SLEEPING, physicsClientId=client)
            p.changeDynamics(obj.id, -1, activationState=p.ACTIVATION_STATE_SLEEP, physicsClientId=client)
            self.world.mark_changed(obj)

    def loosen(self, obj: Object, joints: list[int]) -> None:
        """Stop holding these joints of a fixed object (by index) for a while: their motors cost solver work
        every step. For joints nothing simulated can come near; `put_back` holds them again where they were."""
        client = self.world.client_id
        joints = [j for j in joints if (obj.id, j) not in self._loose]
        if not joints:
            return
        states = p.getJointStates(obj.id, joints, physicsClientId=client)
        for joint, state in zip(joints, states):
            self._loose[(obj.id, joint)] = (obj, state[0], state[1])
        p.setJointMotorControlArray(obj.id, joints, p.VELOCITY_CONTROL, targetVelocities=[0.0] * len(joints),
                                    forces=[0.0] * len(joints), physicsClientId=client)
        self.world.mark_changed(obj)

    def put_back(self, objects: Iterable[Object] | None = None) -> list[Object]:
        """Put `objects` (default: every parked one) back as they were when parked, awake; returns them."""
        client = self.world.client_id
        chosen = list(self._objects.values()) if objects is None else [o for o in objects if o.id in self._objects]
        for obj in chosen:
            saved = self._saved.pop(obj.id)
            del self._objects[obj.id]
            p.resetBasePositionAndOrientation(obj.id, *saved.pose, physicsClientId=client)
            p.resetBaseVelocity(obj.id, *saved.velocity, physicsClientId=client)
            if saved.joints:
                # lists: resetJointStatesMultiDof crashes on tuples (pybullet 3.2.7)
                p.resetJointStatesMultiDof(obj.id, saved.joints, saved.positions, saved.speeds,
                                           physicsClientId=client)
                if obj.fixed:
                    p.setJointMotorControlArray(obj.id, saved.joints, p.VELOCITY_CONTROL,
                                                targetVelocities=[0.0] * len(saved.joints),
                                                forces=[HOLD_FORCE] * len(saved.joints), physicsClientId=client)
            p.changeDynamics(obj.id, -1, activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING, physicsClientId=client)
            p.changeDynamics(obj.id, -1, activationState=p.ACTIVATION_STATE_WAKE_UP, physicsClientId=client)
            self.world.mark_changed(obj)
        if objects is None:
            for (body, joint), (obj, position, velocity) in sorted(self._loose.items()):
                p.resetJointState(body, joint, position, velocity, physicsClientId=client)
                p.setJointMotorControl2(body, joint, p.VELOCITY_CONTROL, targetVelocity=0.0, force=HOLD_FORCE,
                                        physicsClientId=client)
                self.world.mark_changed(obj)
            self._loose.clear()
        return chosen
