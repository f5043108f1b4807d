"""SoloRenderer: a private DIRECT client that renders one object of a world alone.

It holds a copy of each object it was asked about (same model file); before rendering, the
copy takes the object's pose and joint positions, and afterwards it is parked far out of
view. The world itself is never touched — no colours to hide and restore, no bodies to move.
A world makes its own SoloRenderer on first use and closes it when it exits.
"""
from __future__ import annotations

import weakref
from typing import TYPE_CHECKING, Sequence

import numpy as np
import pybullet as p

from .camera import segmentation
from .model_files import MESH_SUFFIXES, mesh_urdf, prepare_urdf
from ..quiet import silenced

if TYPE_CHECKING:
    from .object import Object


class SoloRenderer:
    """A DIRECT client holding copies of the objects asked about, to render each of them alone."""

    def __init__(self) -> None:
        with silenced():
            self.client: int = p.connect(p.DIRECT)
        self._bodies: dict[int, tuple[weakref.ref, int]] = {}
        self._finalizer = weakref.finalize(self, _disconnect, self.client)

    def mask(self, obj: "Object", width: int, height: int, view: Sequence[float],
             projection: Sequence[float]) -> np.ndarray:
        """(height, width) booleans: True where `obj`, rendered with nothing else, covers the pixel."""
        body = self._body_for(obj)
        self._place(obj, body)
        try:
            return segmentation(self.client, width, height, view, projection) == body
        finally:
            self._park(body)

    def close(self) -> None:
        """Disconnect the private client (also done when the renderer is garbage-collected)."""
        self._finalizer()

    def _body_for(self, obj: "Object") -> int:
        entry = self._bodies.get(id(obj))
        if entry is not None and entry[0]() is obj:
            return entry[1]
        if obj.path.suffix.lower() in MESH_SUFFIXES:
            path = mesh_urdf(obj.path, None)
        else:
            path = prepare_urdf(obj.path).path
        with silenced():
            body = p.loadURDF(str(path), useFixedBase=True, physicsClientId=self.client)
        if body < 0:
            raise RuntimeError(f"could not load a copy of '{obj.name}' to render it alone")
        self._bodies[id(obj)] = (weakref.ref(obj), body)
        return body

    def _park(self, body: int) -> None:
        """Put a copy out of every view (each copy has its own spot far below the world)."""
        p.resetBasePositionAndOrientation(body, (0.0, 0.0, -1000.0 - 50.0 * body), (0, 0, 0, 1),
                                          physicsClientId=self.client)

    def _place(self, obj: "Object", body: int) -> None:
        """Give the copy the object's pose and joint positions (both PyBullet's, so the copy matches exactly)."""
        position, orientation = obj.get_com_pose()
        p.resetBasePositionAndOrientation(body, position, orientation, physicsClientId=self.client)
        if obj.movable_joints:
            positions = obj.get_joint_positions()
            for joint in obj.movable_joints:
                p.resetJointState(body, joint.index, positions[joint.name], 0.0, physicsClientId=self.client)


def _disconnect(client: int) -> None:
    try:
        p.disconnect(physicsClientId=client)
    except Exception:  # noqa: BLE001 - already gone at interpreter exit
        pass
