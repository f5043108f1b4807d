"""Typed plan parameters: `params: {target: {type: position, default: [...]}}` declares a parameter's kind of value,
and every value it gets (its default, `-p`, a literal call argument) is checked against it before anything runs."""
from __future__ import annotations

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.kinds import Robots
from pycram_cli.paths import plans_dir
from pycram_cli.plan import bind_params, load_plan, parse_plan
from pycram_cli.robots import bundled_descriptions


def problems(plans, text: str) -> list[InputError]:
    with pytest.raises((InputError, InputErrors)) as err:
        plans.load(text)
    return as_list(err.value)


def test_a_declaration_gives_the_type_default_and_description(plans):
    plan = plans.load("""
        params:
          target: {type: position, default: [1, 0.5, 0.9], description: where it goes}
          types: {type: list}
          speed: 0.5
        body: [{log: "$target $types $speed"}]
    """)
    target, types, speed = plan.params
    assert (target.type, target.default, target.description, target.required) == (
        "position", [1, 0.5, 0.9], "where it goes", False)
    assert (types.type, types.required) == ("list", True)  # a declared type without a default is required
    assert (speed.type, speed.default, speed.required) == (None, 0.5, False)


def test_a_mapping_that_is_no_declaration_stays_a_plain_default(plans):
    plan = plans.load("""
        params:
          counter: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
          job: {type: milk, arm: left}
          kind: {type: bowl}
        body: [{log: "$counter.target $job.type $kind.type"}]
    """)
    assert [p.type for p in plan.params] == [None, None, None]
    assert plan.params[1].default == {"type": "milk", "arm": "left"}
    assert bind_params(plan, {})["kind"] == {"type": "bowl"}


def test_a_default_that_does_not_fit_its_type_is_reported_at_its_line(plans):
    found = problems(plans, """
        params:
          target:
            type: position
            default: [1, 0.5]
          arm: {type: arm, default: middle}
          flag: {type: boolean, default: yes please}
        body: [{log: "$target $arm $flag"}]
    """)
    got = {(p.location.line, p.key): p.message for p in found}
    assert got[(5, "target")] == ("the default of parameter 'target' is a position: expected a position [x, y, z], "
                                  "got a list of 2")
    assert "has no arm 'middle'" in got[(6, "arm")]  # robot names: against every bundled robot without a world
    assert got[(7, "flag")].endswith("expected true or false, got the string 'yes please'")
    assert all(str(p.location.file).endswith(".yaml") for p in found)


def test_a_misspelt_type_is_an_error_with_a_suggestion_not_a_mapping_default(plans):
    found = problems(plans, """
        params:
          target: {type: positon, default: [1, 0.5, 0.9]}
        body: [{log: $target}]
    """)
    assert [(p.location.line, p.message, p.suggestion) for p in found] == [
        (3, "unknown parameter type 'positon'", "did you mean 'position'?")]


def test_given_values_of_the_wrong_shape_are_input_errors_naming_the_parameter_and_the_shape(plans):
    plan = plans.load("""
        params:
          target: {type: position, default: [1, 0.5, 0.9]}
          types: {type: list, default: [milk]}
          turn: {type: orientation, default: [0, 0, 0, 1]}
        body: [{log: "$target $types $turn"}]
    """)
    with pytest.raises(InputErrors) as err:
        bind_params(plan, {"target": [1, 2], "types": "milk", "turn": [0, 0, 1]})
    got = {p.key: (str(p.location), p.message, p.suggestion) for p in as_list(err.value)}
    assert got["target"] == ("-p", "parameter 'target' is a position: expected a position [x, y, z], got a list of 2",
                             "e.g. -p target=[1, 0.5, 0.9]")
    assert got["types"][1] == "parameter 'types' is a list: expected a list, got the string 'milk'"
    assert "expected a quaternion [x, y, z, w] (got 3 numbers)" in got["turn"][1]
    assert bind_params(plan, {"target": [0, 0, 1.5]})["target"] == [0, 0, 1.5]


def test_a_required_typed_parameter_must_be_given_and_says_how(plans):
    plan = plans.load("""
        params: {target: {type: position}}
        body: [{log: $target}]
    """)
    with pytest.raises(InputError) as err:
        bind_params(plan, {})
    assert err.value.message == f"plan '{plan.name}' needs parameter 'target'"
    assert err.value.suggestion == "give it with -p target=VALUE ([x, y, z] in metres, world frame)"
    assert bind_params(plan, {"target": [1, 2, 3]}) == {"target": [1, 2, 3]}


def test_robot_names_in_given_values_are_checked_against_the_robot(plans):
    plan = plans.load("""
        params: {arm: {type: arm, default: left}}
        body: [{log: $arm}]
    """)
    pr2 = Robots(tuple(d for d in bundled_descriptions() if d.name == "pr2"), True)
    with pytest.raises(InputError) as err:
        bind_params(plan, {"arm": "middle"}, robots=pr2)
    assert "pr2 has no arm 'middle'" in err.value.message


def test_a_null_default_makes_null_a_value_of_the_parameter(plans):
    plan = plans.load("""
        params: {near: {type: position, default: null}}
        body: [{log: "near $near"}]
    """)
    assert bind_params(plan, {}) == {"near": None}
    assert bind_params(plan, {"near": None}) == {"near": None}
    with pytest.raises(InputError):
        bind_params(plan, {"near": "close"})


def test_subplan_parameters_are_typed_too_and_literal_arguments_are_checked(plans):
    found = problems(plans, """
        plans:
          put:
            params:
              - {where: {type: position}}
              - {arm: {type: arm, default: left}}
            body: [{log: "$where $arm"}]
        body:
          - call: put
            args: [[1, 2]]
          - call: put
            args: {where: [1, 2, 3], arm: 7}
          - set: {spot: [1, 2]}
          - call: put
            args: [$spot]
    """)
    assert [(p.location.line, p.message) for p in found] == [
        (10, "put(where, arm): parameter 'where' is a position: expected a position [x, y, z], got a list of 2"),
        (12, "put(where, arm): parameter 'arm' is an arm: expected an arm name (arm, left, right), got 7"),
    ]  # $spot is only known when the call runs


def test_the_shipped_plans_declare_their_parameters_types():
    kinds = {name: {p.name: p.type for p in parse_plan(plans_dir() / f"{name}.yaml").params}
             for name in ("fetch_spoon", "set_table_actions", "fetch_milk")}
    assert kinds["fetch_spoon"] == {"target": "position"}
    assert kinds["set_table_actions"] == {"objects": "list", "table": "link", "furniture": "object"}
    assert kinds["fetch_milk"]["target"] == "position" and kinds["fetch_milk"]["look"] == "position"
    for name in kinds:
        load_plan(plans_dir() / f"{name}.yaml")  # their defaults fit
