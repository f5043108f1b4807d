"""A multi-finger hand takes the milk palm-first, wraps it with its fingers, and carries it.

The robot (tests/robots/robot_variants.py) is the zoo's seed-2 robot on wheels with its gripper
replaced by three fingers of two curling revolute joints each; its description says only which
joints the gripper has and their open and closed values: the approach (palm-first), the thumb's
direction (its limits are negative) and the grasp point (the palm's face) are read from the model.
Told to approach fingers-first, as pick-up always did, the same hand closes on nothing.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from pycram_cli.plan import load_plan, run_plan
from pycram_cli.world.pose import compose, invert
from pycram_cli.worldfile.loader import load_world

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "robots"))
from robot_variants import HAND_CLOSED, HAND_FACE, HAND_FINGERS, HAND_PALM, write_multi_finger_robot  # noqa: E402

PICK = "  - action: pick-up\n    object: milk\n"


def _run(tmp_path: Path, body: str, gripper_keys: str = ""):
    world = load_world(write_multi_finger_robot(tmp_path, gripper_keys))
    plan = tmp_path / "plan.yaml"
    plan.write_text("world: kitchen\nbody:\n" + body)
    return world, run_plan(load_plan(plan), world)


def test_the_hand_wraps_the_milk_and_it_moves_with_the_hand(tmp_path: Path) -> None:
    world, result = _run(tmp_path, PICK + "  - action: park-arms\n")
    try:
        assert result.status == "succeeded", result.failure
        robot, milk = world.robot, world.get_object_by_name("milk")
        assert milk in robot.attachments
        assert milk.get_position()[2] > 0.851 + 0.05  # lifted off the counter with the arm, parked
        for finger, _, _ in HAND_FINGERS:  # every finger, the thumb opposite the others, curled onto it
            tip = robot.get_link_id(f"zr2_{finger}_2")
            assert world.distance(robot, milk, 0.003, link_a=tip) < 0.003, finger
            assert 0.3 < abs(robot.get_joint_position(f"zr2_{finger}_2_joint")) < HAND_CLOSED
    finally:
        world.exit()


def test_the_hand_carries_the_milk_to_the_island(tmp_path: Path) -> None:
    world, result = _run(tmp_path, "  - action: transport\n    object-type: milk\n"
                                   "    target: {on: kitchen_island_surface}\n")
    try:
        assert result.status == "succeeded", result.failure
        milk = world.get_object_by_name("milk")
        assert milk not in world.robot.attachments
        x, _, z = milk.get_position()
        assert x < -0.5 and z == pytest.approx(0.862, abs=0.01)  # standing on the island, let go
    finally:
        world.exit()


def test_approached_fingers_first_the_hand_closes_on_nothing(tmp_path: Path) -> None:
    world, result = _run(tmp_path, PICK, "approach: fingers")
    try:
        assert result.status == "failed"
        assert result.failure["type"] == "GripperFailure" and "closed on nothing" in result.failure["message"]
        assert world.get_object_by_name("milk") not in world.robot.attachments
    finally:
        world.exit()


def _milk_in_palm(world) -> tuple[float, float, float]:
    """Where the milk's middle is in the palm's frame."""
    robot, milk = world.robot, world.get_object_by_name("milk")
    lo, hi = milk.get_aabb()
    middle = tuple((a + b) / 2 for a, b in zip(lo, hi))
    return compose(invert(robot.get_link_position_and_orientation("zr2_wrist_twist_link")), (middle, (0, 0, 0, 1)))[0]


@pytest.mark.parametrize("keys, along", [("", HAND_PALM[0] / 2), ("grasp_point: [0.05, 0, -0.045]", 0.05)])
def test_the_milk_is_held_at_the_grasp_point(tmp_path: Path, keys: str, along: float) -> None:
    world, result = _run(tmp_path, PICK, keys)
    try:
        assert result.status == "succeeded", result.failure
        x, y, z = _milk_in_palm(world)
        assert x == pytest.approx(along, abs=0.006)  # along the palm, where the grasp point is
        assert y == pytest.approx(0.0, abs=0.006)
        assert z < -HAND_FACE  # on the side the fingers curl towards
        robot, milk = world.robot, world.get_object_by_name("milk")
        palm = robot.get_link_id("zr2_wrist_twist_link")
        assert world.distance(robot, milk, 0.005, link_a=palm) < 0.005  # against the palm's face
    finally:
        world.exit()


def test_the_gripper_modules_curl_every_joint_its_own_way(tmp_path: Path) -> None:
    world, result = _run(tmp_path, "  - closing-gripper: {gripper: right}\n")
    try:
        assert result.status == "succeeded", result.failure
        joints = world.robot.get_joint_positions([f"zr2_{f}_{k}_joint" for f, _, _ in HAND_FINGERS for k in (1, 2)])
        for name, value in joints.items():  # nothing in the hand: closed all the way, the thumb negative
            assert value == pytest.approx(-HAND_CLOSED if "thumb" in name else HAND_CLOSED, abs=1e-6), name
    finally:
        world.exit()
