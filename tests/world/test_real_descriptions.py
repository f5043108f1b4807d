"""The real ROS descriptions in ../shared/models load through Object (skipped when absent)."""
from __future__ import annotations

import warnings
import xml.etree.ElementTree as ET

import pytest

from pycram_cli import Object
from pycram_cli.world import MissingMeshWarning


def counts(urdf):
    root = ET.parse(urdf).getroot()
    return [l.get("name") for l in root.findall("link")], [j.get("name") for j in root.findall("joint")]


@pytest.mark.parametrize("relative, kind", [("pr2/pr2.urdf", "robot"), ("kitchen/kitchen.urdf", "environment")])
def test_real_models_load_with_every_link_and_joint(world, shared_models, relative, kind):
    urdf = shared_models / relative
    links, joints = counts(urdf)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MissingMeshWarning)
        obj = Object(kind, kind, urdf)
    assert sorted(obj.joint_names) == sorted(joints)
    assert sorted(obj.link_names) == sorted(links)


def test_real_pr2_has_the_frames_the_design_uses(world, shared_models):
    pr2 = Object("pr2", "robot", shared_models / "pr2/pr2.urdf")
    assert pr2.base_link_name == "base_footprint"
    for link in ("wide_stereo_optical_frame", "l_gripper_tool_frame", "r_gripper_tool_frame"):
        pr2.get_link_id(link)
    assert pr2.joint("torso_lift_joint").type == "prismatic"


def test_the_apartment_loads_with_one_warning_about_its_two_missing_meshes(world, shared_models):
    urdf = shared_models / "apartment/apartment.urdf"
    links, joints = counts(urdf)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        apartment = Object("apartment", "environment", urdf)
    missing = [w for w in caught if issubclass(w.category, MissingMeshWarning)]
    assert len(missing) == 1
    assert "windows.dae" in str(missing[0].message) and "oven.dae" in str(missing[0].message)
    assert len(apartment.joint_names) == len(joints)
    assert len(apartment.movable_joints) == 38
