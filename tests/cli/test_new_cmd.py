"""`pycram new plan NAME` writes a commented starting plan that validates (and runs) on its world."""
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


def test_without_a_plans_folder_it_says_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    result = run("new", "plan", "x")
    assert result.exit_code == 2
    assert "plans/x.yaml: cannot write the plan: folder 'plans' does not exist (create it with mkdir plans" in result.stderr
