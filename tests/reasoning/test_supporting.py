"""supporting(a, b): b rests on a — above it, touching it, the contact roughly horizontal."""
from __future__ import annotations

from scenes import fingerprint, put_on

from pycram_cli.reasoning import supporting


def test_the_counter_supports_the_breakfast(scene):
    kitchen = scene.get_object_by_name("kitchen")
    for name in ["milk", "cereal", "bowl", "bottle", "spoon"]:
        assert supporting(kitchen, scene.get_object_by_name(name)), name


def test_support_is_not_symmetric(scene):
    assert not supporting(scene.get_object_by_name("milk"), scene.get_object_by_name("kitchen"))


def test_an_object_stacked_on_another_is_supported_by_it(scene):
    cereal, bowl = scene.get_object_by_name("cereal"), scene.get_object_by_name("bowl")
    x, y, _ = cereal.get_position()
    cereal.set_orientation([0.7071068, 0, 0, 0.7071068])  # lying on its back
    put_on(cereal, scene.get_object_by_name("kitchen"), x, y, cereal.get_orientation())
    put_on(bowl, cereal, x, y)
    assert supporting(cereal, bowl)
    assert not supporting(bowl, cereal)
    assert not supporting(scene.get_object_by_name("kitchen"), bowl)


def test_objects_touching_side_by_side_do_not_support_each_other(scene):
    milk, cereal = scene.get_object_by_name("milk"), scene.get_object_by_name("cereal")
    x, y, z = cereal.get_position()
    milk.set_position([x, y + 0.099 + 0.035 + 0.0005, z])  # touching the cereal's side
    assert not supporting(cereal, milk) and not supporting(milk, cereal)


def test_an_object_hovering_above_is_not_supported(scene):
    milk = scene.get_object_by_name("milk")
    milk.set_position([1.3, 1.0, 0.9])
    assert not supporting(scene.get_object_by_name("kitchen"), milk)


def test_supporting_changes_nothing(scene):
    before = fingerprint(scene)
    supporting(scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk"))
    assert fingerprint(scene) == before


def test_support_can_be_asked_of_one_link(scene):
    kitchen, milk = scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk")
    assert supporting(kitchen, milk, link="sink_area_surface")
    assert not supporting(kitchen, milk, link="kitchen_island_surface")


def test_an_unknown_link_is_an_error_not_a_no(scene):
    import pytest

    with pytest.raises(KeyError, match="did you mean 'sink_area_surface'"):
        supporting(scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk"), link="sink_area_surfac")


def test_a_milk_hovering_a_few_millimetres_above_the_counter_is_not_supported(scene):
    """Real contact (1 mm), not contact's 5 mm: 2-4 mm of air is not resting."""
    kitchen, milk = scene.get_object_by_name("kitchen"), scene.get_object_by_name("milk")
    x, y, z = milk.get_position()
    assert supporting(kitchen, milk)
    for gap in (0.002, 0.003, 0.004):
        milk.set_position([x, y, z + gap])
        assert not supporting(kitchen, milk), gap
    from pycram_cli.reasoning import contact
    assert contact(kitchen, milk)  # still "touching" for contact's documented 5 mm
