"""par, pursue and try_all: real threads, CPL's outcomes, clean cancellation, deterministic traces."""
from __future__ import annotations

import dataclasses
import threading
import time

from pycram_cli.plan import run_plan
from pycram_cli.plan.resources import ResourceAnalysis, designator_resources
from pycram_cli.plan.scheduler import CancelToken, Cancelled, Scheduler
from pycram_cli.plan.trace import comparable, dumps
from pycram_cli.robots import bundled_descriptions

from plan_helpers import messages, nodes, statuses


class Recorder:
    def __init__(self) -> None:
        self.logs: list[str] = []
        self.started: list[str] = []

    def started(self, node) -> None:  # noqa: F811 - observer protocol
        pass

    def finished(self, node) -> None:
        pass

    def log(self, node, message) -> None:
        self.logs.append(message)


def test_par_fails_at_the_first_failure_and_cancels_a_long_running_sibling(plans, world):
    before = threading.active_count()
    started = time.perf_counter()
    result = plans.run("""
        body:
          - par:
              - seq:
                  - wait: 0.05
                  - fail: ManipulationFailure
                    message: drawer stuck
              - seq:
                  - wait: 30
                  - log: never
              - log: quick
    """, world)
    elapsed = time.perf_counter() - started
    assert elapsed < 5, "the cancelled branch did not stop at once"
    assert threading.active_count() == before, "a branch thread was left behind"
    assert result.failure == {"type": "ManipulationFailure", "message": "drawer stuck",
                              "path": "body/0:par/0:seq/1:fail"}
    s = statuses(result.trace)
    assert s["body/0:par"] == "failed"
    assert s["body/0:par/1:seq"] == "cancelled"
    assert s["body/0:par/1:seq/0:wait"] == "cancelled"
    assert s["body/0:par/1:seq/1:log"] == "cancelled"
    assert s["body/0:par/2:log"] == "succeeded"


def test_par_children_run_side_by_side(plans, world):
    started = time.perf_counter()
    result = plans.run("""
        body:
          - par: [{wait: 0.3}, {wait: 0.3}, {wait: 0.3}]
    """, world)
    assert result.status == "succeeded"
    assert time.perf_counter() - started < 0.85  # one after another would take 0.9 s
    waits = [n for p, n in nodes(result.trace).items() if p.endswith(":wait")]
    # their run times overlap
    assert max(n["timing"]["started"] for n in waits) < min(n["timing"]["started"] + n["timing"]["duration"]
                                                          for n in waits)


def test_par_branches_take_turns_step_by_step_in_a_fixed_order(plans, world):
    text = """
        body:
          - par:
              - seq: [{log: a1}, {log: a2}, {log: a3}]
              - seq: [{log: b1}, {log: b2}]
              - par: [{log: c1}, {seq: [{log: d1}, {log: d2}]}]
    """
    orders = set()
    for _ in range(5):
        recorder = Recorder()
        plans.run(text, world, observer=recorder)
        orders.add(tuple(recorder.logs))
    assert orders == {("a1", "b1", "c1", "d1", "a2", "b2", "d2", "a3")}


def test_pursue_ends_with_the_first_branch_to_finish(plans, world):
    before = threading.active_count()
    result = plans.run("""
        body:
          - pursue:
              - wait: 30
              - seq: [{log: a}, {log: b}]
            as: winner
          - log: after
    """, world)
    assert result.status == "succeeded"
    s = statuses(result.trace)
    assert s["body/0:pursue/0:wait"] == "cancelled"
    assert s["body/0:pursue/1:seq"] == "succeeded"
    assert messages(result.trace) == ["a", "b", "after"]
    assert threading.active_count() == before


def test_pursue_takes_the_outcome_of_the_first_branch_even_a_failure(plans, world):
    result = plans.run("""
        body:
          - pursue:
              - seq: [{wait: 30}, {log: never}]
              - seq: [{wait: 0.02}, {fail: NavigationFailure, message: timeout}]
    """, world)
    assert result.failure["type"] == "NavigationFailure"
    assert result.failure["path"] == "body/0:pursue/1:seq/1:fail"
    assert statuses(result.trace)["body/0:pursue/0:seq"] == "cancelled"


def test_try_all_succeeds_at_the_first_success_and_cancels_the_rest(plans, world):
    result = plans.run("""
        body:
          - try_all:
              - fail: PerceptionFailure
                message: not with the left camera
              - seq: [{wait: 0.02}, {log: found it}]
              - seq: [{wait: 30}, {log: never}]
    """, world)
    assert result.status == "succeeded"
    s = statuses(result.trace)
    assert s["body/0:try_all/0:fail"] == "failed"
    assert s["body/0:try_all/1:seq"] == "succeeded"
    assert s["body/0:try_all/2:seq"] == "cancelled"


def test_try_all_reports_every_failure_when_all_fail(plans, world):
    result = plans.run("""
        body:
          - try_all:
              - {fail: PerceptionFailure, message: one}
              - seq: [{wait: 0.01}, {fail: ReachabilityFailure, message: two}]
              - {fail: PerceptionFailure, message: three}
    """, world)
    failure = result.failure
    assert failure["type"] == "Failure"  # no more specific type is common to all three
    assert [(f["type"], f["message"]) for f in failure["failures"]] == [
        ("PerceptionFailure", "one"), ("ReachabilityFailure", "two"), ("PerceptionFailure", "three")]
    assert failure["path"] == "body/0:try_all"


def test_a_failure_inside_par_is_retried_around_it(plans, world):
    result = plans.run("""
        params: {fixed: false}
        body:
          - retry: 1
            on: [GripperFailure]
            recover: [{set: {fixed: true}}]
            body:
              - par:
                  - if: $fixed
                    then: [{log: no need to wait}]
                    else: [{wait: 30}]
                  - if: $fixed
                    then: [{log: fine now}]
                    else: [{fail: GripperFailure, message: open}]
    """, world)
    assert result.status == "succeeded", result.failure
    s = statuses(result.trace)
    assert s["body/0:retry/attempt 1/0:par/0:if"] == "cancelled"
    assert s["body/0:retry/attempt 1/0:par/1:if"] == "failed"
    assert s["body/0:retry/attempt 2/0:par"] == "succeeded"
    assert messages(result.trace) == ["no need to wait", "fine now"]


def test_the_same_par_plan_gives_the_same_trace_every_time(plans, world):
    text = """
        params: {items: [milk, cereal, bowl]}
        plans:
          fetch:
            params: [o]
            body:
              - par:
                  - log: "left arm for $o"
                  - seq: [{log: "drive for $o"}, {set: {last: $o}}]
              - try_all:
                  - {fail: PerceptionFailure, message: "$o not on the left"}
                  - log: "$o seen"
        body:
          - par:
              - for_each: $items
                as: o
                do: [{call: fetch, args: [$o]}]
              - seq: [{log: head}, {log: still head}]
    """
    plan = plans.load(text)
    dumps_seen = set()
    for _ in range(5):
        result = run_plan(plan, world)
        assert result.status == "succeeded", result.failure
        dumps_seen.add(dumps(comparable(result.trace)))
    assert len(dumps_seen) == 1


def test_resources_of_designators_and_subplans(plans):
    pr2 = next(d for d in bundled_descriptions() if d.name == "pr2")

    def used(type_name, slots):
        return designator_resources(type_name, slots, pr2)

    assert used("moving", {"target": [0, 0, 0]}) == {"base"}
    assert used("pick-up", {"object": "milk", "arm": "left"}) == {"arm:left"}
    assert used("pick-up", {"object": "milk"}) == {"arm:left", "arm:right"}
    assert used("place", {"object": "milk", "arm": "$arm", "target": [0, 0, 0]}) == {"arm:left", "arm:right"}
    assert used("move-arm-joints", {"right-arm": "park"}) == {"arm:right"}
    assert used("move-arm-joints", {"arms": {"left": "park", "right": "park"}}) == {"arm:left", "arm:right"}
    assert used("closing-gripper", {"gripper": "right"}) == {"arm:right"}
    assert used("detecting", {"object-type": "milk"}) == {"head"}
    assert used("world-state-detecting", {"object-type": "milk"}) == set()


def test_a_robot_description_can_say_that_two_roles_share_one_resource():
    pr2 = next(d for d in bundled_descriptions() if d.name == "pr2")
    wrist_camera = dataclasses.replace(pr2, resources={"head": "arm:left"})
    assert designator_resources("looking", {"target": [1, 0, 1]}, wrist_camera) == {"arm:left"}
    assert designator_resources("pick-up", {"object": "milk"}, wrist_camera) == {"arm:left", "arm:right"}


def test_without_a_robot_description_arm_steps_share_one_resource():
    assert designator_resources("pick-up", {"object": "milk", "arm": "left"}) == {"arm:*"}
    assert designator_resources("move-arm-joints", {"right-arm": "park"}) == {"arm:*"}


def test_resources_of_subplans(plans):
    plan = plans.load("""
        plans:
          drive: [{moving: {target: [1, 0, 0]}}, {call: drive_again}]
          drive_again: [{call: drive}]
        body:
          - par:
              - move-arm-joints: {left-arm: park}
              - call: drive_again
              - moving: {target: [0, 1, 0]}
              - looking: {target: [1, 1, 1]}
    """)
    analysis = ResourceAnalysis(plan)
    assert analysis.subplans == {"drive": {"base"}, "drive_again": {"base"}}
    assert analysis.waits_for(plan.body[0].steps) == {0: set(), 1: set(), 2: {1}, 3: set()}


def test_a_branch_competing_for_a_resource_starts_after_the_earlier_one_ended():
    scheduler = Scheduler()
    token = CancelToken(notify=scheduler.wake)
    order: list[str] = []
    keys = scheduler.spawn((), 2, {1: {0}})

    def branch(key, name, steps):
        scheduler.acquire(key, token)
        for i in range(steps):
            order.append(f"{name}{i}")
            scheduler.pass_turn(key, token)
        scheduler.finish(key)

    threads = [threading.Thread(target=branch, args=(keys[1], "b", 2)),
               threading.Thread(target=branch, args=(keys[0], "a", 3))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(5)
    assert order == ["a0", "a1", "a2", "b0", "b1"]
    scheduler.acquire((), token)


def test_a_cancelled_token_wakes_a_sleeper_and_propagates_to_children():
    parent = CancelToken()
    child = parent.child()
    grandchild = child.child()
    threading.Timer(0.05, parent.cancel, args=("stop",)).start()
    started = time.perf_counter()
    try:
        grandchild.sleep(10)
    except Cancelled as exc:
        assert str(exc) == "stop"
    assert time.perf_counter() - started < 2
    assert child.cancelled and parent.child().cancelled


def test_traces_do_not_depend_on_thread_timing(plans, world, monkeypatch):
    """Random delays before every step of every thread change nothing in the comparable trace."""
    import random

    from pycram_cli.plan.executor import Exec

    text = """
        body:
          - par:
              - seq: [{log: a1}, {set: {x: 1}}, {log: a3}]
              - try_all:
                  - {fail: PerceptionFailure, message: one}
                  - seq: [{log: b1}, {log: b2}]
              - pursue:
                  - seq: [{log: c1}, {log: c2}, {log: c3}]
                  - seq: [{log: d1}]
              - seq: [{log: e1}, {fail: GripperFailure, message: late}]
              - seq: [{log: f1}, {log: f2}, {log: f3}, {log: f4}]
    """
    plan = plans.load(text)
    reference = dumps(comparable(run_plan(plan, world).trace))
    original = Exec.step

    def jittery(self, node, tn):
        time.sleep(random.random() * 0.003)
        return original(self, node, tn)

    monkeypatch.setattr(Exec, "step", jittery)
    for _ in range(5):
        assert dumps(comparable(run_plan(plan, world).trace)) == reference
    s = statuses(run_plan(plan, world).trace)
    assert s["body/0:par/4:seq/3:log"] == "cancelled" and s["body/0:par/3:seq/1:fail"] == "failed"
