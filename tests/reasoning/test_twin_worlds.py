"""Queries leave no hidden physics state behind (issue 18).

Every pose, velocity and joint reading back bitwise equal after a query is not enough: what the
next simulation step depends on — the broadphase's pairs and their order, contact manifolds,
the solver's warm starts — must be untouched too. So: query one world, simulate it and an
identical twin that was never queried for 1 s, and every body's pose must agree (to 1e-9).
Queries that simulate or try joint values do so on the world's prospection copy.
"""
from __future__ import annotations

import numpy as np
import pybullet as p
import pytest
from scenes import kitchen_world
from test_restore import arrange

from pycram_cli import Object
from pycram_cli.reasoning import blocking, contact, occluding, reachable, stable, supporting, visible
from pycram_cli.world.model_files import simulator_models_dir

QUERIES = {
    "stable": lambda w, o: stable(o("cereal")),
    "contact": lambda w, o: contact(o("kitchen"), o("milk"), links=True),
    "visible": lambda w, o: visible(o("bottle")),
    "occluding": lambda w, o: occluding(o("spoon")),
    "reachable": lambda w, o: reachable(o("milk"), w.robot, "l_gripper_tool_frame", grasp="front"),
    "blocking": lambda w, o: blocking(o("milk"), w.robot, "l_gripper_tool_frame"),
    "supporting": lambda w, o: supporting(o("kitchen"), o("milk")),
}
#: a random kitchen in which stable, reachable and blocking used to leave state behind (drifts of 0.1-1 m after
#: 1 s), and one with the bowl held by the robot
SCENES = [7, "held"]


def build(scene):
    world = kitchen_world()
    if scene == "held":
        arrange(world, np.random.default_rng(3))
        bowl = world.get_object_by_name("bowl")
        if not any(att.parent is world.robot for att in bowl.attachments.values()):
            bowl.set_position(world.robot.get_link_position("r_gripper_tool_frame"))
            world.robot.attach(bowl, "r_gripper_tool_frame")
    else:
        arrange(world, np.random.default_rng(scene))
    return world


def poses(world):
    cid = world.client_id
    found = []
    for obj in world.objects:
        position, orientation = p.getBasePositionAndOrientation(obj.id, physicsClientId=cid)
        joints = [s[0] for s in p.getJointStates(obj.id, [j.index for j in obj.movable_joints], physicsClientId=cid)] \
            if obj.movable_joints else []
        found.append(np.array([*position, *orientation, *joints]))
    return found


@pytest.mark.parametrize("scene", SCENES)
def test_a_queried_world_simulates_exactly_like_a_twin_never_queried(scene):
    twin = build(scene)
    twin.simulate(1.0)
    expected = poses(twin)
    twin.exit()
    held = scene == "held"
    for name, query in QUERIES.items():
        world = build(scene)
        if held:
            assert any(att.parent is world.robot for o in world.objects for att in o.attachments.values())
        query(world, world.get_object_by_name)
        world.simulate(1.0)
        got = poses(world)
        names = [o.name for o in world.objects]
        world.exit()
        for body, x, y in zip(names, got, expected):
            drift = float(np.max(np.abs(x - y)))
            assert drift <= 1e-9, f"after {name} (scene {scene}), {body} drifted by {drift:.3g}"


def test_the_prospection_copy_follows_objects_that_come_and_go(world, data_dir):
    floor = Object("floor", "environment", simulator_models_dir() / "plane.urdf", world=world)
    box = Object("box", "box", data_dir / "cube.obj", (0, 0, 0.5), world=world)
    assert not stable(box)  # in the air: it falls (on the copy)
    assert box.get_position() == (0.0, 0.0, 0.5)
    other = Object("other", "box", data_dir / "cube.obj", (1, 0, 0.5), world=world)
    twin = world.prospection()
    assert [o.name for o in twin.copy.objects] == ["floor", "box", "other"]
    box.remove()
    assert not stable(other)
    assert [o.name for o in world.prospection().copy.objects] == ["floor", "other"]
    assert floor in world.objects and len(world.objects) == 2


@pytest.mark.parametrize("scene", SCENES)
def test_a_run_of_queries_on_one_world_answers_as_on_fresh_worlds_and_leaves_no_trace(scene):
    """The prospection copy is synced once and reused while the world does not change (issue 15): each
    answer must still be the one a fresh world gives, whatever ran before it, and the world untouched."""
    fresh = {}
    for name, query in QUERIES.items():
        world = build(scene)
        fresh[name] = repr(query(world, world.get_object_by_name))
        world.exit()
    twin = build(scene)
    twin.simulate(1.0)
    expected = poses(twin)
    twin.exit()
    world = build(scene)
    for round_ in range(2):
        for name, query in reversed(QUERIES.items()) if round_ else QUERIES.items():
            assert repr(query(world, world.get_object_by_name)) == fresh[name], f"{name} (round {round_})"
    world.simulate(1.0)
    got = poses(world)
    world.exit()
    for x, y in zip(got, expected):
        assert float(np.max(np.abs(x - y))) <= 1e-9
