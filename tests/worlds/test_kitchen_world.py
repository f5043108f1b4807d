"""The default world, worlds/kitchen.yaml: the design's demo scene, at rest, used by every command."""
from __future__ import annotations

import math

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.paths import default_world
from pycram_cli.world.pose import angle_between


def test_the_default_world_is_the_kitchen_with_the_demo_objects(kitchen):
    assert default_world().name == "kitchen.yaml"
    assert [o.name for o in kitchen.objects] == ["floor", "pr2", "kitchen", "milk", "cereal", "bowl", "spoon", "bottle"]
    assert kitchen.robot.name == "pr2"
    kitchen.get_object_by_name("kitchen").get_joint_id("sink_area_left_upper_drawer_main_joint")


def test_everything_is_at_rest_simulating_two_seconds_moves_nothing_by_a_millimetre(kitchen):
    with kitchen.snapshot():
        before = {o.name: o.get_pose() for o in kitchen.objects}
        joints = {o.name: o.get_joint_positions() for o in kitchen.objects}
        kitchen.simulate(2.0)
        for obj in kitchen.objects:
            pos, orn = obj.get_pose()
            assert math.dist(pos, before[obj.name][0]) < 0.001, obj.name
            assert angle_between(orn, before[obj.name][1]) < math.radians(1), obj.name
            assert obj.get_joint_positions() == pytest.approx(joints[obj.name], abs=1e-6), obj.name


def test_the_spoon_lies_inside_the_closed_drawer(kitchen):
    kitchen_obj, spoon = kitchen.get_object_by_name("kitchen"), kitchen.get_object_by_name("spoon")
    lo, hi = kitchen_obj.get_aabb("sink_area_left_upper_drawer_main")
    x, y, z = spoon.get_position()
    assert lo[0] < x < hi[0] and lo[1] < y < hi[1] and lo[2] < z < hi[2]


def test_commands_use_the_kitchen_world_by_default():
    result = CliRunner().invoke(cli, ["world", "show", "--json"])
    assert result.exit_code == 0
    assert '"kitchen.yaml"' in result.stdout or "kitchen.yaml" in result.stdout
