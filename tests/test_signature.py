"""One signature shape: parameters checked, problems naming their parameter, defaults bound, registries by name."""
from __future__ import annotations

from dataclasses import dataclass

import pytest

from pycram_cli.designators import DESIGNATORS
from pycram_cli.designators.actions import ACTIONS
from pycram_cli.kinds import Robots
from pycram_cli.reasoning import QUERIES
from pycram_cli.robots import bundled_descriptions
from pycram_cli.signature import Param, Problem, Registry, Signature

WAVE = Signature((Param("arm", "arm", True, "the arm that waves"),
                  Param("times", "number", doc="how often", default=3),
                  Param("types", "types", doc="what to wave at", default=[])))


@dataclass(frozen=True)
class Thing:
    name: str
    signature: Signature = WAVE


def test_check_names_the_parameter_of_each_problem():
    problems = WAVE.check({"times": "often", "tims": 2}, what="'waving'")
    assert problems == [Problem("slot 'times': expected a number", "times"),
                        Problem("'waving' has no slot 'tims'", "tims", "did you mean 'times'?"),
                        Problem("'waving' needs slot 'arm' (the arm that waves)", "arm")]


def test_check_asks_the_robot_when_it_is_known():
    pr2 = next(d for d in bundled_descriptions() if d.name == "pr2")
    assert WAVE.check({"arm": "middle"}, Robots((pr2,), True), "'waving'")[0].param == "arm"
    assert WAVE.check({"arm": "left"}, Robots((pr2,), True), "'waving'") == []


def test_skipped_values_are_not_checked_but_still_known():
    later = lambda param, value: value == "$arm"  # noqa: E731  (a plan variable)
    assert WAVE.check({"arm": "$arm"}, skip=later) == []


def test_one_of_and_the_check_across_parameters():
    either = Signature((Param("a", "number"), Param("b", "number")), one_of=("a", "b"),
                       across=lambda values, robots: [Problem("a must stay below b", "a")]
                       if values.get("a", 0) > values.get("b", 1) else [])
    assert [str(p) for p in either.check({}, what="'pair'")] == ["'pair' needs one of the slots a, b"]
    assert either.check({"a": 2, "b": 1}) == [Problem("a must stay below b", "a")]


def test_a_query_signature_names_the_query_and_the_value():
    query = Signature((Param("threshold", "distance"),), noun="parameter", names_value=True)
    assert [str(p) for p in query.check({"threshold": "near", "thresold": 1}, what="query 'reachable'")] == [
        "query 'reachable', parameter 'threshold': expected a positive distance in metres, got 'near'",
        "query 'reachable' has no parameter 'thresold' (did you mean 'threshold'?)"]


def test_bind_fills_the_declared_defaults_where_none_is_given():
    assert WAVE.bind({"arm": "left"}) == {"arm": "left", "times": 3, "types": []}
    assert WAVE.bind({"arm": "left", "times": None}) == {"arm": "left", "times": 3, "types": []}
    assert WAVE.bind({"arm": "left", "times": 1}) == {"arm": "left", "times": 1, "types": []}
    first = WAVE.bind({"arm": "left"})
    first["types"].append("milk")
    assert WAVE.bind({"arm": "left"})["types"] == []  # a default is never shared between calls


def test_a_default_reads_as_its_doc_else_its_value():
    assert Param("x", "number", default=0.3).default_text == "0.3"
    assert Param("x", "number", default=0.3, default_doc="0.3, or less").default_text == "0.3, or less"
    assert Param("x", "types", default=[]).default_text == ""


def test_a_registry_refuses_a_name_twice_and_an_unknown_kind():
    registry: Registry[Thing] = Registry("gesture", "gestures")
    registry.declare(Thing("wave"))
    with pytest.raises(ValueError, match="gesture 'wave' is declared twice"):
        registry.declare(Thing("wave"))
    with pytest.raises(ValueError, match="slot 'x': unknown kind 'colour'"):
        registry.declare(Thing("paint", Signature((Param("x", "colour"),))))
    assert list(registry) == ["wave"]


def test_a_registry_suggests_the_closest_name():
    registry: Registry[Thing] = Registry("gesture", "gestures")
    registry.declare(Thing("wave"))
    registry.declare(Thing("nod"))
    assert registry.unknown("wav") == Problem("unknown gesture 'wav'", None, "did you mean 'wave'?")
    assert registry.unknown("bow") == Problem("unknown gesture 'bow'", None, "gestures: wave, nod")


def test_designators_actions_and_queries_each_have_one_registry_of_signatures():
    for registry in (DESIGNATORS, ACTIONS, QUERIES):
        assert isinstance(registry, Registry) and len(registry) > 5
        assert all(isinstance(spec.signature, Signature) and spec.signature.kind_problems() == []
                   for spec in registry.values())


def test_the_drawer_distance_is_declared_once_and_bound_for_its_resolvers():
    motion = DESIGNATORS["accessing"].signature
    action = ACTIONS["open"].signature
    assert motion.param("distance").default == action.param("distance").default == 0.3
    assert motion.bind({})["distance"] == 0.3 and action.bind({"distance": 0.48})["distance"] == 0.48
