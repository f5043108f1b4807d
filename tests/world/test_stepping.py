"""BulletWorld.step, BulletWorld.wake_free_objects and Object.get_com_pose: the physics one step at a time."""
from __future__ import annotations

import math

import pybullet as p
import pytest

from pycram_cli import BulletWorld, Object


@pytest.fixture
def falling(world, data_dir):
    """A cube in mid-air with a second cube attached on top of it."""
    cube = Object("cube", "box", data_dir / "cube.obj", [0.0, 0.0, 1.0])
    lid = Object("lid", "box", data_dir / "cube.obj", [0.3, 0.0, 1.5])
    cube.attach(lid)
    return world, cube, lid


def offset(a, b):
    (ax, ay, az), (bx, by, bz) = a.get_position(), b.get_position()
    return (bx - ax, by - ay, bz - az)


def test_one_step_is_one_240_hz_step_of_the_physics(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.0, 0.0, 1.0])
    world.step()
    velocity = p.getBaseVelocity(cube.id, physicsClientId=world.client_id)[0]
    assert velocity[2] == pytest.approx(-9.81 / 240.0)


def test_step_moves_attached_objects_with_their_parent(falling):
    world, cube, lid = falling
    before = offset(cube, lid)
    start = cube.get_position()
    for _ in range(24):
        world.step()
    assert cube.get_position()[2] < start[2] - 0.01
    assert offset(cube, lid) == pytest.approx(before, abs=1e-9)


def test_simulate_is_the_same_physics_as_stepping(data_dir):
    poses = []
    for stepped in (False, True):
        with BulletWorld() as world:
            cube = Object("cube", "box", data_dir / "cube.obj", [0.0, 0.0, 1.0])
            lid = Object("lid", "box", data_dir / "cube.obj", [0.3, 0.0, 1.5])
            cube.attach(lid)
            Object("floor", "environment", data_dir / "cube.obj", [0.0, 0.0, 0.0])
            if stepped:
                for _ in range(120):
                    world.step()
            else:
                world.simulate(0.5)
            poses.append([o.get_com_pose() for o in world.objects])
    assert poses[0] == poses[1]


def test_step_on_an_exited_world_is_refused(world):
    world.exit()
    with pytest.raises(Exception, match="exited"):
        world.step()


def test_a_sleeping_free_object_falls_again_once_woken(world, data_dir):
    Object("floor", "environment", data_dir / "cube.obj", [0.0, 0.0, 0.0])
    cube = Object("cube", "box", data_dir / "cube.obj", [0.0, 0.0, 0.1])
    p.changeDynamics(cube.id, -1, activationState=p.ACTIVATION_STATE_ENABLE_SLEEPING, physicsClientId=world.client_id)
    world.simulate(3.0)  # at rest long enough for PyBullet to put it to sleep
    cube.set_position([0.0, 0.0, 1.0])
    for _ in range(24):
        world.step()
    assert cube.get_position()[2] == pytest.approx(1.0, abs=1e-9)  # asleep: it hangs in the air
    world.wake_free_objects()
    for _ in range(24):
        world.step()
    assert cube.get_position()[2] < 0.99


def test_the_com_pose_is_pybullets_base_pose_at_the_centre_of_mass(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.2, 0.0, 1.0], (0.0, 0.0, math.sin(0.3), math.cos(0.3)))
    position, orientation = cube.get_com_pose()
    assert (position, orientation) == p.getBasePositionAndOrientation(cube.id, physicsClientId=world.client_id)
    assert position == pytest.approx((0.2, 0.0, 1.05), abs=1e-6)  # the cube's origin is its bottom centre
    assert orientation == pytest.approx(cube.get_orientation())
