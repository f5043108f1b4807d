"""A robot whose wheels rest on the floor, as nearly every real URDF's do, works like one that floats above it.

The bundled robots keep every link a few centimetres above the floor; a user's robot has wheels
or casters touching it (0 mm). What the robot stands on is support, never a collision: reaching,
blocking, locations and navigation only test what moves (the arm, what it holds) and where the
base drives. The robot here is the bundled Fetch with collision shapes on its drive wheels that
reach the floor exactly; it must give the same answers as the bundled Fetch.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.worldfile.loader import load_world

from robot_variants import write_variant

@pytest.fixture(scope="module")
def wheeled_world(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The Fetch kitchen with a Fetch whose drive wheels touch the floor."""
    return write_variant(tmp_path_factory.mktemp("wheeled"), "wheeled_fetch")


def test_the_wheels_touch_the_floor(wheeled_world: Path) -> None:
    world = load_world(wheeled_world)
    try:
        robot = world.get_object_by_name("fetch")
        lowest = min(robot.get_aabb(link)[0][2] for link in ("r_wheel_link", "l_wheel_link"))
        assert lowest == pytest.approx(0.0, abs=5e-3)  # the box has PyBullet's margin
        assert world.distance(robot, world.get_object_by_name("floor"), 0.01) < 0.001
    finally:
        world.exit()


def test_nothing_blocks_a_reach_into_free_air(wheeled_world: Path) -> None:
    result = CliRunner().invoke(cli, ["query", "blocking", "0.6,0.7,1.2", "--world", str(wheeled_world)])
    assert result.exit_code == 0, result.output
    assert "floor" not in result.output


def test_it_finds_the_same_place_to_stand_as_the_robot_above_the_floor(wheeled_world: Path) -> None:
    args = ["locate", "reachable-for", "milk", "--json"]
    wheeled = CliRunner().invoke(cli, [*args, "--world", str(wheeled_world)])
    floating = CliRunner().invoke(cli, [*args, "--world", "kitchen_fetch"])
    assert wheeled.exit_code == 0, wheeled.output
    assert json.loads(wheeled.stdout)["found"] == json.loads(floating.stdout)["found"]


def test_it_drives_onto_the_floor_it_stands_on(wheeled_world: Path) -> None:
    plan = ["run", "plans/set_table_actions.yaml", "--world", str(wheeled_world), "-p", "objects=[milk]"]
    result = CliRunner().invoke(cli, plan)
    assert result.exit_code == 0, result.output
    assert "succeeded" in result.output
