"""What the world offers for looking at it: visual shapes, link poses, framing cameras, images, the display check."""
from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from pycram_cli import Object
from pycram_cli.world import display
from pycram_cli.world.camera import (IMAGE_FORMATS, VIEWS, encode_image, image_format, movable_objects, moved_since,
                                     named_camera, poses, render, robot_camera)


def test_visual_shapes_name_kind_size_colour_and_frame(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0, 0], color=[1, 0, 0])
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    (mesh,) = cube.visual_shapes()
    assert mesh.kind == "mesh" and mesh.mesh_file.name == "cube.obj" and mesh.link == -1
    assert mesh.rgba == (1.0, 0.0, 0.0, 1.0) and mesh.scale == (1.0, 1.0, 1.0)
    kinds = {shape.kind for shape in arm.visual_shapes()}
    assert kinds and kinds <= {"box", "cylinder", "sphere", "capsule", "mesh"}
    for shape in arm.visual_shapes():
        assert len(shape.origin[0]) == 3 and len(shape.origin[1]) == 4
        if shape.kind == "box":
            assert all(v > 0 for v in shape.size)
        if shape.kind in ("cylinder", "capsule"):
            assert shape.radius > 0 and shape.length > 0


def test_link_poses_read_at_once_match_one_by_one(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf", [0.2, 0.1, 0])
    arm.set_joint_positions({"shoulder": 0.4})
    links = [-1, *range(len(arm.joints))]
    batch = arm.link_poses(links)
    for link in links:
        expected = arm.get_link_position_and_orientation(link)
        assert np.allclose(batch[link][0], expected[0]) and np.allclose(batch[link][1], expected[1])


def test_clear_fraction_sees_through_ignored_objects(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0, 0], fixed=True)
    assert world.clear_fraction((0, 0, 0.02), (0, 1, 0.02)) == 1.0
    blocked = world.clear_fraction((0, 0, 0.02), (1, 0, 0.02))
    assert 0.3 < blocked < 0.5
    assert world.clear_fraction((0, 0, 0.02), (1, 0, 0.02), [cube]) == 1.0


def test_image_formats_follow_the_extension():
    rgb = np.zeros((20, 30, 3), dtype=np.uint8)
    rgb[:, :15] = (200, 30, 30)
    for suffix, kind in IMAGE_FORMATS.items():
        data = encode_image(rgb, suffix.upper())
        image = Image.open(io.BytesIO(data))
        assert image.format == kind and image.size == (30, 20)
    assert image_format(".gif") is None
    with pytest.raises(ValueError, match="unknown image type"):
        encode_image(rgb, ".gif")


def test_named_views_frame_what_they_name(kitchen):
    robot = kitchen.robot
    for name in VIEWS:
        camera = named_camera(kitchen, name)
        assert np.linalg.norm(np.subtract(camera.eye, camera.target)) > 0.5
    close = robot_camera(kitchen)
    centre = np.mean(np.asarray(robot.get_aabb()), axis=0)
    assert np.linalg.norm(np.subtract(close.target, centre)) < 0.3  # looks at the robot
    # nothing of the kitchen stands between the camera and the robot
    assert kitchen.clear_fraction(close.target, close.eye, [robot, *movable_objects(kitchen)]) == 1.0
    with pytest.raises(ValueError, match="unknown view"):
        named_camera(kitchen, "sky")


def test_the_robot_view_shows_the_robot(kitchen):
    """The PR2's grippers are the only blue in the kitchen: a render of the robot view shows them."""
    image = render(kitchen, robot_camera(kitchen), 320, 240).astype(int)
    blue = (image[:, :, 2] - image[:, :, 0] > 60) & (image[:, :, 2] > 100)
    assert blue.sum() > 30


def test_moved_since_names_the_objects_that_moved(kitchen):
    before = poses(kitchen)
    milk = kitchen.get_object_by_name("milk")
    with kitchen.snapshot():
        milk.set_position([1.3, 1.1, 0.851])
        assert moved_since(kitchen, before) == [milk]
    assert moved_since(kitchen, before) == []


def test_display_problem_without_a_display(monkeypatch):
    monkeypatch.setattr(display.sys, "platform", "linux")
    monkeypatch.delenv("DISPLAY", raising=False)
    assert display.display_problem() == "no display (DISPLAY is not set)"
    with pytest.raises(display.NoDisplayError, match="cannot open a window: no display .*run under xvfb-run or without `gui`"):
        display.check_display()
    monkeypatch.setenv("DISPLAY", ":987")  # no such server
    assert "cannot open DISPLAY=':987'" in (display.display_problem() or "")
    monkeypatch.setattr(display.sys, "platform", "darwin")
    assert display.display_problem() is None
