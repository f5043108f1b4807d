"""QUERIES, run_query and check_query_args: the queries by name, for plans and the CLI."""
from __future__ import annotations

import json

import pytest
from scenes import COUNTER_POSE

from pycram_cli.errors import InputError
from pycram_cli.reasoning import QUERIES, QueryAnswer, QuerySpec, check_query_args, run_query
from pycram_cli.signature import Param, Problem

PARAMETERS = {
    "stable": ["object"],
    "contact": ["a", "b"],
    "visible": ["object", "from", "threshold"],
    "occluding": ["object", "from"],
    "reachable": ["target", "arm", "grasp", "threshold"],
    "blocking": ["target", "arm", "grasp", "exclude-type", "threshold"],
    "supporting": ["a", "b", "link"],
}


def test_every_query_is_registered_with_the_parameter_names_plans_use():
    assert {name: spec.param_names for name, spec in QUERIES.items()} == PARAMETERS
    for spec in QUERIES.values():
        assert isinstance(spec, QuerySpec) and spec.doc
        assert all(isinstance(param, Param) and param.doc for param in spec.params)


@pytest.mark.parametrize("name, args, result", [
    ("stable", {"object": "milk"}, True),
    ("contact", {"a": "kitchen", "b": "milk"}, True),
    ("visible", {"object": "bottle"}, True),
    ("occluding", {"object": "spoon"}, ["bowl", "kitchen"]),
    ("supporting", {"a": "kitchen", "b": "milk"}, True),
    ("reachable", {"target": "milk"}, False),
    ("reachable", {"target": [1.3, 0.6, 1.0], "arm": "left"}, False),
    ("blocking", {"target": "milk", "arm": "left", "exclude-type": ["environment"]}, []),
])
def test_every_query_answers_with_json_friendly_args_result_and_details(scene, name, args, result):
    answer = run_query(scene, name, args)
    assert isinstance(answer, QueryAnswer) and answer.query == name
    assert answer.result == result
    assert bool(answer) == bool(result)
    json.dumps(answer.to_json(), allow_nan=False)
    assert set(answer.to_json()) == {"query", "args", "result", "details"}


def test_object_names_and_objects_are_both_accepted(scene):
    milk = scene.get_object_by_name("milk")
    by_object = run_query(scene, "contact", {"a": scene.get_object_by_name("kitchen"), "b": milk})
    assert by_object.args == {"a": "kitchen", "b": "milk"}
    assert by_object.result is True


def test_list_answers_carry_the_objects_as_value(scene):
    answer = run_query(scene, "occluding", {"object": "spoon"})
    assert answer.value == [scene.get_object_by_name("bowl"), scene.get_object_by_name("kitchen")]


def test_reachable_tries_the_left_arm_then_the_right(scene):
    scene.robot.set_position_and_orientation(*COUNTER_POSE)
    answer = run_query(scene, "reachable", {"target": "milk"})
    assert answer.result is True and answer.args["arm"] == "left"
    assert answer.details["arm"] == "left" and answer.details["gripper_link"] == "l_gripper_tool_frame"
    assert set(answer.details["joint_positions"]) == {j for j in answer.details["joint_positions"] if j.startswith("l_")}
    right_only = run_query(scene, "reachable", {"target": "milk", "arm": "right", "grasp": "front"})
    assert right_only.result is True and right_only.details["arm"] == "right"
    assert right_only.details["orientation_error"] < 0.1


def test_an_unreachable_target_reports_the_closest_arm(scene):
    answer = run_query(scene, "reachable", {"target": "1.3,0.6,1.0"})
    assert answer.result is False
    assert set(answer.details["arms_tried"]) == {"left", "right"}
    assert answer.details["position_error"] == min(answer.details["arms_tried"].values())


def test_visible_takes_a_camera_and_a_threshold(scene):
    answer = run_query(scene, "visible", {"object": "bottle", "from": [1.35, 0.4, 1.8], "threshold": 0.5})
    assert answer.args == {"object": "bottle", "from": [1.35, 0.4, 1.8], "threshold": 0.5}
    assert answer.details["fraction"] == 1.0
    by_link = run_query(scene, "visible", {"object": "bottle", "from": "head_tilt_link"})
    assert by_link.args["from"] == "head_tilt_link"


def test_blocking_can_leave_out_several_types(scene):
    scene.robot.set_position_and_orientation(*COUNTER_POSE)
    everything = run_query(scene, "blocking", {"target": "milk", "arm": "right", "grasp": "front"})
    assert "kitchen" in everything.result
    assert run_query(scene, "blocking", {"target": "milk", "arm": "right", "grasp": "front",
                                         "exclude-type": "environment"}).result == []


@pytest.mark.parametrize("name, args, message", [
    ("visible", {"object": "botle"}, "no object 'botle' (did you mean 'bottle'?)"),
    ("visble", {"object": "bottle"}, "unknown query 'visble' (did you mean 'visible'?)"),
    ("contact", {"a": "kitchen"}, "missing parameter 'b'"),
    ("contact", {"a": "kitchen", "b": "milk", "c": "x"}, "no parameter 'c'"),
    ("reachable", {"target": "milk", "arm": "middle"}, "robot 'pr2' has no arm 'middle' (arms: left, right)"),
    ("reachable", {"target": "milk", "grasp": "side"}, "unknown grasp 'side' (grasps: front, top, left, right"),
    ("reachable", {"target": "milk", "threshold": -1}, "expected a positive distance"),
    ("visible", {"object": "milk", "from": "head_tilt_lnk"}, "did you mean 'head_tilt_link'?"),
    ("visible", {"object": "milk", "threshold": 2}, "expected a fraction between 0 and 1"),
    ("contact", {"a": "milk", "b": "milk"}, "two different objects"),
])
def test_bad_input_is_an_input_error_with_a_suggestion(scene, name, args, message):
    with pytest.raises(InputError) as caught:
        run_query(scene, name, args)
    assert message in str(caught.value)


def texts(problems: list[Problem]) -> list[str]:
    return [str(problem) for problem in problems]


def test_static_checks_need_no_world():
    assert check_query_args("visible", {"object": "bottle"}) == []
    assert check_query_args("blocking", {"target": [1, 2, 3], "exclude-type": ["environment"], "arm": "left"}) == []
    assert texts(check_query_args("visble", {})) == ["unknown query 'visble' (did you mean 'visible'?)"]
    assert check_query_args("visible", {"object": "bottle", "frm": "x"}) == [
        Problem("query 'visible' has no parameter 'frm'", "frm", "did you mean 'from'?")]
    problems = check_query_args("contact", {"a": "kitchen"})
    assert len(problems) == 1 and "needs parameter 'b'" in problems[0].message and problems[0].param == "b"
    problems = check_query_args("reachable", {"target": [1, 2], "grasp": 5, "threshold": "near"})
    assert [problem.param for problem in problems] == ["target", "grasp", "threshold"]


def test_static_checks_skip_plan_references():
    is_reference = lambda value: isinstance(value, str) and value.startswith("$")  # noqa: E731
    assert check_query_args("reachable", {"target": "$obj", "threshold": "$t"}, is_reference) == []
    assert texts(check_query_args("reachable", {"target": "$obj", "threshold": "$t"})) == [
        "query 'reachable', parameter 'threshold': expected a positive distance in metres, got '$t'"]
