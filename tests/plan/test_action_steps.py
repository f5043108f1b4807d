"""Action steps in plans: `- action: NAME` with the slots beside it, validated like every step, run with their
expansion in the trace (motions, queries, locations, attempts), deterministic, and catchable by failure name."""
from __future__ import annotations

import json

import pytest

from plan_helpers import nodes
from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.plan import load_plan, run_plan
from pycram_cli.plan import trace as traces
from pycram_cli.paths import worlds_dir
from pycram_cli.worldfile.loader import load_world


@pytest.fixture
def world(kitchen):
    with kitchen.snapshot():
        yield kitchen


def problems(plans, text, world=None):
    with pytest.raises((InputError, InputErrors)) as caught:
        load_plan(plans.write(text), world)
    return [(e.location.line, e.key, e.message, e.suggestion) for e in as_list(caught.value)]


def test_action_steps_are_checked_before_anything_runs(plans, kitchen):
    found = problems(plans, """\
        body:
          - action: pickup
            object: milk
          - action: pick-up
            objet: milk
          - action: pick-up
            object: milk
            target: {on: kitchen_island_surface}
          - action: navigate
            target: {on: kitchen_island_surface}
          - action: navigate
            target: {reachable-for: mlik, arm: middle}
          - action: transport
            object: $nothing
            target: {on: kitchen_island_surfac}
          - action: open
            handle: sink_area_left_upper_drawer_handel
        """, kitchen)
    assert (2, "action", "unknown action 'pickup'", "did you mean 'pick-up'?") in found
    assert (5, "objet", "unknown key 'objet' in an 'action' step", "did you mean 'object'?") in found
    assert (4, "object", "action 'pick-up' needs slot 'object' (the object to pick up)", None) in found
    assert (8, "target", "action 'pick-up' has no slot 'target'", "slots: object, arm, grasp") in found
    assert (10, "target", "slot 'target': navigate goes to a base pose: reachable-for, visible-for or accessing (got on)",
            None) in found
    assert (12, "target", "slot 'target': arm: pr2 has no arm 'middle' (arms: left, right)", None) in found
    assert (12, "reachable-for", "'reachable-for': the world has no object 'mlik'", "did you mean 'milk'?") in found
    assert (14, "object", "undefined variable $nothing", None) in found
    assert (15, "on", "'on': the world has no object or link 'kitchen_island_surfac'",
            "did you mean 'kitchen_island_surface'?") in found
    assert (17, "handle", "'handle': the world has no link 'sink_area_left_upper_drawer_handel'",
            "did you mean 'sink_area_left_upper_drawer_handle'?") in found


def test_an_unquoted_on_key_is_read_as_on(plans):
    plan = load_plan(plans.write("""\
        body:
          - action: place
            object: milk
            target: {on: kitchen_island_surface}
        """))
    assert dict(plan.body[0].slots["target"]) == {"on": "kitchen_island_surface"}


def test_an_action_expands_into_child_steps_and_binds_its_value(plans, world):
    result = plans.run("""\
        body:
          - action: pick-up
            object: milk
            as: held
          - log: "holding $held"
        """, world)
    assert result.status == "succeeded", result.failure
    found = nodes(result.trace)
    action = found["body/0:action pick-up"]
    assert action["type"] == "action" and action["action"] == {"type": "pick-up", "slots": {"object": "milk"}}
    assert action["bound"] == {"held": "milk"}
    locate = found["body/0:action pick-up/0:locate"]
    assert locate["location"]["spec"] == {"reachable-for": "milk"} and locate["location"]["found"]["arm"] in ("left", "right")
    assert found["body/0:action pick-up/1:attempt 1/1:pick-up"]["designator"]["resolved"]["object"] == "milk"
    assert found["body/1:log"]["message"] == "holding milk"


def test_a_location_failure_is_caught_by_name(plans, world):
    result = plans.run("""\
        body:
          - try:
              - action: navigate
                target: {reachable-for: [1.3, 0.6, 2.5]}
            catch:
              LocationFailure:
                - log: "$failure.type: $failure.message"
        """, world)
    assert result.status == "succeeded"
    message = nodes(result.trace)["body/0:try/catch LocationFailure/0:log"]["message"]
    assert message.startswith("LocationFailure: no pose for reachable-for (1.3, 0.6, 2.5): ")


def test_actions_run_side_by_side_and_the_trace_is_the_same_every_time(plans):
    text = """\
        body:
          - par:
              - action: park-arms
              - action: navigate
                target: {visible-for: bottle}
          - action: detect
            object: bottle
        """
    plan = plans.load(text)
    runs = []
    for _ in range(2):
        world = load_world()
        try:
            result = run_plan(plan, world)
        finally:
            world.exit()
        assert result.status == "succeeded", result.failure
        runs.append(json.dumps(traces.normalised(traces.comparable(result.trace)), sort_keys=True))
    assert runs[0] == runs[1]


def test_a_plan_with_actions_runs_unchanged_on_the_fetch(plans):
    world = load_world(worlds_dir() / "kitchen_fetch.yaml")
    try:
        result = plans.run("""\
            body:
              - action: transport
                object-type: milk
                target: {on: kitchen_island_surface}
                as: milk
              - assert: {supporting: {a: kitchen, b: $milk, link: kitchen_island_surface}}
            """, world)
    finally:
        world.exit()
    assert result.status == "succeeded", result.failure
