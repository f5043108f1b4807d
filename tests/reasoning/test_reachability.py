"""reachable(target, robot, gripper_link, grasp) and blocking(...): can the arm get there, and what would it touch?"""
from __future__ import annotations

import math

import pytest
from scenes import COUNTER_POSE, fingerprint

from pycram_cli.reasoning import ReachableAnswer, blocking, reachable
from pycram_cli.world.pose import angle_between

LEFT, RIGHT = "l_gripper_tool_frame", "r_gripper_tool_frame"


@pytest.fixture
def at_counter(scene):
    """The robot in front of the counter, where the demo picks the breakfast up."""
    scene.robot.set_position_and_orientation(*COUNTER_POSE)
    return scene


def names(objects):
    return [o.name for o in objects]


def test_the_milk_is_out_of_reach_from_the_start_pose(scene):
    answer = reachable(scene.get_object_by_name("milk"), scene.robot, LEFT)
    assert not answer and answer.position_error > 0.2


@pytest.mark.parametrize("tool", [LEFT, RIGHT])
def test_the_milk_is_reachable_from_the_counter(at_counter, tool):
    milk = at_counter.get_object_by_name("milk")
    answer = reachable(milk, at_counter.robot, tool)
    assert isinstance(answer, ReachableAnswer) and answer
    assert answer.position_error < 0.001 and answer.orientation_error is None
    at_counter.robot.set_joint_positions(answer.joint_positions)
    assert math.dist(at_counter.robot.get_link_position(tool), milk.get_position()) < 0.001


def test_a_named_grasp_is_relative_to_the_robot_base(at_counter):
    robot = at_counter.robot
    answer = reachable(at_counter.get_object_by_name("milk"), robot, RIGHT, grasp="front")
    assert answer and answer.orientation_error < 0.1
    robot.set_joint_positions(answer.joint_positions)
    assert angle_between(robot.get_link_orientation(RIGHT), robot.get_orientation()) < 0.1  # pointing forward


def test_a_grasp_can_be_a_world_quaternion(at_counter):
    top = (0.0, 0.7071068, 0.0, 0.7071068)
    answer = reachable((1.3, 0.8, 1.0), at_counter.robot, LEFT, grasp=top)
    assert answer and answer.orientation_error < 0.1


def test_a_pose_target_uses_its_orientation_as_the_grasp(at_counter):
    top = (0.0, 0.7071068, 0.0, 0.7071068)
    answer = reachable(((1.3, 0.8, 1.0), top), at_counter.robot, LEFT)
    assert answer and answer.orientation_error is not None and answer.orientation_error < 0.1


def test_a_grasp_the_arm_cannot_take_is_unreachable_even_when_the_position_is(at_counter):
    milk, robot = at_counter.get_object_by_name("milk"), at_counter.robot
    assert reachable(milk, robot, RIGHT)
    answer = reachable(milk, robot, RIGHT, grasp="left")  # the right arm pointing to the robot's right side
    assert not answer and (answer.position_error > 0.01 or answer.orientation_error > 0.1)


def test_the_distance_threshold_is_configurable(at_counter):
    target = (1.3, 0.6, 1.9)
    answer = reachable(target, at_counter.robot, LEFT)
    assert not answer
    assert reachable(target, at_counter.robot, LEFT, threshold=answer.position_error + 0.01)


def test_unknown_grasps_name_the_known_ones(at_counter):
    with pytest.raises(ValueError, match="front, top, left, right"):
        reachable((1.3, 0.6, 1.0), at_counter.robot, LEFT, grasp="sideways")


def test_reachable_leaves_the_world_exactly_as_it_was(at_counter):
    before = fingerprint(at_counter)
    reachable(at_counter.get_object_by_name("milk"), at_counter.robot, RIGHT, grasp="front")
    reachable((3.0, 0.0, 1.0), at_counter.robot, LEFT)
    assert fingerprint(at_counter) == before


def test_an_object_in_the_way_blocks_the_arm(at_counter):
    milk, bottle = at_counter.get_object_by_name("milk"), at_counter.get_object_by_name("bottle")
    robot = at_counter.robot
    assert names(blocking(milk, robot, RIGHT, grasp="front", exclude_types=["environment"])) == []
    bottle.set_position((1.19, 1.0, 0.80))  # hanging right where the hand goes
    assert names(blocking(milk, robot, RIGHT, grasp="front", exclude_types=["environment"])) == ["bottle"]


def test_blocking_never_lists_the_target_the_robot_or_excluded_types(at_counter):
    milk, robot = at_counter.get_object_by_name("milk"), at_counter.robot
    found = names(blocking(milk, robot, RIGHT, grasp="front"))
    assert "milk" not in found and "pr2" not in found
    assert "kitchen" in found  # reaching the milk's base, the fingers touch the counter
    assert "kitchen" not in names(blocking(milk, robot, RIGHT, grasp="front", exclude_types=["environment"]))


def test_blocking_an_unreachable_target_uses_the_best_solution(at_counter):
    found = blocking((1.3, 0.8, 0.3), at_counter.robot, RIGHT)  # below the counter top
    assert found == [at_counter.get_object_by_name("kitchen")]


def test_what_the_robot_holds_moves_with_the_hand_and_can_block(at_counter):
    robot, bowl, cereal = at_counter.robot, at_counter.get_object_by_name("bowl"), at_counter.get_object_by_name("cereal")
    over_the_cereal = (1.22, 0.6, 1.1)  # the hand stops short of the box, just above its top
    assert names(blocking(over_the_cereal, robot, LEFT, grasp="front", exclude_types=["environment"])) == []
    robot.set_joint_positions(reachable((1.0, 0.6, 1.2), robot, LEFT, grasp="front").joint_positions)
    hand = robot.get_link_position(LEFT)
    bowl.set_position((hand[0] + 0.06, hand[1], hand[2] - 0.02))  # held in front of the fingers
    robot.attach(bowl, LEFT)
    before = fingerprint(at_counter)
    found = names(blocking(over_the_cereal, robot, LEFT, grasp="front", exclude_types=["environment"]))
    assert found == ["cereal"]  # the held bowl is pushed into the cereal box
    assert "bowl" not in names(blocking(bowl, robot, LEFT))
    assert fingerprint(at_counter) == before


def test_blocking_leaves_the_world_exactly_as_it_was(at_counter):
    before = fingerprint(at_counter)
    blocking(at_counter.get_object_by_name("milk"), at_counter.robot, LEFT, grasp="top")
    blocking((3.0, 0.0, 1.0), at_counter.robot, RIGHT)
    assert fingerprint(at_counter) == before
