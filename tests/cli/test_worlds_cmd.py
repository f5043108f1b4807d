"""`pycram worlds` lists the worlds a name can mean: the working folder's worlds/ first, then the bundled ones."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.paths import worlds_dir


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder whose worlds/ has its own kitchen: the bundled kitchen without the bottle."""
    (tmp_path / "worlds").mkdir()
    lines = (worlds_dir() / "kitchen.yaml").read_text().splitlines(keepends=True)
    index = next(i for i, line in enumerate(lines) if line.startswith("  - name: bottle"))
    end = next((i for i in range(index + 1, len(lines)) if lines[i].startswith("  - ")), len(lines))
    (tmp_path / "worlds" / "kitchen.yaml").write_text("".join(lines[:index] + lines[end:]).replace(
        "description: PR2 in the IAI kitchen", "description: My kitchen"))
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_json_lists_local_worlds_first_then_the_bundled_ones_with_robot_and_objects(folder: Path):
    result = run("worlds", "--json")
    assert result.exit_code == 0, result.output
    entries = json.loads(result.stdout)
    assert [(e["name"], e["source"], e["shadowed"]) for e in entries] == [
        ("kitchen", "local", False), ("kitchen", "bundled", True), ("kitchen_fetch", "bundled", False)]
    local, bundled, fetch = entries
    assert local["path"] == str(Path("worlds") / "kitchen.yaml") and local["description"].startswith("My kitchen")
    assert "bottle" not in [o["name"] for o in local["objects"]]
    assert {"name": "bottle", "type": "bottle"} in bundled["objects"]
    assert bundled["robot"] == {"name": "pr2", "file": "robots/pr2/pr2.urdf", "description": "pr2",
                                "arms": ["left", "right"]}
    assert fetch["robot"]["arms"] == ["arm"]


def test_plain_lines_name_the_robot_and_the_objects(folder: Path):
    result = run("worlds")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0] == f"kitchen  local  {Path('worlds') / 'kitchen.yaml'}"
    assert f"kitchen  bundled (shadowed by the local one)  {worlds_dir() / 'kitchen.yaml'}" in lines
    assert "  robot: fetch (robots/fetch/fetch.urdf, arms: arm)" in lines
    assert "  objects: floor, kitchen, milk, cereal, bowl, spoon, bottle" in lines
