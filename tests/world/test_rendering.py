"""BulletWorld.segmentation and segmentation_alone: which object each pixel shows, with and without the rest."""
from __future__ import annotations

import numpy as np
import pybullet as p
import pytest

from pycram_cli import Object
from pycram_cli.world.camera import projection_matrix, view_matrix

SIZE = 64
#: looking straight down at the origin from 2 m; the window sees about ±0.2 m around it
VIEW = view_matrix((0.0, 0.0, 2.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0))
PROJECTION = projection_matrix(-0.01, 0.01, -0.01, 0.01, 0.1, 5.0)
CENTRE = (SIZE // 2, SIZE // 2)


def test_segmentation_shows_each_objects_id_and_minus_one_for_nothing(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj")
    seg = world.segmentation(SIZE, SIZE, VIEW, PROJECTION)
    assert seg.shape == (SIZE, SIZE)
    assert seg[CENTRE] == cube.id
    assert seg[0, 0] == -1
    assert set(np.unique(seg).tolist()) == {-1, cube.id}


def test_an_object_hidden_behind_another_is_still_there_alone(world, data_dir):
    below = Object("below", "box", data_dir / "cube.obj")
    above = Object("above", "box", data_dir / "cube.obj", [0.0, 0.0, 0.5])
    assert world.segmentation(SIZE, SIZE, VIEW, PROJECTION)[CENTRE] == above.id
    alone = world.segmentation_alone(below, SIZE, SIZE, VIEW, PROJECTION)
    assert alone.dtype == bool and alone[CENTRE] and not alone[0, 0]


def test_the_object_alone_covers_what_it_covers_in_the_world_when_nothing_hides_it(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf", [-0.1, 0.0, 0.0])
    for shoulder in (0.0, 0.4, -0.7):
        arm.set_joint_positions({"shoulder": shoulder, "slide": 0.1})
        seen = world.segmentation(SIZE, SIZE, VIEW, PROJECTION) == arm.id
        alone = world.segmentation_alone(arm, SIZE, SIZE, VIEW, PROJECTION)
        assert seen.any() and np.array_equal(alone, seen)


def test_rendering_changes_nothing_in_the_world(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.02, 0.0, 0.0], color=[1, 0, 0])
    cid = world.client_id
    before = (p.getBasePositionAndOrientation(cube.id, physicsClientId=cid),
              p.getVisualShapeData(cube.id, physicsClientId=cid))
    world.segmentation(SIZE, SIZE, VIEW, PROJECTION)
    world.segmentation_alone(cube, SIZE, SIZE, VIEW, PROJECTION)
    assert (p.getBasePositionAndOrientation(cube.id, physicsClientId=cid),
            p.getVisualShapeData(cube.id, physicsClientId=cid)) == before


def test_the_private_client_is_closed_with_its_world(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj")
    world.segmentation_alone(cube, SIZE, SIZE, VIEW, PROJECTION)
    private = world._prospection.copy.client_id  # white-box: the private client it renders in
    assert p.isConnected(private)
    world.exit()
    assert not p.isConnected(private)


def test_an_exited_world_renders_nothing(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj")
    world.exit()
    with pytest.raises(Exception, match="exited"):
        world.segmentation(SIZE, SIZE, VIEW, PROJECTION)
    with pytest.raises(Exception, match="exited"):
        world.segmentation_alone(cube, SIZE, SIZE, VIEW, PROJECTION)
