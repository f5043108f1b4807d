"""Every problem in a plan is found before anything runs and reported together with file:line:column."""
from __future__ import annotations

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.plan import load_plan
from pycram_cli.worldfile.loader import load_world

BROKEN = """\
params: {object: milk}
plans:
  fetch:
    params: [object, target]
    body:
      - detecting: {object-type: $objct}
        as: obj
      - place: {object: $obj, target: $target}
body:
  - movng: {target: [1, 2, 0]}
  - moving: {targt: [1, 2, 0]}
  - moving: {target: [1, 2]}
  - call: fetch
    args: [milk, [0, 0, 0], extra]
  - call: fetch
    args: [milk]
  - call: fetsh
  - log: $later
  - set: {later: 1}
  - fail: PerceptionErr
  - retry: 2
    on: [NavigationFailur]
    body: [{log: x}]
  - try: [{log: x}]
    catch: {Nope: [{log: y}]}
  - log: hi
    as: foo
  - pick-up: {object: milk}
    colour: red
  - stable: {objekt: milk}
  - if: {stabel: {object: milk}}
    then: [{log: x}]
  - call: fetch
    args: {object: milk, targte: [0, 0, 0]}
"""

EXPECTED = [
    (6, 34, "undefined variable $objct"),
    (10, 5, "unknown node type 'movng'"),
    (11, 5, "'moving' needs slot 'target'"),
    (11, 21, "'moving' has no slot 'targt'"),
    (12, 22, "slot 'target': expected a position [x, y, z]"),
    (14, 11, "too many arguments: fetch(object, target) takes 2, got 3"),
    (16, 11, "missing argument target: fetch(object, target) needs 2, got 1"),
    (17, 5, "undefined subplan 'fetsh'"),
    (18, 10, "variable $later is used before it is bound (at line 19)"),
    (20, 11, "unknown failure type 'PerceptionErr'"),
    (22, 10, "unknown failure type 'NavigationFailur'"),
    (25, 13, "unknown failure type 'Nope'"),
    (27, 5, "'log' does not produce a value to bind with 'as'"),
    (29, 5, "unknown key 'colour' in a 'pick-up' step"),
    (30, 14, "query 'stable' has no parameter 'objekt'"),
    (31, 10, "unknown query 'stabel' in a condition"),
    (34, 26, "fetch(object, target) has no parameter 'targte'"),
    (34, 11, "missing argument target: fetch(object, target) needs 2, got 1"),
]


def problems(path):
    with pytest.raises((InputError, InputErrors)) as err:
        load_plan(path)
    return as_list(err.value)


def test_all_problems_are_reported_together_with_line_and_column(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text(BROKEN)
    found = problems(path)
    got = [(p.location.line, p.location.column, p.message) for p in found]
    for line, column, message in EXPECTED:
        assert any(g[0] == line and g[1] == column and message in g[2] for g in got), \
            f"missing {line}:{column} {message!r}; got:\n" + "\n".join(map(str, got))
    assert all(p.location.file == str(path) for p in found)
    # one problem per mistake: the missing 'target' of the second fetch call is the only one there
    assert len([g for g in got if g[0] == 16]) == 1


def test_suggestions_name_the_closest_valid_name(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text(BROKEN)
    hints = {p.message: p.suggestion for p in problems(path)}
    assert hints["unknown node type 'movng'"] == "did you mean 'moving'?"
    assert hints["undefined subplan 'fetsh'"] == "did you mean 'fetch'?"
    assert hints["undefined variable $objct"] == "did you mean '$object'?"
    assert hints["unknown failure type 'PerceptionErr'"] == "did you mean 'PerceptionError'?"


@pytest.mark.parametrize("text, message", [
    ("body: [{log: a, seq: [{log: b}]}]", "a step has exactly one node type, found 'log' and 'seq'"),
    ("body: [log]", "a step must be a mapping with one node type"),
    ("body: []", "expected at least one step"),
    ("bodyy: []", "unknown key 'bodyy' in the plan"),
    ("body: [{par: {log: a}}]", None),
    ("body: [{retry: -1, body: [{log: a}]}]", "expected how many times to retry"),
    ("body: [{for_each: 3, as: x, do: [{log: a}]}]", "expected a list or a $variable"),
    ("body: [{for_each: [1], as: $x, do: [{log: a}]}]", "write a variable name without '$' here"),
    ("body: [{wait: soon}]", "expected a number of seconds"),
    ("body: [{if: maybe, then: [{log: a}]}]", "expected a condition"),
    ("body: [{if: true}]", "an 'if' step needs 'then'"),
    ("plans: {par: [{log: a}]}\nbody: [{log: a}]", "a subplan cannot be named 'par'"),
    ("params: {a: $b}\nbody: [{log: a}]", "the default of parameter 'a' cannot use variables"),
    ("world: nowhere\nbody: [{log: a}]", "world file not found: 'nowhere'"),
])
def test_single_mistakes(tmp_path, text, message):
    path = tmp_path / "p.yaml"
    path.write_text(text + "\n")
    if message is None:
        load_plan(path)  # a single step where a list is expected is a list of one
        return
    found = problems(path)
    assert any(message in p.message for p in found), [str(p) for p in found]
    assert all(p.location.line is not None for p in found)


def test_a_step_that_does_not_parse_does_not_cascade_into_undefined_variables(tmp_path):
    path = tmp_path / "p.yaml"
    path.write_text("body:\n  - detectng: {object-type: milk}\n    as: obj\n  - log: $obj\n")
    found = problems(path)
    assert [p.message for p in found] == ["unknown node type 'detectng'"]


def test_scopes_are_per_subplan_with_global_parameters(tmp_path):
    path = tmp_path / "p.yaml"
    path.write_text(
        "params: {who: milk}\n"
        "plans:\n"
        "  sub:\n"
        "    params: [x]\n"
        "    body: [{log: '$who $x'}, {log: $y}]\n"
        "body:\n"
        "  - set: {y: 1}\n"
        "  - log: $x\n"
        "  - try: [{log: a}]\n"
        "    catch: {Failure: [{log: $failure.message}]}\n")
    found = problems(path)
    assert sorted((p.location.line, p.message) for p in found) == [
        (5, "undefined variable $y"), (8, "undefined variable $x")]


def test_with_a_world_object_names_are_checked_too(tmp_path):
    path = tmp_path / "p.yaml"
    path.write_text("body:\n  - pick-up: {object: mlik}\n  - stable: {object: bowll}\n"
                    "  - detecting: {object-type: anything}\n")
    world = load_world()
    try:
        with pytest.raises(InputErrors) as err:
            load_plan(path, world=world)
    finally:
        world.exit()
    found = [(p.location.line, p.message, p.suggestion) for p in err.value.errors]
    assert found == [(2, "'object': the world has no object 'mlik'", "did you mean 'milk'?"),
                     (3, "'object': the world has no object 'bowll'", "did you mean 'bowl'?")]


def test_designators_need_a_robot_in_the_world(tmp_path):
    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    world = tmp_path / "w.yaml"
    world.write_text("objects:\n  - {name: floor, type: environment, file: environments/floor/floor.urdf}\n")
    plan = tmp_path / "p.yaml"
    plan.write_text("world: w.yaml\nbody:\n  - log: hello\n  - moving: {target: [0.65, 0.7, 0]}\n  - moving: {target: [0, 0, 0]}\n")
    result = CliRunner().invoke(cli, ["run", str(plan)])
    assert result.exit_code == 2
    assert result.output.count("the world has no robot to perform 'moving'") == 1
    assert f"{plan}:4:13: moving:" in result.output


def test_a_query_problem_points_at_the_argument_it_names(tmp_path):
    """Query problems carry their parameter: a bad value is shown at the value, an unknown name at the key, a missing
    one at the arguments, in a step and in a condition alike."""
    path = tmp_path / "p.yaml"
    path.write_text("body:\n"
                    "  - visible: {object: milk, threshold: 2}\n"
                    "  - assert: {contact: {a: milk, bb: bowl}}\n")
    got = {p.message: (p.location.line, p.location.column, p.suggestion) for p in problems(path)}
    assert got["query 'visible', parameter 'threshold': expected a fraction between 0 and 1, got 2"] == (2, 40, None)
    assert got["query 'contact' has no parameter 'bb'"] == (3, 33, "did you mean 'b'?")
    assert got["query 'contact' needs parameter 'b' (an object name)"][:2] == (3, 23)
