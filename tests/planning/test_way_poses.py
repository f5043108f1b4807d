"""The poses a way round goes through (`paths._shifted`) are searched for only as long as a waypoint needs.

A waypoint need only be within the reach thresholds: an arm that reaches it only to within millimetres (zoo seed 21's
pan, three pitch joints, telescope and wrist roll, keeping the tool's orientation while it moves up) creeps towards
that residual for as long as a search may run. Each of the two searches of a waypoint (from where the arm is, from
the middle of its ranges) stops after `VIA_ITERATIONS`; the pose found still counts (it is within the thresholds).
"""
from __future__ import annotations

import pytest

from pycram_cli.planning import paths
from pycram_cli.reasoning import ik_search
from pycram_cli.robots import Robot
from pycram_cli.robots.zoo import generate, write_world
from pycram_cli.worldfile.loader import load_world


@pytest.fixture
def creeping_arm(tmp_path):
    world = load_world(write_world(generate(21), tmp_path))
    yield Robot.of(world)
    world.exit()


def test_a_waypoint_the_arm_reaches_only_to_millimetres_is_found_within_the_waypoints_iterations(creeping_arm,
                                                                                                 monkeypatch):
    robot = creeping_arm
    arm = next(iter(robot.description.arms))
    start = robot.body.get_joint_positions(list(robot.description.arm(arm).joints))
    steps: list[int] = []
    original = ik_search._GroupSearch.step

    def counted(self: ik_search._GroupSearch) -> None:
        steps.append(1)
        original(self)

    monkeypatch.setattr(ik_search._GroupSearch, "step", counted)
    up = paths._shifted(robot, arm, start, 0.1)
    assert up is not None  # 10 cm up from the parked arm: reached, within the thresholds
    assert 0 < len(steps) <= 2 * paths.VIA_ITERATIONS  # it used to creep on for MAX_ITERATIONS (60) per search
