"""A slot left open is a choice: pick-up tries every free arm (nearest first) and grasp (the description's order)
with its own planning before it fails, and its failure says what each alternative ran into.

In clutter (a bowl turned 45° beside the milk) the left arm's front grasp would put its forearm
inside the bowl; the right arm and other grasps are free, and pick-up takes one of them.
"""
from __future__ import annotations

import math
from typing import Iterator

import pytest

from pycram_cli.designators import perform
from pycram_cli.failures import ReachabilityFailure
from pycram_cli.paths import worlds_dir
from pycram_cli.world import BulletWorld
from pycram_cli.world.pose import yaw_quaternion
from pycram_cli.worldfile.loader import load_world


@pytest.fixture
def cluttered() -> Iterator[BulletWorld]:
    """The PR2 in front of the milk, a bowl turned 45° beside the milk on the robot's left."""
    world = load_world(worlds_dir() / "kitchen.yaml")
    world.get_object_by_name("bowl").set_position_and_orientation((1.16, 1.14, 0.852), yaw_quaternion(math.radians(45)))
    assert world.robot is not None
    world.robot.set_position_and_orientation((0.7, 1.0, 0.0), (0, 0, 0, 1))
    yield world
    world.exit()


def test_an_open_arm_and_grasp_take_the_way_that_is_free(cluttered: BulletWorld) -> None:
    performed = perform(cluttered, "pick-up", {"object": "milk"})
    assert performed.resolved["arm"] == "right"
    assert cluttered.get_object_by_name("milk") in cluttered.robot.attachments  # type: ignore[union-attr]


def test_an_open_grasp_tries_every_grasp_of_the_given_arm(cluttered: BulletWorld) -> None:
    performed = perform(cluttered, "pick-up", {"object": "milk", "arm": "left"})
    assert performed.resolved["grasp"] != "front"  # the forearm would be inside the bowl


def test_when_nothing_takes_it_the_failure_says_what_each_way_ran_into(cluttered: BulletWorld) -> None:
    assert cluttered.robot is not None
    cluttered.robot.set_position_and_orientation((0.1, 1.0, 0.0), (0, 0, 0, 1))  # a metre from the counter
    with pytest.raises(ReachabilityFailure) as caught:
        perform(cluttered, "pick-up", {"object": "milk"})
    message = str(caught.value)
    for arm in ("left", "right"):
        for grasp in ("front", "top"):
            assert f"the {arm} arm with a {grasp} grasp" in message
    assert len(caught.value.details["tried"]) >= 4
