"""contact(a, b): touching within a small tolerance, read without stepping the simulation."""
from __future__ import annotations

import math

import pytest
from scenes import fingerprint

from pycram_cli.reasoning import ContactAnswer, contact


def test_the_milk_touches_the_kitchen_counter(scene):
    answer = contact(scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk"))
    assert isinstance(answer, ContactAnswer) and answer
    assert abs(answer.distance) < 0.001


def test_contact_can_name_the_touching_links(scene):
    answer = contact(scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk"), links=True)
    assert answer.links == [("sink_area_surface", "milk")]
    assert contact(scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk")).links == []


def test_objects_apart_are_not_in_contact_and_the_distance_says_how_far(scene):
    milk, cereal = scene.get_object_by_name("milk"), scene.get_object_by_name("cereal")
    answer = contact(milk, cereal)
    assert not answer
    assert 0.2 < answer.distance < 0.4  # 0.4 m between centres, minus the half widths


def test_far_apart_objects_report_an_infinite_distance(scene):
    assert contact(scene.get_object_by_name("milk"), scene.get_object_by_name("floor")).distance == math.inf


def test_a_teleport_is_seen_at_once_without_a_simulation_step(scene):
    milk, cereal = scene.get_object_by_name("milk"), scene.get_object_by_name("cereal")
    x, y, z = cereal.get_position()
    milk.set_position([x, y + 0.099 + 0.035 + 0.002, z])  # 2 mm beside the cereal box
    assert contact(milk, cereal)
    assert not contact(milk, cereal, tolerance=0.001)


def test_contact_is_symmetric(scene):
    k, m = scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk")
    assert bool(contact(k, m)) == bool(contact(m, k))


def test_the_spoon_lies_in_the_drawer(scene):
    answer = contact(scene.get_object_by_name("kitchen"), scene.get_object_by_name("spoon"), links=True)
    assert answer
    assert ("sink_area_left_upper_drawer_main", "spoon") in answer.links


def test_an_object_cannot_touch_itself(scene):
    milk = scene.get_object_by_name("milk")
    with pytest.raises(ValueError, match="two different objects"):
        contact(milk, milk)


def test_contact_changes_nothing(scene):
    before = fingerprint(scene)
    contact(scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk"), links=True)
    assert fingerprint(scene) == before
