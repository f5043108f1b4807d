"""BulletWorld.closest_points and distance: how close two objects' collision shapes are, as they are now."""
from __future__ import annotations

import dataclasses
import math

import pytest

from pycram_cli import BulletWorld, Object
from pycram_cli.world import ClosestPoint, WorldError

#: PyBullet pads every mesh shape with a 1 mm collision margin
MARGIN = 0.0025


@pytest.fixture
def cubes(world, data_dir):
    a = Object("a", "box", data_dir / "cube.obj", [0.0, 0.0, 0.0])
    b = Object("b", "box", data_dir / "cube.obj", [0.09, 0.0, 0.0])  # 1 cm into a
    return world, a, b


def test_interpenetrating_objects_report_a_negative_distance_and_their_links(cubes):
    world, a, b = cubes
    points = world.closest_points(a, b, 0.0)
    assert points and all(isinstance(pt, ClosestPoint) for pt in points)
    assert {(pt.link_a, pt.link_b) for pt in points} == {(-1, -1)}
    assert min(pt.distance for pt in points) == pytest.approx(-0.01, abs=MARGIN)


def test_the_normal_on_b_points_from_b_towards_a(cubes):
    world, a, b = cubes
    pt = min(world.closest_points(a, b, 0.0), key=lambda pt: pt.distance)
    assert pt.normal_on_b == pytest.approx((-1.0, 0.0, 0.0), abs=1e-6)
    assert pt.position_on_a[0] == pytest.approx(0.05, abs=MARGIN)
    assert pt.position_on_b[0] == pytest.approx(0.04, abs=MARGIN)


def test_objects_farther_apart_than_the_distance_have_no_closest_points(cubes):
    world, a, b = cubes
    b.set_position([0.5, 0.0, 0.0])
    assert world.closest_points(a, b, 0.1) == []
    far = world.closest_points(a, b, 1.0)
    assert min(pt.distance for pt in far) == pytest.approx(0.4, abs=MARGIN)


def test_a_teleport_counts_at_once_without_a_simulation_step(cubes):
    world, a, b = cubes
    b.set_position([0.2, 0.0, 0.0])
    assert world.closest_points(a, b, 0.0) == []
    b.set_position([0.05, 0.0, 0.0])
    assert world.closest_points(a, b, 0.0)


def test_closest_points_name_the_touching_link_and_can_be_restricted_to_links(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    cube = Object("cube", "box", data_dir / "cube.obj", [0.4, 0.0, 0.15])  # through the upper arm
    upper = arm.get_link_id("upper")
    points = world.closest_points(arm, cube, 0.0)
    assert {(pt.link_a, pt.link_b) for pt in points} == {(upper, -1)}
    assert world.closest_points(arm, cube, 0.0, link_a=upper)
    assert world.closest_points(arm, cube, 0.0, link_a=arm.get_link_id("base")) == []
    assert world.closest_points(cube, arm, 0.0, link_b=upper)[0].link_b == upper


def test_closest_points_are_frozen_data(cubes):
    world, a, b = cubes
    pt = world.closest_points(a, b, 0.0)[0]
    with pytest.raises(dataclasses.FrozenInstanceError):
        pt.distance = 0.0  # type: ignore[misc]


def test_objects_of_another_world_are_refused(cubes, data_dir):
    world, a, _ = cubes
    with BulletWorld() as other_world:
        other = Object("c", "box", data_dir / "cube.obj", world=other_world)
        with pytest.raises(WorldError, match="not both in this world"):
            world.closest_points(a, other, 0.0)


def test_distance_is_the_smallest_closest_point_distance_and_inf_beyond_the_search(cubes):
    world, a, b = cubes
    assert world.distance(a, b, 0.0) == min(pt.distance for pt in world.closest_points(a, b, 0.0))
    assert world.distance(a, b, 0.0) < 0.0
    b.set_position([0.5, 0.0, 0.0])
    assert world.distance(a, b, 0.1) == math.inf
    assert world.distance(a, b, 1.0) == pytest.approx(0.4, abs=MARGIN)


def test_distance_can_be_restricted_to_links(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    cube = Object("cube", "box", data_dir / "cube.obj", [0.4, 0.0, 0.15])  # through the upper arm
    assert world.distance(arm, cube, 0.0, link_a=arm.get_link_id("upper")) < 0.0
    assert world.distance(arm, cube, 0.0, link_a=arm.get_link_id("base")) == math.inf


def test_an_exited_world_answers_no_geometry(cubes):
    world, a, b = cubes
    world.exit()
    with pytest.raises(WorldError, match="exited"):
        world.closest_points(a, b, 0.0)
    with pytest.raises(WorldError, match="exited"):
        world.distance(a, b, 0.0)
