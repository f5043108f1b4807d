"""Object.reset_joints and Object.joints_kept: trying joint values and putting them back exactly."""
from __future__ import annotations

import pybullet as p
import pytest

from pycram_cli import Object

JOINTS = ["shoulder", "slide", "wrist"]


@pytest.fixture
def arm(world, data_dir):
    return Object("arm", "thing", data_dir / "arm.urdf", fixed=True)


def raw_states(obj):
    """Positions and velocities as PyBullet holds them (compared bitwise)."""
    cid = obj.world.client_id
    return [(s[0], s[1]) for s in p.getJointStates(obj.id, [obj.get_joint_id(n) for n in JOINTS], physicsClientId=cid)]


def set_moving(obj):
    """Joints mid-motion: positions that are not round numbers, non-zero velocities."""
    cid = obj.world.client_id
    for name, (q, v) in zip(JOINTS, [(0.123456789, 0.7), (0.0312, -0.05), (2.5, 3.0)]):
        p.resetJointState(obj.id, obj.get_joint_id(name), q, v, physicsClientId=cid)


def test_joints_kept_puts_positions_and_velocities_back_bitwise(arm):
    set_moving(arm)
    before = raw_states(arm)
    with arm.joints_kept(JOINTS):
        arm.set_joint_positions({"shoulder": 1.0, "slide": 0.2, "wrist": -1.0})
        assert raw_states(arm) != before
    assert raw_states(arm) == before


def test_joints_tried_and_put_back_leave_the_object_at_its_version(world, arm):
    """What is kept by an object's version (a collision check, a floor map, the prospection copy) stays valid after a
    query that only tried joint values; a change the block leaves behind gives the object a new version."""
    set_moving(arm)
    version = world.version_of(arm)
    with arm.joints_kept(JOINTS):
        arm.reset_joints({"shoulder": 1.0, "slide": 0.1})
        assert world.version_of(arm) != version
    assert world.version_of(arm) == version
    with arm.joints_kept(["shoulder"]):
        arm.reset_joints({"shoulder": 1.0, "slide": 0.1})  # slide is not put back
    assert world.version_of(arm) != version and arm.get_joint_position("slide") == 0.1


def test_joints_kept_puts_them_back_when_the_block_fails(arm):
    set_moving(arm)
    before = raw_states(arm)
    with pytest.raises(RuntimeError), arm.joints_kept(["shoulder"]):
        arm.reset_joints({"shoulder": -1.0})
        raise RuntimeError("boom")
    assert raw_states(arm) == before


def test_joints_kept_keeps_only_the_named_joints(arm):
    with arm.joints_kept(["shoulder"]):
        arm.reset_joints({"shoulder": 1.0, "slide": 0.1})
    assert arm.get_joint_positions(["shoulder", "slide"]) == {"shoulder": 0.0, "slide": 0.1}


def test_joints_kept_refuses_unknown_joints_before_anything_changes(arm):
    with pytest.raises(KeyError, match="did you mean 'shoulder'"):
        with arm.joints_kept(["shouldr"]):
            pytest.fail("the block must not run")


def test_reset_joints_skips_limits_and_events_and_zeroes_velocities(world, arm):
    set_moving(arm)
    events = []
    world.manipulation_event += lambda *args: events.append(args)
    arm.reset_joints({"slide": 0.5})  # beyond its 0.2 m limit
    assert arm.get_joint_position("slide") == 0.5
    assert events == []
    assert raw_states(arm)[1] == (0.5, 0.0)


def test_reset_joints_leaves_attached_objects_where_they_are(world, arm, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0.0, 0.3])
    arm.attach(cube, parent_link="hand")
    before = cube.get_pose()
    arm.reset_joints({"shoulder": 1.0})
    assert cube.get_pose() == before


def test_reset_joints_names_an_unknown_joint_with_a_suggestion(arm):
    with pytest.raises(KeyError, match="did you mean 'slide'"):
        arm.reset_joints({"slid": 0.1})
