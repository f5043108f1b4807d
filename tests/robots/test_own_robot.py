"""A user brings their own robot: a one-armed KUKA iiwa (pybullet_data) described by a small YAML file.

Nothing of pycram's code knows this robot: its arm name, tool frame, poses and grasps are data.
"""
from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pybullet_data
import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.scenario import prepare

KUKA = Path(pybullet_data.getDataPath()) / "kuka_iiwa" / "model.urdf"

DESCRIPTION = """\
name: kuka
base_link: lbr_iiwa_link_0
mobile: false                      # bolted to the floor: `moving` is refused before anything runs
arms:
  arm:                             # one arm, named as the user likes
    joints: [lbr_iiwa_joint_1, lbr_iiwa_joint_2, lbr_iiwa_joint_3, lbr_iiwa_joint_4,
             lbr_iiwa_joint_5, lbr_iiwa_joint_6, lbr_iiwa_joint_7]
    tool_frame: lbr_iiwa_link_7    # no gripper: what it picks up sticks to the flange
    poses:
      home: [0, 0.3, 0, -1.6, 0, 1.2, 0]
grasps:
  top: [1, 0, 0, 0]                # the flange pointing down
"""

WORLD = """\
objects:
  - {name: floor, type: environment, file: plane.urdf}
  - {name: kuka, type: robot, file: %s, description: kuka.yaml}
  - {name: cube, type: cube, file: cube_small.urdf, position: [0.55, 0.0, 0.026]}
"""

PLAN = """\
world: world.yaml
body:
  - move-arm-joints: {arms: {arm: home}}
  - pick-up: {object: cube}
  - place: {object: cube, target: [0.0, 0.55, 0.001]}
  - move-arm-joints: {arms: {arm: home}}
  - assert: {reachable: {target: [0.45, 0.0, 0.4]}}
"""


@pytest.fixture
def kuka_dir(tmp_path: Path) -> Path:
    (tmp_path / "kuka.yaml").write_text(DESCRIPTION)
    (tmp_path / "world.yaml").write_text(WORLD % KUKA)
    (tmp_path / "plan.yaml").write_text(PLAN)
    return tmp_path


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def test_a_plan_for_a_one_armed_robot_validates_and_runs(kuka_dir: Path):
    result = prepare(kuka_dir / "plan.yaml").run()
    assert result.succeeded, result.failure
    cube = result.trace["final_state"]["objects"]["cube"]
    assert cube["position"] == pytest.approx([0.0, 0.55, 0.025], abs=1e-3)  # standing on the floor (its origin: its middle)
    resolved = [n["designator"]["resolved"] for n in _nodes(result.trace["root"]) if "designator" in n]
    assert resolved[1] == {"object": "cube", "arm": "arm", "grasp": "top"}  # the robot's only arm and grasp


def test_reachable_answers_for_the_robot(kuka_dir: Path):
    data = json.loads(run("query", "reachable", "0.45,0,0.4", "--world", str(kuka_dir / "world.yaml"), "--json").stdout)
    assert data["result"] is True
    assert data["details"]["arm"] == "arm" and data["details"]["gripper_link"] == "lbr_iiwa_link_7"
    far = json.loads(run("query", "reachable", "3,0,0.4", "--world", str(kuka_dir / "world.yaml"), "--json").stdout)
    assert far["result"] is False and set(far["details"]["arms_tried"]) == {"arm"}


@pytest.mark.parametrize("step, message", [
    ("pick-up: {object: cube, arm: left}", "kuka has no arm 'left' (arms: arm)"),
    ("move-arm-joints: {left-arm: park}", "kuka has no arm 'left'"),
    ("move-arm-joints: {arms: {arm: park}}", "kuka has no pose 'park' (poses: home)"),
    ("pick-up: {object: cube, grasp: front}", "kuka has no grasp 'front' (grasps: top)"),
    ("moving: {target: [1, 0, 0]}", "robot 'kuka' cannot perform 'moving': its base cannot move"),
    ("looking: {target: [1, 0, 0]}", "robot 'kuka' cannot perform 'looking': it has no camera"),
])
def test_what_the_robot_does_not_have_is_an_input_error_before_anything_runs(kuka_dir: Path, step: str, message: str):
    plan = kuka_dir / "bad.yaml"
    plan.write_text(f"world: world.yaml\nbody:\n  - {step}\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2, result.output
    assert message in result.stderr
    assert f"{plan}:3:" in result.stderr


def test_a_description_beside_the_urdf_is_found_without_naming_it(tmp_path: Path):
    (tmp_path / "model.urdf").write_text(KUKA.read_text().replace('filename="meshes/', f'filename="{KUKA.parent}/meshes/'))
    (tmp_path / "model.yaml").write_text(DESCRIPTION)
    (tmp_path / "world.yaml").write_text(WORLD.replace(", description: kuka.yaml", "") % (tmp_path / "model.urdf"))
    data = json.loads(run("query", "reachable", "0.45,0,0.4", "--world", str(tmp_path / "world.yaml"), "--json").stdout)
    assert data["details"]["arm"] == "arm"


@pytest.mark.parametrize("edit, line, key, message", [
    (lambda d: d.replace("lbr_iiwa_joint_7]", "lbr_iiwa_joint_8]"), 6, "arms.arm.joints",
     "the model model.urdf has no joint 'lbr_iiwa_joint_8'"),
    (lambda d: d.replace("tool_frame: lbr_iiwa_link_7 ", "tool_frame: [lbr_iiwa_link_7]"), 8, "tool_frame",
     "expected a name"),
    (lambda d: d.replace("home: [0, 0.3, 0, -1.6, 0, 1.2, 0]", "home: [0, 0.3]"), 10, "poses.home",
     "expected 7 numbers, got 2"),
    (lambda d: d.replace("top: [1, 0, 0, 0]", "top: [1, 0, 0, 1]"), 12, "grasps.top", "quaternion must have unit length"),
    (lambda d: d.replace("arms:", "armz:"), 4, "armz", "unknown key 'armz'"),
])
def test_a_broken_description_is_an_input_error_naming_file_line_and_key(kuka_dir: Path, edit, line, key, message):
    description = kuka_dir / "kuka.yaml"
    description.write_text(edit(DESCRIPTION))
    result = run("query", "reachable", "0.45,0,0.4", "--world", str(kuka_dir / "world.yaml"))
    assert result.exit_code == 2, result.output
    assert message in result.stderr
    assert str(description) in result.stderr and f"{key}:" in result.stderr
    if "model" not in message:
        assert f"{description}:{line}:" in result.stderr


def test_a_robot_without_a_description_is_an_input_error_not_a_crash(tmp_path: Path):
    (tmp_path / "world.yaml").write_text(WORLD.replace(", description: kuka.yaml", "") % KUKA)
    result = run("query", "reachable", "0.45,0,0.4", "--world", str(tmp_path / "world.yaml"))
    assert result.exit_code == 2, result.output
    assert "robot 'kuka' has no description naming its arms" in result.stderr
    assert "docs/robots.md" in result.stderr


def _nodes(node: dict) -> list[dict]:
    found = [node]
    for child in node.get("children", []):
        found.extend(_nodes(child))
    return found


# -- values the description gives, checked against the model before anything runs (issue 29) ------------------


@pytest.mark.parametrize("edit, line, key, message", [
    (lambda d: d.replace("home: [0, 0.3,", "home: [5, 0.3,"), 10, "arms.arm.poses.home",
     "pose 'home': lbr_iiwa_joint_1 is 5, outside its limits [-2.96706, 2.96706]"),
    (lambda d: d.replace("    poses:", "    gripper: {joints: [lbr_iiwa_joint_7], open: 4, closed: 0}\n    poses:"), 9,
     "arms.arm.gripper.open", "the gripper's open value 4 is outside lbr_iiwa_joint_7's limits [-3.05433, 3.05433]"),
    (lambda d: d + "camera: {frame: lbr_iiwa_link_7, horizontal_fov: 100, vertical_fov: 1}\n", 13,
     "camera.horizontal_fov", "a field of view must be an angle between 0 and pi (radians), got 100"),
    (lambda d: d + "camera: {frame: lbr_iiwa_link_7, horizontal_fov: 1, vertical_fov: 1, near: 5, far: 2}\n", 13,
     "camera.near", "near (5) must be less than far (2)"),
])
def test_values_a_description_gives_are_checked_against_its_model_at_validate(kuka_dir: Path, edit, line, key, message):
    description = kuka_dir / "kuka.yaml"
    description.write_text(edit(DESCRIPTION))
    result = run("validate", str(kuka_dir / "world.yaml"))
    assert result.exit_code == 2, result.output
    assert message in result.stderr
    assert f"{description}:{line}:" in result.stderr and f"{key}:" in result.stderr


def test_a_process_module_for_an_unknown_designator_is_an_error_with_the_closest_name(kuka_dir: Path):
    description = kuka_dir / "kuka.yaml"
    description.write_text(DESCRIPTION + "process_modules: {pick-upp: pick-up}\n")
    for command in (("validate", str(kuka_dir / "world.yaml")), ("validate", str(kuka_dir / "plan.yaml"))):
        result = run(*command)
        assert result.exit_code == 2, result.output
        assert f"{description}:13:19: process_modules.pick-upp: no designator 'pick-upp' (did you mean 'pick-up'?)" \
            in result.stderr


def test_joint_values_for_the_design_slot_names_are_counted_against_the_arm(tmp_path: Path):
    plan = tmp_path / "p.yaml"
    plan.write_text("world: kitchen\nbody:\n  - move-arm-joints: {left-arm: [0, 0, 0]}\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2, result.output
    assert f"{plan}:3:" in result.stderr and "the left arm has 7 joints" in result.stderr and "got 3 values" in result.stderr


def test_locate_for_a_robot_without_arms_says_it_cannot(kuka_dir: Path):
    (kuka_dir / "kuka.yaml").write_text("name: kuka\nbase_link: lbr_iiwa_link_0\narms: {}\n")
    for args in (("reachable-for", "cube"), ("accessing", "lbr_iiwa_link_7"), ("reachable-for", "0.5,0,0.3")):
        result = run("locate", *args, "--world", str(kuka_dir / "world.yaml"))
        assert result.exit_code == 2, result.output
        assert "Traceback" not in result.output and "internal error" not in result.stderr
        assert "it has no arms" in result.stderr


@pytest.mark.parametrize("step", ["action: park-arms", "action: pick-up\n    object: cube"])
def test_an_action_for_a_robot_without_a_description_is_refused_at_validate(tmp_path: Path, step: str):
    (tmp_path / "world.yaml").write_text(WORLD.replace(", description: kuka.yaml", "") % KUKA)
    plan = tmp_path / "plan.yaml"
    plan.write_text(f"world: world.yaml\nbody:\n  - {step}\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2, result.output
    assert f"{plan}:3:" in result.stderr and "no robot description for 'kuka' (model.urdf)" in result.stderr


def test_actions_run_on_a_bolted_down_robot_from_where_it_stands(kuka_dir: Path):
    """Action designators need no mobile base: where to stand is where the robot stands (the floor it is bolted to
    holds it up), and a spot on the floor, a plane hundreds of metres wide, is looked for near where it is asked."""
    plan = kuka_dir / "actions.yaml"
    plan.write_text("world: world.yaml\nbody:\n  - action: pick-up\n    object: cube\n"
                    "  - action: place\n    object: cube\n    target: {on: floor, near: [0.0, 0.55, 0.0]}\n")
    assert run("validate", str(plan)).exit_code == 0
    result = run("run", str(plan), "--json")
    assert result.exit_code == 0, result.output
    assert "(1 of 1 tried)" in run("run", str(plan)).output  # one pose: its own


def test_a_bolted_down_robot_that_cannot_reach_says_so(kuka_dir: Path):
    (kuka_dir / "far.yaml").write_text((kuka_dir / "world.yaml").read_text().replace("[0.55, 0.0, 0.026]",
                                                                                     "[2.0, 0.0, 0.026]"))
    plan = kuka_dir / "far_plan.yaml"
    plan.write_text("world: far.yaml\nbody:\n  - action: pick-up\n    object: cube\n")
    result = run("run", str(plan))
    assert result.exit_code == 1, result.output
    assert "no pose for reachable-for cube: 1 candidate: 1 out of reach" in " ".join(result.output.split())


def test_new_plan_writes_only_what_a_bolted_down_robot_without_a_camera_can_do(kuka_dir: Path, monkeypatch):
    monkeypatch.chdir(kuka_dir)
    assert run("new", "plan", "mine", "--world", "world.yaml").exit_code == 0
    text = (kuka_dir / "plans" / "mine.yaml").read_text()
    assert "navigate" not in text and "look-at" not in text and "detect" not in text
    assert run("validate", "plans/mine.yaml").exit_code == 0
    assert run("run", "plans/mine.yaml").exit_code == 0
