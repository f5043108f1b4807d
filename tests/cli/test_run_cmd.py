"""`pycram run` from a user's point of view: exit codes, summary, progress, --json, --trace, -p, --world."""
from __future__ import annotations

import json
import textwrap

from click.testing import CliRunner

from pycram_cli.cli.main import cli


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def small_world(tmp_path, name="small.yaml", x=0.5):
    return write(tmp_path, name, f"""
        objects:
          - {{name: floor, type: environment, file: plane.urdf}}
          - {{name: box, type: box, file: cube_small.urdf, position: [{x}, 0, 0.025]}}
    """)


def plan(tmp_path, body, name="p.yaml", extra=""):
    small_world(tmp_path)
    return write(tmp_path, name, f"world: small.yaml\nparams: {{who: box}}\n{extra}body:\n" + textwrap.indent(
        textwrap.dedent(body), "  "))


def test_a_plan_that_succeeds_exits_0_with_a_summary(tmp_path):
    path = plan(tmp_path, """
        - log: "hello $who"
        - par: [{log: a}, {log: b}]
    """)
    result = run("run", str(path))
    assert result.exit_code == 0, result.output
    assert "plan p.yaml succeeded in" in result.stdout
    # progress goes to stderr, one line per step when not on a terminal (tests/cli/test_run_log.py)
    assert "  ok        0:log  “hello box”" in result.stderr


def test_a_plan_that_fails_exits_1_and_says_where_and_why(tmp_path):
    path = plan(tmp_path, """
        - log: start
        - fail: PerceptionFailure
          message: "no $who in sight"
    """)
    result = run("run", str(path))
    assert result.exit_code == 1
    assert "PerceptionFailure at body/1:fail" in result.stdout
    assert f"({path}:6:5)" in result.stdout
    assert "no box in sight" in result.stdout


def test_an_invalid_plan_exits_2_with_every_problem(tmp_path):
    path = plan(tmp_path, """
        - movng: {target: [0, 0, 0]}
        - log: $nobody
    """)
    result = run("run", str(path))
    assert result.exit_code == 2
    assert f"{path}:5:5: movng: unknown node type 'movng' (did you mean 'moving'?)" in result.stderr
    assert f"{path}:6:10" in result.stderr and "undefined variable $nobody" in result.stderr
    assert "2 problems found" in result.stderr


def test_parameters_from_the_command_line(tmp_path):
    path = plan(tmp_path, "- log: \"hello $who at $where\"\n", extra="")
    path.write_text(path.read_text().replace("params: {who: box}", "params: {who: box, where: [0, 0, 0]}"))
    result = run("run", str(path), "-p", "who=floor", "-p", "where=[1, 2.5, 0]", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["trace"]["params"] == {"who": "floor", "where": [1, 2.5, 0]}
    assert data["trace"]["root"]["children"][0]["message"] == "hello floor at [1, 2.5, 0]"


def test_an_unknown_parameter_exits_2_with_a_suggestion(tmp_path):
    path = plan(tmp_path, "- log: $who\n")
    result = run("run", str(path), "-p", "whoo=floor")
    assert result.exit_code == 2
    assert "plan 'p' has no parameter 'whoo' (did you mean 'who'?)" in result.stderr
    assert run("run", str(path), "-p", "who").exit_code == 2


def test_a_parameter_value_of_the_wrong_shape_exits_2_before_anything_is_simulated():
    from pycram_cli.world import BulletWorld

    worlds_before = len(BulletWorld._live)
    result = run("run", "fetch_spoon", "-p", "target=[1,2]")  # fetch_spoon declares target a position
    assert result.exit_code == 2
    assert ("-p: target: parameter 'target' is a position: expected a position [x, y, z], got a list of 2 "
            "(e.g. -p target=[-0.8, 1.4, 0.862])") in result.stderr
    assert "running" not in result.stderr and len(BulletWorld._live) == worlds_before  # nothing ran


def test_a_required_typed_parameter_left_out_exits_2_saying_what_to_give(tmp_path):
    path = plan(tmp_path, "- log: $where\n", extra="")
    path.write_text(path.read_text().replace("params: {who: box}", "params: {who: box, where: {type: position}}"))
    result = run("run", str(path))
    assert result.exit_code == 2
    assert "-p: where: plan 'p' needs parameter 'where' (give it with -p where=VALUE ([x, y, z]" in result.stderr
    assert run("run", str(path), "-p", "where=[1, 2, 0]").exit_code == 0


def test_json_prints_status_failure_and_trace_only(tmp_path):
    path = plan(tmp_path, """
        - fail: GripperFailure
          message: slipped
    """)
    result = run("run", str(path), "--json")
    assert result.exit_code == 1
    data = json.loads(result.stdout)
    assert data["status"] == "failed"
    assert data["failure"] == {"type": "GripperFailure", "message": "slipped", "path": "body/0:fail"}
    assert data["trace"]["format"] == "pycram-trace"
    assert data["trace"]["final_state"]["objects"]["box"]["position"] == [0.5, 0.0, 0.025]


def test_trace_file_and_world_override(tmp_path):
    path = plan(tmp_path, "- log: hi\n")
    other = small_world(tmp_path, "other.yaml", x=0.75)
    (tmp_path / "out").mkdir()  # output folders are not made (tests/cli/test_output_files.py)
    out = tmp_path / "out" / "t.json"
    result = run("run", str(path), "--world", str(other), "--trace", str(out))
    assert result.exit_code == 0, result.output
    data = json.loads(out.read_text())
    assert data["world"] == "other.yaml"
    assert data["final_state"]["objects"]["box"]["position"][0] == 0.75
    assert "timing" in data["root"]
    bad = run("run", str(path), "--world", str(tmp_path / "nope.yaml"))
    assert bad.exit_code == 2 and "world file not found" in bad.stderr


def test_validate_accepts_plan_files(tmp_path):
    good = plan(tmp_path, "- log: hi\n")
    result = run("validate", str(good))
    assert result.exit_code == 0 and "valid plan file" in result.stdout
    bad = plan(tmp_path, "- lgo: hi\n", name="bad.yaml")
    result = run("validate", str(bad))
    assert result.exit_code == 2 and "unknown node type 'lgo' (did you mean 'log'?)" in result.stderr


def test_a_missing_plan_file(tmp_path):
    result = run("run", str(tmp_path / "nothing.yaml"))
    assert result.exit_code == 2 and "plan file not found" in result.stderr


def test_designators_run_on_the_kitchen(tmp_path):
    path = write(tmp_path, "k.yaml", """
        world: kitchen
        body:
          - par:
              - move-arm-joints: {left-arm: park, right-arm: park}
              - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
              - looking: {object: milk}
          - detecting: {object-type: milk}
            as: obj
          - assert: {not: {contact: {a: $obj, b: pr2}}}
          - log: "found $obj.name"
    """)
    result = run("run", str(path), "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    nodes = {n["path"]: n for n in data["trace"]["root"]["children"][0]["children"]}
    moving = nodes["body/0:par/1:moving"]["designator"]
    assert moving["slots"] == {"target": [0.65, 0.7, 0.0], "orientation": [0.0, 0.0, 0.0, 1.0]}
    assert "resolved" in moving
    assert data["trace"]["final_state"]["objects"]["pr2"]["position"][:2] == [0.65, 0.7]
    assert data["trace"]["root"]["children"][3]["message"] == "found milk"


def test_pace_slows_a_run_down_so_it_can_be_watched(tmp_path):
    import time

    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    plan = tmp_path / "p.yaml"
    plan.write_text("world: kitchen\nbody:\n  - move-arm-joints: {left-arm: park}\n  - move-arm-joints: {right-arm: park}\n")
    start = time.perf_counter()
    result = CliRunner().invoke(cli, ["run", str(plan), "--pace", "0.3"])
    assert result.exit_code == 0, result.output
    assert time.perf_counter() - start >= 0.6  # two motions, 0.3 s after each


def test_render_writes_a_png_of_the_final_scene(tmp_path):
    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    plan = tmp_path / "p.yaml"
    plan.write_text("world: kitchen\nbody:\n  - moving: {target: [0.65, 0.7, 0]}\n")
    out = tmp_path / "after.png"
    result = CliRunner().invoke(cli, ["run", str(plan), "--render", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:4] == b"\x89PNG"


def test_render_takes_a_camera_a_size_and_a_format(tmp_path):
    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    plan = tmp_path / "p.yaml"
    plan.write_text("world: kitchen\nbody:\n  - moving: {target: [0.65, 0.7, 0]}\n")
    out = tmp_path / "after.jpeg"
    result = CliRunner().invoke(cli, ["run", str(plan), "--render", str(out), "--camera", "target", "--size", "64x48"])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:3] == b"\xff\xd8\xff"
    assert f"wrote {out} (64x48 JPEG)" in result.stderr
    # checked before the plan runs
    result = CliRunner().invoke(cli, ["run", str(plan), "--render", str(tmp_path / "none" / "x.png")])
    assert result.exit_code == 2 and "x.png" in result.stderr and "running" not in result.stderr


def test_a_camera_without_render_is_an_input_error():
    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    result = CliRunner().invoke(cli, ["run", "set_table", "--camera", "robot"])
    assert result.exit_code == 2 and "no --render FILE is given" in result.stderr


def test_a_folder_given_as_the_plan_or_world_says_it_is_a_folder(tmp_path, monkeypatch):
    (tmp_path / "plans").mkdir()
    (tmp_path / "plans" / "mine.yaml").write_text("body: [{log: hi}]\n")
    monkeypatch.chdir(tmp_path)
    result = run("run", "plans")
    assert result.exit_code == 2
    assert "'plans' is a folder, not a plan file (name a file in it: mine.yaml)" in result.stderr
    world = run("run", "plans/mine.yaml", "--world", "plans")
    assert world.exit_code == 2 and "'plans' is a folder, not a world file" in world.stderr


def test_no_follow_needs_the_gui():
    result = run("run", "set_table", "--no-follow")
    assert result.exit_code == 2
    assert "--no-follow: keeps the first view of the --gui window, but no --gui is given (add --gui" in result.stderr
