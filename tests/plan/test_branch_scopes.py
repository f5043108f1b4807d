"""Each branch of par, pursue and try_all has its own bindings (CPL): reads see the enclosing scope, writes stay
in the branch, unless a step binds with `scope: plan`."""
from __future__ import annotations

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list

from plan_helpers import messages


def test_sibling_for_each_loops_with_the_same_variable_name_each_see_their_own_items(plans, world):
    # the branches take turns after every leaf step, so with one shared scope each loop would read the other's item
    result = plans.run("""
        body:
          - par:
              - for_each: [a, b, c]
                as: item
                do: [{log: "left $item"}, {log: "left again $item"}]
              - for_each: [x, y, z]
                as: item
                do: [{log: "right $item"}, {log: "right again $item"}]
    """, world)
    assert result.status == "succeeded", result.failure
    logs = messages(result.trace)
    assert [m for m in logs if m.startswith("left")] == [
        "left a", "left again a", "left b", "left again b", "left c", "left again c"]
    assert [m for m in logs if m.startswith("right")] == [
        "right x", "right again x", "right y", "right again y", "right z", "right again z"]


def test_an_as_in_one_branch_does_not_overwrite_a_sibling_or_the_enclosing_binding(plans, world):
    result = plans.run("""
        body:
          - set: {who: outer}
          - par:
              - seq: [{set: {who: left}}, {log: "a $who"}, {log: "b $who"}]
              - seq: [{log: "c $who"}, {set: {who: right}}, {log: "d $who"}]
          - log: "after $who"
    """, world)
    assert result.status == "succeeded", result.failure
    assert sorted(messages(result.trace)) == ["a left", "after outer", "b left", "c outer", "d right"]


def test_scope_plan_binds_beyond_the_branch(plans, world):
    result = plans.run("""
        body:
          - pursue:
              - seq:
                  - set: {found: first}
                    scope: plan
                  - log: found
              - wait: 1
          - try_all:
              - seq: [{log: x}]
                as: winner
                scope: plan
          - par:
              - set: {count: 1}
          - log: "$found $winner"
    """, world)
    assert result.status == "succeeded", result.failure
    assert messages(result.trace)[-1] == "first null"  # a seq's value is its last step's (a log's: null)


def test_a_branch_variable_used_after_the_step_is_reported_before_anything_runs(plans):
    with pytest.raises((InputError, InputErrors)) as err:
        plans.load("""
            body:
              - par:
                  - world-state-detecting: {object-type: milk}
                    as: milk
                  - log: meanwhile
              - log: $milk
        """)
    problems = as_list(err.value)
    assert len(problems) == 1
    assert "bound inside a branch of a concurrent step (at line 5)" in problems[0].message
    assert problems[0].suggestion == "add 'scope: plan' beside its 'as' to use it after the step"
    assert problems[0].location.line == 7


def test_a_sibling_branch_cannot_read_another_branchs_binding(plans):
    with pytest.raises((InputError, InputErrors)) as err:
        plans.load("""
            body:
              - par:
                  - set: {x: 1}
                  - log: $x
        """)
    assert "bound inside a branch" in as_list(err.value)[0].message


def test_scope_takes_plan_or_branch_and_needs_something_to_bind(plans):
    with pytest.raises((InputError, InputErrors)) as err:
        plans.load("""
            body:
              - seq: [{log: a}]
                as: a
                scope: everywhere
              - seq: [{log: b}]
                scope: plan
              - log: c
                scope: plan
        """)
    found = sorted((p.location.line, p.message) for p in as_list(err.value))
    assert found == [(5, "expected scope: plan or scope: branch, got the string 'everywhere'"),
                     (7, "'scope' says where 'seq' binds its value: it needs 'as'"),
                     (9, "'log' does not produce a value to bind with 'scope'")]
