"""Object.joints: each Joint carries the constants a kinematic chain needs, in PyBullet's convention.

PyBullet chains centre-of-mass frames: a joint's `parent_frame` leads from the parent's centre of
mass to the joint origin, turned like the child's centre-of-mass frame; the axis is given in
that frame; `inertial_frame` is the child's centre of mass in its URDF link frame.
"""
from __future__ import annotations

import math

import pybullet as p
import pytest

from pycram_cli import Object
from pycram_cli.world.pose import compose, rotate

TILTED = """<?xml version="1.0"?>
<robot name="tilted">
  <link name="base">
    <inertial><origin xyz="0.02 -0.01 0.03" rpy="0.1 0 0"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><origin xyz="0.1 0.02 0" rpy="0 0.2 0.3"/><mass value="0.5"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
    <collision><geometry><box size="0.3 0.05 0.05"/></geometry></collision>
  </link>
  <link name="tip">
    <inertial><origin xyz="0 0 0.01"/><mass value="0.1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <link name="sensor">
    <inertial><mass value="0.01"/><inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/></inertial>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0.1 0.05 0.3" rpy="0.3 -0.2 0.7"/><axis xyz="0 1 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="extend" type="prismatic">
    <parent link="arm"/><child link="tip"/>
    <origin xyz="0.3 0 0" rpy="0 0.4 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
  </joint>
  <joint name="mount" type="fixed">
    <parent link="tip"/><child link="sensor"/>
    <origin xyz="0 0 0.05" rpy="0 0 1.2"/>
  </joint>
</robot>
"""


@pytest.fixture
def tilted(world, tmp_path):
    path = tmp_path / "tilted.urdf"
    path.write_text(TILTED)
    robot = Object("tilted", "robot", path, [0.5, -0.2, 0.1], (0.0, 0.0, math.sin(0.25), math.cos(0.25)))
    robot.set_joint_positions({"hinge": 0.0, "extend": 0.0})
    return robot


def link_state(robot, joint):
    """PyBullet's (centre-of-mass frame, URDF link frame) of a joint's child link, in the world."""
    state = p.getLinkState(robot.id, joint.index, computeForwardKinematics=True, physicsClientId=robot.world.client_id)
    return (state[0], state[1]), (state[4], state[5])


def assert_same_pose(ours, theirs):
    """Equal up to PyBullet's single precision (a quaternion and its negative are the same rotation)."""
    assert ours[0] == pytest.approx(tuple(theirs[0]), abs=1e-6)
    q, r = ours[1], theirs[1]
    assert min(max(abs(a - b) for a, b in zip(q, r)), max(abs(a + b) for a, b in zip(q, r))) < 1e-6


def test_joints_have_type_names_and_parents(tilted):
    hinge, extend, _ = tilted.joints
    assert [j.type for j in tilted.joints] == ["revolute", "prismatic", "fixed"]
    assert [j.parent_index for j in tilted.joints] == [-1, hinge.index, extend.index]


def test_the_parent_frame_leads_from_the_parents_centre_of_mass_to_the_joint_turned_like_the_childs(tilted):
    parent_com = tilted.get_com_pose()  # the base's centre of mass
    for joint in tilted.joints:
        com, link = link_state(tilted, joint)
        position, orientation = compose(parent_com, joint.parent_frame)
        assert_same_pose((position, orientation), (link[0], com[1]))
        parent_com = com


def test_the_inertial_frame_is_the_centre_of_mass_in_the_link_frame(tilted):
    for joint in tilted.joints:
        com, link = link_state(tilted, joint)
        assert_same_pose(compose(link, joint.inertial_frame), com)


def test_the_axis_is_given_in_the_childs_centre_of_mass_frame(tilted):
    urdf_axes = {"hinge": (0.0, 1.0, 1.0), "extend": (1.0, 0.0, 0.0)}
    for name, axis in urdf_axes.items():
        joint = tilted.joint(name)
        com, link = link_state(tilted, joint)
        assert rotate(com[1], joint.axis) == pytest.approx(rotate(link[1], axis), abs=1e-6)
    assert tilted.joint("mount").axis == (0.0, 0.0, 0.0)


def test_a_continuous_joint_is_named_so_with_unbounded_limits(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    wrist = arm.joint("wrist")
    assert (wrist.type, wrist.lower, wrist.upper) == ("continuous", -math.inf, math.inf)
    assert wrist.parent_index == arm.get_joint_id("slide")
