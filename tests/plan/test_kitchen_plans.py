"""Plans with motion designators and reasoning queries on the kitchen: data flow, recursion, determinism."""
from __future__ import annotations

import random
import sys
import threading

import pytest

from pycram_cli.plan import run_plan
from pycram_cli.plan.trace import comparable, dumps
from pycram_cli.worldfile.loader import load_world

from plan_helpers import messages, nodes, statuses


@pytest.fixture
def kitchen():
    world = load_world()
    yield world
    world.exit()


PAR_PLAN = """
    world: kitchen
    body:
      - par:
          - seq:
              - move-arm-joints: {left-arm: park}
              - looking: {target: [1.3, 0.6, 0.9]}
          - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
          - seq:
              - move-arm-joints: {right-arm: park}
              - world-state-detecting: {object-type: bowl}
                as: bowl
          - looking: {object: milk}
      - par:
          - detecting: {object-type: milk}
            as: milk
            scope: plan                            # seen after the par (a branch's bindings stay in it)
          - blocking: {target: bowl, arm: left, exclude-type: [environment]}
            as: blockers
            scope: plan
      - log: "milk $milk, blockers of the bowl: $blockers"
"""


def test_a_par_plan_on_the_kitchen_gives_the_same_trace_however_threads_interleave(plans):
    plan = plans.load(PAR_PLAN)
    seen = set()
    interval = sys.getswitchinterval()
    try:
        for run in range(5):
            sys.setswitchinterval(random.choice([1e-6, 1e-4, interval]))
            world = load_world()
            try:
                result = run_plan(plan, world)
            finally:
                world.exit()
            assert result.status == "succeeded", result.failure
            seen.add(dumps(comparable(result.trace)))
    finally:
        sys.setswitchinterval(interval)
    assert len(seen) == 1


def test_branches_using_the_same_resource_are_serialised_in_declaration_order(plans, kitchen):
    result = plans.run("""
        body:
          - par:
              - seq: [{moving: {target: [0.3, 0.7, 0]}}, {log: first drive done}]
              - seq: [{log: second branch starts}, {moving: {target: [0.65, 0.7, 0]}}]
              - log: no resource, runs at once
    """, kitchen)
    assert result.status == "succeeded", result.failure
    assert messages(result.trace) == ["first drive done", "second branch starts", "no resource, runs at once"]
    n = nodes(result.trace)
    first_end = n["body/0:par/0:seq"]["timing"]["started"] + n["body/0:par/0:seq"]["timing"]["duration"]
    assert n["body/0:par/1:seq"]["timing"]["started"] >= first_end
    assert n["body/0:par/2:log"]["timing"]["started"] < first_end
    assert result.trace["final_state"]["objects"]["pr2"]["position"][:2] == [0.65, 0.7]


def test_moving_a_blocking_object_first_by_recursion(plans, kitchen):
    """The demo's pattern: fetch an object; if something blocks it, first fetch that (recursively)."""
    result = plans.run("""
        params: {object: bowl}
        plans:
          clear:
            params: [object]
            body:
              - world-state-detecting: {object-type: $object}
                as: obj
              - blocking: {target: $obj, arm: left, exclude-type: [environment]}
                as: blockers
              - if: $blockers
                then:
                  - log: "$blockers.0 blocks $obj: clear it first"
                  - call: clear
                    args: [$blockers.0.type]
              - log: "reaching for $obj"
        body:
          - par:
              - move-arm-joints: {left-arm: park, right-arm: park}
              - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
          - call: clear
            args: [$object]
    """, kitchen)
    assert result.status == "succeeded", result.failure
    assert messages(result.trace) == ["milk blocks bowl: clear it first", "reaching for milk", "reaching for bowl"]
    inner = nodes(result.trace)["body/1:call clear/2:if/then/1:call clear"]
    assert inner["call"] == {"plan": "clear", "args": {"object": "milk"}}


def test_a_failing_designator_is_recorded_with_its_slots_and_handled(plans, kitchen):
    result = plans.run("""
        body:
          - try:
              - detecting: {object-type: teapot}
                as: pot
            catch:
              PerceptionFailure:
                - log: "$failure.type: $failure.message"
          - unless: {contact: {a: milk, b: pr2}}
            then: [{log: not touching}]
    """, kitchen)
    assert result.status == "succeeded"
    n = nodes(result.trace)
    detecting = n["body/0:try/try/0:detecting"]
    assert detecting["status"] == "failed" and detecting["designator"]["slots"] == {"object-type": "teapot"}
    assert detecting["failure"]["type"] == "PerceptionFailure"
    assert n["body/1:unless"]["condition"]["query"]["name"] == "contact"
    assert n["body/1:unless"]["condition"]["holds"] is False
    assert messages(result.trace)[-1] == "not touching"


def test_cancellation_stops_a_branch_between_designators_and_leaves_no_thread(plans, kitchen):
    before = threading.active_count()
    result = plans.run("""
        body:
          - par:
              - seq:
                  - moving: {target: [0.3, 0.7, 0]}
                  - wait: 0.05
                  - fail: NavigationFailure
                    message: lost
              - seq:
                  - looking: {target: [1.3, 0.6, 0.9]}
                  - wait: 20
                  - looking: {target: [1.3, 1.0, 0.9]}
    """, kitchen)
    assert threading.active_count() == before
    s = statuses(result.trace)
    assert s["body/0:par/1:seq/0:looking"] == "succeeded"
    assert s["body/0:par/1:seq/1:wait"] == "cancelled"
    assert s["body/0:par/1:seq/2:looking"] == "cancelled"
    assert "designator" not in nodes(result.trace)["body/0:par/1:seq/2:looking"]
