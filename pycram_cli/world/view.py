"""ViewRenderer: a private DIRECT client that renders chosen parts of a world's objects, and nothing else.

PyBullet's TinyRenderer touches every triangle of every body in its client for every picture,
however small the picture and wherever the body is: on the real PR2 in the real kitchen a 32×32
window costs 15 ms, of which the object asked about is 0.4 ms. It skips bodies whose colour has
alpha 0. So this client holds a copy of each object it was asked to draw (same model file,
loaded with a fixed base: no physics here), every link drawn with alpha 0 unless the picture
needs it; before a picture the needed links get alpha 1 and the copies that changed since they
were last drawn (object versions, see BulletWorld.version) take the object's pose and joint
positions. The world itself is never touched — no colours to hide and restore, no bodies to move.
Colours do not matter here: it renders segmentation (which object each pixel shows), given
back with the world's object ids. A world makes its ViewRenderer on first use and closes it
when it exits.
"""
from __future__ import annotations

import weakref
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Mapping, Sequence

import numpy as np
import pybullet as p

from .camera import segmentation_and_depth
from .model_files import MESH_SUFFIXES, mesh_urdf, prepare_urdf
from ..quiet import silenced

if TYPE_CHECKING:
    from .object import Object

SHOWN = (1.0, 1.0, 1.0, 1.0)
HIDDEN = (1.0, 1.0, 1.0, 0.0)


@dataclass
class _Copy:
    original: "weakref.ref[Object]"
    body: int
    links: list[int]  # the links with visual shapes
    version: int | None = None  # the original's version it was last placed at
    shown: set[int] = field(default_factory=set)  # links drawn now


class ViewRenderer:
    """A DIRECT client holding copies of the objects asked about, to render any choice of their links."""

    def __init__(self) -> None:
        with silenced():
            self.client: int = p.connect(p.DIRECT)
        self._copies: dict[int, _Copy] = {}  # by id() of the original object
        self._finalizer = weakref.finalize(self, _disconnect, self.client)

    def segmentation(self, parts: Mapping["Object", Sequence[int] | None], width: int, height: int,
                     view: Sequence[float], projection: Sequence[float]) -> np.ndarray:
        """(height, width) world object ids seen at each pixel (-1: nothing) when only `parts` are drawn:
        for each object the links to draw (by index, -1: the base), or None for all of them."""
        return self.picture(parts, width, height, view, projection)[0]

    def picture(self, parts: Mapping["Object", Sequence[int] | None], width: int, height: int,
                view: Sequence[float], projection: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
        """`segmentation` and the picture's depth buffer (0..1, growing with distance; 1: nothing)."""
        wanted: dict[int, tuple[_Copy, set[int]]] = {}
        for obj, links in parts.items():
            copy = self._copy_of(obj)
            chosen = set(copy.links) if links is None else set(links) & set(copy.links)
            if chosen:
                wanted[id(obj)] = (copy, chosen)
                self._place(obj, copy)
        for key, copy in self._copies.items():
            self._show(copy, wanted[key][1] if key in wanted else set())
        seg, depth = segmentation_and_depth(self.client, width, height, view, projection)
        ids = np.full(max([c.body for c in self._copies.values()], default=0) + 2, -1, dtype=np.int64)
        for copy in self._copies.values():
            original = copy.original()
            if original is not None:
                ids[copy.body] = original.id
        return ids[seg], depth  # -1 stays -1 (the last entry)

    def close(self) -> None:
        """Disconnect the private client (also done when the renderer is garbage-collected)."""
        self._finalizer()

    # -- copies -------------------------------------------------------------------------------------------
    def _copy_of(self, obj: "Object") -> _Copy:
        copy = self._copies.get(id(obj))
        if copy is not None and copy.original() is obj:
            return copy
        if copy is not None:  # a copy of an object gone, whose id() was taken again
            p.removeBody(copy.body, physicsClientId=self.client)
        if obj.path.suffix.lower() in MESH_SUFFIXES:
            path = mesh_urdf(obj.path, None)
        else:
            path = prepare_urdf(obj.path).path
        with silenced():
            body = p.loadURDF(str(path), useFixedBase=True, physicsClientId=self.client)
        if body < 0:
            raise RuntimeError(f"could not load a copy of '{obj.name}' to render it")
        links = [link for link, _ in obj.drawn_links()]  # as the world draws them (not the fully transparent)
        copy = _Copy(weakref.ref(obj), body, links, shown=set(links))
        self._show(copy, set())
        self._copies[id(obj)] = copy
        return copy

    def _show(self, copy: _Copy, links: set[int]) -> None:
        """Draw exactly `links` of a copy (changing only the links whose state differs)."""
        for link in copy.shown - links:
            p.changeVisualShape(copy.body, link, rgbaColor=HIDDEN, physicsClientId=self.client)
        for link in links - copy.shown:
            p.changeVisualShape(copy.body, link, rgbaColor=SHOWN, physicsClientId=self.client)
        copy.shown = set(links)

    def _place(self, obj: "Object", copy: _Copy) -> None:
        """Give the copy the object's pose and joint positions (PyBullet's own numbers), unless it has them."""
        version = obj.version
        if copy.version == version:
            return
        position, orientation = obj.get_com_pose()
        p.resetBasePositionAndOrientation(copy.body, position, orientation, physicsClientId=self.client)
        if obj.movable_joints:
            positions = obj.get_joint_positions()
            joints = [j.index for j in obj.movable_joints]
            # lists: resetJointStatesMultiDof crashes on tuples (pybullet 3.2.7)
            p.resetJointStatesMultiDof(copy.body, joints, [[positions[j.name]] for j in obj.movable_joints],
                                       [[0.0] for _ in joints], physicsClientId=self.client)
        copy.version = version


def _disconnect(client: int) -> None:
    try:
        p.disconnect(physicsClientId=client)
    except Exception:  # noqa: BLE001 - already gone at interpreter exit
        pass
