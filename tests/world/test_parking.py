"""Parking: objects taken out of a simulation for a while and put back bitwise (issue 15)."""
from __future__ import annotations

import pybullet as p

from pycram_cli import Object
from pycram_cli.world.parking import Parking


def raw(obj):
    cid = obj.world.client_id
    joints = [j.index for j in obj.joints]
    return (p.getBasePositionAndOrientation(obj.id, physicsClientId=cid), p.getBaseVelocity(obj.id, physicsClientId=cid),
            tuple(s[:2] for s in p.getJointStates(obj.id, joints, physicsClientId=cid)) if joints else ())


def test_parked_objects_stay_out_of_the_way_and_come_back_exactly(world, data_dir):
    floor = Object("floor", "environment", data_dir / "cube.obj", [0, 0, -0.1])
    arm = Object("arm", "robot", data_dir / "arm.urdf", [2, 0, 0])
    arm.set_joint_positions({"shoulder": 0.7, "slide": 0.1})
    cube = Object("cube", "box", data_dir / "cube.obj", [0.0, 0.0, 0.3])
    other = Object("other", "box", data_dir / "cube.obj", [0.5, 0.5, 0.5])
    world.simulate(0.1)  # moving: velocities matter
    before = {o.name: raw(o) for o in (arm, cube, other)}
    parking = Parking(world)
    version = world.version
    parking.park([cube, arm])
    assert world.version != version and cube in parking and other not in parking
    assert cube.get_position()[2] < -1000 and arm.get_position()[2] < -1000
    world.simulate(0.1)  # it falls asleep in the first step or two, far from everything
    parked = raw(cube)
    world.simulate(0.5)
    assert raw(cube)[0] == parked[0] and parked[0][0][2] > -2000.01  # and then costs nothing, asleep
    assert other.get_position()[2] < 0.45  # the rest was simulated
    other_after = raw(other)
    parking.put_back([cube])
    assert raw(cube) == before["cube"] and arm in parking
    parking.put_back()
    assert raw(arm) == before["arm"] and parking.parked == []
    assert raw(other) == other_after


def test_loosened_joints_are_held_again_where_they_were(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    arm.set_joint_positions({"shoulder": 0.7})
    before = raw(arm)
    parking = Parking(world)
    parking.loosen(arm, [arm.get_joint_id("shoulder")])
    world.simulate(0.2)
    parking.put_back()
    assert raw(arm)[2] == before[2]
    world.simulate(0.2)  # held again: the motors keep it
    assert abs(arm.get_joint_position("shoulder") - 0.7) < 1e-3
