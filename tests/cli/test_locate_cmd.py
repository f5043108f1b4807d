"""`pycram locate GOAL TARGET`: location designators from the command line, with a picture of the floor map."""
from __future__ import annotations

import json
import struct

from click.testing import CliRunner

from pycram_cli.cli.main import cli


def locate(*args: str):
    return CliRunner().invoke(cli, ["locate", *args])


def png_size(path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def test_reachable_for_lists_the_poses_found_and_what_was_ruled_out():
    result = locate("reachable-for", "milk", "-n", "2")
    assert result.exit_code == 0, result.output
    assert "reachable-for milk: 2 found" in result.stdout
    assert "candidates: " in result.stdout and "out of reach" in result.stdout and "collide" in result.stdout


def test_json_gives_poses_scores_and_the_reasons(tmp_path):
    plot = tmp_path / "map.png"
    result = locate("reachable-for", "milk", "--visible-for", "milk", "--arm", "left", "--json", "--plot", str(plot))
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["status"] == "found" and data["location"] == {"reachable-for": "milk", "visible-for": "milk", "arm": "left"}
    first = data["found"][0]
    assert first["arm"] == "left" and len(first["position"]) == 3 and "score" in first and "look-at" in first
    assert data["candidates"] > 1000 and data["ruled_out"]["out of reach"] > 0
    width, height = png_size(plot)
    assert width > 200 and height > 200


def test_a_spot_on_a_surface(tmp_path):
    plot = tmp_path / "spots.png"
    result = locate("on", "kitchen_island_surface", "--for", "milk", "--near", "-1,2,0.9", "--json", "--plot", str(plot))
    assert result.exit_code == 0, result.output
    spot = json.loads(result.stdout)["found"][0]
    assert spot["surface"] == "kitchen_island_surface" and abs(spot["position"][2] - 0.862) < 1e-6
    assert png_size(plot)[0] > 100


def test_the_fetch_kitchen_and_accessing():
    result = locate("accessing", "sink_area_left_upper_drawer_handle", "--world", "kitchen_fetch", "--json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["found"][0]["arm"] == "arm"


def test_an_unsatisfiable_location_exits_1_saying_why():
    result = locate("reachable-for", "1.3,0.6,2.5")
    assert result.exit_code == 1
    assert "no pose for reachable-for (1.3, 0.6, 2.5): " in result.output and "out of reach" in result.output
    data = json.loads(locate("reachable-for", "1.3,0.6,2.5", "--json").stdout)
    assert data["status"] == "failed" and data["found"] == [] and data["failure"].startswith("no pose for")


def test_unknown_objects_and_surfaces_are_input_errors():
    result = locate("reachable-for", "mlik")
    assert result.exit_code == 2 and "no object 'mlik' (did you mean 'milk'?)" in result.output
    result = locate("on", "kitchen_island_surfac", "--for", "milk")
    assert result.exit_code == 2 and "did you mean 'kitchen_island_surface'?" in result.output
    result = locate("on", "kitchen_island_surface")
    assert result.exit_code == 2 and "which object should fit on kitchen_island_surface?" in result.output
    result = locate("reachable-for", "milk", "--arm", "middle", "--json")
    assert result.exit_code == 2 and json.loads(result.stdout)["status"] == "error"
    assert locate("behind", "milk").exit_code == 2


def test_a_position_target_is_read_in_the_forms_a_user_writes():
    for words in (["1.3,0.6,1.0"], ["[1.3, 0.6, 1.0]"], ["1.3,", "0.6,", "1.0"], ["1.3", "0.6", "1.0"]):
        result = locate("reachable-for", *words, "-n", "1", "--json")
        assert json.loads(result.stdout)["location"]["reachable-for"] == [1.3, 0.6, 1.0], words


def test_a_target_that_cannot_be_read_shows_how_a_position_is_written():
    for words in (["1.3", "0.6"], ["1.3,0.6"], ["milk", "bowl"]):
        result = locate("reachable-for", *words)
        assert result.exit_code == 2, words
        assert "expected one TARGET (an object, a link or a position)" in result.stderr
        assert "a position is written 1.3,0.6,1.0 or [1.3,0.6,1.0]" in result.stderr
