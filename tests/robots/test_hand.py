"""How a gripper approaches and closes, as its description says or, where it says nothing, as its model shows.

A hand whose fingers curl towards its palm (tests/robots/robot_variants.py: three fingers of two
revolute joints each, the thumb curling with negative values) is palm-first: it approaches along
the palm's normal and holds objects against the palm's face, every finger joint closing by its
coupling. Grippers whose fingers close against each other (the PR2's, the Fetch's, the zoo's) stay
fingers-first, their joints all set to the gripper's value, held at the tool frame, as before.
A bad value of the new keys is an input error at its line (exit code 2).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.robots import description_for
from pycram_cli.robots.tool import hand, tool_axes
from pycram_cli.robots.zoo import generate, write
from pycram_cli.world.pose import quat_to_matrix
from pycram_cli.worldfile.loader import load_world

from robot_variants import HAND_FACE, HAND_PALM, write_multi_finger_robot


def _hand_of(world_file: Path):
    world = load_world(world_file)
    desc = description_for(world.robot)
    arm = next(iter(desc.arms.values()))
    return world, desc, arm


@pytest.mark.parametrize("opened", [0.0, 0.5])  # open flat, or a little curled
def test_a_hand_whose_fingers_curl_towards_its_palm_is_palm_first_as_its_model_shows(tmp_path: Path,
                                                                                   opened: float) -> None:
    world, desc, arm = _hand_of(write_multi_finger_robot(tmp_path, kitchen=False, opened=opened))
    try:
        found = hand(world.robot, arm)
        assert found.approach == "palm"
        assert found.coupling == (1.0, 1.0, 1.0, 1.0, -1.0, -1.0)  # the thumb's limits are negative: it curls so
        assert found.palm_normal == (0.0, 0.0, -1.0)  # the fingers curl towards the palm's -z face
        # held against the middle of the palm's face (the tool frame is at the wrist, the palm's origin)
        assert found.grasp_offset == pytest.approx((HAND_PALM[0] / 2, 0.0, -HAND_FACE), abs=1e-5)
        assert tool_axes(world.robot, arm)[:, 0] == pytest.approx([0, 0, -1])
        # the named grasps (the description has none) turn the palm's normal, not the wrist, to where they reach
        front = quat_to_matrix(desc.grasps["front"]) @ np.array([0.0, 0.0, -1.0])
        top = quat_to_matrix(desc.grasps["top"]) @ np.array([0.0, 0.0, -1.0])
        assert front == pytest.approx([1, 0, 0], abs=1e-9) and top == pytest.approx([0, 0, -1], abs=1e-9)
    finally:
        world.exit()


def test_what_the_description_says_of_the_hand_is_taken_over_the_model(tmp_path: Path) -> None:
    keys = "approach: fingers\ncoupling: [1, 1, 1, 1, -1, -1]\ngrasp_point: [0.0375, 0, -0.05]"
    world, _, arm = _hand_of(write_multi_finger_robot(tmp_path, keys, kitchen=False))
    try:
        found = hand(world.robot, arm)
        assert found.approach == "fingers"
        assert tool_axes(world.robot, arm)[:, 0] == pytest.approx([1, 0, 0])  # along the wrist's roll axis
        assert found.grasp_offset == pytest.approx((0.0375, 0.0, -0.05))  # the palm's frame is the tool frame
    finally:
        world.exit()


@pytest.mark.parametrize("world_name", ["kitchen", "kitchen_fetch"])
def test_the_bundled_grippers_stay_fingers_first_held_at_their_tool_frames(world_name: str) -> None:
    world = load_world(world_name)
    try:
        for arm in description_for(world.robot).arms.values():
            found = hand(world.robot, arm)
            assert found.approach == "fingers", arm.name
            assert found.coupling == (1.0,) * len(arm.gripper.joints)
            assert found.grasp_offset == (0.0, 0.0, 0.0)
    finally:
        world.exit()


@pytest.mark.parametrize("seed", [0, 2, 3])  # two revolute claws, one prismatic finger, two prismatic fingers
def test_the_zoo_grippers_stay_fingers_first(tmp_path: Path, seed: int) -> None:
    urdf = write(generate(seed), tmp_path)
    world_file = tmp_path / "world.yaml"
    world_file.write_text("objects:\n  - {name: floor, type: environment, file: environments/floor/floor.urdf}\n"
                          f"  - {{name: zoo, type: robot, file: {urdf}}}\n")
    world, desc, arm = _hand_of(world_file)
    try:
        found = hand(world.robot, arm)
        assert (found.approach, found.grasp_offset) == ("fingers", (0.0, 0.0, 0.0))
        assert found.coupling == (1.0,) * len(arm.gripper.joints)
        assert tool_axes(world.robot, arm)[:, 0] == pytest.approx([1, 0, 0])  # the zoo's tool x points out of the hand
    finally:
        world.exit()


@pytest.mark.parametrize("keys, key, message, suggestion", [
    ("approach: palms", "approach", "expected how the hand approaches (fingers or palm)", "did you mean 'palm'?"),
    ("approach: sideways", "approach", "expected how the hand approaches", "one of: fingers, palm"),
    ("coupling: [1, 1]", "coupling", "expected 6 numbers, got 2", None),
    ("coupling: [1, 1, 1, 1, 0, 0]", "coupling", "a coupling of 0 would leave a gripper joint still", None),
    ("coupling: [1, 1, 1, 1, 1, 1]", "coupling", "outside zr2_thumb_1_joint's limits [-1.5, 0]",
     "a coupling of -1 for zr2_thumb_1_joint turns it the other way"),
    ("grasp_point: [0, 0]", "grasp_point", "expected 3 numbers, got 2", None),
    ("approach: palm\nNO_PALM", "approach", "a palm-first hand needs the arm's palm_link", "add palm_link"),
])
def test_a_bad_hand_is_an_input_error_at_its_line(tmp_path: Path, keys: str, key: str, message: str,
                                                  suggestion: str | None) -> None:
    world = write_multi_finger_robot(tmp_path, keys.replace("\nNO_PALM", ""), kitchen=False)
    description = next(tmp_path.glob("*_hand.yaml"))
    if "NO_PALM" in keys:
        description.write_text("".join(line for line in description.read_text().splitlines(keepends=True)
                                       if "palm_link:" not in line))
    line = next(i for i, text in enumerate(description.read_text().splitlines(), 1) if f" {key}:" in text)
    plan = tmp_path / "plan.yaml"
    plan.write_text(f"world: {world}\nbody:\n  - log: hello\n")
    result = CliRunner().invoke(cli, ["validate", str(plan)])
    assert result.exit_code == 2, result.output
    assert f"{description}:{line}:" in result.stderr
    assert f"arms.right.gripper.{key}:" in result.stderr and message in result.stderr
    if suggestion:
        assert suggestion in result.stderr
