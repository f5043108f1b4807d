"""`reachable` asked of an object answers for pick-up: the grasps pick-up will use, from the object's own frame.

Over seeded random base poses in front of the counter, on each bundled robot: where `reachable`
says yes, `pick-up` (arm and grasp left open) succeeds; where pick-up succeeds, `reachable` said yes.
The object's origin (the milk's bottom centre) is not what the hand reaches for, so reaching it
says nothing about picking it up.
"""
from __future__ import annotations

import math
import random

import pytest

from pycram_cli.designators import perform
from pycram_cli.failures import Failure
from pycram_cli.paths import worlds_dir
from pycram_cli.planning.contacts import collisions
from pycram_cli.reasoning import run_query
from pycram_cli.world.pose import yaw_quaternion
from pycram_cli.worldfile.loader import load_world

POSES = 14


def base_poses(seed: int) -> list[tuple[float, float, float]]:
    """Base poses near the counter, facing it give or take 60°, some too far."""
    rng = random.Random(seed)
    return [(rng.uniform(0.3, 1.0), rng.uniform(0.2, 1.8), math.radians(rng.uniform(-60, 60))) for _ in range(POSES)]


@pytest.mark.parametrize("world_name, seed", [("kitchen", 1), ("kitchen_fetch", 2)])
def test_reachable_says_yes_exactly_where_pick_up_succeeds(world_name: str, seed: int) -> None:
    world = load_world(worlds_dir() / f"{world_name}.yaml")
    try:
        robot = world.robot
        assert robot is not None
        outcomes = []
        for x, y, yaw in base_poses(seed):
            with world.snapshot():
                robot.set_position_and_orientation((x, y, 0.0), yaw_quaternion(yaw))
                if collisions(robot):
                    continue
                answer = run_query(world, "reachable", {"target": "milk"})
                try:
                    perform(world, "pick-up", {"object": "milk"})
                    picked = True
                except Failure:
                    picked = False
                assert bool(answer.result) == picked, (x, y, yaw, answer.details)
                outcomes.append(picked)
        assert True in outcomes and False in outcomes  # both answers were tested
    finally:
        world.exit()


def test_the_answer_names_the_arm_and_grasp_pick_up_takes() -> None:
    world = load_world(worlds_dir() / "kitchen.yaml")
    try:
        assert world.robot is not None
        world.robot.set_position_and_orientation((0.75, 1.0, 0.0), (0, 0, 0, 1))
        answer = run_query(world, "reachable", {"target": "milk"})
        assert answer.result
        performed = perform(world, "pick-up", {"object": "milk"})
        assert (answer.details["arm"], answer.details["grasp"]) == (performed.resolved["arm"], performed.resolved["grasp"])
    finally:
        world.exit()
