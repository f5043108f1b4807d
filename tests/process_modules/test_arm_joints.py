"""move-arm-joints goes around what is in the way, as move-tcp does (issue 23): the straight path in joint space
first, then the ways `move_over` tries, then a joint-space search; it fails only when none is found, naming what
blocks, and then nothing has moved."""
from __future__ import annotations

import math

import pytest

from pycram_cli.designators import perform
from pycram_cli.failures import ManipulationFailure
from pycram_cli.planning import motion, paths
from pycram_cli.planning.reach import arm_configuration
from pycram_cli.robots import Robot
from pycram_cli.world.pose import yaw_quaternion

#: the robot beside the oven, turned 45° away from it, its left arm reaching down and out: the straight path to park
#: brushes the oven's cabinet (oven_area_area) 44 % of the way, and the way around needs a search (found with 147 legs
#: and 451 configurations checked, about 192 legs of the budget)
BESIDE_THE_OVEN = ((0.559, 1.407, 0.0), -45.0, "left", [-0.569, 0.622, 1.89, -1.264, -3.085, -1.048, -2.348])


@pytest.fixture
def world(kitchen):
    with kitchen.snapshot():
        yield kitchen


def beside_the_oven(world):
    """The robot as in BESIDE_THE_OVEN; its arm's joints."""
    position, yaw, arm, values = BESIDE_THE_OVEN
    world.robot.set_position_and_orientation(position, yaw_quaternion(math.radians(yaw)))
    world.robot.move_attached()
    joints = Robot.of(world).description.arm(arm).joints
    world.robot.reset_joints(dict(zip(joints, values)))
    return arm, joints


def object_poses(world):
    return {obj.name: obj.get_pose() for obj in world.objects if obj is not world.robot}


def test_the_straight_way_to_park_beside_the_oven_is_blocked(world):
    arm, joints = beside_the_oven(world)
    robot = Robot.of(world)
    park = arm_configuration(robot, arm, "park")
    assert motion.hits_at(robot, dict(zip(joints, world.robot.get_joint_positions(joints).values()))) == []
    assert motion.hits_at_goal(robot, park) == []
    fraction, hits, _ = motion.Motion(robot, joints).walk(park)
    assert hits and hits[0].obstacle.name == "kitchen" and hits[0].link.startswith("oven_area")
    assert 0.3 < fraction < 0.6
    # a small budget finds no way around; the search of a motion to a tool pose does
    assert paths.search_path(robot, park, edges=100) is None
    assert paths.search_path(robot, park)


def test_move_arm_joints_to_park_goes_around_the_oven(world, monkeypatch):
    arm, joints = beside_the_oven(world)
    robot = Robot.of(world)
    park = arm_configuration(robot, arm, "park")
    before = object_poses(world)
    legs: list[dict[str, float]] = []
    real_move = motion.move

    def recorded(robot_, goal, what, *args, **kwargs):
        real_move(robot_, goal, what, *args, **kwargs)  # raises when the leg is blocked: only free legs are kept
        legs.append(dict(robot_.body.get_joint_positions(list(goal))))

    monkeypatch.setattr(motion, "move", recorded)
    perform(world, "move-arm-joints", {f"{arm}-arm": "park"})
    reached = world.robot.get_joint_positions(joints)
    for name in joints:
        assert math.remainder(reached[name] - park[name], 2 * math.pi) == pytest.approx(0.0, abs=1e-6)
    assert object_poses(world) == before  # nothing was pushed aside
    assert motion.hits_at(robot, park) == []
    assert len(legs) >= 2  # around: through at least one configuration on the way, each leg checked free


def test_a_target_inside_the_oven_fails_at_once_naming_it_and_nothing_moves(world):
    perform(world, "moving", {"target": [0.75, 1.9, 0], "orientation": [0, 0, 0, 1]})
    before = world.robot.get_joint_positions()
    # the left arm stretched straight ahead at shoulder height: its hand inside the oven's front
    with pytest.raises(ManipulationFailure, match=r"moving the left arm would collide: .* inside kitchen "
                                                  r"\(oven_area_[a-z_]+\).*at its goal") as failure:
        perform(world, "move-arm-joints", {"left-arm": [0.0, 0.0, 0.0, -0.15, 0.0, -0.1, 0.0]})
    assert failure.value.details["colliding"][0] == "kitchen"
    assert world.robot.get_joint_positions() == before


def test_when_no_way_is_found_the_failure_names_what_blocks_and_nothing_moves(world, monkeypatch):
    arm, joints = beside_the_oven(world)
    monkeypatch.setattr(paths, "search_path", lambda *args, **kwargs: None)  # a world where the search finds none
    from pycram_cli.process_modules import arms
    calls: list[str] = []
    real_move_over = arms.move_over

    def recorded(robot_, arm_, *args, **kwargs):
        calls.append(arm_)
        return real_move_over(robot_, arm_, *args, **kwargs)

    monkeypatch.setattr(arms, "move_over", recorded)
    before = world.robot.get_joint_positions()
    with pytest.raises(ManipulationFailure, match=r"moving the left arm would collide: .* inside kitchen "
                                                  r"\(oven_area_area\), [0-9]+% of the way; no way around it"):
        perform(world, "move-arm-joints", {"right-arm": [-1.0, 0.0, -1.463, -2.12, 1.766, -0.07, 0.0], "left-arm": "park"})
    assert world.robot.get_joint_positions() == before  # the right arm, free to move, did not move alone either
    assert calls == ["right", "left"]  # the right arm had moved when the left one found no way: it was put back


def test_a_goal_inside_something_is_refused_before_any_way_around_is_tried(world, monkeypatch):
    """`move_over` (a location's arm test, pick-up's way to the pre-grasp pose) asks first whether the goal itself is
    inside something: every way around ends there, and so would the search. A blocked candidate pose no longer walks
    its seventy ways before it fails."""
    perform(world, "moving", {"target": [0.75, 1.9, 0], "orientation": [0, 0, 0, 1]})
    robot = Robot.of(world)
    inside_the_oven = dict(zip(robot.description.arm("left").joints, [0.0, 0.0, 0.0, -0.15, 0.0, -0.1, 0.0]))
    walked: list[dict[str, float]] = []
    real_move = motion.move

    def recorded(robot_, goal, *args, **kwargs):
        walked.append(dict(goal))
        return real_move(robot_, goal, *args, **kwargs)

    monkeypatch.setattr(motion, "move", recorded)
    monkeypatch.setattr(paths, "search_path", lambda *args, **kwargs: pytest.fail("searched for a way to a blocked goal"))
    before = world.robot.get_joint_positions()
    with pytest.raises(ManipulationFailure, match=r"inside kitchen \(oven_area_[a-z_]+\)"):
        paths.move_over(robot, "left", inside_the_oven, "the left arm's motion into the oven")
    assert walked == [inside_the_oven]  # the straight path only
    assert world.robot.get_joint_positions() == before
