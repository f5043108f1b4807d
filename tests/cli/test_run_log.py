"""`pycram run`'s progress when stderr is not a terminal (CI logs): an indented log of the plan tree, in pre-order."""
from __future__ import annotations

import json
import re
import textwrap

from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.cli.run_log import WIDTH


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def log_lines(result) -> list[str]:
    """The log: stderr without the info lines before it and the `wrote` lines after it."""
    return [line for line in result.stderr.splitlines() if not line.startswith(("info:", "warning:"))]


def write_plan(tmp_path, body: str) -> str:
    (tmp_path / "w.yaml").write_text("objects:\n  - {name: floor, type: environment, file: plane.urdf}\n")
    path = tmp_path / "p.yaml"
    path.write_text("world: w.yaml\nbody:\n" + textwrap.indent(textwrap.dedent(body), "  "))
    return str(path)


def line_of(lines: list[str], pattern: str) -> int:
    found = [i for i, line in enumerate(lines) if re.search(pattern, line)]
    assert found, f"no line matches {pattern!r} in:\n" + "\n".join(lines)
    return found[0]


def depth(line: str) -> int:
    return (len(line) - len(line.lstrip(" "))) // 2


def test_fetch_spoon_logs_the_tree_in_pre_order_with_short_names_indented_by_depth():
    result = run("run", "fetch_spoon")
    assert result.exit_code == 0, result.output
    lines = log_lines(result)
    assert lines[0] == "body"
    # parents before their children, children in the plan's order, each level two spaces deeper
    par, park, drive = (line_of(lines, p) for p in (r"^  0:par$", r"0:move-arm-joints", r"1:moving"))
    assert par < park < drive and depth(lines[park]) == depth(lines[par]) + 1
    retry, attempt1, recover1, attempt2 = (line_of(lines, p) for p in (r"^  1:retry", r"attempt 1", r"recover 1",
                                                                        r"attempt 2"))
    assert drive < retry < attempt1 < recover1 < attempt2 < line_of(lines, r"2:pick-up")
    assert depth(lines[attempt1]) == 2 and depth(lines[line_of(lines, r"0:looking")]) == 3
    # a node's own label, never its whole path
    assert "body/" not in result.stderr
    assert re.match(r"^  ok +7:assert  stable\(object=spoon\) → true: holds", lines[-1])


def test_a_failure_a_retry_recovered_from_is_marked_recovered_not_failed():
    result = run("run", "fetch_spoon")
    lines = log_lines(result)
    detecting = lines[line_of(lines, r"1:detecting  object-type=spoon  PerceptionFailure")]
    assert detecting.lstrip().startswith("recovered ")
    assert "FAILED" not in result.stderr
    assert "plan fetch_spoon.yaml succeeded" in result.stdout


def test_no_line_is_longer_than_the_cap_and_long_ones_end_in_an_ellipsis():
    result = run("run", "set_table")
    assert result.exit_code == 0, result.output
    lines = result.stderr.splitlines()
    assert max(len(line) for line in lines) <= WIDTH
    assert any(line.endswith("…") for line in lines)
    # the parameters are shortened too, the files that ran are named in full
    assert re.search(r"^info: running .*plans/set_table\.yaml on .*worlds/kitchen\.yaml$", result.stderr, re.M)


def test_a_fatal_failure_is_failed_and_the_steps_it_skipped_follow_it(tmp_path):
    plan = write_plan(tmp_path, """
        - log: start
        - fail: PerceptionFailure
          message: no milk in sight
        - log: never
    """)
    result = run("run", plan)
    assert result.exit_code == 1
    assert log_lines(result) == [
        "body",
        "  ok        0:log  “start”  " + log_lines(result)[1].rsplit("  ", 1)[1],
        "  FAILED    1:fail  PerceptionFailure: no milk in sight  " + log_lines(result)[2].rsplit("  ", 1)[1],
        "  skipped   2:log",
    ]


def test_a_composite_whose_own_failure_arose_at_it_gets_a_closing_line(tmp_path):
    plan = write_plan(tmp_path, """
        - try_all:
            - fail: PerceptionFailure
            - fail: NavigationFailure
    """)
    lines = log_lines(run("run", plan))
    header, first, second, closing = (line_of(lines, p) for p in (r"^  0:try_all$", r"FAILED +0:fail", r"FAILED +1:fail",
                                                                   r"^  FAILED +0:try_all  Failure: all 2"))
    assert header < first < second < closing


def test_parallel_branches_are_printed_one_after_another_in_the_plans_order(tmp_path):
    plan = write_plan(tmp_path, """
        - par:
            - seq: [{wait: 0.1}, {log: slow}]
            - log: fast
    """)
    lines = log_lines(run("run", plan))
    assert line_of(lines, r"“slow”") < line_of(lines, r"“fast”")  # the fast branch ended first, yet comes second
    assert depth(lines[line_of(lines, r"“slow”")]) == 3 and depth(lines[line_of(lines, r"“fast”")]) == 2


def test_a_retry_that_never_succeeds_logs_its_folded_attempts_as_failed(tmp_path):
    plan = write_plan(tmp_path, """
        - retry: 9
          body: [{fail: GripperFailure}]
    """)
    result = run("run", plan)
    assert result.exit_code == 1
    lines = log_lines(result)
    # the attempts the trace keeps, and between them the count of those it folded, in order
    assert line_of(lines, r"attempt 1$") < line_of(lines, r"FAILED +folded attempts  \d+ entries folded") < line_of(
        lines, r"attempt 10$")
    assert "recovered" not in result.stderr  # nothing above succeeded: every attempt's failure is fatal
    assert all(line.lstrip().startswith("FAILED ") for line in lines if "0:fail" in line)


def test_json_output_has_no_log():
    result = run("run", "fetch_spoon", "--json")
    assert result.exit_code == 0
    assert json.loads(result.stdout)["status"] == "succeeded"
    assert "body" not in result.stderr and "recovered" not in result.stderr
