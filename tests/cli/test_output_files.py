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


def test_locate_and_sweep_plots_follow_the_same_rule(tmp_path, small_plan):
    (small_plan.parent / "p.vary.yaml").write_text("seed: 1\n")
    located = run("locate", "reachable-for", "milk", "--plot", str(tmp_path / "nf5" / "map.png"))
    swept = run("sweep", str(small_plan), "-n", "1", "--out", str(tmp_path / "s"), "--plot", str(tmp_path / "nf5" / "map.png"))
    for result in (located, swept):
        assert result.exit_code == 2, result.output
        assert f"{tmp_path / 'nf5' / 'map.png'}: cannot write the" in result.stderr and "does not exist" in result.stderr
    assert not (tmp_path / "nf5").exists() and not (tmp_path / "s").exists()  # refused before the sweep began


def test_two_outputs_naming_the_same_file_are_refused_before_the_run(tmp_path, small_plan):
    (tmp_path / "link.html").symlink_to(tmp_path / "same.html")
    for other in ("same.html", "./same.html", "link.html"):
        result = run("run", str(small_plan), "--trace", str(tmp_path / "same.html"), "--report", str(tmp_path / other))
        assert result.exit_code == 2, result.output
        assert "the trace and the report name the same file" in result.stderr
        assert "running" not in result.stderr
    assert not (tmp_path / "same.html").exists()


def test_trace_show_never_writes_its_report_over_the_trace_it_reads(tmp_path, small_plan):
    trace = tmp_path / "t.html"
    assert run("run", str(small_plan), "--trace", str(trace)).exit_code == 0
    before = trace.read_bytes()
    result = run("trace", "show", str(trace), "--report", str(tmp_path / "." / "t.html"))
    assert result.exit_code == 2, result.output
    assert f"{tmp_path / '.' / 't.html'}: the report would replace the trace it is made from" in result.stderr
    assert trace.read_bytes() == before
