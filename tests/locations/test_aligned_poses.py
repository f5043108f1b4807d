"""Base poses in line with an arm's reach line (resolve.line_poses, pull_aligned_poses, aligned_reach_line): an arm
that keeps its tool in its pan's plane (a pan, pitches and a wrist roll) reaches with a front grasp only straight
ahead of itself, so the candidates for it put that line through the target, whatever the arm's mount offset."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pycram_cli.locations import locate
from pycram_cli.locations.resolve import (STEP, ArmGeometry, aligned_reach_line, line_poses, pull_aligned_poses,
                                          straight_reach_line)
from pycram_cli.process_modules import Robot
from pycram_cli.robots.zoo import generate, write_world
from pycram_cli.worldfile.loader import load_world


HANDLE = "sink_area_left_upper_drawer_handle"


def _in_base_frame(point, x, y, yaw):
    dx, dy = point[0] - x, point[1] - y
    return np.cos(yaw) * dx + np.sin(yaw) * dy, -np.sin(yaw) * dx + np.cos(yaw) * dy


@pytest.mark.parametrize("heading", [0.0, math.pi / 2, -2.5])
def test_the_reach_line_of_an_offset_arm_runs_through_the_point(heading):
    arm = ArmGeometry("right", np.array([0.12, -0.2, 0.9]), 0.8)
    point = (1.2, 0.9, 0.8)
    xs, ys, yaws = line_poses(point, heading, arm, line=-0.23)
    assert len(xs) == int(0.8 / STEP)
    assert np.allclose(yaws, heading)
    ahead, lateral = _in_base_frame(point, xs, ys, yaws)
    assert np.allclose(lateral, -0.23)  # the point lies on the arm's line, not on the base's centre line
    assert np.allclose(np.diff(ahead), STEP) and ahead[0] == pytest.approx(0.12 + STEP)  # shoulder to arm's length


def test_pull_aligned_poses_face_into_the_drawer():
    arm = ArmGeometry("arm", np.array([0.1, 0.05, 1.0]), 0.7)
    closed, opened = (1.19, 0.89, 0.77), (0.71, 0.89, 0.77)  # pulled towards -x
    xs, ys, yaws = pull_aligned_poses(closed, opened, arm, line=0.05)
    assert np.allclose(yaws, 0.0) and np.all(xs < closed[0])
    assert np.allclose(ys, 0.89 - 0.05)
    assert all(len(a) == 0 for a in pull_aligned_poses(closed, closed, arm, 0.0))  # no pull: none


@pytest.fixture(scope="module")
def zoo_world(tmp_path_factory):
    world = load_world(write_world(generate(1), Path(tmp_path_factory.mktemp("zoo1"))))
    yield world
    world.exit()


def test_only_an_arm_that_cannot_orient_its_tool_freely_gets_a_reach_line(zoo_world):
    robot = Robot.of(zoo_world)
    arm = next(iter(robot.description.arms))
    line = aligned_reach_line(robot, arm)  # seed 1: pan, three pitches, a wrist roll
    assert line is not None and line == pytest.approx(straight_reach_line(robot, arm))


def test_a_five_joint_arm_finds_where_to_open_the_drawer_in_line_with_its_pull(zoo_world):
    robot = Robot.of(zoo_world)
    arm = next(iter(robot.description.arms))
    with zoo_world.snapshot():
        pose = locate(zoo_world, {"accessing": HANDLE}).next()
    assert pose.arm == arm and pose.grasp == "front"
    kitchen = zoo_world.get_object_by_name("kitchen")
    handle = kitchen.get_link_position(HANDLE)
    pull = kitchen.joint("sink_area_left_upper_drawer_main_joint")
    assert pose.yaw == pytest.approx(0.0, abs=1e-5)  # facing along the pull (this drawer opens towards -x)
    _, lateral = _in_base_frame(handle, pose.position[0], pose.position[1], pose.yaw)
    assert lateral == pytest.approx(aligned_reach_line(robot, arm), abs=1e-6)  # the handle on the arm's line
    assert pull.type == "prismatic"


def test_the_pr2s_arms_get_none():
    world = load_world()
    try:
        robot = Robot.of(world)
        assert all(aligned_reach_line(robot, arm) is None for arm in robot.description.arms)
    finally:
        world.exit()
