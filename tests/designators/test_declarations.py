"""Designators are checked before anything runs: every problem names the slot."""
from __future__ import annotations

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.designators import DESIGNATORS, check_designator
from pycram_cli.kinds import Robots
from pycram_cli.robots import bundled_descriptions

DESIGN_SLOTS = {
    "moving": {"target", "orientation"},
    "pick-up": {"object", "arm", "grasp"},
    "place": {"object", "target", "arm"},
    "accessing": {"drawer-handle", "drawer-joint", "part-of", "distance", "arm"},
    "looking": {"target", "object"},
    "opening-gripper": {"gripper"},
    "closing-gripper": {"gripper"},
    "detecting": {"object-type"},
    "move-tcp": {"target", "orientation", "arm"},
    "move-arm-joints": {"arms", "left-arm", "right-arm"},  # arms: {ARM: config}; left-arm/right-arm: the design's names
    "world-state-detecting": {"object-type"},
}
#: designators of ours, beyond the design's (the actions need them)
OUR_SLOTS = {"moving-torso": {"position"}}


def test_the_eleven_designators_of_the_design_with_their_slots():
    assert {name: set(spec.slot_names) for name, spec in DESIGNATORS.items()} == {**DESIGN_SLOTS, **OUR_SLOTS}


def messages(type_name, slots, robots=Robots()):
    return [(p.message, p.param, p.suggestion) for p in check_designator(type_name, slots, robots=robots)]


def pr2() -> Robots:
    return Robots(tuple(d for d in bundled_descriptions() if d.name == "pr2"), True)


def test_a_missing_required_slot_is_named():
    assert messages("place", {"object": "milk"}) == [("'place' needs slot 'target' (where it stands: x, y (and z, optionally: the height of the surface))", "target", None)]


def test_an_unknown_slot_gets_the_closest_valid_name():
    found = messages("accessing", {"drawer-joint": "j", "drawr-handle": "h", "part-of": "kitchen"})
    assert ("'accessing' has no slot 'drawr-handle'", "drawr-handle", "did you mean 'drawer-handle'?") in found


@pytest.mark.parametrize("type_name, slots, expected", [
    ("moving", {"target": [1, 2]}, "slot 'target': expected a position [x, y, z]"),
    ("moving", {"target": [1, 2, 0], "orientation": [0, 0, 1]}, "slot 'orientation': expected a quaternion [x, y, z, w] (got 3 numbers)"),
    ("accessing", {"drawer-joint": "j", "drawer-handle": "h", "part-of": "k", "distance": "far"}, "slot 'distance': expected a number"),
    ("move-arm-joints", {"left-arm": 3}, "slot 'left-arm': expected a named pose"),
])
def test_a_wrong_value_type_is_named(type_name, slots, expected):
    assert any(m.startswith(expected) for m, _, _ in messages(type_name, slots))


@pytest.mark.parametrize("type_name, slots, expected", [
    ("pick-up", {"object": "milk", "arm": "middle"}, "slot 'arm': pr2 has no arm 'middle' (arms: left, right)"),
    ("pick-up", {"object": "milk", "grasp": "side"}, "slot 'grasp': pr2 has no grasp 'side' (grasps: front, top, left, right)"),
    ("move-arm-joints", {"left-arm": "parked"}, "slot 'left-arm': pr2 has no pose 'parked' (did you mean 'park'?)"),
    ("move-arm-joints", {"arms": {"middle": "park"}}, "slot 'arms': middle: pr2 has no arm 'middle'"),
])
def test_robot_names_are_checked_against_the_robots_description(type_name, slots, expected):
    assert any(m.startswith(expected) for m, _, _ in messages(type_name, slots, pr2()))


def test_without_a_known_robot_any_arm_name_passes_the_static_check():
    assert messages("pick-up", {"object": "milk", "arm": "middle"}) == []


def test_looking_needs_a_target_or_an_object():
    assert messages("looking", {}) == [("'looking' needs one of the slots target, object", None, None)]


def test_an_unknown_designator_type_gets_the_closest_one():
    assert messages("pickup", {}) == [("unknown designator type 'pickup'", None, "did you mean 'pick-up'?")]


def test_pycram_designators_documents_every_type_and_slot():
    result = CliRunner().invoke(cli, ["designators"])
    assert result.exit_code == 0
    for name, slots in DESIGN_SLOTS.items():
        assert name in result.output
        for slot in slots:
            assert slot in result.output
    assert "[x, y, z] in metres, world frame" in result.output  # value formats survive the table's markup


def test_pycram_designators_json_and_unknown_type():
    runner = CliRunner()
    import json

    data = json.loads(runner.invoke(cli, ["designators", "place", "--json"]).stdout)
    assert data[0]["type"] == "place"
    assert [(s["name"], s["required"]) for s in data[0]["slots"]] == [("object", True), ("target", True), ("arm", False)]
    bad = runner.invoke(cli, ["designators", "pickup"])
    assert bad.exit_code == 2 and "did you mean 'pick-up'?" in bad.output


def test_pycram_designators_shows_arm_and_grasp_names_per_bundled_robot():
    import json

    data = json.loads(CliRunner().invoke(cli, ["designators", "pick-up", "--json"]).stdout)
    arm = next(s for s in data[0]["slots"] if s["name"] == "arm")
    assert arm["values_per_robot"] == {"fetch": ["arm"], "pr2": ["left", "right"]}
    text = CliRunner().invoke(cli, ["designators", "pick-up"]).output
    assert "fetch: arm" in text and "pr2: left, right" in text
