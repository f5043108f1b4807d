"""Output paths follow one rule in every command: a missing folder is an input error (exit 2), never made silently.

(`sweep --out DIR` is not an output file but the sweep's results folder, which the sweep makes.)
"""
from __future__ import annotations

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


@pytest.fixture
def small_plan(tmp_path):
    (tmp_path / "w.yaml").write_text("objects:\n  - {name: floor, type: environment, file: plane.urdf}\n")
    plan = tmp_path / "p.yaml"
    plan.write_text("world: w.yaml\nbody:\n  - log: hello\n")
    return plan


@pytest.mark.parametrize("option, name", [("--trace", "x.json"), ("--render", "x.png"), ("--report", "x.html")])
def test_run_refuses_an_output_in_a_missing_folder_before_anything_runs(tmp_path, small_plan, option, name):
    target = tmp_path / "nf5" / name
    result = run("run", str(small_plan), option, str(target))
    assert result.exit_code == 2, result.output
    assert f"error: {target}: cannot write the" in result.stderr and "folder" in result.stderr
    assert "does not exist" in result.stderr
    assert "running" not in result.stderr and "Traceback" not in result.output
    assert not (tmp_path / "nf5").exists()  # not made


def test_run_writes_a_trace_into_an_existing_folder(tmp_path, small_plan):
    (tmp_path / "out").mkdir()
    result = run("run", str(small_plan), "--trace", str(tmp_path / "out" / "x.json"))
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "x.json").is_file()


def test_trace_show_report_and_world_render_follow_the_same_rule(tmp_path, small_plan):
    trace = tmp_path / "t.json"
    assert run("run", str(small_plan), "--trace", str(trace)).exit_code == 0
    shown = run("trace", "show", str(trace), "--report", str(tmp_path / "nf5" / "r.html"))
    rendered = run("world", "render", str(tmp_path / "w.yaml"), "-o", str(tmp_path / "nf5" / "s.png"))
    for result in (shown, rendered):
        assert result.exit_code == 2 and "does not exist" in result.stderr, result.output
    assert not (tmp_path / "nf5").exists()
