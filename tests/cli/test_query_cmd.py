"""`pycram query QUERY ARGS`: reasoning questions from the command line, as a user asks them."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli


def query(*args: str):
    return CliRunner().invoke(cli, ["query", *args])


def query_json(*args: str) -> dict:
    result = query(*args, "--json")
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


@pytest.mark.parametrize("args, says", [
    (["visible", "bottle"], "bottle is visible: 100% of its pixels seen from wide_stereo_optical_frame"),
    (["occluding", "spoon"], "spoon is occluded by: bowl, kitchen"),
    (["contact", "kitchen", "milk"], "kitchen and milk are in contact"),
    (["stable", "milk"], "milk is stable"),
    (["supporting", "kitchen", "milk"], "kitchen supports milk (at sink_area_surface)"),
    (["reachable", "milk", "--arm", "right", "--grasp", "front"],
     "milk is NOT reachable from here: pick-up with the right arm finds no grasp (out of reach: the nearest grasp stays"),
    (["reachable", "1.3,0.6,1.0", "--arm", "left"], "(1.3, 0.6, 1) is NOT reachable (best: the left arm"),
    (["blocking", "milk", "--arm", "left", "--exclude-type", "environment"], "nothing blocks the left arm reaching milk"),
])
def test_each_query_answers_in_one_line_with_its_key_figure(args, says):
    result = query(*args)
    assert result.exit_code == 0, result.output
    assert says in result.stdout


def test_json_output_is_one_object_with_query_args_result_and_details():
    data = query_json("visible", "bottle")
    assert data["query"] == "visible"
    assert data["args"] == {"object": "bottle", "from": "wide_stereo_optical_frame", "threshold": 0.8}
    assert data["result"] is True
    assert data["details"]["fraction"] == 1.0


def test_a_position_target_and_options_reach_the_query():
    data = query_json("reachable", "1.3,0.6,1.0", "--arm", "left", "--threshold", "0.5")
    assert data["args"]["target"] == [1.3, 0.6, 1.0]
    assert data["args"]["arm"] == "left" and data["args"]["threshold"] == 0.5
    assert data["result"] is True  # within 50 cm
    assert data["details"]["position_error"] < 0.5


def test_negative_coordinates_are_positions_not_options():
    data = query_json("reachable", "-0.8,1,0.93", "--arm", "left")
    assert data["args"]["target"] == [-0.8, 1.0, 0.93]


def test_from_sets_the_camera_as_a_position_or_a_link():
    assert query_json("visible", "bottle", "--from", "1.35,0.4,1.8")["args"]["from"] == [1.35, 0.4, 1.8]
    assert query_json("occluding", "milk", "--from", "head_tilt_link")["details"]["camera"] == "head_tilt_link"


def test_exclude_type_can_be_repeated():
    data = query_json("blocking", "milk", "--exclude-type", "environment", "--exclude-type", "bowl")
    assert data["args"]["exclude-type"] == ["environment", "bowl"]


def test_a_negative_answer_still_exits_zero():
    result = query("visible", "spoon")
    assert result.exit_code == 0
    assert "spoon is NOT visible: 0%" in result.stdout


@pytest.mark.parametrize("args, message", [
    (["visible", "botle"], "no object 'botle' (did you mean 'bottle'?)"),
    (["visble", "bottle"], "unknown query 'visble' (did you mean 'visible'?)"),
    (["contact", "kitchen"], "missing arguments: expected 2 (a, b), got 1"),
    (["stable", "milk", "bowl"], "too many arguments"),
    (["stable", "milk", "--arm", "left"], "option --arm does not apply to 'stable'"),
    (["reachable", "milk", "--arm", "middle"], "robot 'pr2' has no arm 'middle' (arms: left, right)"),
    (["reachable", "milk", "--grasp", "side"], "unknown grasp 'side'"),
    (["visible", "milk", "--from", "head_tilt_lnk"], "did you mean 'head_tilt_link'?"),
    (["visible", "milk", "--world", "kitchn"], "world file not found"),
])
def test_bad_input_exits_2_with_a_helpful_message(args, message):
    result = query(*args)
    assert result.exit_code == 2, result.output
    assert message in result.stderr
    assert result.stdout == ""


def test_help_lists_every_query():
    result = query("--help")
    assert result.exit_code == 0
    for name in ("stable", "contact", "visible", "occluding", "reachable", "blocking", "supporting"):
        assert name in result.stdout


def test_end_to_end_json_on_stdout_only():
    done = subprocess.run([sys.executable, "-m", "pycram_cli.cli.main", "query", "contact", "kitchen", "milk", "--json"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert data["result"] is True and data["details"]["links"] == [["sink_area_surface", "milk"]]


def test_end_to_end_bad_object_exits_2():
    done = subprocess.run([sys.executable, "-m", "pycram_cli.cli.main", "query", "visible", "botle"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert "no object 'botle' (did you mean 'bottle'?)" in done.stderr


@pytest.mark.parametrize("words", [
    ["[1.3,0.6,1.0]"], ["1.3,0.6,1.0"], ["1.3, 0.6, 1.0"], ["1.3,", "0.6,", "1.0"], ["[1.3,", "0.6,", "1.0]"],
    ["1.3", "0.6", "1.0"], ["(1.3, 0.6, 1.0)"],
])
def test_a_position_is_read_in_every_form_a_user_writes(words):
    assert query_json("reachable", *words, "--arm", "left")["args"]["target"] == [1.3, 0.6, 1.0]


def test_a_position_after_an_option_may_be_three_numbers():
    assert query_json("visible", "bottle", "--from", "1.35", "0.4", "1.8")["args"]["from"] == [1.35, 0.4, 1.8]


@pytest.mark.parametrize("words, message", [
    (["1.3,0.6"], "cannot read '1.3,0.6' as a position (3 numbers) (write a position as 1.3,0.6,1.0 or [1.3,0.6,1.0]"),
    (["1.3", "0.6"], "too many arguments: expected 1 (target), got 2 (usage: pycram query reachable TARGET"),
])
def test_a_position_that_cannot_be_read_shows_the_forms_it_may_take(words, message):
    result = query("reachable", *words)
    assert result.exit_code == 2, result.output
    assert message in result.stderr and "'1.3, 0.6, 1.0'" in result.stderr


def test_at_stands_the_robot_where_it_is_asked_before_answering():
    assert query_json("reachable", "milk")["result"] is False  # 1.3 m from the counter
    placed = query_json("reachable", "milk", "--at", "0.8,0.95,6")  # where `pycram locate reachable-for milk` says
    assert placed["result"] is True
    assert query_json("reachable", "milk", "--at", "0.8", "0.95", "6") == placed
    assert query_json("blocking", "milk", "--at", "0.8,0.95,6", "--exclude-type", "environment")["result"] == []
    seen = query_json("visible", "spoon", "--at", "0.8,0.95")
    assert seen["result"] is False  # the spoon is in the drawer wherever it stands


def test_at_that_cannot_be_read_or_does_not_apply_is_exit_2():
    bad = query("reachable", "milk", "--at", "0.8")
    assert bad.exit_code == 2 and "cannot read '0.8' as a base pose (give X,Y or X,Y,YAW (metres, yaw in degrees" in bad.stderr
    other = query("stable", "milk", "--at", "1,1")
    assert other.exit_code == 2 and "option --at does not apply to 'stable'" in other.stderr


def test_at_inside_something_says_so():
    result = query("reachable", "milk", "--at", "1.3,1.0")
    assert result.exit_code == 0 and "warning: --at 1.3,1: pr2 stands inside" in result.stderr


def test_at_is_in_the_help():
    assert "--at X,Y[,YAW]" in query("--help").stdout and "YAW degrees" in query("--help").stdout


def test_stable_says_an_object_that_never_comes_to_rest_rocks_in_words_and_in_json(tmp_path):
    """A half cylinder on its round side, tilted 5° on the island (bench/stable_tolerance.py's rocker)."""
    import importlib.util
    import math
    from pathlib import Path

    bench = Path(__file__).resolve().parents[2] / "bench" / "stable_tolerance.py"
    spec = importlib.util.spec_from_file_location("stable_tolerance", bench)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    mesh = module.rocker_mesh(tmp_path)
    tilt = math.radians(5.0)
    z = 0.861 + 0.05 * (1 - math.cos(tilt)) + 0.001  # its lowest point 1 mm above the island, as worlds stand things
    world = tmp_path / "rocking.yaml"
    world.write_text("extends: kitchen\nobjects:\n"
                     f"  - {{name: rocker, type: rocker, file: {mesh}, position: [-1.1, 1.0, {z:.6f}], "
                     f"orientation: [{math.sin(tilt / 2):.7f}, 0, 0, {math.cos(tilt / 2):.7f}]}}\n")
    said = query("stable", "rocker", "--world", str(world))
    assert said.exit_code == 0 and "rocker is NOT stable: it is not at rest, it rocks back and forth by" in said.stdout
    details = query_json("stable", "rocker", "--world", str(world))["details"]
    assert details["motion"] == "rocks" and math.radians(5) < details["amplitude"]["rotation"] < math.radians(15)
