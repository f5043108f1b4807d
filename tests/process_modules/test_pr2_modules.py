"""Every designator performed on the kitchen world with the PR2, including each failure."""
from __future__ import annotations

import math

import numpy as np
import pytest

from pycram_cli.designators import DESIGNATORS, perform
from pycram_cli.errors import InputError
from pycram_cli.failures import (GripperFailure, ManipulationFailure, NavigationFailure, PerceptionFailure,
                                 ReachabilityFailure)
from pycram_cli.process_modules import PROCESS_MODULES
from pycram_cli.robots import description_for
from pycram_cli.world.pose import compose, invert

COUNTER = {"target": [0.65, 0.7, 0], "orientation": [0, 0, 0, 1]}
ISLAND = {"target": [-0.3, 1.0, 0], "orientation": [0, 0, 1, 0]}
DRAWER = {"drawer-joint": "sink_area_left_upper_drawer_main_joint",
          "drawer-handle": "sink_area_left_upper_drawer_handle", "part-of": "kitchen", "arm": "left", "distance": 0.3}


@pytest.fixture
def world(kitchen):
    with kitchen.snapshot():
        yield kitchen


def tool_position(world, arm):
    desc = description_for(world.robot)
    return np.array(world.robot.get_link_position(desc.arm(arm).tool_frame))


def test_every_designator_names_a_registered_process_module():
    assert {name: spec.module in PROCESS_MODULES for name, spec in DESIGNATORS.items()} == {
        name: True for name in ("moving", "pick-up", "place", "accessing", "looking", "opening-gripper",
                                "closing-gripper", "detecting", "move-tcp", "move-arm-joints", "world-state-detecting",
                                "moving-torso")}


def test_moving_teleports_the_base_and_keeps_the_orientation_by_default(world):
    before = world.robot.get_orientation()
    done = perform(world, "moving", {"target": [0.65, 0.7, 0]})
    assert world.robot.get_position() == (0.65, 0.7, 0.0)
    assert done.resolved["orientation"] == pytest.approx(list(before))


def test_moving_into_the_counter_fails_and_leaves_the_robot_where_it_was(world):
    with pytest.raises(NavigationFailure, match=r"cannot stand at \(1\.300, 0\.700\): it would collide with .*kitchen \(base_link"):
        perform(world, "moving", {"target": [1.3, 0.7, 0]})
    assert world.robot.get_position() == (0.0, 0.7, 0.0)


def test_move_arm_joints_parks_both_arms_by_name(world):
    perform(world, "move-arm-joints", {"left-arm": [0.5, 0, 0, -1, 0, -0.5, 0], "right-arm": "park"})
    desc = description_for(world.robot)
    joints = world.robot.get_joint_positions(desc.arm("right").joints)
    assert list(joints.values()) == pytest.approx(desc.arm("right").poses["park"])
    assert world.robot.get_joint_position("l_shoulder_pan_joint") == 0.5


def test_move_arm_joints_with_an_unknown_pose_name_suggests_one(world):
    with pytest.raises(InputError, match="no pose 'parc' \\(did you mean 'park'\\?\\)"):
        perform(world, "move-arm-joints", {"left-arm": "parc"})


def test_looking_points_the_cameras_optical_axis_at_the_target(world):
    target = (1.3, 0.6, 1.0)
    perform(world, "looking", {"target": list(target)})
    camera = world.robot.get_link_position_and_orientation(description_for(world.robot).camera.frame)
    local = np.array(compose(invert(camera), (target, (0, 0, 0, 1)))[0])
    assert math.degrees(math.acos(local[2] / np.linalg.norm(local))) < 1.0


def test_looking_beyond_the_head_limits_fails(world):
    with pytest.raises(ReachabilityFailure, match="head cannot turn far enough"):
        perform(world, "looking", {"target": [0.0, 0.7, 6.0]})


def test_detecting_finds_a_visible_object_by_type(world):
    perform(world, "moving", COUNTER)
    perform(world, "looking", {"target": [1.3, 0.8, 0.95]})
    assert perform(world, "detecting", {"object-type": "milk"}).result is world.get_object_by_name("milk")


def test_detecting_the_spoon_in_the_closed_drawer_is_a_perception_failure(world):
    perform(world, "moving", COUNTER)
    perform(world, "looking", {"target": [1.3, 0.9, 0.75]})
    with pytest.raises(PerceptionFailure, match="no spoon is visible from the robot's camera"):
        perform(world, "detecting", {"object-type": "spoon"})
    with pytest.raises(PerceptionFailure, match="no object of type 'fork'"):
        perform(world, "detecting", {"object-type": "fork"})


def test_world_state_detecting_finds_objects_whether_visible_or_not(world):
    assert perform(world, "world-state-detecting", {"object-type": "spoon"}).result.name == "spoon"
    with pytest.raises(PerceptionFailure):
        perform(world, "world-state-detecting", {"object-type": "fork"})


def test_accessing_pulls_the_drawer_open_with_the_spoon_inside(world):
    events = []
    world.manipulation_event += lambda obj, joint, old, new: events.append((obj.name, joint))
    spoon = world.get_object_by_name("spoon")
    x_before = spoon.get_position()[0]
    perform(world, "moving", COUNTER)
    done = perform(world, "accessing", {k: v for k, v in DRAWER.items() if k not in ("arm", "distance")})
    kitchen = world.get_object_by_name("kitchen")
    assert kitchen.get_joint_position(DRAWER["drawer-joint"]) == pytest.approx(0.3)
    assert spoon.get_position()[0] == pytest.approx(x_before - 0.3, abs=1e-6)
    assert done.resolved["distance"] == 0.3 and done.resolved["arm"] in ("left", "right")
    assert ("kitchen", DRAWER["drawer-joint"]) in events
    perform(world, "looking", {"object": "spoon"})
    assert perform(world, "detecting", {"object-type": "spoon"}).result is spoon


def test_pick_up_attaches_the_object_to_the_tool_frame(world):
    milk = world.get_object_by_name("milk")
    perform(world, "moving", COUNTER)
    done = perform(world, "pick-up", {"object": "milk"})
    arm = done.resolved["arm"]
    assert done.resolved["grasp"] in ("front", "top", "left", "right")
    assert milk in world.robot.attachments
    centre = (np.array(milk.get_aabb()[0]) + np.array(milk.get_aabb()[1])) / 2
    assert np.linalg.norm(tool_position(world, arm) - centre) < 0.03
    perform(world, "moving", {"target": [0.3, 0.7, 0]})
    assert milk.get_position()[0] == pytest.approx(1.3 - 0.35, abs=1e-6)


def test_pick_up_out_of_reach_says_how_far_off_it_stays(world):
    with pytest.raises(ReachabilityFailure, match=r"right arm cannot reach milk.* cm away"):
        perform(world, "pick-up", {"object": "milk", "arm": "right", "grasp": "front"})


def test_pick_up_with_a_full_gripper_is_a_gripper_failure(world):
    perform(world, "moving", COUNTER)
    perform(world, "pick-up", {"object": "milk", "arm": "left"})
    with pytest.raises(GripperFailure, match="left gripper already holds milk"):
        perform(world, "pick-up", {"object": "bowl", "arm": "left"})


def test_place_puts_the_held_object_at_the_target_and_lets_go(world):
    milk = world.get_object_by_name("milk")
    perform(world, "moving", COUNTER)
    perform(world, "pick-up", {"object": "milk", "arm": "left"})
    perform(world, "move-arm-joints", {"left-arm": "park", "right-arm": "park"})  # carry it tucked in
    perform(world, "moving", ISLAND)
    perform(world, "place", {"object": "milk", "target": [-0.8, 1.0, 0.862]})
    assert milk.get_position() == pytest.approx((-0.8, 1.0, 0.862), abs=0.005)
    assert milk not in world.robot.attachments
    world.simulate(1.0)
    assert milk.get_position() == pytest.approx((-0.8, 1.0, 0.862), abs=0.005)


def test_place_without_holding_the_object_is_a_manipulation_failure(world):
    with pytest.raises(ManipulationFailure, match="not holding it"):
        perform(world, "place", {"object": "milk", "target": [-0.8, 1.0, 0.862]})


def test_place_out_of_reach_is_a_reachability_failure(world):
    perform(world, "moving", COUNTER)
    perform(world, "pick-up", {"object": "milk", "arm": "left"})
    with pytest.raises(ReachabilityFailure, match="left arm cannot place milk"):
        perform(world, "place", {"object": "milk", "target": [-0.8, 1.0, 0.862]})


def test_grippers_open_and_close(world):
    desc = description_for(world.robot).arm("right").gripper
    perform(world, "opening-gripper", {"gripper": "right"})
    assert world.robot.get_joint_position(desc.joints[0]) == pytest.approx(desc.open)
    perform(world, "closing-gripper", {"gripper": "right"})
    assert world.robot.get_joint_position(desc.joints[0]) == pytest.approx(desc.closed)


def test_move_tcp_brings_the_tool_frame_to_the_target(world):
    perform(world, "moving", COUNTER)
    done = perform(world, "move-tcp", {"target": [1.1, 0.5, 1.0], "orientation": "front"})
    assert np.linalg.norm(tool_position(world, done.resolved["arm"]) - [1.1, 0.5, 1.0]) < 0.01


def test_move_tcp_out_of_reach_fails(world):
    with pytest.raises(ReachabilityFailure, match="no arm can reach"):
        perform(world, "move-tcp", {"target": [3.0, 3.0, 3.0]})


def test_bad_slots_are_input_errors_naming_the_slot(world):
    from pycram_cli.errors import InputError, InputErrors

    with pytest.raises((InputError, InputErrors), match="did you mean 'object'"):
        perform(world, "pick-up", {"objekt": "milk"})
    with pytest.raises(InputError, match="no object 'mlk' \\(did you mean 'milk'\\?\\)"):
        perform(world, "pick-up", {"object": "mlk"})


def test_pick_up_chooses_a_grasp_the_gripper_can_hold(world):
    perform(world, "moving", COUNTER)
    with world.snapshot():
        cereal = perform(world, "pick-up", {"object": "cereal", "arm": "right"})
        assert cereal.resolved["grasp"] == "top"  # 19 cm wide from the front: taken from above, across its 7 cm depth
    bowl = perform(world, "pick-up", {"object": "bowl", "arm": "right"})
    assert bowl.resolved["grasp"] == "top"  # by the rim (resources/objects/grasps.yaml)


def test_a_grasp_the_gripper_cannot_hold_is_a_gripper_failure(world):
    perform(world, "moving", COUNTER)
    with pytest.raises(GripperFailure, match="cannot hold cereal with a front grasp: it is 19.\\d cm wide"):
        perform(world, "pick-up", {"object": "cereal", "arm": "right", "grasp": "front"})
    with pytest.raises(GripperFailure, match="cannot hold bowl with a front grasp: bowl objects are not held that way"):
        perform(world, "pick-up", {"object": "bowl", "arm": "right", "grasp": "front"})


def test_a_flat_object_is_taken_from_the_top(world):
    perform(world, "moving", COUNTER)
    perform(world, "accessing", DRAWER)
    with pytest.raises(GripperFailure, match="spoon with a front grasp: spoon objects are not held that way"):
        perform(world, "pick-up", {"object": "spoon", "arm": "right", "grasp": "front"})  # by the handle, from above
    assert perform(world, "pick-up", {"object": "spoon", "arm": "right"}).resolved["grasp"] == "top"


def test_the_gripper_closes_on_the_object_not_through_it(world):
    perform(world, "moving", COUNTER)
    perform(world, "pick-up", {"object": "milk", "arm": "left"})
    gripper = description_for(world.robot).arm("left").gripper
    opening = world.robot.get_joint_position(gripper.joints[0])
    assert gripper.closed < opening < gripper.open
