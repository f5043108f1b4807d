"""`pycram run --report` and `pycram trace show --report`: one self-contained HTML file that replays a run."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli

REPO = Path(__file__).resolve().parents[2]
MAX_BYTES = 10 * 1000 * 1000


def run(*args: str):
    return CliRunner().invoke(cli, [str(a) for a in args])


def page_data(path: Path) -> dict:
    text = path.read_text(encoding="utf-8")
    match = re.search(r'<script type="application/json" id="pycram-data">(.*?)</script>', text, re.S)
    assert match, "the page carries its data"
    return json.loads(match.group(1))


@pytest.fixture
def set_table_report(set_table_run):
    """set_table's report and trace, made once for the report tests (tests/report/conftest.py)."""
    return set_table_run


def test_the_report_is_one_small_self_contained_file(set_table_report):
    report, _ = set_table_report
    text = report.read_text(encoding="utf-8")
    assert report.stat().st_size <= MAX_BYTES
    assert round(report.stat().st_size / 1e6, 1) == 0.8  # as README.md says ("set_table's: 0.8 MB")
    assert text.startswith("<!DOCTYPE html>")
    # nothing is loaded from elsewhere: no external scripts, styles, images or fetches
    assert not re.search(r"<(script|link|img|iframe)[^>]+(src|href)=", text)
    assert "fetch(" not in text.split('id="pycram-data"')[1]
    assert "var THREE=" in text  # three.js is inline


def test_the_report_holds_the_scene_once_and_a_frame_per_step(set_table_report):
    data = page_data(set_table_report[0])
    scene, frames = data["scene"], data["frames"]
    assert [b["name"] for b in scene["bodies"]] == ["floor", "pr2", "kitchen", "milk", "cereal", "bowl", "spoon", "bottle"]
    names = [m["name"] for m in scene["meshes"]]
    assert sorted(names) == sorted(set(names)) == sorted(["milk.obj", "breakfast_cereal.obj", "bowl.obj", "spoon.obj",
                                                          "bottle.obj"])
    assert scene["skipped"] == []
    trace = data["trace"]
    assert "replay" not in trace and trace["status"] == "succeeded"
    assert len(frames) == len(json.loads(set_table_report[1].read_text())["replay"]["steps"]) + 1
    drawn = sum(len(b["links"]) for b in scene["bodies"])
    assert len(frames[0]["poses"]) == 9 * drawn  # frame 0: every drawn link
    assert all(len(f["poses"]) < len(frames[0]["poses"]) for f in frames[1:])  # then only what moved
    assert all(len(f["camera"]) == 6 for f in frames)
    # the bowl was carried: its pose changes in some frame
    bowl = [b["name"] for b in scene["bodies"]].index("bowl")
    assert any(f["poses"][i] == bowl for f in frames[1:] for i in range(0, len(f["poses"]), 9))


def test_trace_show_writes_the_same_report_from_the_saved_trace(set_table_report, tmp_path):
    report, saved = set_table_report
    again = tmp_path / "again.html"
    result = run("trace", "show", saved, "--report", again)
    assert result.exit_code == 0, result.output
    first, second = page_data(report), page_data(again)
    assert first["scene"] == second["scene"]
    assert [f["path"] for f in first["frames"]] == [f["path"] for f in second["frames"]]
    assert first["frames"][-1]["poses"] == second["frames"][-1]["poses"]


def test_a_trace_without_replay_still_gets_a_report(tmp_path):
    golden = REPO / "tests" / "golden" / "fetch_spoon.trace.json"
    out = tmp_path / "golden.html"
    result = run("trace", "show", golden, "--report", out)
    assert result.exit_code == 0, result.output
    assert "has no replay record" in result.stderr
    data = page_data(out)
    assert len(data["frames"]) == 1 and data["replayed"] is False


def test_report_file_problems_are_input_errors(tmp_path):
    for bad, message in ((tmp_path / "r.pdf", "cannot tell the report's format from '.pdf'"),
                         (tmp_path / "no" / "r.html", "folder")):
        result = run("run", "set_table", "--report", bad)
        assert result.exit_code == 2 and str(bad) in result.stderr and message in result.stderr


def test_a_failure_recovered_from_is_marked_recovered_in_the_page_data(tmp_path):
    (tmp_path / "p.yaml").write_text(
        "world: kitchen\nbody:\n  - try: [{fail: GripperFailure, message: slipped}]\n"
        "    catch: {GripperFailure: [{log: handled}]}\n")
    out = tmp_path / "r.html"
    assert run("run", tmp_path / "p.yaml", "--report", out).exit_code == 0
    data = page_data(out)
    node = data["trace"]["root"]["children"][0]["children"][0]
    assert node["status"] == "failed" and data["trace"]["status"] == "succeeded"  # the page shows it as recovered
    assert "recovered" in out.read_text()


def test_names_and_messages_that_look_like_html_are_embedded_so_the_page_still_starts(tmp_path):
    # `<!--<script>` in the data made Chromium read the rest of the page as script data: the page stayed blank
    hostile = "a</script><!--<script>x</ScRiPt>&amp;\u2028"
    (tmp_path / "w.yaml").write_text("objects:\n  - {name: floor, type: environment, file: plane.urdf}\n"
                                     f"  - {{name: {json.dumps(hostile)}, type: box, file: cube_small.urdf, "
                                     "position: [0.5, 0, 0.025]}\n")
    (tmp_path / "p.yaml").write_text(f"world: w.yaml\nbody:\n  - log: {json.dumps('<!--<script>' + hostile)}\n")
    out = tmp_path / "r.html"
    result = run("run", tmp_path / "p.yaml", "--report", out)
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8")
    embedded = text.split('<script type="application/json" id="pycram-data">', 1)[1].split("</script>", 1)[0]
    assert "<" not in embedded and ">" not in embedded  # nothing in the data can open or close an element
    data = page_data(out)
    assert hostile in json.dumps(data, ensure_ascii=False)
    assert ('<!--<script>' + hostile) in json.dumps(data, ensure_ascii=False)
    assert text.rstrip().endswith("</html>") and text.count("<script") == text.lower().count("</script>")


@pytest.fixture
def actions_trace(actions_run):
    """set_table_actions' report and trace, made once for the report tests (tests/report/conftest.py)."""
    return actions_run


def test_the_report_of_set_table_actions_stays_under_2_mb(actions_trace):
    report, _ = actions_trace
    assert report.stat().st_size < 2_000_000
    data = page_data(report)
    assert sum(1 for f in data["frames"] if f.get("candidates")) >= 15  # with every locate step's candidate map


def test_with_the_real_pr2s_detailed_meshes_the_report_stays_under_2_mb(actions_trace, shared_models, tmp_path):
    _, saved = actions_trace
    world = (REPO / "worlds" / "kitchen.yaml").read_text().replace(
        "file: robots/pr2/pr2.urdf", f"file: {shared_models / 'pr2' / 'pr2.urdf'}")
    (tmp_path / "real.yaml").write_text(world)
    out = tmp_path / "real.html"
    result = run("trace", "show", saved, "--world", tmp_path / "real.yaml", "--report", out)
    assert result.exit_code == 0, result.output
    data = page_data(out)
    pr2 = next(b for b in data["scene"]["bodies"] if b["name"] == "pr2")
    meshes = {data["scene"]["meshes"][s["mesh"]]["name"] for link in pr2["links"] for s in link["shapes"] if "mesh" in s}
    assert {"base.dae", "upper_arm.dae", "head_tilt.dae", "l_finger.dae"} <= meshes  # its COLLADA looks are drawn
    assert data["scene"]["skipped"] == []
    assert out.stat().st_size < 2_000_000


def test_the_reasoning_of_a_step_is_in_its_frame(set_table_report):
    data = page_data(set_table_report[0])
    names = [b["name"] for b in data["scene"]["bodies"]]
    reach = [f["reasoning"] for f in data["frames"] if (f.get("reasoning") or {}).get("kind") == "reach"]
    # the bowl's blocking query: the cereal is in the way (set_table moves it first)
    assert any([names[b] for b in r["objects"]] == ["bowl"] and [names[b] for b in r["blockers"]] == ["cereal"]
               for r in reach)
    views = [f["reasoning"] for f in data["frames"] if (f.get("reasoning") or {}).get("kind") == "view"]
    assert views and all(len(v["eye"]) == 3 and len(v["axes"]) == 9 and 0 < v["fov"][0] < 3.2 for v in views)
    # the camera's optical axes are a rotation: unit and orthogonal
    import numpy as np
    axes = np.array(views[0]["axes"]).reshape(3, 3)
    assert np.allclose(axes @ axes.T, np.eye(3), atol=1e-3)


PROJECTING = """\
world: kitchen
body:
  - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
  - project:
      alternatives:
        front: [{pick-up: {object: cereal, arm: right, grasp: front}}]
        top: [{pick-up: {object: cereal, arm: right, grasp: top}}]
      runs: 2
      vary: {cereal: {noise: [0.01, 0.01, 0], yaw: 0.2}}
"""


@pytest.fixture(scope="module")
def projecting_report(tmp_path_factory):
    folder = tmp_path_factory.mktemp("projecting")
    (folder / "plan.yaml").write_text(PROJECTING)
    result = run("run", folder / "plan.yaml", "--report", folder / "run.html", "--trace", folder / "run.json")
    assert result.exit_code == 0, result.output
    return folder


def test_the_report_holds_each_kept_projected_run_as_a_replay_of_its_own(projecting_report):
    data = page_data(projecting_report / "run.html")
    table = data["trace"]["root"]["children"][1]["projection"]["alternatives"]
    kept = data["projections"]["body/1:project"]
    assert sorted(kept) == ["front", "top"] and all(sorted(runs) == ["0", "1"] for runs in kept.values())
    for name, runs in kept.items():
        for run_number, replay in runs.items():
            outcome = table[name]["outcomes"][int(run_number)]
            assert replay["status"] == outcome["status"]
            assert replay["root"]["path"] == f"body/1:project/projected {name} {run_number}"
            assert len(replay["frames"]) == 2  # before the pick-up, after it
            assert [f["path"] for f in replay["failures"]] == (
                [] if outcome["status"] == "succeeded" else [f"body/1:project/projected {name} {run_number}/0:pick-up"])
    assert table["front"]["failures"] and table["top"]["succeeded"] == 2
    # the main replay is the real run's: driving, then the chosen pick-up
    assert [f["path"] for f in data["frames"][1:]] == ["body/0:moving", "body/1:project/chosen top/0:pick-up"]


def test_a_saved_trace_with_projected_replays_makes_the_same_report(projecting_report, tmp_path):
    result = run("trace", "show", projecting_report / "run.json", "--report", tmp_path / "again.html")
    assert result.exit_code == 0, result.output
    again, first = page_data(tmp_path / "again.html"), page_data(projecting_report / "run.html")

    def untimed(value):  # the trace file keeps timings to the microsecond
        if isinstance(value, dict):
            return {k: untimed(v) for k, v in value.items() if k != "timing"}
        return [untimed(v) for v in value] if isinstance(value, list) else value

    assert untimed(again["projections"]) == untimed(first["projections"])
