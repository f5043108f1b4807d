"""Action designators from Python: declared once, checked, expanded into motions, queries and locations,
trying the next candidate when a choice fails; the same code drives the PR2 and the Fetch."""
from __future__ import annotations

import pytest

from pycram_cli.designators import DESIGNATORS
from pycram_cli.designators.actions import ACTIONS, check_action, perform_action
from pycram_cli.errors import InputError, InputErrors
from pycram_cli.failures import Failure, LocationFailure, NavigationFailure
from pycram_cli.kinds import Robots
from pycram_cli.paths import worlds_dir
from pycram_cli.planning import motion, paths
from pycram_cli.process_modules.navigation import Navigation
from pycram_cli.reasoning import stable, supporting
from pycram_cli.robots import Robot, bundled_descriptions
from pycram_cli.worldfile.loader import load_world

HANDLE = "sink_area_left_upper_drawer_handle"
JOINT = "sink_area_left_upper_drawer_main_joint"
ISLAND = {"on": "kitchen_island_surface"}

ACTION_SLOTS = {
    "navigate": {"target"},
    "park-arms": {"arm"},
    "move-torso": {"position"},
    "look-at": {"target"},
    "detect": {"object-type", "object"},
    "search": {"object-type", "object"},
    "pick-up": {"object", "arm", "grasp"},
    "place": {"object", "target", "arm"},
    "open": {"handle", "joint", "part-of", "distance", "arm"},
    "close": {"handle", "joint", "part-of", "arm"},
    "transport": {"object", "object-type", "target", "arm", "grasp"},
}


@pytest.fixture
def world(kitchen):
    with kitchen.snapshot():
        yield kitchen


def children(record):
    return [(c["label"], c["status"]) for c in record["children"]]


def test_the_actions_and_their_slots():
    assert {name: set(spec.slot_names) for name, spec in ACTIONS.items()} == ACTION_SLOTS
    assert {"pick-up", "place"} <= set(DESIGNATORS) & set(ACTIONS)  # the two names both registries have


def test_static_checks_name_slots_and_locations():
    def messages(name, slots):
        pr2 = Robots(tuple(d for d in bundled_descriptions() if d.name == "pr2"), True)
        return [p.message for p in check_action(name, slots, lambda v: "$" in str(v), pr2)]

    assert messages("transprt", {}) == ["unknown action 'transprt'"]
    assert messages("pick-up", {"object": "milk", "arm": "middle"}) == ["slot 'arm': pr2 has no arm 'middle' (arms: left, right)"]
    assert messages("navigate", {}) == ["action 'navigate' needs slot 'target' (where to stand: {reachable-for: ...}, {visible-for: ...} or {accessing: ...})"]
    assert messages("navigate", {"target": {"on": "kitchen_island_surface"}}) == [
        "slot 'target': navigate goes to a base pose: reachable-for, visible-for or accessing (got on)"]
    assert messages("transport", {"object": "milk", "target": {"reachable-for": "milk"}}) == [
        "slot 'target': transport brings an object onto a surface: {on: SURFACE} (got reachable-for)"]
    # a location with a variable in it is still checked key by key
    assert messages("navigate", {"target": {"reachable-for": "$obj", "grasp": "sideways"}}) == [
        "slot 'target': grasp: pr2 has no grasp 'sideways' (grasps: front, top, left, right)"]
    assert messages("detect", {}) == ["action 'detect' needs one of the slots object-type, object"]


def test_bad_slots_are_input_errors_before_anything_moves(world):
    with pytest.raises(InputErrors, match="has no slot 'objet' \\(did you mean 'object'\\?\\)"):
        perform_action(world, "pick-up", {"objet": "milk"})
    with pytest.raises(InputError, match="pr2 has no arm 'middle'"):
        perform_action(world, "pick-up", {"object": "milk", "arm": "middle"})


def test_pick_up_finds_where_to_stand_which_arm_and_grasp(world):
    record: dict = {}
    milk = perform_action(world, "pick-up", {"object": "milk"}, record)
    robot = Robot.of(world)
    assert robot.arm_holding(milk) is not None
    action = record["children"][0]
    assert action["label"] == "0:action pick-up" and action["status"] == "succeeded"
    assert [label for label, _ in children(action)] == ["0:locate", "1:attempt 1"]
    attempt = action["children"][1]
    assert [c["type"] for c in attempt["children"]] == ["moving", "pick-up", "move-arm-joints"]
    found = action["children"][0]["location"]["found"]
    assert attempt["children"][1]["designator"]["resolved"]["arm"] == found["arm"]


def test_when_a_choice_fails_the_next_candidate_is_tried(world, monkeypatch):
    calls = []
    original = Navigation.execute

    def flaky(self, robot, slots):
        calls.append(list(slots["target"]))
        if len(calls) == 1:
            raise NavigationFailure("a cat sat there")
        return original(self, robot, slots)

    monkeypatch.setattr(Navigation, "execute", flaky)
    record: dict = {}
    perform_action(world, "navigate", {"target": {"reachable-for": "milk"}}, record)
    action = record["children"][0]
    assert children(action) == [("0:locate", "succeeded"), ("1:attempt 1", "failed"), ("2:locate", "succeeded"),
                                ("3:attempt 2", "succeeded")]
    assert action["children"][1]["failure"]["message"] == "a cat sat there"
    assert calls[0] != calls[1]


def test_an_unsatisfiable_location_fails_the_action_with_a_location_failure(world):
    with pytest.raises(LocationFailure, match=r"out of reach$"):
        perform_action(world, "navigate", {"target": {"reachable-for": [1.3, 0.6, 2.5]}})


def test_unknown_names_met_while_acting_are_failures_not_tracebacks(world):
    with pytest.raises(Failure, match="no object 'mlik'.*did you mean 'milk'"):
        perform_action(world, "navigate", {"target": {"reachable-for": "mlik"}})
    with pytest.raises(Failure, match="no link 'no_such_handle'"):
        perform_action(world, "open", {"handle": "no_such_handle"})


def test_transport_brings_the_milk_to_a_free_spot_where_it_stands(world):
    record: dict = {}
    milk = perform_action(world, "transport", {"object-type": "milk", "target": ISLAND}, record)
    kitchen = world.get_object_by_name("kitchen")
    assert stable(milk) and supporting(kitchen, milk, "kitchen_island_surface")
    assert not world.robot.attachments
    transport = record["children"][0]
    assert [c["label"] for c in transport["children"]] == [
        "0:action search", "1:action pick-up", "2:action place", "3:action park-arms", "4:stable"]


def test_open_and_close_a_drawer_by_its_handle_or_its_joint(world):
    kitchen = world.get_object_by_name("kitchen")
    perform_action(world, "open", {"handle": HANDLE})
    assert kitchen.get_joint_position(JOINT) == pytest.approx(0.3)
    perform_action(world, "close", {"joint": JOINT})
    assert kitchen.get_joint_position(JOINT) == pytest.approx(0.0, abs=1e-9)


def test_the_arm_rests_after_opening_a_drawer_along_the_way_its_location_test_found(world, monkeypatch):
    """The location test tries the pull with what the drawer holds riding along, as the action pulls it: the arm's
    way back from the handle (a joint-space search here) is then the action's to take, not to search again."""
    world.cache.forget(motion.MEMO)
    searches = []
    search = paths._Search.run
    monkeypatch.setattr(paths._Search, "run", lambda self, end: searches.append(1) or search(self, end))
    perform_action(world, "open", {"handle": HANDLE, "distance": 0.48})
    assert world.get_object_by_name("kitchen").get_joint_position(JOINT) == pytest.approx(0.48)
    assert len(searches) == 1


def test_search_opens_the_drawer_the_spoon_is_in(world):
    record: dict = {}
    spoon = perform_action(world, "search", {"object-type": "spoon"}, record)
    assert spoon.name == "spoon"
    labels = [c["label"] for c in record["children"][0]["children"]]
    assert labels[:2] == ["0:world-state-detecting", "1:action open"]
    assert world.get_object_by_name("kitchen").get_joint_position(JOINT) == pytest.approx(0.48)


def test_the_simple_actions(world):
    perform_action(world, "move-torso", {"position": 0.2})
    assert world.robot.get_joint_position("torso_lift_joint") == pytest.approx(0.2)
    perform_action(world, "look-at", {"target": "bottle"})
    assert perform_action(world, "detect", {"object": "bottle"}).name == "bottle"
    perform_action(world, "move-torso", {})
    assert world.robot.get_joint_position("torso_lift_joint") == pytest.approx(0.3)


def test_the_fetch_transports_with_the_same_code():
    world = load_world(worlds_dir() / "kitchen_fetch.yaml")
    try:
        for kind in ("bowl", "milk"):
            obj = perform_action(world, "transport", {"object-type": kind, "target": ISLAND})
            assert stable(obj) and supporting(world.get_object_by_name("kitchen"), obj, "kitchen_island_surface")
    finally:
        world.exit()


def test_pycram_designators_lists_the_actions_with_their_slots():
    import json

    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    listing = CliRunner().invoke(cli, ["designators", "--actions"]).output
    for name in ACTIONS:
        assert f"action {name} — " in listing
    assert "moving — " not in listing
    both = json.loads(CliRunner().invoke(cli, ["designators", "pick-up", "--json"]).stdout)
    assert [(d["type"], d["level"]) for d in both] == [("pick-up", "motion"), ("pick-up", "action")]
    assert both[1]["written"] == "action: pick-up"
    transport = json.loads(CliRunner().invoke(cli, ["designators", "transport", "--json"]).stdout)[0]
    target = next(s for s in transport["slots"] if s["name"] == "target")
    assert target["kind"] == "location" and target["required"]
    assert CliRunner().invoke(cli, ["designators", "transprt"]).exit_code == 2


def test_transport_says_what_the_placed_object_does_when_it_is_not_stable(world, monkeypatch):
    """The failure names the motion `stable` saw (here made to rock: the query's answer is replaced)."""
    import importlib
    import math

    from pycram_cli.failures import ReasoningFailure
    from pycram_cli.reasoning import StableAnswer

    rocking = StableAnswer(False, 0.003, 0.17, 0.06, "rocks", (0.003, math.radians(9.5)), 1.0)
    stable_module = importlib.import_module("pycram_cli.reasoning.stable")  # the package's `stable` is the function
    monkeypatch.setattr(stable_module, "stable", lambda obj: rocking)
    with pytest.raises(ReasoningFailure, match=r"milk is not stable where it was placed: it is not at rest, it rocks "
                                               r"back and forth by 9\.50° and 3\.00 mm") as failure:
        perform_action(world, "transport", {"object-type": "milk", "target": ISLAND})
    assert failure.value.details["motion"] == "rocks"


def test_transport_closes_the_drawer_it_took_the_spoon_out_of(world):
    """CRAM's transport seals what it accessed: a drawer left open stands where the robot must stand for what it
    fetches next (in a sweep of the demo, the bowl could then be reached from nowhere)."""
    record: dict = {}
    spoon = perform_action(world, "transport", {"object-type": "spoon", "target": {"on": "kitchen_island_surface"}},
                           record)
    kitchen = world.get_object_by_name("kitchen")
    assert supporting(kitchen, spoon, "kitchen_island_surface")
    assert kitchen.get_joint_position(JOINT) == pytest.approx(0.0, abs=1e-3)
    labels = [c["label"] for c in record["children"][0]["children"]]
    assert labels[-1] == "5:action close"


def test_transport_leaves_a_drawer_it_did_not_take_from_as_it_was(world):
    kitchen = world.get_object_by_name("kitchen")
    perform_action(world, "open", {"handle": HANDLE})
    perform_action(world, "transport", {"object-type": "milk", "target": {"on": "kitchen_island_surface"}})
    assert kitchen.get_joint_position(JOINT) == pytest.approx(0.3)
