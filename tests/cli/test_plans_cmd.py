"""`pycram plans` lists the plans a name can mean: the working folder's plans/ first, then the bundled ones."""
from __future__ import annotations

import io
import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner
from rich.console import Console

from pycram_cli.cli import console
from pycram_cli.cli.main import cli
from pycram_cli.paths import plans_dir


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder whose plans/ has its own fetch_spoon (shadowing the bundled one) and a plan of its own."""
    (tmp_path / "plans").mkdir()
    local = tmp_path / "plans" / "fetch_spoon.yaml"
    shutil.copy(plans_dir() / "fetch_spoon.yaml", local)
    local.write_text(local.read_text().replace("description: Find the spoon", "description: My spoon"))
    (tmp_path / "plans" / "mine.yaml").write_text(
        "description: mine\nparams:\n  where: {type: position, description: somewhere}\n  n: 3\nbody: [{log: $where}]\n")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_json_lists_local_plans_first_then_the_bundled_ones_with_their_parameters(folder: Path):
    result = run("plans", "--json")
    assert result.exit_code == 0, result.output
    entries = json.loads(result.stdout)
    assert [(e["name"], e["source"]) for e in entries[:2]] == [("fetch_spoon", "local"), ("mine", "local")]
    assert entries[0]["path"] == str(Path("plans") / "fetch_spoon.yaml") and entries[0]["description"].startswith("My spoon")
    bundled = {e["name"]: e for e in entries[2:]}
    assert all(e["source"] == "bundled" for e in entries[2:])
    assert bundled["fetch_spoon"]["shadowed"] is True and bundled["set_table"]["shadowed"] is False
    assert bundled["fetch_spoon"]["path"] == str(plans_dir() / "fetch_spoon.yaml")
    assert bundled["fetch_spoon"]["params"] == [{"name": "target", "type": "position", "required": False,
                                                 "default": [-0.8, 1.4, 0.862],
                                                 "description": "where the spoon goes on the island"}]
    assert entries[1]["params"] == [
        {"name": "where", "type": "position", "required": True, "default": None, "description": "somewhere"},
        {"name": "n", "type": None, "required": False, "default": 3, "description": ""}]
    assert "set_table.vary" not in bundled  # variation files are no plans


def test_plain_lines_say_where_each_plan_comes_from_and_its_parameters(folder: Path):
    result = run("plans")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0] == f"fetch_spoon  local  {Path('plans') / 'fetch_spoon.yaml'}"
    assert "  target: position = [-0.8, 1.4, 0.862]  where the spoon goes on the island" in lines
    assert "  where: position (required)  somewhere" in lines and "  n = 3" in lines
    assert f"fetch_spoon  bundled (shadowed by the local one)  {plans_dir() / 'fetch_spoon.yaml'}" in lines
    assert "  world: kitchen_fetch" in lines  # fetch_milk's


def test_on_a_terminal_it_is_a_table(folder: Path, monkeypatch: pytest.MonkeyPatch):
    screen = io.StringIO()
    monkeypatch.setattr(console, "out", Console(file=screen, force_terminal=True, width=200, color_system=None))
    assert run("plans").exit_code == 0
    text = screen.getvalue()
    assert "┃ name" in text and "parameters" in text
    assert "target: position = [-0.8, 1.4, 0.862]" in text  # [x, y, z] is shown, not taken for markup


def test_a_plan_that_cannot_be_read_is_listed_with_its_problem(folder: Path):
    (folder / "plans" / "broken.yaml").write_text("body: [\n")
    result = run("plans")
    assert result.exit_code == 0
    assert "broken  local" in result.stdout and "  not valid: plans/broken.yaml:" in result.stdout
