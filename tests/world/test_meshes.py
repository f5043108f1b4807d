"""Reading OBJ meshes: plain files in bulk, every other form line by line, with the same result."""
from __future__ import annotations

import numpy as np
import pytest

from pycram_cli.world.meshes import read_mesh

TRIANGLE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0]], dtype=float)


@pytest.mark.parametrize("text, triangles", [
    ("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", [[0, 1, 2]]),
    ("v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n", [[0, 1, 2]]),
    ("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\n", [[0, 1, 2]]),
    ("v 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nf 1 2 3\n", [[0, 1, 2]]),
    ("# a comment\nv  0 0 0\nv 1 0 0\nv 1 1 0\n\nf 1 2 3\n", [[0, 1, 2]]),
])
def test_obj_files_of_every_form_read_alike(tmp_path, text, triangles):
    path = tmp_path / "mesh.obj"
    path.write_text(text)
    mesh = read_mesh(path)
    assert np.array_equal(mesh.vertices, TRIANGLE) and mesh.triangles.tolist() == triangles


def test_polygons_are_fanned_into_triangles(tmp_path):
    path = tmp_path / "quad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    assert read_mesh(path).triangles.tolist() == [[0, 1, 2], [0, 2, 3]]


def test_a_vertex_with_two_coordinates_is_refused(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n")
    with pytest.raises(ValueError, match="three coordinates"):
        read_mesh(path)
