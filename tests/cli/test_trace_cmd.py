"""`pycram trace show|diff`: saved traces as trees, and comparisons with a float tolerance."""
from __future__ import annotations

import json
import textwrap

from click.testing import CliRunner

from pycram_cli.cli.main import cli


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def traced(tmp_path, name="t.json", x=0.5, message="hello"):
    (tmp_path / "w.yaml").write_text(textwrap.dedent(f"""
        objects:
          - {{name: floor, type: environment, file: plane.urdf}}
          - {{name: box, type: box, file: cube_small.urdf, position: [{x}, 0, 0.025]}}
    """))
    (tmp_path / "p.yaml").write_text(textwrap.dedent("""
        world: w.yaml
        params: {message: hello}
        body:
          - log: $message
          - try_all:
              - {fail: PerceptionFailure, message: left}
              - seq: [{wait: 0.01}, {log: right}]
          - try: [{fail: GripperFailure, message: slipped}]
            catch: {GripperFailure: [{log: handled}]}
    """))
    out = tmp_path / name
    result = run("run", str(tmp_path / "p.yaml"), "--trace", str(out), "-p", f"message={message}")
    assert result.exit_code == 0, result.output
    return out


def test_show_prints_the_tree_with_statuses_and_the_final_state(tmp_path):
    path = traced(tmp_path)
    result = run("trace", "show", str(path))
    assert result.exit_code == 0, result.output
    out = result.stdout
    assert "p.yaml on w.yaml: succeeded" in out
    # the live view's tree: a failure that try_all or a catch recovered from is shown as recovered
    for line in ("✓ 0:log  “hello”", "↺ 0:fail  PerceptionFailure: left", "✓ catch GripperFailure",
                 "✓ 1:try_all", "↺ 0:fail  GripperFailure: slipped"):
        assert line in out, out
    assert "box" in out and "(0.500, 0.000, 0.025)" in out


def test_show_without_timings(tmp_path):
    out = run("trace", "show", "--no-timing", str(traced(tmp_path))).stdout
    assert " s\n" not in out.split("final state")[0]


def test_diff_of_two_runs_of_the_same_plan_is_empty(tmp_path):
    a = traced(tmp_path, "a.json")
    b = traced(tmp_path, "b.json")
    assert json.loads(a.read_text())["root"]["timing"] != json.loads(b.read_text())["root"]["timing"]
    result = run("trace", "diff", str(a), str(b))
    assert result.exit_code == 0, result.output
    assert "match" in result.stdout


def test_diff_lists_what_differs_by_node_path_and_exits_1(tmp_path):
    a = traced(tmp_path, "a.json")
    b = traced(tmp_path, "b.json", x=0.6, message="bye")
    result = run("trace", "diff", str(a), str(b))
    assert result.exit_code == 1
    out = result.stdout
    assert 'body/0:log: message: "hello" != "bye"' in out
    assert "final_state.objects.box.position[0]: 0.5 != 0.6" in out


def test_diff_tolerance(tmp_path):
    a = traced(tmp_path, "a.json")
    b = traced(tmp_path, "b.json", x=0.5004)
    assert run("trace", "diff", str(a), str(b)).exit_code == 0
    strict = run("trace", "diff", str(a), str(b), "--atol", "1e-5")
    assert strict.exit_code == 1 and "position[0]" in strict.stdout
    data = json.loads(run("trace", "diff", str(a), str(b), "--atol", "1e-5", "--json").stdout)
    assert data["same"] is False and data["differences"][0]["field"] == "final_state.objects.box.position[0]"


def test_diff_reports_steps_present_in_only_one_trace(tmp_path):
    a = traced(tmp_path, "a.json")
    data = json.loads(a.read_text())
    data["root"]["children"].pop()
    b = tmp_path / "b.json"
    b.write_text(json.dumps(data))
    out = run("trace", "diff", str(a), str(b)).stdout
    assert "body: children" in out and "2:try" in out


def test_not_a_trace_file_exits_2(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{\"x\": 1}")
    result = run("trace", "show", str(bad))
    assert result.exit_code == 2 and "not a pycram trace" in result.stderr
    broken = tmp_path / "broken.json"
    broken.write_text("{")
    assert run("trace", "diff", str(broken), str(bad)).exit_code == 2
    assert run("trace", "show", str(tmp_path / "none.json")).exit_code == 2


def json_output(tmp_path, name="out.json"):
    """What `pycram run PLAN --json > out.json` leaves: status, failure, duration and the trace inside."""
    traced(tmp_path)  # writes the plan and its world
    result = run("run", str(tmp_path / "p.yaml"), "--json")
    assert result.exit_code == 0, result.output
    out = tmp_path / name
    out.write_text(result.stdout)
    assert set(json.loads(result.stdout)) == {"status", "failure", "duration", "trace"}
    return out


def test_show_reads_what_run_json_printed(tmp_path):
    result = run("trace", "show", str(json_output(tmp_path)))
    assert result.exit_code == 0, result.output
    assert "p.yaml on w.yaml: succeeded" in result.stdout and "↺ 0:fail  PerceptionFailure: left" in result.stdout


def test_diff_compares_run_json_output_with_a_saved_trace(tmp_path):
    saved = traced(tmp_path, "saved.json")
    result = run("trace", "diff", str(json_output(tmp_path)), str(saved))
    assert result.exit_code == 0, result.output
    assert "match" in result.stdout


def test_a_problem_inside_run_json_output_is_reported_at_its_place(tmp_path):
    path = json_output(tmp_path)
    data = json.loads(path.read_text())
    data["trace"]["root"]["status"] = "great"
    path.write_text(json.dumps(data, indent=2))
    result = run("trace", "show", str(path))
    assert result.exit_code == 2
    line = next(i for i, text in enumerate(path.read_text().splitlines(), 1) if '"great"' in text)
    assert f"{path}:{line}:" in result.stderr and "unknown status" in result.stderr
