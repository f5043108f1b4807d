"""World versions: a number that changes with every change of the world and only then (issue 15).

What is derived from a world — the prospection copy's sync, a saved state — is reused while the
version stays, so every way of changing a world must change it, and reading must not.
"""
from __future__ import annotations

import pybullet as p
import pytest

from pycram_cli import Object
from pycram_cli.world import prospection as prospection_module


@pytest.fixture
def scene(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0.5, 0.0])
    other = Object("other", "box", data_dir / "cube.obj", [1.5, 0.5, 0.0])
    return world, arm, cube, other


def changes(world, action):
    before = world.version
    action()
    return world.version != before


def test_every_way_of_changing_the_world_changes_its_version(scene, data_dir):
    world, arm, cube, other = scene
    extra = []
    assert changes(world, lambda: cube.set_position([0.5, 0.5, 0.2]))
    assert changes(world, lambda: cube.set_orientation([0, 0, 0.6, 0.8]))
    assert changes(world, lambda: arm.set_joint_positions({"shoulder": 0.4}))
    assert changes(world, lambda: arm.reset_joints({"shoulder": 0.1}))
    assert changes(world, lambda: arm.attach(cube, "hand"))
    assert changes(world, lambda: arm.set_joint_positions({"shoulder": 0.2}))  # the held cube follows
    assert changes(world, lambda: arm.detach(cube))
    assert changes(world, lambda: world.step())
    assert changes(world, lambda: world.simulate(0.05))
    assert changes(world, lambda: world.set_gravity([0, 0, -1]))
    assert changes(world, lambda: extra.append(Object("new", "box", data_dir / "cube.obj", [3, 3, 0])))
    assert changes(world, lambda: extra[0].remove())

    def kept():
        with arm.joints_kept(["shoulder"]):
            arm.reset_joints({"shoulder": 1.0})
    assert changes(world, kept)


def test_reading_and_querying_the_world_do_not_change_its_version(scene):
    world, arm, cube, other = scene
    version = world.version
    cube.get_pose(), arm.get_joint_positions(), cube.get_aabb(), world.closest_points(cube, other, 2.0)
    world.wake_free_objects()
    world.prospection()  # syncing the copy only reads the world
    assert world.version == version


def test_an_objects_version_follows_its_own_changes_and_every_step(scene):
    world, arm, cube, other = scene
    cube_version, other_version = cube.version, other.version
    cube.set_position([0.5, 0.5, 0.3])
    assert cube.version != cube_version and other.version == other_version
    world.step()  # a step may move anything
    assert other.version != other_version


def test_restoring_a_state_gives_back_its_versions_and_a_snapshot_after_it_is_free(scene):
    world, arm, cube, other = scene
    state = world.save_state()
    versions = (world.version, cube.version, other.version)
    assert world.save_state() is state  # nothing changed: the same state again
    world.release_state(state)
    cube.set_position([2, 2, 2])
    world.simulate(0.1)
    world.restore_state(state)
    assert (world.version, cube.version, other.version) == versions
    assert world.save_state() is state
    world.release_state(state)
    world.release_state(state)


def test_a_state_saved_after_a_change_is_a_new_one_and_old_ones_are_freed_once_released(scene):
    world, arm, cube, other = scene
    first = world.save_state()
    cube.set_position([0.5, 0.5, 0.4])
    second = world.save_state()
    assert second.state_id != first.state_id
    world.restore_state(first)  # still held: restorable
    assert cube.get_position() == (0.5, 0.5, 0.0)
    world.release_state(first)
    world.release_state(second)
    with world.snapshot():
        other.set_position([9, 9, 9])
    assert other.get_position() == (1.5, 0.5, 0.0)


def test_direct_pybullet_changes_count_once_marked(scene):
    world, arm, cube, other = scene
    version = world.version
    p.resetBasePositionAndOrientation(cube.id, [0, 0, 3], [0, 0, 0, 1], physicsClientId=world.client_id)
    assert world.version == version  # invisible to the world ...
    world.mark_changed(cube)  # ... until said
    assert world.version != version
    assert world.prospection().copy_of(cube).get_position() == cube.get_position()


def test_the_prospection_reads_the_world_once_per_change(scene, monkeypatch):
    world, arm, cube, other = scene
    reads = []
    original = prospection_module._read
    monkeypatch.setattr(prospection_module, "_read", lambda obj, version: reads.append(obj.name) or original(obj, version))
    world.prospection()
    assert sorted(reads) == ["arm", "cube", "other"]
    reads.clear()
    for _ in range(10):
        twin = world.prospection()
        twin.copy_of(cube).set_position([0, 0, 5])  # a query moving the copy: written back next time
        twin.copy.simulate(0.01)
    assert reads == []
    assert world.prospection().copy_of(cube).get_pose() == cube.get_pose()
    cube.set_position([0.6, 0.5, 0.0])
    world.prospection()
    assert reads == ["cube"]
    copy = world.prospection().copy_of(cube)
    assert p.getBasePositionAndOrientation(copy.id, physicsClientId=copy.world.client_id) == \
        p.getBasePositionAndOrientation(cube.id, physicsClientId=world.client_id)


def test_link_boxes_read_at_once_are_pybullets_and_follow_every_change(scene):
    world, arm, cube, other = scene
    links = range(-1, len(arm.joints))
    lo, hi = arm.link_aabbs()
    assert lo.shape == hi.shape == (len(arm.joints) + 1, 3)
    assert [(tuple(a), tuple(b)) for a, b in zip(lo, hi)] == [arm.get_aabb(link) for link in links]
    assert arm.link_aabbs()[0] is lo  # kept while the arm stands still
    before = cube.link_aabbs()[0].copy()
    cube.set_position([0.5, 0.5, 0.3])  # read again once it moved
    assert cube.link_aabbs()[0][0][2] == pytest.approx(before[0][2] + 0.3)
    with world.snapshot():
        arm.set_joint_positions({"shoulder": 0.9})
        moved = [tuple(v) for v in arm.link_aabbs()[1]]
        assert moved == [arm.get_aabb(link)[1] for link in links] and moved != [tuple(v) for v in hi]
    assert [tuple(v) for v in arm.link_aabbs()[1]] == [tuple(v) for v in hi]  # restored, so are its boxes
    some_lo, some_hi = arm.link_aabbs([0])
    assert (tuple(some_lo[0]), tuple(some_hi[0])) == arm.get_aabb(0)
