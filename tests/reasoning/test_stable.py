"""stable(obj): the object does not move more than 1 mm or 1° while the world is simulated for 2 s.

Every verdict must agree with a plain 2 s simulation of the whole world.
"""
from __future__ import annotations

import math

import pytest
from scenes import COUNTER_POSE, ISLAND_TOP, fingerprint, plain_stable, put_on, tilt_about_x

from pycram_cli.reasoning import StableAnswer, stable

KITCHEN_OBJECTS = ["milk", "cereal", "bowl", "spoon", "bottle"]


@pytest.mark.parametrize("name", KITCHEN_OBJECTS)
def test_every_object_of_the_kitchen_world_is_stable_as_loaded(scene, name):
    obj = scene.get_object_by_name(name)
    answer = stable(obj)
    assert answer.stable and answer.displacement < 0.001 and answer.rotation < math.radians(1)
    assert plain_stable(scene, obj)[0]


def test_the_milk_on_the_counter_is_stable_and_the_robot_base_does_not_slide(scene):
    milk, robot = scene.get_object_by_name("milk"), scene.robot
    robot.set_position_and_orientation(*COUNTER_POSE)  # robot right in front of the counter
    base = robot.get_pose()
    answer = stable(milk)
    assert isinstance(answer, StableAnswer) and answer
    assert answer.displacement < 1e-4
    assert robot.get_pose() == base


def test_an_object_in_the_air_is_unstable(scene):
    milk = scene.get_object_by_name("milk")
    milk.set_position([1.5, 0.5, 1.3])
    answer = stable(milk)
    assert not answer and answer.displacement > 0.001
    assert not plain_stable(scene, milk)[0]


def test_an_object_half_over_the_counter_edge_tips_and_is_unstable(scene):
    cereal, kitchen = scene.get_object_by_name("cereal"), scene.get_object_by_name("kitchen")
    put_on(cereal, kitchen, -0.67, 1.5)  # centre right on the island's edge: half of it overhangs
    assert not stable(cereal)
    assert not plain_stable(scene, cereal)[0]


def test_an_object_with_a_small_overhang_is_stable(scene):
    cereal, kitchen = scene.get_object_by_name("cereal"), scene.get_object_by_name("kitchen")
    put_on(cereal, kitchen, -0.67 - 0.02, 1.5)  # centre 2 cm inside the edge
    assert stable(cereal)
    assert plain_stable(scene, cereal)[0]


@pytest.mark.parametrize("degrees", [20.0, 35.46, 50.0])
def test_a_tall_box_on_one_edge_falls_and_is_unstable(scene, degrees):
    # 35.46° puts the cereal box's centre of mass right above its edge (balanced, but not stable)
    cereal, kitchen = scene.get_object_by_name("cereal"), scene.get_object_by_name("kitchen")
    put_on(cereal, kitchen, -1.0, 1.5, tilt_about_x(math.radians(degrees)))
    answer = stable(cereal)
    assert not answer
    assert answer.rotation > math.radians(1) or answer.displacement > 0.001
    assert not plain_stable(scene, cereal)[0]


def test_a_slowly_tipping_object_is_not_declared_stable_early(scene):
    # centre of mass 0.5 mm beyond the island's edge: it starts to tip very slowly
    cereal, kitchen = scene.get_object_by_name("cereal"), scene.get_object_by_name("kitchen")
    put_on(cereal, kitchen, -0.67 + 0.0005, 1.5)
    answer = stable(cereal)
    assert not answer and answer.simulated > 0.1  # not a fall: a slow start
    assert not plain_stable(scene, cereal)[0]


@pytest.mark.parametrize("offset", [-0.004, -0.002, -0.001, 0.0, 0.001, 0.002])
def test_verdicts_near_the_tipping_point_agree_with_a_plain_simulation(scene, offset):
    bottle, kitchen = scene.get_object_by_name("bottle"), scene.get_object_by_name("kitchen")
    put_on(bottle, kitchen, -0.67 + offset, 2.0)  # the bottle's centre near the island's edge
    assert stable(bottle).stable == plain_stable(scene, bottle)[0]


def test_objects_resting_on_the_island_are_stable(scene):
    kitchen = scene.get_object_by_name("kitchen")
    for i, name in enumerate(["milk", "bowl", "bottle"]):
        obj = scene.get_object_by_name(name)
        put_on(obj, kitchen, -1.1, 1.0 + 0.3 * i)
        assert obj.get_aabb()[0][2] == pytest.approx(ISLAND_TOP, abs=0.005)
    for name in ["milk", "bowl", "bottle"]:
        assert stable(scene.get_object_by_name(name))


def test_a_stable_answer_usually_needs_far_less_than_two_seconds(scene):
    answer = stable(scene.get_object_by_name("milk"))
    assert answer and answer.simulated < 1.0


def test_fixed_objects_are_stable_without_simulating(scene):
    assert stable(scene.get_object_by_name("kitchen")) == StableAnswer(True, 0.0, 0.0, 0.0)
    assert stable(scene.robot)


def test_an_object_held_by_the_robot_is_stable(scene):
    bottle = scene.get_object_by_name("bottle")
    bottle.set_position([0.3, 0.7, 1.2])  # in the air, but held
    scene.robot.attach(bottle, "l_gripper_tool_frame")
    assert stable(bottle)


def test_stable_leaves_the_world_exactly_as_it_was(scene):
    milk = scene.get_object_by_name("milk")
    milk.set_position([1.5, 0.5, 1.3])  # falls during the query
    before = fingerprint(scene)
    stable(milk)
    assert fingerprint(scene) == before
    scene.simulate(0.1)  # and it is not left asleep where it was put back
    assert milk.get_position()[2] < 1.29


def test_something_falling_onto_a_resting_object_makes_it_unstable(scene):
    milk, bottle = scene.get_object_by_name("milk"), scene.get_object_by_name("bottle")
    bottle.set_position([1.3, 1.0, 2.0])  # dropped from above: hits the milk after about 0.4 s
    answer = stable(milk)
    assert not answer and answer.simulated > 0.3
    assert not plain_stable(scene, milk)[0]
