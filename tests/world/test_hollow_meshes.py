"""Hollow meshes (a bowl) collide as convex pieces of their surface, not as their convex hull: their inside is empty."""
from __future__ import annotations

from pycram_cli import Object
from pycram_cli.paths import resources_dir
from pycram_cli.world.meshes import read_mesh

BOWL = resources_dir() / "objects" / "bowl.obj"


def small_cube(tmp_path, size=0.01):
    h = size / 2
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    faces = [(1, 2, 4, 3), (5, 7, 8, 6), (1, 5, 6, 2), (3, 4, 8, 7), (1, 3, 7, 5), (2, 6, 8, 4)]
    path = tmp_path / "probe.obj"
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners)
                    + "".join(f"f {a} {c} {b}\nf {a} {d} {c}\n" for a, b, c, d in faces))
    return path


def test_the_bowl_is_hollow_and_the_milk_carton_is_not():
    assert read_mesh(BOWL).is_hollow()
    assert not read_mesh(resources_dir() / "objects" / "milk.obj").is_hollow()
    assert not read_mesh(resources_dir() / "objects" / "spoon.obj").is_hollow()


def test_something_inside_the_bowl_does_not_touch_it_but_its_wall_does(world, tmp_path):
    bowl = Object("bowl", "bowl", BOWL, [0, 0, 0], fixed=True)
    probe = Object("probe", "probe", small_cube(tmp_path), [0, 0, 0.03], fixed=True)
    # 3 cm above the bottom, in the middle: the convex hull would swallow it; the bowl's foot piece (its bottom
    # centimetre, 1.4 cm with the overlap) ends about 1 cm below
    assert world.distance(bowl, probe, 0.05) > 0.007
    probe.set_position([0.05, 0, 0.05])  # about 1 cm from the inner wall, 1 cm below the rim
    assert 0.004 < world.distance(bowl, probe, 0.05) < 0.012  # the pieces follow the wall within 2-3 mm
    probe.set_position([0.073, 0, 0.055])  # in the wall
    assert world.distance(bowl, probe, 0.05) < 0


def test_pieces_follow_the_surface_within_a_few_millimetres():
    mesh = read_mesh(BOWL)
    pieces = mesh.convex_pieces()
    assert 20 < len(pieces) < 400
    lo, hi = mesh.bounds
    foot, *walls = pieces
    assert foot[:, 2].max() < lo[2] + 0.015  # what it stands on: one flat piece
    for cloud in walls:  # every other piece is a patch of the surface: inside the mesh's box, a few cells across
        assert (cloud >= lo - 1e-9).all() and (cloud <= hi + 1e-9).all()
        assert (cloud.max(axis=0) - cloud.min(axis=0)).max() < 0.04
