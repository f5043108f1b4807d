"""BulletWorld: clients, current world, gravity, simulation, events, isolation."""
from __future__ import annotations

import pybullet as p
import pybullet_data
import pytest

from pycram_cli import BulletWorld, Event, Object
from pycram_cli.world import WorldError

PLANE = f"{pybullet_data.getDataPath()}/plane.urdf"


def test_a_direct_world_has_its_own_client_and_default_gravity(world):
    assert p.isConnected(world.client_id)
    assert world.gravity == (0.0, 0.0, -9.81)
    world.set_gravity([0, 0, -1.62])
    assert world.gravity == (0.0, 0.0, -1.62)


def test_gravity_must_be_three_numbers(world):
    with pytest.raises(ValueError, match="expected 3 numbers, got 2"):
        world.set_gravity([0, -9.81])


def test_current_world_is_the_newest_live_world_whatever_order_they_exit():
    a, b, c = BulletWorld(), BulletWorld(), BulletWorld()
    assert BulletWorld.current_world is c
    b.exit()
    assert BulletWorld.current_world is c
    c.exit()
    assert BulletWorld.current_world is a
    a.exit()
    assert BulletWorld.current_world is None or BulletWorld.current_world.alive


def test_world_is_a_context_manager_that_exits():
    with BulletWorld() as w:
        client = w.client_id
        assert p.isConnected(client)
    assert not p.isConnected(client)
    assert not w.alive


def test_objects_default_to_the_current_world():
    with BulletWorld() as w:
        cube = Object("cube", "box", PLANE)
        assert cube.world is w and w.objects == [cube]


def test_two_worlds_never_see_each_others_changes(data_dir):
    with BulletWorld() as w1, BulletWorld() as w2:
        a = Object("cube", "box", data_dir / "cube.obj", [0, 0, 1], world=w1)
        b = Object("cube", "box", data_dir / "cube.obj", [0, 0, 1], world=w2)
        a.set_position([5, 5, 5])
        assert b.get_position() == (0.0, 0.0, 1.0)
        w2.simulate(0.5)
        assert a.get_position() == (5.0, 5.0, 5.0)
        assert b.get_position()[2] < 1.0
        assert w1.get_objects_by_name("cube") == [a] and w2.get_objects_by_name("cube") == [b]


def test_simulate_steps_at_240_hz(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0, 0, 10])
    world.simulate(0.5)  # free fall: z = 10 - g t^2 / 2 (discretised)
    assert cube.get_position()[2] == pytest.approx(10 - 9.81 * 0.5**2 / 2, abs=0.02)


def test_lookup_by_name_type_and_id(world, data_dir):
    floor = Object("floor", "environment", PLANE)
    cube = Object("cube", "box", data_dir / "cube.obj", [0, 0, 1])
    assert world.get_objects_by_type("box") == [cube]
    assert world.get_object_by_id(floor.id) is floor
    assert world.get_objects_by_name("nothing") == []


def test_robot_is_the_first_robot_object_or_assigned(world, data_dir):
    assert world.robot is None
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    assert world.robot is arm
    other = Object("other", "robot", data_dir / "arm.urdf", [1, 0, 0])
    world.robot = other
    assert world.robot is other


def test_only_one_gui_world_at_a_time(monkeypatch):
    sentinel = object()
    monkeypatch.setattr(BulletWorld, "_gui_world", sentinel)
    with pytest.raises(WorldError, match="a GUI world is already open"):
        BulletWorld(mode="gui")


def test_unknown_mode_is_rejected():
    with pytest.raises(ValueError, match="'direct' or 'gui'"):
        BulletWorld(mode="headless")


def test_event_handlers_are_added_removed_and_called():
    calls = []
    event = Event("test")

    def handler(*args):
        calls.append(args)

    event += handler
    event(1, 2)
    event.fire(3)
    event -= handler
    event()
    assert calls == [(1, 2), (3,)]
    with pytest.raises(ValueError):
        event -= handler


def test_world_events_fire_on_attach_detach_and_manipulation(world, data_dir):
    seen = []
    world.attachment_event += lambda parent, child: seen.append(("attach", parent.name, child.name))
    world.detachment_event += lambda parent, child: seen.append(("detach", parent.name, child.name))
    world.manipulation_event += lambda obj, joint, old, new: seen.append(("manipulate", obj.name, joint, new))
    cabinet = Object("cabinet", "environment", data_dir / "arm.urdf")
    robot = Object("robot", "robot", data_dir / "arm.urdf", [2, 0, 0])
    cube = Object("cube", "box", data_dir / "cube.obj", [0, 0, 1])
    robot.attach(cube)
    robot.detach(cube)
    cabinet.set_joint_position("slide", 0.1)
    robot.set_joint_position("slide", 0.1)  # robots moving their own joints are not manipulation
    assert seen == [("attach", "robot", "cube"), ("detach", "robot", "cube"), ("manipulate", "cabinet", "slide", 0.1)]


def test_a_world_is_connected_until_it_exits():
    world = BulletWorld()
    assert world.is_connected()
    world.exit()
    assert not world.is_connected()


def test_a_world_made_in_code_has_no_source_file(world):
    assert world.source is None
