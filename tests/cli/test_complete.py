"""Shell completion completes plan, world, query, designator, object and link names (nothing is simulated)."""
from __future__ import annotations

from pathlib import Path

import pytest
from click.shell_completion import ShellComplete

from pycram_cli.cli.main import cli
from pycram_cli.paths import plans_dir
from pycram_cli.reasoning import QUERIES

KITCHEN_OBJECTS = ["floor", "pr2", "kitchen", "milk", "cereal", "bowl", "spoon", "bottle"]


def complete(line: str) -> list[str]:
    """What the shell is offered for the last word of `line` (an empty last word when it ends in a space)."""
    words = line.split(" ")
    return [item.value for item in ShellComplete(cli, {}, "pycram", "_PYCRAM_COMPLETE").get_completions(
        words[:-1], words[-1])]


def kinds(line: str) -> list[str]:
    words = line.split(" ")
    return [item.type for item in ShellComplete(cli, {}, "pycram", "_PYCRAM_COMPLETE").get_completions(
        words[:-1], words[-1])]


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder with a plan and a world of its own."""
    (tmp_path / "plans").mkdir()
    (tmp_path / "plans" / "fetch_mine.yaml").write_text("description: mine\nbody: [{log: hi}]\n")
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "tiny.yaml").write_text(
        "objects:\n  - {name: floor, type: environment, file: plane.urdf}\n"
        "  - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}\n")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_plan_names_local_first_then_bundled(folder: Path):
    bundled = sorted(p.stem for p in plans_dir().glob("*.yaml") if not p.name.endswith(".vary.yaml"))
    assert complete("run ") == ["fetch_mine", *bundled]
    assert complete("run fetch_") == ["fetch_mine", "fetch_milk", "fetch_spoon"]
    assert complete("sweep set_table_") == ["set_table_actions"]


def test_world_names_for_every_world_option_and_argument(folder: Path):
    assert complete("run set_table --world ") == ["tiny", "kitchen", "kitchen_fetch"]
    assert complete("query visible milk --world kitchen_") == ["kitchen_fetch"]
    assert complete("world show t") == ["tiny"]
    assert complete("new plan x --world k") == ["kitchen", "kitchen_fetch"]
    assert complete("validate t") == ["tiny"]  # validate takes plans and worlds
    assert complete("validate fetch_m") == ["fetch_mine", "fetch_milk"]


def test_what_looks_like_a_path_completes_as_a_file(folder: Path):
    assert kinds("run plans/") == ["file"] and kinds("run ./p") == ["file"]
    assert kinds("run nothing_like_it") == ["file"]


def test_query_and_designator_names():
    assert complete("query ") == list(QUERIES)
    assert complete("query st") == ["stable"]
    assert complete("designators pick") == ["pick-up"]


def test_object_names_of_the_default_or_the_chosen_world(folder: Path):
    assert complete("query visible ") == KITCHEN_OBJECTS
    assert complete("query contact kitchen b") == ["bowl", "bottle"]
    assert complete("query visible --world tiny ") == ["floor", "box"]
    assert complete("locate reachable-for ") == KITCHEN_OBJECTS
    assert complete("locate on kitchen_island_surface --for m") == ["milk"]


def test_link_names_for_locations_on_surfaces_and_handles():
    handles = complete("locate accessing sink_area_left_")
    assert handles[0] == "sink_area_left_upper_drawer_handle" and all("handle" in h for h in handles[:3])
    assert "kitchen_island_surface" in complete("locate on kitchen_island")


def test_the_objects_of_a_world_that_extends_another_are_its_and_its_bases(folder: Path):
    (folder / "worlds" / "mine.yaml").write_text(
        "extends: kitchen\nobjects:\n  - {name: mug, type: mug, file: objects/mug.urdf}\n")
    assert complete("query stable --world mine ") == [*KITCHEN_OBJECTS, "mug"]
