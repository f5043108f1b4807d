"""Bounded resources for any plan (issue 18): nesting, branches, recursion, threads and the trace's size."""
from __future__ import annotations

import threading
import time

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.limits import MAX_BRANCHES, MAX_PLAN_DEPTH, MAX_RUNNING_BRANCHES, RETRY_KEPT
from pycram_cli.plan import load_plan
from pycram_cli.plan.executor import Run

from plan_helpers import nodes, statuses


def problems(plans, text: str) -> list[str]:
    with pytest.raises((InputError, InputErrors)) as info:
        plans.load(text)
    return [e.format() for e in as_list(info.value)]


def test_a_par_with_2000_branches_is_refused_naming_its_place(plans):
    branches = "".join(f"      - log: b{i}\n" for i in range(2000))
    started = time.monotonic()
    found = problems(plans, "body:\n  - par:\n" + branches)
    assert time.monotonic() - started < 10
    assert len(found) == 1 and ":3:7: par: 'par' has 2000 branches, more than 256 (the limit)" in found[0]


def test_steps_nested_deeper_than_the_limit_are_refused(plans):
    depth = MAX_PLAN_DEPTH + 5
    text = "body:\n" + "".join("  " * (i + 1) + "- seq:\n" for i in range(depth)) + "  " * (depth + 1) + "- log: x\n"
    found = problems(plans, text)
    assert len(found) == 1 and f"steps nested more than {MAX_PLAN_DEPTH} levels deep (the limit)" in found[0]


def test_a_subplan_that_calls_itself_twice_in_par_ends_with_a_clear_error(plans, world):
    started = time.monotonic()
    before = threading.active_count()
    result = plans.run("""
        plans:
          twice:
            - par: [{call: twice}, {call: twice}]
        body: [{call: twice}]
    """, world)
    assert time.monotonic() - started < 5
    assert threading.active_count() == before, "branch threads were left behind"
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert "(the limit" in result.failure["message"]
    assert result.failure["path"].startswith("body/0:call twice/0:par/0:call twice/0:par/")
    assert not [p for p, s in statuses(result.trace).items() if s in ("pending", "running")]


def test_a_limit_is_not_caught_by_plan_handlers_nor_retried(plans, world):
    result = plans.run("""
        plans:
          forever: [{call: forever}]
        body:
          - retry: 1000
            body:
              - try: [{call: forever}]
                catch: {Failure: [{log: caught}]}
    """, world)
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert "nested calls" in result.failure["message"]
    assert "body/0:retry/attempt 2" not in nodes(result.trace)


def test_a_huge_retry_count_of_a_failing_body_keeps_the_trace_bounded(plans, world):
    result = plans.run("""
        body:
          - retry: 2000
            body: [{log: trying}, {fail: PerceptionFailure, message: not seen}]
            recover: [{log: again}]
    """, world)
    assert result.status == "failed"
    retry = nodes(result.trace)["body/0:retry"]
    assert retry["retries"] == 2000
    labels = [child["path"].rsplit("/", 1)[-1] for child in retry["children"]]
    kept = [f"attempt {i}" for i in range(1, RETRY_KEPT + 1)]
    assert labels[:2 * RETRY_KEPT] == [x for i in range(1, RETRY_KEPT + 1) for x in (f"attempt {i}", f"recover {i}")]
    assert labels[2 * RETRY_KEPT] == "folded attempts" and labels[-1] == "attempt 2001"
    folded = retry["children"][2 * RETRY_KEPT]
    assert folded["type"] == "folded" and folded["status"] == "failed"
    folds = 2001 - 2 * RETRY_KEPT - 1  # the last attempt fails the retry before the one before it is folded
    assert folded["folded"] == {"steps": 2 * folds, "failures": {"PerceptionFailure: not seen": folds}}
    assert len(nodes(result.trace)) < 40
    assert kept[0] in labels


def test_a_retry_of_a_billion_attempts_runs_in_bounded_memory_until_stopped(plans, world):
    plan = load_plan(plans.write("""
        body:
          - retry: 1000000000
            body: [{fail: PerceptionFailure, message: not seen}]
    """))
    run = Run(plan, world, {})
    done = threading.Event()
    thread = threading.Thread(target=lambda: (run.execute(), done.set()), daemon=True)
    thread.start()
    time.sleep(1.0)
    retries = run.root.children[0].info.get("retries", 0) if run.root.children else 0
    held = sum(1 for _ in run.root.walk())
    run.cancel("enough")
    thread.join(5)
    assert done.is_set(), "the run did not stop when cancelled"
    assert retries > 500, "the retry loop did not run"
    assert held < 20, f"{held} trace nodes held after {retries} attempts"


def test_at_most_so_many_branches_of_a_par_run_at_once_and_all_of_them_run(plans, world):
    alive: list[int] = []

    class Watch:
        def started(self, node):
            alive.append(threading.active_count())

        def finished(self, node):
            pass

        def log(self, node, message):
            pass

    count = MAX_BRANCHES
    before = threading.active_count()
    branches = "".join(f"      - seq: [{{wait: 0.001}}, {{log: b{i}}}]\n" for i in range(count))
    result = plans.run("body:\n  - par:\n" + branches, world, observer=Watch())
    assert result.status == "succeeded"
    assert max(alive) <= before + MAX_RUNNING_BRANCHES
    messages = [n["message"] for n in nodes(result.trace).values() if n["type"] == "log"]
    assert messages == [f"b{i}" for i in range(count)]  # in declaration order, all of them
    assert threading.active_count() == before


def test_a_par_failure_cancels_the_branches_that_have_not_started_yet(plans, world):
    branches = "".join(f"      - log: b{i}\n" for i in range(MAX_RUNNING_BRANCHES + 10))
    result = plans.run("body:\n  - par:\n      - fail: GripperFailure\n" + branches, world)
    assert result.status == "failed" and result.failure["type"] == "GripperFailure"
    s = statuses(result.trace)
    last = f"body/0:par/{MAX_RUNNING_BRANCHES + 10}:log"
    assert s[last] == "cancelled"


def test_more_branch_threads_than_the_limit_at_once_stop_the_run(plans, world):
    inner = "[" + ", ".join(["{wait: 0.5}"] * 20) + "]"
    before = threading.active_count()
    started = time.monotonic()
    result = plans.run("body:\n  - par:\n" + "".join(f"      - par: {inner}\n" for _ in range(20)), world)
    assert time.monotonic() - started < 5
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert result.failure["message"] == "more than 256 branches running at once (the limit)"
    assert threading.active_count() == before


# -- values that grow at run time (issue 29) ---------------------------------------------------------------


def test_a_list_doubled_step_after_step_stops_at_the_value_limit_naming_the_step(plans, world):
    from pycram_cli.limits import MAX_VALUE_ITEMS
    steps = "".join(f"  - set: {{x{i + 1}: [$x{i}, $x{i}]}}\n" for i in range(40))
    started = time.monotonic()
    result = plans.run("body:\n  - set: {x0: [1]}\n" + steps, world)
    assert time.monotonic() - started < 10
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert f"more than {MAX_VALUE_ITEMS} items" in result.failure["message"]
    assert "(the limit" in result.failure["message"]
    first = next(k for k in range(41) if 2 ** (k + 1) - 1 > MAX_VALUE_ITEMS)  # $xk: 2^k numbers in 2^k - 1 lists
    assert result.failure["path"] == f"body/{first}:set"


def test_a_string_doubled_step_after_step_stops_at_the_value_limit(plans, world):
    from pycram_cli.limits import MAX_VALUE_CHARS
    steps = "".join(f"  - set: {{s{i + 1}: \"$s{i}$s{i}\"}}\n" for i in range(40))
    started = time.monotonic()
    result = plans.run("body:\n  - set: {s0: ab}\n" + steps, world)
    assert time.monotonic() - started < 10
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert f"more than {MAX_VALUE_CHARS} characters" in result.failure["message"]


def test_a_value_nested_deeper_than_the_limit_at_run_time_stops_the_run(plans, world):
    result = plans.run("""
        body:
          - set: {x: [1], n: [%s]}
          - for_each: $n
            as: i
            do:
              - set: {x: [$x]}
                scope: plan
    """ % ", ".join(["0"] * 500), world)
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert "nested more than" in result.failure["message"]


def test_the_values_of_one_set_count_together(plans, world):
    from pycram_cli.limits import MAX_VALUE_ITEMS
    doubling = "".join(f"  - set: {{x{i + 1}: [$x{i}, $x{i}]}}\n" for i in range(15))  # $x15: 65 535 items
    result = plans.run("body:\n  - set: {x0: 1}\n" + doubling + "  - set: {a: $x15, b: $x15}\n", world)
    assert result.status == "failed" and result.failure["type"] == "LimitExceeded"
    assert f"more than {MAX_VALUE_ITEMS} items" in result.failure["message"]
    assert result.failure["path"] == "body/16:set"
