"""COLLADA meshes for the page: triangles placed by the scene's nodes, in metres; real robots' files agree with
their collision meshes."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pycram_cli.report.collada import read_collada
from pycram_cli.world.meshes import read_mesh

SQUARE = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="g"><mesh>
      <source id="p"><float_array id="pa" count="12">0 0 0 10 0 0 10 10 0 0 10 0</float_array>
        <technique_common><accessor source="#pa" count="4" stride="3"/></technique_common></source>
      <source id="t"><float_array id="ta" count="8">0 0 1 0 1 1 0 1</float_array>
        <technique_common><accessor source="#ta" count="4" stride="2"/></technique_common></source>
      <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><input semantic="TEXCOORD" source="#t" offset="1"/>
        <p>0 0 1 1 2 2</p></triangles>
      <polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/><vcount>4</vcount><p>0 1 2 3</p></polylist>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="a"><translate>100 0 0</translate>
      <node id="b"><rotate>0 0 1 90</rotate><scale>2 2 2</scale><instance_geometry url="#g"/></node>
    </node>
  </visual_scene></library_visual_scenes>
</COLLADA>"""


def test_triangles_and_polygons_are_placed_by_the_nodes_in_metres(tmp_path):
    path = tmp_path / "square.dae"
    path.write_text(SQUARE)
    vertices, triangles = read_collada(path)
    assert len(triangles) == 1 + 2  # the triangle, and the quad fanned into two
    # scaled by 2, turned 90° about z, moved 100 cm along x; centimetres to metres
    assert vertices[triangles[0]] == pytest.approx(np.array([[1.0, 0, 0], [1.0, 0.2, 0], [0.8, 0.2, 0]]), abs=1e-9)


def test_what_is_not_collada_is_a_value_error(tmp_path):
    broken = SQUARE.replace("<p>0 1 2 3</p>", "<p>0 1 9 3</p>")  # a vertex the mesh does not have
    for text in ("not xml", "<?xml version='1.0'?><mesh/>", broken, SQUARE.replace('meter="0.01"', 'meter="x"')):
        path = tmp_path / "bad.dae"
        path.write_text(text)
        with pytest.raises(ValueError):
            read_collada(path)


def test_real_robots_collada_meshes_agree_with_their_collision_meshes(shared_models):
    pairs = []
    for dae in sorted(shared_models.glob("*/*/meshes/**/*.dae")):
        for stl in (dae.with_suffix(".stl"), dae.with_name(dae.stem + "_L.stl"), dae.with_name(dae.stem + "_collision.STL")):
            if stl.is_file():
                pairs.append((dae, stl))
                break
    assert len(pairs) >= 15
    close = 0
    for dae, stl in pairs:
        vertices, _ = read_collada(dae)
        collision = read_mesh(stl).vertices
        size = float(np.linalg.norm(collision.max(axis=0) - collision.min(axis=0)))
        gap = max(np.abs(vertices.min(axis=0) - collision.min(axis=0)).max(),
                  np.abs(vertices.max(axis=0) - collision.max(axis=0)).max())
        assert gap < 0.3 * size, dae.name  # never turned or scaled otherwise (the up axis, the unit)
        close += gap < 0.01
    assert close >= 0.9 * len(pairs)  # nearly all the same box to 1 cm (a collision mesh may leave a part out)
