"""ViewRenderer: renders chosen parts of a world's objects, and nothing else, in the world's private copy.

PyBullet's TinyRenderer touches every triangle of every body in its client for every picture,
however small the picture and wherever the body is: on the real PR2 in the real kitchen a 32×32
window costs 15 ms, of which the object asked about is 0.4 ms. It skips bodies whose colour has
alpha 0. So pictures are taken in the world's prospection client (prospection.py: a private
DIRECT client holding a copy of every object, brought in sync with the world once per change),
where every link is drawn with alpha 0 unless the picture needs it: before a picture the needed
links get alpha 1, the others alpha 0 again (only the links whose state changes are touched).
The world itself is never touched — no colours to hide and restore, no bodies to move — and no
model is loaded twice. Colours do not matter here (nor to physics): the pictures are
segmentation (which object each pixel shows, given back with the world's object ids) and depth.
"""
from __future__ import annotations

import weakref
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
import pybullet as p

from .camera import segmentation_and_depth

if TYPE_CHECKING:
    from .bullet_world import BulletWorld
    from .object import Object

SHOWN = (1.0, 1.0, 1.0, 1.0)
HIDDEN = (1.0, 1.0, 1.0, 0.0)


class ViewRenderer:
    """Pictures of any choice of a world's links, from the world's prospection copy."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        # for each copy: the links it draws at all, and those drawn now
        self._links: weakref.WeakKeyDictionary[Object, tuple[list[int], set[int]]] = weakref.WeakKeyDictionary()
        self._showing: weakref.WeakSet[Object] = weakref.WeakSet()  # the copies with links drawn now

    def picture(self, parts: Mapping[Object, Sequence[int] | None], width: int, height: int,
                view: Sequence[float], projection: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
        """(height, width) world object ids seen at each pixel (-1: nothing) when only `parts` are drawn — for
        each object the links to draw (by index, -1: the base), or None for all — and the depth buffer
        (0..1, growing with distance; 1 where nothing is)."""
        twin = self.world.prospection()
        client = twin.copy.client_id
        for copy in twin.copy.objects:  # copies seen for the first time: hidden
            if copy not in self._links:
                self._drawn(twin.original_of(copy), copy)
        wanted: dict[int, tuple[Object, set[int]]] = {}
        for obj, links in parts.items():
            copy = twin.copy_of(obj)
            drawn = self._drawn(obj, copy)
            wanted[id(copy)] = (copy, set(drawn) if links is None else set(links) & set(drawn))
        showing = {id(c): c for c in self._showing if c in self._links}
        for key in set(wanted) | set(showing):
            copy, chosen = wanted.get(key) or (showing[key], set())
            drawn, shown = self._links[copy]
            for link in shown - chosen:
                p.changeVisualShape(copy.id, link, rgbaColor=HIDDEN, physicsClientId=client)
            for link in chosen - shown:
                p.changeVisualShape(copy.id, link, rgbaColor=SHOWN, physicsClientId=client)
            self._links[copy] = (drawn, chosen)
        self._showing = weakref.WeakSet(c for c, chosen in wanted.values() if chosen)
        seg, depth = segmentation_and_depth(client, width, height, view, projection)
        ids = np.full(max([c.id for c in twin.copy.objects], default=0) + 2, -1, dtype=np.int64)
        for copy in twin.copy.objects:
            ids[copy.id] = twin.original_of(copy).id
        return ids[seg], depth  # -1 stays -1 (the last entry)

    def _drawn(self, original: Object, copy: Object) -> list[int]:
        """The links of a copy to manage: those its original draws. A copy seen for the first time is hidden."""
        known = self._links.get(copy)
        if known is not None:
            return known[0]
        drawn = [link for link, _ in original.drawn_links()]
        client = copy.world.client_id
        for row in p.getVisualShapeData(copy.id, physicsClientId=client):
            p.changeVisualShape(copy.id, row[1], rgbaColor=HIDDEN, physicsClientId=client)
        self._links[copy] = (drawn, set())
        return drawn
