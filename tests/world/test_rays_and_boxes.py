"""BulletWorld.cast_rays (what is under a spot) and Object.get_local_aabb (an object's box in its own frame)."""
from __future__ import annotations

import math

import pytest

from pycram_cli import Object
from pycram_cli.paths import resources_dir
from pycram_cli.world.pose import yaw_quaternion

MILK = resources_dir() / "objects" / "milk.obj"


def test_a_ray_reports_the_first_shape_it_meets_and_sees_through_what_it_is_told_to(world, data_dir):
    floor = Object("floor", "environment", "plane.urdf")
    low = Object("low", "box", data_dir / "cube.obj", [0.0, 0.0, 0.0], fixed=True)
    high = Object("high", "box", data_dir / "cube.obj", [0.0, 0.0, 0.5], fixed=True)
    hit, miss = world.cast_rays([(0, 0, 2), (5, 5, 2)], [(0, 0, -1), (5, 5, 1)])
    assert hit.object is high and hit.position[2] == pytest.approx(0.5 + _top(high, 0.5), abs=2e-3)
    assert hit.normal == pytest.approx((0, 0, 1), abs=1e-6) and 0 < hit.fraction < 1
    assert miss is None
    through, = world.cast_rays([(0, 0, 2)], [(0, 0, -1)], ignore=[high])
    assert through.object is low
    both, = world.cast_rays([(0, 0, 2)], [(0, 0, -1)], ignore=[high, low])
    assert both.object is floor and both.position[2] == pytest.approx(0.0, abs=1e-6)


def _top(obj, z):
    return obj.get_aabb()[1][2] - z - 0.004  # the box without PyBullet's box margin, roughly


def test_the_local_box_of_a_mesh_is_its_vertices_box_whatever_its_pose(world):
    milk = Object("milk", "milk", MILK, [1, 2, 3], yaw_quaternion(math.radians(20)))
    lo, hi = milk.get_local_aabb()
    assert lo == pytest.approx((-0.035, -0.035, 0.0), abs=1e-6)
    assert hi == pytest.approx((0.035, 0.035, 0.22), abs=1e-6)
    wide = milk.get_aabb()  # the world box of a carton turned 20° is wider than the carton
    assert wide[1][0] - wide[0][0] > 0.08


def test_the_local_box_of_a_link_is_in_the_links_frame(world):
    kitchen = Object("kitchen", "environment", resources_dir() / "environments" / "kitchen" / "kitchen.urdf")
    lo, hi = kitchen.get_link_local_aabb("sink_area_left_upper_drawer_handle")
    size = sorted(h - l for l, h in zip(lo, hi))
    assert size[0] < 0.04 and size[2] > 0.5  # a bar: thin one way, long the other
