"""A location where an arm reaches (reachable-for, accessing) tries other torso heights when the arm reaches from no
pose with the torso where it is (base_poses.py `_next_torso`), and the pose it finds says the height (`BasePose.torso`),
which the actions move the torso to on arriving (`go`; the whole demo on this robot: bench/zoo.py).

Zoo seed 12's 5-joint arm (a pan, three pitches, a wrist roll) holds the 27 cm cereal box only from above (its sides
are wider than the gripper opens, but for the narrow ones, which it cannot turn its tool to), and reaches its top only
with the torso raised above its default.
"""
from __future__ import annotations

import time
from pathlib import Path

import pytest

from pycram_cli.designators import perform
from pycram_cli.failures import LocationFailure
from pycram_cli.locations import LocationSpec
from pycram_cli.locations.spec import find_handle
from pycram_cli.locations import BasePoseResolution, take_from_here
from pycram_cli.robots import Robot
from pycram_cli.robots.zoo import generate, write_world
from pycram_cli.worldfile.loader import load_world

LIMIT = 8  # candidates given the expensive tests per pass: enough here, and fast


@pytest.fixture(scope="module")
def zoo_world(tmp_path_factory):
    world = load_world(write_world(generate(12), Path(tmp_path_factory.mktemp("zoo12"))))
    yield world
    world.exit()


def test_the_pose_found_with_the_torso_raised_says_so_and_pick_up_takes_the_cereal_from_it(zoo_world):
    robot = Robot.of(zoo_world)
    joint = robot.description.torso_joint
    cereal = zoo_world.get_object_by_name("cereal")
    default = robot.body.get_joint_positions([joint])[joint]
    with zoo_world.snapshot():
        start = time.perf_counter()
        pose = BasePoseResolution(robot, LocationSpec(reachable_for=cereal), limit=LIMIT).next()
        assert time.perf_counter() - start < 60
    assert robot.body.get_joint_positions([joint])[joint] == default  # the world is left as it was
    assert pose.torso is not None and pose.torso > default + 0.02
    assert pose.to_json()["torso"] == pose.torso
    with zoo_world.snapshot():
        robot.body.set_position_and_orientation(pose.position, pose.orientation)
        assert not take_from_here(robot.body, cereal)  # not with the torso where it is ...
        robot.body.reset_joints({joint: pose.torso})
        assert take_from_here(robot.body, cereal)  # ... but raised
        robot.body.reset_joints({joint: default})
        perform(zoo_world, "moving-torso", {"position": pose.torso})  # as the actions do on arriving (`go`)
        perform(zoo_world, "pick-up", {"object": "cereal", "arm": pose.arm, "grasp": pose.grasp})
        assert robot.arm_holding(cereal) == pose.arm


def test_a_robot_without_a_torso_out_of_reach_fails_with_one_pass(tmp_path):
    world = load_world(write_world(generate(1), tmp_path))
    try:
        robot = Robot.of(world)
        assert robot.description.torso_joint is None
        far = (3.0, 3.0, 2.5)  # above the room: out of every arm's reach
        with world.snapshot(), pytest.raises(LocationFailure) as failure:
            BasePoseResolution(robot, LocationSpec(reachable_for=far), limit=2).next()
        assert "torso" not in str(failure.value)
    finally:
        world.exit()


def test_a_robot_on_a_tall_lift_lowers_it_to_open_a_drawer(tmp_path):
    # zoo seed 12 on a lift that rises 1.6 m, standing at the top: no pose reaches the drawer's handle from up there;
    # the accessing location lowers the torso, and `open` (as search does) moves it there on arriving and pulls
    from xml.etree import ElementTree

    from pycram_cli.designators.actions import perform_action

    zoo = generate(12)
    world_file = write_world(zoo, tmp_path)
    robot_file = next(tmp_path.glob("*.urdf"))
    tree = ElementTree.parse(robot_file)
    joint = next(j for j in tree.getroot().findall("joint") if j.get("name") == zoo.torso_joint)
    joint.find("limit").set("upper", "1.6")
    tree.write(robot_file)
    world = load_world(world_file)
    try:
        robot = Robot.of(world)
        robot.body.reset_joints({zoo.torso_joint: 1.6})
        kitchen = world.get_object_by_name("kitchen")
        handle = "sink_area_left_upper_drawer_handle"
        with world.snapshot():
            pose = BasePoseResolution(robot, LocationSpec(accessing=find_handle(world, handle, "handle"))).next()
        assert pose.torso is not None and pose.torso < 1.6 - 0.1
        perform_action(world, "open", {"handle": handle, "distance": 0.3})
        assert robot.body.get_joint_positions([zoo.torso_joint])[zoo.torso_joint] < 1.5
        assert kitchen.get_joint_positions(["sink_area_left_upper_drawer_main_joint"])[
            "sink_area_left_upper_drawer_main_joint"] == pytest.approx(0.3, abs=0.02)
    finally:
        world.exit()
