"""`pycram trace diff A B --report diff.html`: two runs' replays side by side, their first divergence found and marked."""
from __future__ import annotations

import json
import re
import shutil

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.report.compare import state_notes, step_differences


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.fixture(scope="module")
def runs(tmp_path_factory, set_table_run, failed_run):
    """set_table as it is (A) and with the milk's target over the island's edge (B) (their traces made once for the
    report tests, tests/report/conftest.py), and their comparison page."""
    folder = tmp_path_factory.mktemp("compare")
    shutil.copyfile(set_table_run[1], folder / "a.json")
    shutil.copyfile(failed_run[1], folder / "b.json")
    result = run("trace", "diff", folder / "a.json", folder / "b.json", "--report", folder / "diff.html")
    assert result.exit_code == 1, result.output  # they differ
    assert f"wrote {folder / 'diff.html'} (comparison report" in result.stderr
    return folder


def load(path):
    return json.loads(path.read_text())


def test_a_run_compared_with_itself_has_no_divergence(runs):
    a = load(runs / "a.json")
    assert step_differences(a, a) == []


def test_the_first_divergence_is_the_first_step_that_did_something_else(runs):
    a, b = load(runs / "a.json"), load(runs / "b.json")
    found = step_differences(a, b)
    first = found[0]
    assert first.step == 1  # A looks the bowl up first, B the milk
    assert 'designator.resolved.object-type: "bowl" != "milk"' in first.notes
    steps_b = len(b["replay"]["steps"])
    assert [d.step for d in found if d.notes == (f"run B ended after {steps_b} steps",)] == \
        list(range(steps_b + 1, len(a["replay"]["steps"]) + 1))


def test_a_different_state_after_the_same_step_is_a_divergence(runs):
    a = load(runs / "a.json")
    b = json.loads(json.dumps(a))
    b["replay"]["steps"][4]["changed"]["milk"] = {"position": [1.0, 2.0, 0.9], "orientation": [0, 0, 0, 1]}
    [found, *later] = step_differences(a, b)
    assert found.step == 5 and found.notes[0].startswith("milk is at (") and "(1.00, 2.00, 0.90) in B" in found.notes[0]
    assert later and all("milk is at" in d.notes[0] for d in later)  # until A moves the milk there too: never


def test_state_notes_name_objects_poses_and_joints_beyond_the_tolerance():
    a = {"box": {"position": [0, 0, 0], "orientation": [0, 0, 0, 1], "joints": {"lid": 0.1}}}
    b = {"box": {"position": [0, 0, 0.0005], "orientation": [0, 0, 0, 1], "joints": {"lid": 0.5}}, "cup": {}}
    assert state_notes(a, b, 1e-3) == ["box's joints differ: lid", "cup is only in B"]
    assert state_notes(a, a, 1e-3) == []


def test_the_page_holds_both_reports_and_the_differences(runs):
    text = (runs / "diff.html").read_text(encoding="utf-8")
    data = json.loads(re.search(r'<script type="application/json" id="diff-data">(.*?)</script>', text, re.S).group(1))
    assert data["divergence"] == 1 and data["a"]["status"] == "succeeded" and data["b"]["status"] == "failed"
    assert data["b"]["failure"] == "ReasoningFailure: milk is not stable where it was placed"
    assert list(data["a"]["params"]) == ["jobs"]  # only what differs between the runs
    for side in ("a", "b"):
        page = json.loads(re.search(rf'<script type="application/json" id="page-{side}">(.*?)</script>', text, re.S).group(1))
        assert page.startswith("<!DOCTYPE html>") and 'id="pycram-data"' in page
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=", text)  # offline: nothing loaded from elsewhere


@pytest.mark.parametrize("name, message", [
    ("diff.png", "cannot tell the report's format from '.png'"),
    ("trace.html", "the report would replace a trace it is made from"),
    ("missing/diff.html", "folder"),
])
def test_bad_report_paths_are_refused(runs, name, message):
    (runs / "trace.html").write_text((runs / "b.json").read_text())  # a trace may have any name
    result = run("trace", "diff", runs / "a.json", runs / "trace.html", "--report", runs / name)
    assert result.exit_code == 2 and message in result.stderr, result.stderr
