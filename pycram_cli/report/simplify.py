"""Fewer triangles for the page, the same shape: meshes over a budget are simplified by vertex clustering.

A real robot's meshes can hold hundreds of thousands of triangles, which a report carries as text (base64):
a real robot's report came to 6 MB. `simplify` snaps the vertices to a grid (each cell's vertices become their
mean), drops the triangles that collapse and those left twice, and widens the grid until the mesh fits the
budget. The outline of a shape stays within about a cell (at most 1/100 of its size at the first try). Every
mesh is welded first (`weld`: each position once), which changes nothing drawn.
"""
from __future__ import annotations

import numpy as np

#: triangles one mesh may keep on the page
MAX_PAGE_TRIANGLES = 4000
#: the first grid: this fraction of the mesh's bounding-box diagonal
FIRST_CELL = 1 / 200


def simplify(vertices: np.ndarray, triangles: np.ndarray,
             budget: int = MAX_PAGE_TRIANGLES) -> tuple[np.ndarray, np.ndarray]:
    """`vertices` (n, 3) and `triangles` (m, 3) with at most `budget` triangles (only welded when already so)."""
    vertices, triangles = weld(vertices, triangles)
    if len(triangles) <= budget or not len(vertices):
        return vertices, triangles
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    cell = max(float(np.linalg.norm(hi - lo)) * FIRST_CELL, 1e-6)
    while True:
        keys = np.floor((vertices - lo) / cell).astype(np.int64)
        _, cluster, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
        cluster = cluster.reshape(-1)
        merged = np.zeros((len(counts), 3))
        np.add.at(merged, cluster, vertices)
        merged /= counts[:, None]
        tris = cluster[triangles]
        keep = (tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 0] != tris[:, 2])
        tris = tris[keep]
        _, first = np.unique(np.sort(tris, axis=1), axis=0, return_index=True)
        tris = tris[np.sort(first)]
        if len(tris) <= budget:
            used, index = np.unique(tris.reshape(-1), return_inverse=True)
            return merged[used], index.reshape(-1, 3)
        cell *= 1.5


def weld(vertices: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The same triangles with each position stored once (an STL repeats every corner for each triangle), as the
    page stores them (float32)."""
    if not len(vertices):
        return vertices, triangles
    unique, index = np.unique(np.asarray(vertices, dtype=np.float32), axis=0, return_inverse=True)
    return unique.astype(float), index.reshape(-1)[triangles]
