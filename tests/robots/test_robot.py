"""The Robot: the world's robot body with its description, which the world keeps (set once by the world loader),
not a table beside the worlds; every floor above robots/ takes it."""
from __future__ import annotations

import dataclasses

import pytest

from pycram_cli.errors import InputError
from pycram_cli.paths import resources_dir
from pycram_cli.robots import Robot, assign_description, description_for
from pycram_cli.world import BulletWorld, Object
from pycram_cli.worldfile.loader import load_world


def test_the_loader_sets_the_robots_description_once_and_its_world_keeps_it() -> None:
    world = load_world()
    try:
        robot = Robot.of(world)
        assert robot.body is world.robot and robot.description.name == "pr2"
        assert world.described_robot == (world.robot, robot.description)
        assert Robot.of(world).description is robot.description  # asked again: the same description, not read again
        assert robot.arm("left") is robot.description.arms["left"]
        with pytest.raises(KeyError, match="has no arm 'middle'"):
            robot.arm("middle")
    finally:
        world.exit()


def test_each_world_keeps_its_own_robots_description() -> None:
    first, second = load_world(), load_world()
    try:
        renamed = dataclasses.replace(description_for(first.robot), name="pr2-renamed")
        assign_description(first.robot, renamed)
        assert Robot.of(first).description.name == "pr2-renamed"
        assert Robot.of(second).description.name == "pr2"
    finally:
        first.exit()
        second.exit()


def test_a_robot_built_in_python_finds_its_description_once_and_forgets_it_when_removed() -> None:
    world = BulletWorld()
    try:
        urdf = resources_dir() / "robots" / "pr2" / "pr2.urdf"
        body = Object("pr2", "robot", urdf, world=world)
        assert world.described_robot is None  # nothing read until asked
        found = description_for(body)
        assert found is not None and found.name == "pr2"
        assert world.described_robot == (body, found) and description_for(body) is found
        body.remove()
        assert world.described_robot is None and world.robot is None
        with pytest.raises(InputError, match="no robot"):
            Robot.of(world)
    finally:
        world.exit()
