"""Saved states put the world back exactly: poses, joints, velocities, attachments."""
from __future__ import annotations

import random

import pybullet as p
import pytest

from pycram_cli import Object
from pycram_cli.locations import locate
from pycram_cli.world import StateError


def full_state(world):
    cid = world.client_id
    state = []
    for obj in world.objects:
        state.append((obj.name, p.getBasePositionAndOrientation(obj.id, physicsClientId=cid),
                      p.getBaseVelocity(obj.id, physicsClientId=cid),
                      tuple(p.getJointState(obj.id, j.index, physicsClientId=cid)[:2] for j in obj.joints),
                      tuple(sorted((a.parent.name, a.child.name, a.parent_link, a.transform) for a in obj.attachments.values()))))
    return state


def test_restore_is_bitwise_exact_after_simulating_moving_and_attaching(world, data_dir):
    rng = random.Random(4)
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    cubes = [Object(f"c{i}", "box", data_dir / "cube.obj", [rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(0.5, 2)])
             for i in range(5)]
    world.simulate(0.3)  # objects are now moving: velocities matter
    before = full_state(world)
    state = world.save_state()
    arm.attach(cubes[0], "hand")
    arm.set_joint_positions({"shoulder": 1.2, "slide": 0.15})
    cubes[1].set_position([9, 9, 9])
    world.simulate(0.7)
    world.restore_state(state)
    assert full_state(world) == before


def test_snapshot_undoes_everything_inside_the_block(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0, 0.5])
    arm.attach(cube)
    before = full_state(world)
    with world.snapshot():
        arm.detach(cube)
        cube.set_position([0, 0, 3])
        world.simulate(0.2)
    assert full_state(world) == before
    arm.set_position([1, 0, 0])  # the restored attachment still works
    assert cube.get_position() == pytest.approx((1.5, 0, 0.5))


def test_restoring_after_objects_were_added_is_a_clear_error(world, data_dir):
    state = world.save_state()
    Object("cube", "box", data_dir / "cube.obj")
    with pytest.raises(StateError, match="objects were added or removed"):
        world.restore_state(state)


def test_a_reset_with_no_step_since_the_last_is_a_restore_and_simulates_on_exactly_as_a_full_one(world, data_dir):
    """reset_to steps once to refresh the contact caches; when nothing stepped since the last reset to the same
    state (a projected run that only teleports and asks), the caches are that reset's, and the restore alone is
    the same world: what follows simulates bitwise as after a full reset."""
    Object("floor", "environment", "plane.urdf")
    cubes = [Object(f"c{i}", "box", data_dir / "cube.obj", [0.3 * i, 0.0, 0.2 + 0.1 * i]) for i in range(3)]
    world.simulate(0.2)  # falling and landing: contacts matter from here on
    state = world.save_state()

    world.simulate(0.1)
    world.reset_to(state)  # a full reset (the world stepped)
    world.simulate(0.5)
    after_full = full_state(world)

    world.reset_to(state)
    cubes[0].set_position([2.0, 2.0, 0.5])  # teleports, no step
    taken = world._steps_taken
    world.reset_to(state)  # nothing stepped since the last reset to this state: a restore
    assert world._steps_taken == taken
    world.simulate(0.5)
    assert full_state(world) == after_full


def test_reset_to_forgets_what_was_worked_out_about_the_world(kitchen):
    """A world reset as if just loaded remembers no answer of the runs before (IK answers, walks, floor maps): an
    answer kept for a question within a rounding of the next run's would give it an earlier run's bits (a sweep's
    outcomes then depended on which scenarios its worker had run before)."""
    state = kitchen.save_state()
    try:
        locate(kitchen, {"reachable-for": "milk"}).next()
        assert kitchen.cache.names()
        kitchen.reset_to(state)
        assert kitchen.cache.names() == []
    finally:
        kitchen.reset_to(state)
        kitchen.release_state(state)
