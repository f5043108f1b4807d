"""Specification of the object meshes in resources/objects (Wavefront OBJ, metres).

Every mesh is a closed, consistently oriented triangle mesh whose origin is the
centre of the object's bottom face (bounding box centred on x = y = 0, z from 0).
"""
from __future__ import annotations

import math
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
OBJECTS = REPO / "resources" / "objects"
GENERATOR = OBJECTS / "generate.py"

# name -> bounding box size (x, y, z) in metres
SIZES = {
    "milk": (0.07, 0.07, 0.22),
    "breakfast_cereal": (0.07, 0.19, 0.27),
    "bowl": (0.15, 0.15, 0.06),
    "spoon": (0.16, 0.042, 0.004),
    "bottle": (0.065, 0.065, 0.25),
}


def read_obj(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Minimal OBJ reader: vertices and (triangulated) faces, 0-based indices."""
    vertices: list[list[float]] = []
    faces: list[list[int]] = []
    for line in path.read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(v) for v in parts[1:4]])
        elif parts[0] == "f":
            idx = [int(token.split("/")[0]) for token in parts[1:]]
            idx = [i - 1 if i > 0 else len(vertices) + i for i in idx]
            faces += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return np.array(vertices), np.array(faces)


def signed_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


@pytest.fixture(params=sorted(SIZES))
def mesh(request):
    vertices, faces = read_obj(OBJECTS / f"{request.param}.obj")
    return request.param, vertices, faces


def test_mesh_parses(mesh):
    name, vertices, faces = mesh
    assert len(vertices) >= 8 and len(faces) >= 12, name
    assert faces.min() >= 0 and faces.max() < len(vertices)


def test_mesh_is_watertight_and_consistently_oriented(mesh):
    name, _, faces = mesh
    undirected: Counter = Counter()
    directed: Counter = Counter()
    for tri in faces:
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            assert a != b, f"{name}: degenerate triangle {tri}"
            undirected[frozenset((a, b))] += 1
            directed[(a, b)] += 1
    assert all(count == 2 for count in undirected.values()), f"{name}: open or non-manifold edges"
    assert all(count == 1 for count in directed.values()), f"{name}: inconsistent triangle orientation"


def test_mesh_has_positive_volume(mesh):
    name, vertices, faces = mesh
    assert signed_volume(vertices, faces) > 0, f"{name}: normals point inward"


def test_bounding_box_size(mesh):
    name, vertices, _ = mesh
    size = vertices.max(axis=0) - vertices.min(axis=0)
    assert size == pytest.approx(SIZES[name], abs=0.01)


def test_origin_is_centre_of_the_bottom_face(mesh):
    name, vertices, _ = mesh
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    assert lo[2] == pytest.approx(0.0, abs=0.005), name
    assert (lo[:2] + hi[:2]) / 2 == pytest.approx([0.0, 0.0], abs=0.005), name


def test_bowl_is_hollow():
    vertices, faces = read_obj(OBJECTS / "bowl.obj")
    size = vertices.max(axis=0) - vertices.min(axis=0)
    cylinder = math.pi * (size[0] / 2) ** 2 * size[2]
    assert signed_volume(vertices, faces) < 0.35 * cylinder
    # the two vertices on the axis are the outer and the inner bottom: the inner
    # bottom lies just above the floor, so the inside of the bowl is empty
    on_axis = vertices[(np.abs(vertices[:, 0]) < 1e-9) & (np.abs(vertices[:, 1]) < 1e-9)][:, 2]
    assert sorted(on_axis)[0] == pytest.approx(0.0, abs=1e-6)
    assert 0.002 < sorted(on_axis)[-1] < 0.015, "the inner bottom of the bowl must be near its floor"


def test_spoon_is_thin_and_long_along_x():
    vertices, _ = read_obj(OBJECTS / "spoon.obj")
    size = vertices.max(axis=0) - vertices.min(axis=0)
    assert size[2] < 0.006
    assert size[0] == pytest.approx(0.16, abs=0.01) and size[0] > 3 * size[1]


def test_generated_meshes_are_up_to_date(tmp_path):
    subprocess.run([sys.executable, str(GENERATOR), "--out", str(tmp_path)], check=True, capture_output=True)
    for name in SIZES:
        assert (tmp_path / f"{name}.obj").read_bytes() == (OBJECTS / f"{name}.obj").read_bytes(), \
            f"{name}.obj is stale: re-run resources/objects/generate.py"
