"""Values known before the run are checked against the world wherever they flow: a parameter's value (its default,
`-p`, a sweep's draw), a `for_each` item or a literal, in an action's slots, inside its location, in an
`object-type`, and as a subplan's argument. A misspelling is an input error at the line that uses it, with a
suggestion, as in a literal slot."""
from __future__ import annotations

from pathlib import Path

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.scenario import prepare

ACTIONS = """\
world: kitchen
params:
  object: {type: object, default: milk}
body:
  - action: navigate
    target: {reachable-for: $object, visible-for: $object}
  - action: detect
    object: $object
"""


def problems(tmp_path: Path, text: str, **params: object) -> list[tuple[int, str, str | None]]:
    path = tmp_path / "plan.yaml"
    path.write_text(text)
    with pytest.raises((InputError, InputErrors)) as err:
        prepare(path, params=params)
    return [(p.location.line, p.message, p.suggestion) for p in as_list(err.value)]


def test_a_misspelt_parameter_value_is_found_in_an_actions_slots_and_its_location(tmp_path: Path):
    assert problems(tmp_path, ACTIONS, object="milkk") == [
        (6, "'reachable-for': the world has no object 'milkk' ($object)", "did you mean 'milk'?"),
        (6, "'visible-for': the world has no object 'milkk' ($object)", "did you mean 'milk'?"),
        (8, "'object': the world has no object 'milkk' ($object)", "did you mean 'milk'?"),
    ]


def test_a_parameter_value_the_world_has_passes(tmp_path: Path):
    path = tmp_path / "plan.yaml"
    path.write_text(ACTIONS)
    assert prepare(path, params={"object": "bowl"}).params == {"object": "bowl"}


def test_a_misspelt_default_of_an_object_parameter_is_found_at_the_default(tmp_path: Path):
    found = problems(tmp_path, "world: kitchen\nparams:\n  object: {type: object, default: bowll}\nbody:\n"
                               "  - log: $object\n")
    assert found == [(3, "the default of parameter 'object' is an object: the world has no object 'bowll'",
                      "did you mean 'bowl'?")]


def test_an_object_type_close_to_one_of_the_worlds_is_a_misspelling(tmp_path: Path):
    found = problems(tmp_path, "world: kitchen\nparams: {kind: milk}\nbody:\n"
                               "  - action: transport\n    object-type: mlik\n    target: {on: kitchen_island_surface}\n"
                               "  - detecting: {object-type: $kind}\n", kind="bwol")
    assert found == [(5, "'object-type': the world has no object of type 'mlik'", "did you mean 'milk'?"),
                     (7, "'object-type': the world has no object of type 'bwol' ($kind)", "did you mean 'bowl'?")]


def test_an_object_type_far_from_every_type_of_the_world_may_be_looked_for(tmp_path: Path):
    path = tmp_path / "plan.yaml"
    path.write_text("world: kitchen\nbody:\n  - try: [{detecting: {object-type: teapot}}]\n"
                    "    catch: {PerceptionFailure: [{log: no teapot}]}\n")
    assert prepare(path).plan.path == path  # a PerceptionFailure at run time, which the plan catches


def test_a_subplans_argument_from_a_variable_is_checked_against_its_typed_parameter(tmp_path: Path):
    found = problems(tmp_path, """\
world: kitchen
params: {thing: bowl}
plans:
  fetch:
    params: {obj: {type: object}}
    body: [{log: $obj}]
body:
  - call: fetch
    args: [$thing]
  - for_each: [milk, cerael]
    as: o
    do:
      - call: fetch
        args: {obj: $o}
""", thing="bottel")
    assert found == [
        (9, "fetch(obj): parameter 'obj' is an object: the world has no object 'bottel' ($thing)",
         "did you mean 'bottle'?"),
        (14, "fetch(obj): parameter 'obj' is an object: the world has no object 'cerael' ($o)",
         "did you mean 'cereal'?"),
    ]
