"""`pycram validate` checks what `run` checks, for files and for names of plans and worlds."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli

REPO = Path(__file__).resolve().parents[2]


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def test_bundled_plans_and_worlds_are_validated_by_name():
    result = run("validate", "set_table", "kitchen")
    assert result.exit_code == 0, result.output
    assert "set_table.yaml: valid plan file" in result.stdout and "kitchen.yaml: valid world file" in result.stdout


def test_a_plan_is_checked_against_its_world_as_run_would(tmp_path: Path):
    plan = tmp_path / "typo.yaml"
    plan.write_text("body:\n  - pick-up: {object: botle}\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2
    assert f"{plan}:2:" in result.stderr and "the world has no object 'botle' (did you mean 'bottle'?)" in result.stderr


def test_a_name_means_the_working_folders_own_plan_before_the_bundled_one(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    (tmp_path / "plans").mkdir()
    local = tmp_path / "plans" / "set_table.yaml"
    shutil.copy(REPO / "plans" / "set_table.yaml", local)
    local.write_text(local.read_text().replace("\nbody:\n", "\nbody:\n  - log: edited here\n", 1))
    monkeypatch.chdir(tmp_path)
    result = run("run", "set_table", "--json")
    assert result.exit_code == 0, result.output
    assert "edited here" in result.stdout
    plain = run("run", "set_table")
    assert str(Path("plans") / "set_table.yaml") in plain.stderr  # says which file it ran


def test_parameter_values_given_with_p_are_checked_as_run_would_check_them():
    result = run("validate", "fetch_spoon", "-p", "target=[1, 2]")
    assert result.exit_code == 2
    assert "-p: target: parameter 'target' is a position: expected a position [x, y, z], got a list of 2" in result.stderr
    unknown = run("validate", "fetch_spoon", "-p", "targte=[1, 2, 0.9]")
    assert unknown.exit_code == 2 and "has no parameter 'targte' (did you mean 'target'?)" in unknown.stderr
    fine = run("validate", "fetch_spoon", "-p", "target=[-0.8, 1.2, 0.862]")
    assert fine.exit_code == 0, fine.output
    assert "fetch_spoon.yaml: valid plan file" in fine.stdout


def test_a_parameter_value_naming_no_object_of_the_world_is_found_where_the_plan_uses_it(tmp_path: Path):
    plan = tmp_path / "pick.yaml"
    plan.write_text("params: {thing: {type: object, default: milk}}\nbody:\n  - pick-up: {object: $thing}\n")
    assert run("validate", str(plan)).exit_code == 0
    result = run("validate", str(plan), "-p", "thing=botle")
    assert result.exit_code == 2
    assert f"{plan}:3:" in result.stderr and "the world has no object 'botle' ($thing)" in result.stderr


def test_p_without_a_plan_to_set_it_for_is_an_input_error():
    result = run("validate", "kitchen", "-p", "target=[1, 2, 3]")
    assert result.exit_code == 2 and "-p: sets a plan parameter, but no plan or variation file is given" in result.stderr


def test_a_plans_world_of_the_same_name_is_the_world_not_the_plan(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    (tmp_path / "plans").mkdir()
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "mine.yaml").write_text("extends: kitchen\n")
    (tmp_path / "plans" / "mine.yaml").write_text("world: mine\nbody:\n  - stable: {object: milk}\n")
    monkeypatch.chdir(tmp_path)
    result = run("validate", "plans/mine.yaml")
    assert result.exit_code == 0, result.output
    assert run("run", "mine").exit_code == 0
