"""Fixtures of the motion tests: the bundled kitchen taken through a snapshot with no walks remembered, and the
PR2 before its counter with an arm motion reaching out over it."""
from __future__ import annotations

from collections.abc import Iterator

import pytest

from pycram_cli import BulletWorld
from pycram_cli.planning import motion
from pycram_cli.planning.reach import arm_configuration
from pycram_cli.robots import Robot


@pytest.fixture
def world(kitchen: BulletWorld) -> Iterator[BulletWorld]:
    """The module's kitchen (tests/conftest.py), put back after the test, with no walks or searches remembered."""
    with kitchen.snapshot():
        kitchen.cache.forget(motion.MEMO)
        yield kitchen
        kitchen.cache.forget(motion.MEMO)


@pytest.fixture
def counter(world: BulletWorld) -> tuple[Robot, list[str], dict[str, float]]:
    """The PR2 before the counter (as the demo stands to take the milk), its left arm parked; the arm's joints, and
    a goal reaching out over the counter."""
    world.robot.set_position_and_orientation((0.65, 0.7, 0.0), (0.0, 0.0, 0.0, 1.0))
    robot = Robot.of(world)
    park = arm_configuration(robot, "left", "park")
    world.robot.reset_joints(park)
    joints = list(park)
    out = dict(zip(joints, [0.3, -0.2, 0.5, -1.0, 0.0, -0.5, 0.0]))
    return robot, joints, out
