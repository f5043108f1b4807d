"""Meshes over the page's budget are simplified and keep their shape; every mesh is welded."""
from __future__ import annotations

import numpy as np

from pycram_cli.report.simplify import MAX_PAGE_TRIANGLES, simplify, weld


def sphere(n: int) -> tuple[np.ndarray, np.ndarray]:
    """A UV sphere of radius 0.1 m with about 2 n² triangles."""
    theta, phi = np.meshgrid(np.linspace(0, np.pi, n + 1), np.linspace(0, 2 * np.pi, n + 1), indexing="ij")
    points = 0.1 * np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1)
    index = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    a, b, c, d = index[:-1, :-1], index[:-1, 1:], index[1:, :-1], index[1:, 1:]
    triangles = np.concatenate([np.stack([a, c, b], -1).reshape(-1, 3), np.stack([b, c, d], -1).reshape(-1, 3)])
    return points.reshape(-1, 3), triangles


def test_a_detailed_mesh_fits_the_budget_and_keeps_its_shape():
    vertices, triangles = sphere(150)  # 45 000 triangles
    small_v, small_t = simplify(vertices, triangles)
    assert len(small_t) <= MAX_PAGE_TRIANGLES < len(triangles)
    assert small_v.min(axis=0) == __import__("pytest").approx(vertices.min(axis=0), abs=0.01)
    assert small_v.max(axis=0) == __import__("pytest").approx(vertices.max(axis=0), abs=0.01)
    radii = np.linalg.norm(small_v, axis=1)
    assert np.abs(radii - 0.1).max() < 0.01  # still a sphere: every vertex within 1 cm of the surface
    assert small_t.max() < len(small_v) and len(np.unique(np.sort(small_t, axis=1), axis=0)) == len(small_t)


def test_a_small_mesh_is_only_welded():
    corners = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)  # as in an STL
    triangles = np.array([[0, 1, 2], [3, 4, 5]])
    v, t = simplify(corners, triangles)
    assert len(v) == 4 and len(t) == 2
    assert np.array_equal(v[t], corners[triangles])  # the same triangles
    assert weld(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))[0].shape == (0, 3)
