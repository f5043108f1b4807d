"""The boxes of a link's collision shapes, one per shape: what a compound link (a cabinet of panels, a handle bar
on a door) really occupies, where its one bounding box would fill the gaps between its parts.

PyBullet gives a link's bounding box only as a whole (`getAABB`). A kitchen cabinet made of panels, a plinth set back
under its doors and a handle bar out front is, as one box, solid from the handle to the wall and from the floor up: a
robot's base could not stand where its wheels go under the handle. `shape_boxes` gives a box per collision shape
instead (PyBullet's `getCollisionShapeData`: boxes, spheres, cylinders and capsules by their sizes, meshes by their
vertices, `getMeshData`), each placed with the link, world-aligned. Where a shape's extent cannot be read (a plane, a
mesh without vertex data) or the boxes do not fit in PyBullet's own box of the link (a frame read wrongly), the link's
box is the answer, as before: never less than PyBullet's.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pybullet as p

from ..quiet import silenced
from .pose import quat_to_matrix

if TYPE_CHECKING:
    from .object import Object

#: the world's cache table of each object's shapes, in their links' frames (they never change)
SHAPES = "collision shapes"
#: how far (m) the shapes' boxes may reach beyond PyBullet's box of the link (its collision margin, rounding)
FITS = 0.01

Box = tuple[np.ndarray, np.ndarray]


def _corners(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])


def _local_shapes(obj: Object, link: int) -> list[np.ndarray] | None:
    """Each collision shape of the link as the corners (8, 3) of its box in the link's centre-of-mass frame (where
    PyBullet places shapes), or None when one of them cannot be read."""
    cid = obj.world.client_id
    found = []
    for index, shape in enumerate(p.getCollisionShapeData(obj.id, link, physicsClientId=cid)):
        kind, size, frame = shape[2], shape[3], (shape[5], shape[6])
        if kind == p.GEOM_MESH:
            with silenced():  # PyBullet prints a line per vertex buffer it cannot read
                count, vertices = p.getMeshData(obj.id, link, collisionShapeIndex=index, physicsClientId=cid)
            if count <= 0 or not vertices:
                return None
            points = np.asarray(vertices, dtype=float)  # already in the link's frame
            found.append(_corners(points.min(axis=0), points.max(axis=0)))
            continue
        if kind == p.GEOM_BOX:
            half = np.asarray(size, dtype=float) / 2.0
        elif kind == p.GEOM_SPHERE:
            half = np.full(3, float(size[0]))
        elif kind in (p.GEOM_CYLINDER, p.GEOM_CAPSULE):
            length, radius = float(size[0]), float(size[1])
            half = np.array([radius, radius, length / 2.0 + (radius if kind == p.GEOM_CAPSULE else 0.0)])
        else:
            return None
        turn = quat_to_matrix(frame[1])
        found.append(_corners(-half, half) @ turn.T + np.asarray(frame[0], dtype=float))
    return found


def shape_boxes(obj: Object, link: int) -> list[Box]:
    """World-aligned boxes (min corner, max corner) of the link's collision shapes as it stands, one per shape; the
    link's own box (PyBullet's) when it has one shape, when a shape cannot be read or when the boxes do not fit in it."""
    lo, hi = (np.asarray(v, dtype=float) for v in obj.get_aabb(link))
    whole = [(lo, hi)]
    table = obj.world.cache.table(SHAPES, obj)
    if link not in table:
        table[link] = _local_shapes(obj, link)
    local: list[np.ndarray] | None = table[link]
    if local is None or len(local) <= 1:
        return whole
    cid = obj.world.client_id
    if link == -1:
        position, orientation = p.getBasePositionAndOrientation(obj.id, physicsClientId=cid)
    else:
        position, orientation = p.getLinkState(obj.id, link, physicsClientId=cid)[:2]
    turn, origin = quat_to_matrix(orientation), np.asarray(position, dtype=float)
    boxes = []
    for corners in local:
        points = corners @ turn.T + origin
        boxes.append((points.min(axis=0), points.max(axis=0)))
    if any((b_lo < lo - FITS).any() or (b_hi > hi + FITS).any() for b_lo, b_hi in boxes):
        return whole
    return boxes
