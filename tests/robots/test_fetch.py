"""The Fetch, the second bundled robot, is pure data: every designator and query works for it.

The kitchen with a Fetch (worlds/kitchen_fetch.yaml) gets its description by the URDF's robot
name (resources/robots/fetch/fetch.yaml): one arm named `arm`, a two-finger gripper, a pan/tilt
head with the head camera, a torso lift. What it lacks (a right arm, a pose or grasp it has not
got) is an input error naming what it has, before anything runs.
"""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.designators import perform
from pycram_cli.errors import InputError
from pycram_cli.failures import NavigationFailure, PerceptionFailure
from pycram_cli.paths import worlds_dir
from pycram_cli.reasoning import run_query, stable
from pycram_cli.robots import description_for
from pycram_cli.world.pose import compose, invert
from pycram_cli.worldfile.loader import load_world

WORLD = worlds_dir() / "kitchen_fetch.yaml"
COUNTER = {"target": [0.8, 1.0, 0], "orientation": [0, 0, 0, 1]}
ISLAND = {"target": [-0.35, 1.0, 0], "orientation": [0, 0, 1, 0]}
DRAWER = {"drawer-joint": "sink_area_left_upper_drawer_main_joint",
          "drawer-handle": "sink_area_left_upper_drawer_handle", "part-of": "kitchen", "distance": 0.3}
FINGERS = ("l_gripper_finger_joint", "r_gripper_finger_joint")


@pytest.fixture(scope="module")
def kitchen():
    world = load_world(WORLD)
    yield world
    world.exit()


@pytest.fixture
def world(kitchen):
    with kitchen.snapshot():
        yield kitchen


def obj(world, name):
    return world.get_object_by_name(name)


def tool(world) -> np.ndarray:
    return np.array(world.robot.get_link_position("gripper_link"))


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


# -- the world and its robot ---------------------------------------------------------------------


def test_the_kitchen_has_a_fetch_with_the_bundled_description_and_the_same_objects_as_the_pr2s(world):
    desc = description_for(world.robot)
    assert world.robot.name == "fetch" and desc.name == "fetch"
    assert desc.path.name == "fetch.yaml" and list(desc.arms) == ["arm"]
    pr2_kitchen = load_world()
    try:
        theirs = {o.name: (o.type, o.get_position()) for o in pr2_kitchen.objects if o.type != "robot"}
    finally:
        pr2_kitchen.exit()
    assert {o.name: (o.type, o.get_position()) for o in world.objects if o.type != "robot"} == theirs


def test_the_world_raises_the_torso_to_the_descriptions_default_and_parks_the_arm(world):
    desc = description_for(world.robot)
    assert world.robot.get_joint_position(desc.torso_joint) == pytest.approx(desc.torso_default)
    arm = desc.arm("arm")
    assert list(world.robot.get_joint_positions(arm.joints).values()) == pytest.approx(arm.poses["park"])


def test_everything_stands_still_in_the_world_as_loaded(world):
    for name in ("milk", "cereal", "bowl", "bottle", "spoon"):
        assert stable(obj(world, name)), name


# -- every motion designator -------------------------------------------------------------------


def test_moving_drives_to_the_counter_and_refuses_to_drive_into_it(world):
    perform(world, "moving", COUNTER)
    assert world.robot.get_position() == (0.8, 1.0, 0.0)
    with pytest.raises(NavigationFailure, match=r"would collide with .*kitchen \(base_link"):
        perform(world, "moving", {"target": [1.1, 1.0, 0]})
    assert world.robot.get_position() == (0.8, 1.0, 0.0)


def test_move_arm_joints_takes_the_arms_own_name_and_its_poses(world):
    desc = description_for(world.robot).arm("arm")
    for pose in ("carry", "park"):
        perform(world, "move-arm-joints", {"arms": {"arm": pose}})
        assert list(world.robot.get_joint_positions(desc.joints).values()) == pytest.approx(desc.poses[pose])
    perform(world, "move-arm-joints", {"arms": {"arm": {"shoulder_pan_joint": 0.5}}})
    assert world.robot.get_joint_position("shoulder_pan_joint") == 0.5


def test_looking_points_the_head_cameras_optical_axis_at_the_target(world):
    perform(world, "moving", COUNTER)
    target = (1.3, 0.6, 0.9)
    perform(world, "looking", {"target": list(target)})
    camera = world.robot.get_link_position_and_orientation("head_camera_rgb_optical_frame")
    local = np.array(compose(invert(camera), (target, (0, 0, 0, 1)))[0])
    assert math.degrees(math.acos(local[2] / np.linalg.norm(local))) < 1.0


def test_detecting_sees_the_milk_from_the_head_camera_but_not_the_spoon_in_the_closed_drawer(world):
    perform(world, "moving", COUNTER)
    perform(world, "looking", {"target": [1.3, 1.0, 0.95]})
    assert perform(world, "detecting", {"object-type": "milk"}).result is obj(world, "milk")
    with pytest.raises(PerceptionFailure, match="no spoon is visible"):
        perform(world, "detecting", {"object-type": "spoon"})
    assert perform(world, "world-state-detecting", {"object-type": "spoon"}).result is obj(world, "spoon")


def test_the_gripper_opens_and_closes_both_fingers(world):
    perform(world, "opening-gripper", {"gripper": "arm"})
    assert list(world.robot.get_joint_positions(FINGERS).values()) == [0.05, 0.05]
    perform(world, "closing-gripper", {"gripper": "arm"})
    assert list(world.robot.get_joint_positions(FINGERS).values()) == [0.0, 0.0]


def test_move_tcp_brings_the_gripper_to_a_point_with_a_grasp_orientation(world):
    perform(world, "moving", COUNTER)
    done = perform(world, "move-tcp", {"target": [1.2, 1.0, 1.1], "orientation": "top"})
    assert done.resolved["arm"] == "arm"
    assert np.linalg.norm(tool(world) - [1.2, 1.0, 1.1]) < 0.01


def test_pick_up_resolves_the_only_arm_and_a_grasp_that_reaches_then_place_puts_the_milk_on_the_island(world):
    perform(world, "moving", COUNTER)
    milk = obj(world, "milk")
    done = perform(world, "pick-up", {"object": "milk"})
    # close to the counter a front grasp of the tall carton is out of reach: from above it is
    assert done.resolved == {"object": "milk", "arm": "arm", "grasp": "top"}
    assert world.robot.attachments[milk].parent_link == world.robot.get_link_id("gripper_link")
    # both fingers close on the 7 cm carton (its box, with PyBullet's collision margin, is 7.8 cm)
    left, right = world.robot.get_joint_positions(FINGERS).values()
    assert left == right and 0.035 <= left < 0.042  # closed on it, not left open (0.05)
    perform(world, "move-arm-joints", {"arms": {"arm": "carry"}})
    perform(world, "moving", ISLAND)
    done = perform(world, "place", {"object": "milk", "target": [-0.8, 1.0, 0.862]})
    assert done.resolved["arm"] == "arm"
    assert milk not in world.robot.attachments
    perform(world, "move-arm-joints", {"arms": {"arm": "park"}})
    assert milk.get_position() == pytest.approx((-0.8, 1.0, 0.862), abs=1e-3)  # where physics let it settle
    assert stable(milk)


def test_accessing_opens_the_drawer_with_the_arm_and_the_spoon_can_then_be_seen(world):
    perform(world, "moving", {"target": [0.6, 0.89, 0], "orientation": [0, 0, 0, 1]})
    done = perform(world, "accessing", DRAWER)
    assert done.resolved["arm"] == "arm"
    assert obj(world, "kitchen").get_joint_position(DRAWER["drawer-joint"]) == pytest.approx(0.3)
    perform(world, "move-arm-joints", {"arms": {"arm": "park"}})
    perform(world, "looking", {"target": [1.25, 0.9, 0.72]})
    assert perform(world, "detecting", {"object-type": "spoon"}).result is obj(world, "spoon")


# -- every reasoning query -------------------------------------------------------------------------


@pytest.mark.parametrize("query, args, expected", [
    ("stable", {"object": "milk"}, True),
    ("contact", {"a": "kitchen", "b": "milk"}, True),
    ("supporting", {"a": "kitchen", "b": "milk"}, True),
    ("visible", {"object": "milk"}, True),
    ("visible", {"object": "spoon"}, False),
    ("occluding", {"object": "spoon"}, ["kitchen"]),
])
def test_perception_and_physics_queries_answer_on_the_fetch_kitchen(world, query, args, expected):
    answer = run_query(world, query, args)
    assert answer.result == expected
    if query in ("visible", "occluding"):
        assert answer.args["from"] == "head_camera_rgb_optical_frame"


def test_reachable_and_blocking_answer_for_the_arm_from_the_counter(world):
    perform(world, "moving", COUNTER)
    reach = run_query(world, "reachable", {"target": "milk", "grasp": "top"})
    assert reach.result is True and reach.args["arm"] == "arm"
    assert set(reach.details["joint_positions"]) == set(description_for(world.robot).arm("arm").joints)
    far = run_query(world, "reachable", {"target": [1.3, 1.0, 2.3]})
    assert far.result is False and far.details["position_error"] > 0.1
    blockers = run_query(world, "blocking", {"target": "milk", "grasp": "top", "exclude-type": ["environment"]})
    assert blockers.result == []


# -- what the Fetch has not got: input errors naming what it has ----------------------------------------


@pytest.mark.parametrize("step, message", [
    ("pick-up: {object: milk, arm: right}", "fetch has no arm 'right' (arms: arm)"),
    ("place: {object: milk, target: [-0.8, 1, 0.862], arm: left}", "fetch has no arm 'left' (arms: arm)"),
    ("move-arm-joints: {left-arm: park}", "fetch has no arm 'left' (arms: arm)"),
    ("move-arm-joints: {arms: {arm: tuck}}", "fetch has no pose 'tuck' (poses: park, carry)"),
    ("pick-up: {object: milk, grasp: side}", "fetch has no grasp 'side' (grasps: front, top, left, right)"),
    ("opening-gripper: {gripper: right}", "fetch has no arm 'right' (arms: arm)"),
])
def test_asking_for_what_the_fetch_lacks_is_an_input_error_before_anything_runs(tmp_path: Path, step, message):
    plan = tmp_path / "plan.yaml"
    plan.write_text(f"world: kitchen_fetch\nbody:\n  - {step}\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2, result.output
    assert message in result.stderr
    assert f"{plan}:3:" in result.stderr


def test_performing_with_an_arm_the_fetch_lacks_says_which_arms_it_has(world):
    with pytest.raises(InputError, match=r"no arm 'right' \(arms: arm\)"):
        perform(world, "pick-up", {"object": "milk", "arm": "right"})


def test_failures_name_the_fetchs_arm_and_gripper_as_a_sentence_would(world):
    # its only arm is called `arm`: "the arm cannot take ...", never "the arm arm"
    from pycram_cli.failures import ManipulationFailure, ReachabilityFailure
    from pycram_cli.planning.pick_place import plan_grasp
    from pycram_cli.robots import Robot
    perform(world, "moving", COUNTER)
    robot = Robot.of(world)
    said = []
    for grasp in robot.description.grasps:
        try:
            plan_grasp(robot, "arm", obj(world, "milk"), grasp)
        except (ManipulationFailure, ReachabilityFailure) as failure:
            said.append(str(failure))
    assert said, "some grasp of the milk fails from the counter"
    assert all("arm arm" not in text and "arm gripper" not in text for text in said), said
    assert any(text.startswith(("arm cannot reach milk", "the arm cannot take milk")) for text in said), said


def test_a_query_for_an_arm_the_fetch_lacks_is_an_input_error():
    result = run("query", "reachable", "milk", "--arm", "right", "--world", "kitchen_fetch")
    assert result.exit_code == 2, result.output
    assert "robot 'fetch' has no arm 'right' (arms: arm)" in result.stderr


# -- the command line -------------------------------------------------------------------------------


def test_world_show_lists_the_fetch_kitchen():
    result = run("world", "show", str(WORLD))
    assert result.exit_code == 0, result.output
    for text in ("kitchen_fetch.yaml: 8 objects", "fetch", "robots/fetch/fetch.urdf", "milk"):
        assert text in result.stdout
    assert re.search(r"torso_lift_joint +0\.300 m", result.stdout)
    data = json.loads(run("world", "show", "kitchen_fetch", "--json").stdout)
    assert data["robot"] == "fetch"


def test_query_visible_milk_uses_the_fetchs_head_camera():
    result = run("query", "visible", "milk", "--world", "kitchen_fetch")
    assert result.exit_code == 0, result.output
    assert "milk is visible: 100% of its pixels seen from head_camera_rgb_optical_frame" in result.stdout


def test_query_reachable_milk_answers_for_the_fetchs_arm():
    result = run("query", "reachable", "milk", "--world", "kitchen_fetch", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    # from where the world puts it, 0.7 m behind the counter's edge, the arm is short of the milk
    assert data["result"] is False
    assert data["details"]["arm"] == "arm" and data["details"]["gripper_link"] == "gripper_link"
    assert list(data["details"]["arms_tried"]) == ["arm"]
    text = run("query", "reachable", "milk", "--world", "kitchen_fetch")
    assert text.exit_code == 0 and "milk is NOT reachable" in text.stdout
