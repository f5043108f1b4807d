"""A new user's first hour, as the README tells it, in a fresh empty folder: run the demo, make a world from the
kitchen with a mug from pybullet_data, a plan that takes the mug to the island, validate both, run it with a
replay report, then sweep it over a few varied scenarios. Every step is a command a user types."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli


def pycram(*args: str, code: int = 0):
    result = CliRunner().invoke(cli, list(args))
    assert result.exit_code == code, f"pycram {' '.join(args)}: exit {result.exit_code}\n{result.output}"
    return result


def uncomment_the_mug(world: Path) -> None:
    """What the user does in their editor: the commented mug of `new world` made an object of the world."""
    text = world.read_text()
    assert "  # - name: mug" in text and "objects/mug.urdf" in text  # pybullet_data's mug, offered commented
    world.write_text(text.replace("  # - name: mug", "  - name: mug").replace("  #   ", "    "))


def take_it_to_the_island(plan: Path) -> None:
    """What the user adds to the plan `new plan` wrote: the mug by default, and a place step after the pick-up."""
    text = plan.read_text()
    assert "    default: milk\n" in text
    plan.write_text(text.replace("    default: milk\n", "    default: mug\n")
                    + "  - action: place                     # put it on the island\n"
                      "    object: $seen\n"
                      "    target: {on: kitchen_island_surface}\n")


def test_the_first_hour_from_an_empty_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    monkeypatch.chdir(tmp_path)
    demo = pycram("run", "set_table")
    assert "plan set_table.yaml succeeded" in demo.output

    made = pycram("new", "world", "mine", "--from", "kitchen")
    assert "made the folder worlds/" in made.stderr
    uncomment_the_mug(tmp_path / "worlds" / "mine.yaml")
    pycram("validate", "worlds/mine.yaml")
    assert "mug is stable" in pycram("query", "stable", "mug", "--world", "mine").stdout

    planned = pycram("new", "plan", "mine", "--world", "mine")
    assert "made the folder plans/" in planned.stderr
    take_it_to_the_island(tmp_path / "plans" / "mine.yaml")
    assert "plans/mine.yaml: valid plan file" in pycram("validate", "plans/mine.yaml").stdout
    typo = pycram("validate", "plans/mine.yaml", "-p", "object=mugg", code=2)
    assert "plans/mine.yaml:16:" in typo.stderr and "did you mean 'mug'?" in typo.stderr

    ran = pycram("run", "mine", "--report", "run.html", "--trace", "run.json")
    assert "plan mine.yaml succeeded" in ran.output and (tmp_path / "run.html").stat().st_size > 100_000
    mug = json.loads((tmp_path / "run.json").read_text())["final_state"]["objects"]["mug"]
    assert mug["position"][0] < -0.5 and abs(mug["position"][2] - 0.862) < 0.01  # on the island, standing

    pycram("new", "vary", "mine")
    vary = (tmp_path / "plans" / "mine.vary.yaml").read_text()
    assert "\n  mug: {noise:" in vary  # the object the plan works on
    pycram("validate", "plans/mine.vary.yaml")
    swept = pycram("sweep", "mine", "-n", "2", "--workers", "1", "--json")
    summary = json.loads(swept.stdout)
    assert summary["runs"] == 2 and summary["succeeded"] == 2, summary["failures"]
    again = pycram("sweep", "mine", "-n", "2", "--workers", "1", code=2)
    assert "--resume" in again.stderr and "--force" in again.stderr
