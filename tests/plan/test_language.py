"""The plan language, one feature at a time, with leaves that need no robot (log, set, fail, assert)."""
from __future__ import annotations

import pytest

from pycram_cli.errors import InputError, InputErrors
from pycram_cli.plan import bind_params, parse_assignments

from plan_helpers import messages, nodes, statuses


def test_seq_runs_steps_in_order_and_a_failure_skips_the_rest(plans, world):
    result = plans.run("""
        body:
          - log: one
          - seq: [{log: two}, {fail: GripperFailure, message: slipped}, {log: never}]
          - log: never either
    """, world)
    assert result.status == "failed"
    assert messages(result.trace) == ["one", "two"]
    assert result.failure == {"type": "GripperFailure", "message": "slipped", "path": "body/1:seq/1:fail"}
    s = statuses(result.trace)
    assert s["body/1:seq/2:log"] == "skipped" and s["body/2:log"] == "skipped"
    assert s["body/1:seq"] == "failed" and s["body"] == "failed"


def test_an_unhandled_failure_names_the_path_of_the_node_that_failed_through_calls(plans, world):
    result = plans.run("""
        plans:
          inner:
            - log: inside
            - fail: ReachabilityFailure
              message: "arm too short"
          outer:
            - call: inner
        body:
          - call: outer
    """, world)
    assert result.failure["path"] == "body/0:call outer/0:call inner/1:fail"
    assert result.failure["type"] == "ReachabilityFailure"
    # every enclosing node records the same origin
    assert nodes(result.trace)["body/0:call outer"]["failure"]["path"] == result.failure["path"]


def test_variables_bound_with_as_and_used_later_with_attribute_access(plans, world):
    result = plans.run("""
        plans:
          pair:
            params: [a, b]
            body: [{log: "$a+$b"}]
            returns: [$a, $b]
        body:
          - call: pair
            args: [x, {k: v}]
            as: p
          - log: "first $p.0, key ${p.1.k}, length $p.length, dollars $$5"
          - set: {n: 3}
          - log: $n
    """, world)
    assert result.status == "succeeded", result.failure
    assert messages(result.trace) == ["x+{k: v}", "first x, key v, length 2, dollars $5", "3"]
    assert nodes(result.trace)["body/0:call pair"]["bound"] == {"p": ["x", {"k": "v"}]}


def test_parameters_have_defaults_and_can_be_overridden(plans, world):
    text = """
        params: {object: milk, target: [1, 0.5, 0.9]}
        body:
          - log: "$object to $target"
    """
    assert messages(plans.run(text, world).trace) == ["milk to [1, 0.5, 0.9]"]
    overridden = plans.run(text, world, parse_assignments(["object=cereal", "target=[0, 0, 1.5]"]))
    assert messages(overridden.trace) == ["cereal to [0, 0, 1.5]"]
    assert overridden.trace["params"] == {"object": "cereal", "target": [0, 0, 1.5]}


def test_unknown_and_missing_parameters_are_input_errors_with_suggestions(plans):
    plan = plans.load("""
        params: [object, {speed: 1}]
        body: [{log: $object}]
    """)
    with pytest.raises(InputErrors) as err:
        bind_params(plan, {"objekt": "milk"})
    text = str(err.value)
    assert "no parameter 'objekt'" in text and "did you mean 'object'?" in text
    assert "needs parameter 'object'" in text
    assert bind_params(plan, {"object": "milk"}) == {"object": "milk", "speed": 1}
    with pytest.raises(InputError):
        parse_assignments(["novalue"])


def test_subplans_take_positional_or_named_arguments_with_defaults(plans, world):
    result = plans.run("""
        plans:
          greet:
            params: [name, {punct: "!"}]
            body: [{log: "hi $name$punct"}]
        body:
          - call: greet
            args: [ann]
          - call: greet
            args: {punct: "?", name: bob}
    """, world)
    assert messages(result.trace) == ["hi ann!", "hi bob?"]
    assert nodes(result.trace)["body/1:call greet"]["call"] == {"plan": "greet", "args": {"name": "bob", "punct": "?"}}


def test_subplans_recurse_with_arguments(plans, world):
    result = plans.run("""
        plans:
          descend:
            params: [tree]
            body:
              - log: "at $tree.0"
              - if: $tree.1
                then: [{call: descend, args: [$tree.1]}]
        body:
          - call: descend
            args: [[a, [b, [c, []]]]]
    """, world)
    assert result.status == "succeeded"
    assert messages(result.trace) == ["at a", "at b", "at c"]
    assert "body/0:call descend/1:if/then/0:call descend/1:if/then/0:call descend/0:log" in nodes(result.trace)


def test_endless_recursion_fails_cleanly(plans, world):
    result = plans.run("""
        plans:
          forever: [{call: forever}]
        body: [{call: forever}]
    """, world)
    assert result.status == "failed" and "nested calls" in result.failure["message"]


def test_if_and_unless_on_variables_and_literals(plans, world):
    result = plans.run("""
        params: {items: [], name: milk}
        body:
          - if: $items
            then: [{log: has items}]
            else: [{log: no items}]
          - unless: $items
            then: [{log: "unless ran"}]
          - if: $name
            then: [{log: "named $name"}]
          - if: {not: true}
            then: [{log: never}]
            else: [{log: "not true is false"}]
          - for_each: [{object: milk, arm: left}, {object: spoon, arm: right, drawer: true}]
            as: job
            do:
              - if: {equal: [$job.object, spoon]}
                then: [{log: "open the drawer for the $job.object"}]
              - if: $job.drawer
                then: [{log: "drawer flag for $job.object"}]
    """, world)
    assert messages(result.trace) == ["no items", "unless ran", "named milk", "not true is false",
                                      "open the drawer for the spoon", "drawer flag for spoon"]
    n = nodes(result.trace)
    assert n["body/0:if"]["condition"] == {"variable": "$items", "value": [], "holds": False}
    assert "body/0:if/else" in n and "body/0:if/then" not in n


def test_for_each_over_a_literal_list_and_a_variable(plans, world):
    result = plans.run("""
        params: {objects: [milk, cereal]}
        body:
          - for_each: $objects
            as: o
            do: [{log: "fetch $o"}]
          - for_each: [1, 2]
            as: i
            do: [{log: "i=$i"}, {log: "o is still $o"}]
    """, world)
    assert messages(result.trace) == ["fetch milk", "fetch cereal", "i=1", "o is still cereal", "i=2",
                                      "o is still cereal"]
    n = nodes(result.trace)
    assert n["body/0:for_each/item 1"]["item"] == "cereal"
    assert n["body/0:for_each"]["items"] == ["milk", "cereal"]


def test_retry_with_recovery_before_each_new_attempt(plans, world):
    result = plans.run("""
        body:
          - set: {ready: false}
          - retry: 3
            on: [PerceptionFailure]
            recover:
              - log: looking again
              - set: {ready: true}
            body:
              - unless: $ready
                then: [{fail: PerceptionFailure, message: not seen}]
              - log: seen
    """, world)
    assert result.status == "succeeded"
    assert messages(result.trace) == ["looking again", "seen"]
    n = nodes(result.trace)
    assert n["body/1:retry"]["retries"] == 1
    assert n["body/1:retry/attempt 1"]["status"] == "failed"
    assert n["body/1:retry/recover 1"]["status"] == "succeeded"
    assert n["body/1:retry/attempt 2"]["status"] == "succeeded"


def test_retry_gives_up_after_its_count_and_passes_other_failures_through(plans, world):
    exhausted = plans.run("""
        body:
          - retry: 2
            on: [NavigationFailure]
            body: [{fail: NavigationFailure, message: blocked}]
    """, world)
    assert exhausted.status == "failed"
    assert exhausted.failure["path"] == "body/0:retry/attempt 3/0:fail"
    assert nodes(exhausted.trace)["body/0:retry"]["retries"] == 2
    other = plans.run("""
        body:
          - retry: 5
            on: [NavigationFailure]
            body: [{fail: GripperFailure, message: dropped}]
    """, world)
    assert other.failure["type"] == "GripperFailure"
    assert "body/0:retry/attempt 2" not in nodes(other.trace)


def test_handlers_are_chosen_by_failure_type_in_order(plans, world):
    result = plans.run("""
        plans:
          attempt:
            params: [kind]
            body:
              - try: [{fail: $kind, message: "a $kind"}]
                catch:
                  NavigationFailure: [{log: "navigation handler: $failure.message"}]
                  Failure: [{log: "generic handler: $failure.type at $failure.path"}]
        body:
          - call: attempt
            args: [NavigationFailure]
          - call: attempt
            args: [PerceptionFailure]
    """, world)
    assert result.status == "succeeded"
    assert messages(result.trace) == [
        "navigation handler: a NavigationFailure",
        "generic handler: PerceptionFailure at body/1:call attempt/0:try/try/0:fail",
    ]
    caught = nodes(result.trace)["body/1:call attempt/0:try/catch Failure"]["caught"]
    assert caught["type"] == "PerceptionFailure"


def test_a_handler_can_re_raise_and_unhandled_types_propagate(plans, world):
    rethrown = plans.run("""
        body:
          - try: [{fail: GripperFailure, message: dropped}]
            catch:
              GripperFailure: [{log: cleaning up}, {fail: $failure}]
    """, world)
    assert rethrown.failure == {"type": "GripperFailure", "message": "dropped", "path": "body/0:try/try/0:fail"}
    unhandled = plans.run("""
        body:
          - try: [{fail: GripperFailure, message: dropped}]
            catch:
              PerceptionFailure: [{log: never}]
    """, world)
    assert unhandled.failure["type"] == "GripperFailure"
    assert messages(unhandled.trace) == []


def test_design_aliases_for_failure_types(plans, world):
    result = plans.run("""
        body:
          - try: [{fail: PerceptionError, message: x}]
            catch:
              PerceptionFailure: [{log: caught}]
    """, world)
    assert messages(result.trace) == ["caught"]


def test_try_in_order_stops_at_the_first_success(plans, world):
    result = plans.run("""
        body:
          - try_in_order:
              - fail: PerceptionFailure
                message: first
              - log: second works
              - log: third never
            as: v
    """, world)
    assert result.status == "succeeded"
    s = statuses(result.trace)
    assert s["body/0:try_in_order/0:fail"] == "failed"
    assert s["body/0:try_in_order/1:log"] == "succeeded"
    assert s["body/0:try_in_order/2:log"] == "skipped"


def test_try_in_order_fails_with_every_failure_when_none_succeeds(plans, world):
    result = plans.run("""
        body:
          - try_in_order:
              - {fail: PerceptionFailure, message: "not on the counter"}
              - {fail: PerceptionFailure, message: "not in the drawer"}
    """, world)
    failure = result.failure
    assert failure["type"] == "PerceptionFailure"  # the most specific type all of them share
    assert [f["message"] for f in failure["failures"]] == ["not on the counter", "not in the drawer"]
    assert [f["path"] for f in failure["failures"]] == ["body/0:try_in_order/0:fail", "body/0:try_in_order/1:fail"]


def test_assert_on_a_variable_with_a_default_or_given_failure(plans, world):
    default = plans.run("""
        params: {ok: false}
        body: [{assert: $ok}]
    """, world)
    assert default.failure["type"] == "ReasoningFailure"
    assert "$ok does not hold" in default.failure["message"]
    given = plans.run("""
        params: {found: [], object: milk}
        body:
          - assert: $found
            failure: PerceptionFailure
            message: "$object is not there"
    """, world)
    assert given.failure == {"type": "PerceptionFailure", "message": "milk is not there", "path": "body/0:assert"}


def test_a_variable_bound_only_in_a_branch_that_did_not_run_is_a_failure_at_run_time(plans, world):
    result = plans.run("""
        params: {flag: false}
        body:
          - if: $flag
            then: [{set: {x: 1}}]
          - log: $x
    """, world)
    assert result.status == "failed"
    assert result.failure["path"] == "body/1:log" and "$x" in result.failure["message"]


def test_wait_and_the_value_of_composites(plans, world):
    result = plans.run("""
        body:
          - seq: [{set: {a: 1}}, {wait: 0.01}, {log: done}]
            as: last
          - par: [{log: x}, {log: y}]
            as: values
          - log: "$values"
    """, world)
    assert result.status == "succeeded"
    assert nodes(result.trace)["body/2:log"]["message"] == "[null, null]"
    assert nodes(result.trace)["body/0:seq/1:wait"]["seconds"] == 0.01
