"""A camera looks wherever it is mounted: on a pan/tilt head, fixed on the body, or on the wrist.

The description says which camera frame sees; where it sits is read from the model. Without a
head, `looking` turns the base (a fixed camera) or moves the arm (a wrist camera), `visible-for`
finds poses from which the camera sees the object, and the action-level demo runs unchanged.
"""
from __future__ import annotations

import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.designators import perform
from pycram_cli.failures import ReachabilityFailure
from pycram_cli.planning.head import Mount, camera_mount, in_view
from pycram_cli.robots import Robot
from pycram_cli.worldfile.loader import load_world

from robot_variants import write_variant

MILK_TOP = [1.3, 1.0, 0.95]


@pytest.fixture(scope="module", params=["head", "body", "wrist"])
def mounted(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> tuple[str, Path]:
    kind = request.param
    return kind, write_variant(tmp_path_factory.mktemp(kind), f"{kind}_camera_fetch", camera=kind)


def test_the_mount_is_read_from_the_model(mounted: tuple[str, Path]) -> None:
    kind, path = mounted
    world = load_world(path)
    try:
        mount = camera_mount(Robot.of(world))
        assert mount.kind is Mount(kind)
        assert mount.arm == ("arm" if kind == "wrist" else None)
    finally:
        world.exit()


def test_looking_points_the_camera_at_the_target(mounted: tuple[str, Path]) -> None:
    kind, path = mounted
    world = load_world(path)
    try:
        robot = Robot.of(world)
        perform(world, "moving", {"target": [0.75, 0.8, 0], "orientation": [0, 0, 0.7071068, 0.7071068]})
        assert not in_view(robot, MILK_TOP)  # facing along the counter: 70° off to the right
        perform(world, "looking", {"target": MILK_TOP})
        assert in_view(robot, MILK_TOP)
        position = robot.body.get_position()
        assert math.dist(position[:2], (0.75, 0.8)) < 1e-9  # turning in place, if at all
    finally:
        world.exit()


def test_a_fixed_camera_that_cannot_see_says_why(tmp_path: Path) -> None:
    world = load_world(write_variant(tmp_path, "fixed_fetch", camera="body"))
    try:
        with pytest.raises(ReachabilityFailure, match="fixed on the body"):
            perform(world, "looking", {"target": [0.0, 0.7, 3.0]})  # straight above the robot
    finally:
        world.exit()


def test_visible_for_finds_poses_for_every_mount(mounted: tuple[str, Path]) -> None:
    _, path = mounted
    result = CliRunner().invoke(cli, ["locate", "visible-for", "milk", "--world", str(path), "-n", "1"])
    assert result.exit_code == 0, result.output


def test_the_action_demo_runs_unchanged_on_every_mount(mounted: tuple[str, Path]) -> None:
    _, path = mounted
    result = CliRunner().invoke(cli, ["run", "plans/set_table_actions.yaml", "--world", str(path),
                                      "-p", "objects=[milk, spoon]"])
    assert result.exit_code == 0, result.output
