"""Grasp planning takes the first way to hold an object whose open gripper gets in to it: a way whose way in from
its pre-grasp pose brushes a neighbour is passed over for the next way (pick-up moves in until the first touch, so
its fingers would close on nothing), and only when every way does is the grasp refused, saying so."""
from __future__ import annotations

import pytest

from pycram_cli.failures import ManipulationFailure
from pycram_cli.planning import pick_place
from pycram_cli.robots import Robot


@pytest.fixture
def before_milk(world):
    """The PR2 before the counter where the demo takes the milk from the top, its arms parked."""
    world.robot.set_position_and_orientation((0.75, 1.15, 0.0), (0.0, 0.0, 0.041393, 0.999143))
    return Robot.of(world), world.get_object_by_name("milk")


def brushing(monkeypatch, ways: int):
    """Make the first `ways` ways in brush the bottle (as the cereal's did on the Fetch); the ways tried, in order."""
    tried: list[tuple] = []
    original = pick_place._approach_hits

    def approach(robot, obj, pre, solution, opened):
        tried.append(tuple(solution.joint_positions.values()))
        hits = original(robot, obj, pre, solution, opened)
        if len(tried) <= ways:
            bottle = robot.world.get_object_by_name("bottle")
            hits = [pick_place.motion.Hit("r_gripper_l_finger_tip_link", bottle, "bottle", 0.002)]
        return hits

    monkeypatch.setattr(pick_place, "_approach_hits", approach)
    return tried


def test_a_way_in_that_brushes_a_neighbour_is_passed_over_for_the_next(before_milk, monkeypatch):
    robot, milk = before_milk
    tried = brushing(monkeypatch, 1)
    _, _, solution = pick_place.plan_grasp(robot, "right", milk, "top")
    assert len(tried) == 2 and tuple(solution.joint_positions.values()) == tried[1]


def test_a_grasp_every_way_in_of_which_brushes_is_refused_saying_so(before_milk, monkeypatch):
    robot, milk = before_milk
    brushing(monkeypatch, 1000)
    with pytest.raises(ManipulationFailure, match="on the way in from the pre-grasp pose") as caught:
        pick_place.plan_grasp(robot, "right", milk, "top")
    assert "bottle" in caught.value.details["colliding"]
