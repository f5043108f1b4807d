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
