"""Attachments follow their parent at once — on teleports, joint changes, chains and simulation."""
from __future__ import annotations

import pytest

from pycram_cli import Object


@pytest.fixture
def scene(arm_scene):
    return arm_scene


def test_attached_object_follows_a_teleported_parent_without_a_simulation_step(scene):
    _, arm, cube = scene
    arm.attach(cube)
    arm.set_position([1, 1, 0])
    assert cube.get_position() == pytest.approx((1.5, 1.0, 0.5))


def test_attached_object_follows_a_link_when_joints_change(scene):
    _, arm, cube = scene
    arm.attach(cube, parent_link="hand")
    before = cube.get_position()
    arm.set_joint_position("slide", 0.2)
    after = cube.get_position()
    assert after[0] - before[0] == pytest.approx(0.2)


def test_attachments_chain(scene, data_dir):
    world, arm, cube = scene
    ball = Object("ball", "box", data_dir / "cube.obj", [0.5, 0, 0.7])
    arm.attach(cube, "hand")
    cube.attach(ball)
    arm.set_joint_position("shoulder", 1.0)
    arm.set_position([0, 0, 1])
    cx, cy, cz = cube.get_position()
    bx, by, bz = ball.get_position()
    assert (bx - cx, by - cy, bz - cz) == pytest.approx((0, 0, 0.2), abs=1e-9)


def test_attaching_twice_changes_nothing_and_either_side_detaches(scene):
    world, arm, cube = scene
    events = []
    world.attachment_event += lambda *a: events.append(a)
    arm.attach(cube)
    arm.attach(cube, "hand")
    cube.attach(arm)
    assert len(events) == 1 and arm.attachments[cube].parent_link == -1
    cube.detach(arm)
    assert arm.attachments == {} and cube.attachments == {}
    arm.set_position([3, 0, 0])
    assert cube.get_position() == (0.5, 0.0, 0.5)


def test_moving_the_child_keeps_it_attached_at_its_new_offset(scene):
    _, arm, cube = scene
    arm.attach(cube)
    cube.set_position([0.5, 0, 0.8])
    arm.set_position([1, 0, 0])
    assert cube.get_position() == pytest.approx((1.5, 0, 0.8))


def test_attached_object_stays_attached_while_simulating(scene):
    world, arm, cube = scene
    arm.attach(cube, "hand")
    start = cube.get_position()
    world.simulate(1.0)  # gravity would pull a free cube down by ~5 m
    assert cube.get_position() == pytest.approx(start, abs=1e-6)


def test_detaching_something_not_attached_is_an_error(scene):
    _, arm, cube = scene
    with pytest.raises(ValueError, match="not attached"):
        arm.detach(cube)



def test_placement_tells_two_ways_to_the_same_place_alike(scene):
    _, _, cube = scene
    before = cube.placement()
    cube.set_position([0.7, 0, 0.5])
    assert cube.placement() != before
    cube.set_position([0.5, 0, 0.5])
    assert cube.placement() == before
