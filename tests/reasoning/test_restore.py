"""Property: every query leaves the world exactly as it found it.

Poses, joint positions, velocities (of bodies and joints) and attachments are compared
bitwise before and after each query, over randomly arranged kitchens: objects on the
counter, in the air, tilted, moving, held by the robot; the robot somewhere in front of
the counter with its arms anywhere and its joints moving; the drawer part open.
"""
from __future__ import annotations

import math

import numpy as np
import pybullet as p
import pytest
from scenes import fingerprint, put_on

from pycram_cli.reasoning import (blocking, contact, occluding, reachable, run_query, solve_link, stable, supporting,
                                  visible)

FREE = ["milk", "cereal", "bowl", "spoon", "bottle"]
SCENES = 20


def arrange(world, rng):
    """A random but reproducible arrangement of the kitchen."""
    cid = world.client_id
    robot, kitchen = world.robot, world.get_object_by_name("kitchen")
    yaw = rng.uniform(-0.5, 0.5)
    robot.set_position_and_orientation((rng.uniform(0.4, 0.75), rng.uniform(0.3, 1.1), 0.0),
                                       (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)))
    for joint in robot.movable_joints:
        lo, hi = (joint.lower, joint.upper) if joint.limited else (-math.pi, math.pi)
        p.resetJointState(robot.id, joint.index, rng.uniform(lo, hi), rng.normal(0.0, 0.3), physicsClientId=cid)
    drawer = kitchen.get_joint_id("sink_area_left_upper_drawer_main_joint")
    p.resetJointState(kitchen.id, drawer, rng.uniform(0.0, 0.4), rng.normal(0.0, 0.1), physicsClientId=cid)
    for name in FREE:
        obj = world.get_object_by_name(name)
        where = rng.integers(0, 4)
        angle = rng.uniform(-0.6, 0.6)
        orientation = (math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2))
        if where == 0:  # on the counter, upright
            put_on(obj, kitchen, rng.uniform(1.3, 1.75), rng.uniform(-0.2, 1.25))
        elif where == 1:  # in the air, tilted
            obj.set_position_and_orientation((rng.uniform(1.0, 1.8), rng.uniform(0.0, 1.2), rng.uniform(0.9, 1.5)),
                                             orientation)
        elif where == 2:  # on the counter, tilted (it may fall)
            put_on(obj, kitchen, rng.uniform(1.3, 1.75), rng.uniform(-0.2, 1.25), orientation)
        # where == 3: where the world file put it
        if rng.random() < 0.5:
            p.resetBaseVelocity(obj.id, rng.normal(0.0, 0.2, 3).tolist(), rng.normal(0.0, 1.0, 3).tolist(),
                                physicsClientId=cid)
    if rng.random() < 0.5:
        held = world.get_object_by_name(FREE[rng.integers(0, len(FREE))])
        hand = robot.get_link_position("r_gripper_tool_frame")
        held.set_position(hand)
        robot.attach(held, "r_gripper_tool_frame")
    world.mark_changed()  # joints and velocities were set through PyBullet directly


def queries(world, rng):
    """Every query, called the way plans and processes call them."""
    robot = world.robot
    objects = {name: world.get_object_by_name(name) for name in FREE}
    kitchen = world.get_object_by_name("kitchen")
    a, b = (objects[n] for n in rng.choice(FREE, 2, replace=False))
    position = [float(rng.uniform(1.0, 1.6)), float(rng.uniform(0.2, 1.2)), float(rng.uniform(0.7, 1.3))]
    grasp = ["front", "top", "left", "right", None][rng.integers(0, 5)]
    tool = ["l_gripper_tool_frame", "r_gripper_tool_frame"][rng.integers(0, 2)]
    return [
        ("stable", lambda: stable(a)),
        ("contact", lambda: contact(kitchen, a, links=True)),
        ("contact pair", lambda: contact(a, b)),
        ("supporting", lambda: supporting(kitchen, a)),
        ("visible", lambda: visible(a)),
        ("visible from a position", lambda: visible(b, [0.5, 0.5, 1.6])),
        ("occluding", lambda: occluding(a)),
        ("reachable object", lambda: reachable(a, robot, tool, grasp=grasp)),
        ("reachable position", lambda: reachable(position, robot, tool)),
        ("blocking", lambda: blocking(a, robot, tool, grasp=grasp)),
        ("blocking position", lambda: blocking(position, robot, tool, exclude_types=["environment"])),
        ("solve", lambda: solve_link(robot, tool, position)),
        ("run_query stable", lambda: run_query(world, "stable", {"object": b.name})),
        ("run_query blocking", lambda: run_query(world, "blocking", {"target": position})),
        ("run_query reachable", lambda: run_query(world, "reachable", {"target": a.name, "grasp": "front"})),
    ]


@pytest.mark.parametrize("seed", range(SCENES))
def test_every_query_leaves_a_random_world_exactly_as_it_found_it(scene, seed):
    rng = np.random.default_rng(seed)
    arrange(scene, rng)
    for label, query in queries(scene, rng):
        before = fingerprint(scene)
        query()
        assert fingerprint(scene) == before, f"{label} changed the world (scene {seed})"
