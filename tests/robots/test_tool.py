"""The tool frame as the model has it, and the named grasps of a robot whose description names none.

The bundled robots write their grasps by hand; computed from their models (the wrist's roll axis
is the approach, the fingers' spread the closing axis), they come out the same. A description
without `grasps:` gets front, top, left and right for its own tool frame, whatever its axes.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pybullet_data
import pytest

from pycram_cli.robots import description_for, load_description
from pycram_cli.robots.tool import model_grasps
from pycram_cli.world.pose import quat_to_matrix
from pycram_cli.worldfile.loader import load_world


@pytest.mark.parametrize("world_name", ["kitchen", "kitchen_fetch"])
def test_the_bundled_robots_hand_written_grasps_are_what_their_models_show(world_name: str) -> None:
    world = load_world(world_name)
    try:
        desc = description_for(world.robot)
        for arm in desc.arms.values():
            computed = model_grasps(world.robot, arm)
            for name, written in desc.grasps.items():
                assert abs(abs(float(np.dot(written, computed[name]))) - 1.0) < 1e-6, (arm.name, name)  # written to 7 digits
    finally:
        world.exit()


KUKA = Path(pybullet_data.getDataPath()) / "kuka_iiwa" / "model.urdf"
DESCRIPTION = """\
name: kuka
base_link: lbr_iiwa_link_0
mobile: false
arms:
  arm:
    joints: [lbr_iiwa_joint_1, lbr_iiwa_joint_2, lbr_iiwa_joint_3, lbr_iiwa_joint_4,
             lbr_iiwa_joint_5, lbr_iiwa_joint_6, lbr_iiwa_joint_7]
    tool_frame: lbr_iiwa_link_7
"""


def test_a_description_without_grasps_gets_the_named_grasps_of_its_tool_frame(tmp_path: Path) -> None:
    (tmp_path / "kuka.yaml").write_text(DESCRIPTION)
    (tmp_path / "world.yaml").write_text(
        f"objects:\n  - {{name: floor, type: environment, file: plane.urdf}}\n"
        f"  - {{name: kuka, type: robot, file: {KUKA}, description: kuka.yaml}}\n")
    assert list(load_description(tmp_path / "kuka.yaml").grasps) == ["front", "top", "left", "right"]
    world = load_world(tmp_path / "world.yaml")
    try:
        grasps = description_for(world.robot).grasps
        # the flange's approach axis is its z: top points it down, front forward
        assert quat_to_matrix(grasps["top"])[:, 2] == pytest.approx([0, 0, -1], abs=1e-9)
        assert quat_to_matrix(grasps["front"])[:, 2] == pytest.approx([1, 0, 0], abs=1e-9)
    finally:
        world.exit()


def test_a_hand_written_grasp_that_approaches_from_elsewhere_is_warned_of_with_the_one_that_would_not(
        tmp_path: Path) -> None:
    """The PR2's grasps copied onto a robot whose tool frame points out of the hand along z: 'front' would approach
    from below. The warning names the file, the key and the orientation that approaches forward."""
    (tmp_path / "kuka.yaml").write_text(DESCRIPTION + "grasps:\n  front: [0, 0, 0, 1]\n")
    (tmp_path / "world.yaml").write_text(
        f"objects:\n  - {{name: kuka, type: robot, file: {KUKA}, description: kuka.yaml}}\n")
    with pytest.warns(UserWarning, match=r"kuka.yaml:\d+:\d+: grasps.front: the tool approaches along \(0, 0, 1\)"
                                         r".*\[0, 0.7071, 0, 0.7071\] would"):
        load_world(tmp_path / "world.yaml").exit()
