"""`pycram new plan|world|vary` writes a commented starting file that validates: a plan (that runs on its world),
a world extending another, a plan's variations for sweeps."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.paths import worlds_dir
from pycram_cli.plan import parse_plan


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    (tmp_path / "plans").mkdir()
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_new_plan_is_written_to_plans_and_validates(folder: Path):
    result = run("new", "plan", "fetch_it")
    assert result.exit_code == 0, result.output
    path = folder / "plans" / "fetch_it.yaml"
    text = path.read_text()
    assert text.startswith("# fetch_it: a starting plan") and "pycram validate plans/fetch_it.yaml" in text
    plan = parse_plan(path)
    assert plan.world == "kitchen" and plan.description
    [param] = plan.params
    assert (param.name, param.type, param.default) == ("object", "object", "milk")
    steps = [node.label() for node in plan.body]
    assert steps == ["par", "action look-at", "action detect", "action pick-up", "log"]
    checked = run("validate", "fetch_it")  # a local plan by name
    assert checked.exit_code == 0, checked.output


def test_the_new_plan_runs_and_picks_the_object_up(folder: Path):
    assert run("new", "plan", "fetch_it").exit_code == 0
    result = run("run", "fetch_it", "-p", "object=bowl", "--json")
    assert result.exit_code == 0, result.output
    trace = json.loads(result.stdout)["trace"]
    assert [a["child"] for a in trace["final_state"]["attachments"]] == ["bowl"]


def test_another_world_and_output_file(folder: Path):
    out = folder / "mine.yaml"
    result = run("new", "plan", "mine", "--world", str(worlds_dir() / "kitchen_fetch.yaml"), "-o", str(out))
    assert result.exit_code == 0, result.output
    assert parse_plan(out).world == str(worlds_dir() / "kitchen_fetch.yaml")
    assert run("validate", str(out)).exit_code == 0
    named = run("new", "plan", "fetchy", "--world", "kitchen_fetch")
    assert named.exit_code == 0 and parse_plan(folder / "plans" / "fetchy.yaml").world == "kitchen_fetch"


def test_an_existing_file_is_kept_unless_force_is_given(folder: Path):
    path = folder / "plans" / "fetch_it.yaml"
    path.write_text("mine\n")
    result = run("new", "plan", "fetch_it")
    assert result.exit_code == 2
    assert "plans/fetch_it.yaml: the file exists already (give --force to overwrite it" in result.stderr
    assert path.read_text() == "mine\n"
    assert run("new", "plan", "fetch_it", "--force").exit_code == 0
    assert path.read_text().startswith("# fetch_it")


def test_a_missing_folder_a_bad_name_or_an_unknown_world_is_exit_2(folder: Path):
    missing = run("new", "plan", "x", "-o", str(folder / "nowhere" / "x.yaml"))
    assert missing.exit_code == 2 and "folder" in missing.stderr and "does not exist" in missing.stderr
    assert not (folder / "nowhere").exists()
    bad = run("new", "plan", "../x")
    assert bad.exit_code == 2 and "'../x' is not a plan name" in bad.stderr
    world = run("new", "plan", "x", "--world", "kitchn")
    assert world.exit_code == 2 and "did you mean 'kitchen'?" in world.stderr
    assert not (folder / "plans" / "x.yaml").exists()


def test_without_a_plans_folder_it_makes_one_and_says_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    result = run("new", "plan", "x")
    assert result.exit_code == 0, result.output
    assert "made the folder plans/ (it did not exist)" in result.stderr
    assert (tmp_path / "plans" / "x.yaml").is_file()
    (tmp_path / "worlds").write_text("not a folder\n")
    blocked = run("new", "world", "x")
    assert blocked.exit_code == 2 and "worlds/x.yaml: 'worlds' is not a folder" in blocked.stderr


def test_a_folder_is_not_made_when_the_command_fails(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    assert run("new", "plan", "x", "--world", "kitchn").exit_code == 2
    assert run("new", "world", "x", "--from", "kitchn").exit_code == 2
    assert list(tmp_path.iterdir()) == []


def test_the_new_world_extends_the_one_it_is_made_from_and_validates(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    result = run("new", "world", "my_kitchen", "--from", "kitchen")
    assert result.exit_code == 0, result.output
    path = tmp_path / "worlds" / "my_kitchen.yaml"
    text = path.read_text()
    assert "\nextends: kitchen " in text and "# - name: mug" in text
    checked = run("validate", "my_kitchen")
    assert checked.exit_code == 0, checked.output
    listed = run("worlds", "--json")
    [mine] = [w for w in json.loads(listed.stdout) if w["name"] == "my_kitchen"]
    assert [o["name"] for o in mine["objects"]] == ["floor", "pr2", "kitchen", "milk", "cereal", "bowl", "spoon",
                                                    "bottle"]
    uncommented = text.replace("  # - name: mug", "  - name: mug").replace("  #   ", "    ")
    path.write_text(uncommented)
    assert run("validate", str(path)).exit_code == 0
    assert run("world", "show", "my_kitchen", "--json").exit_code == 0


def test_the_new_world_from_another_file_names_it_relative_to_itself(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    assert run("new", "world", "base", "--from", "kitchen_fetch").exit_code == 0
    result = run("new", "world", "mine", "--from", "worlds/base.yaml")
    assert result.exit_code == 0, result.output
    assert "\nextends: base.yaml " in (tmp_path / "worlds" / "mine.yaml").read_text()
    assert run("validate", "worlds/mine.yaml").exit_code == 0


def test_the_new_variation_file_goes_beside_its_plan_and_validates(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    assert run("new", "plan", "fetch_it").exit_code == 0
    result = run("new", "vary", "fetch_it")
    assert result.exit_code == 0, result.output
    text = (tmp_path / "plans" / "fetch_it.vary.yaml").read_text()
    assert "\nplan: fetch_it " in text and "pycram sweep fetch_it -n 20 " in text and "# params: {object: [milk]}" in text
    checked = run("validate", "plans/fetch_it.vary.yaml")
    assert checked.exit_code == 0, checked.output
    again = run("new", "vary", "fetch_it")
    assert again.exit_code == 2 and "give --force to overwrite it" in again.stderr
    bundled = run("new", "vary", "set_table", "-o", "mine.vary.yaml")
    assert bundled.exit_code == 0, bundled.output
    assert "\nplan: set_table " in (tmp_path / "mine.vary.yaml").read_text()
    assert run("validate", "mine.vary.yaml").exit_code == 0
    missing = run("new", "vary", "fetch_itt")
    assert missing.exit_code == 2 and "did you mean 'fetch_it'?" in missing.stderr
