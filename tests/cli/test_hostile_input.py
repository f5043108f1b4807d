"""Hostile and malformed input (issue 18): exit 2 with file:line:column, the key and a message — never a
traceback, a hang, a wrong exit code or a memory blow-up. One representative case per row of the issue's table."""
from __future__ import annotations

import os
import re
import textwrap
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.worldfile.spec import parse_world

REPO = Path(__file__).resolve().parents[2]


def run(*args: str, timeout: float = 20.0):
    started = time.monotonic()
    result = CliRunner().invoke(cli, list(args))
    assert time.monotonic() - started < timeout, f"pycram {' '.join(args)} took too long"
    assert "Traceback" not in result.output, result.output
    return result


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def small_world(tmp_path: Path, extra: str = "") -> Path:
    return write(tmp_path, "w.yaml", """
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
    """ + extra)


def a_plan(tmp_path: Path, body: str, name: str = "p.yaml") -> Path:
    small_world(tmp_path)
    return write(tmp_path, name, "world: w.yaml\nbody:\n" + textwrap.indent(textwrap.dedent(body), "  "))


# -- file-system errors: exit 2 naming the key, not an internal error --------------------------------------


def test_a_file_name_too_long_in_a_world_is_exit_2_at_its_key(tmp_path):
    world = write(tmp_path, "w.yaml", f"""
        objects:
          - {{name: box, type: box, file: {"x" * 300}.urdf}}
    """)
    result = run("validate", str(world))
    assert result.exit_code == 2
    assert f"{world}:3:34: file: cannot read" in result.stderr and "file name too long" in result.stderr


def test_a_named_pipe_as_the_plan_is_refused_at_once(tmp_path):
    fifo = tmp_path / "plan.yaml"
    os.mkfifo(fifo)
    result = run("validate", str(fifo), timeout=5)
    assert result.exit_code == 2
    assert "named pipe, not a regular file" in result.stderr
    assert run("run", str(fifo), timeout=5).exit_code == 2


def test_a_symlink_to_dev_zero_as_the_plan_is_refused_without_reading_it(tmp_path):
    link = tmp_path / "plan.yaml"
    link.symlink_to("/dev/zero")
    result = run("run", str(link), timeout=5)
    assert result.exit_code == 2
    assert "character device, not a regular file" in result.stderr


def test_a_folder_and_a_huge_file_are_input_errors(tmp_path):
    (tmp_path / "dir.yaml").mkdir()
    assert "a folder" in run("validate", str(tmp_path / "dir.yaml")).stderr
    huge = tmp_path / "huge.yaml"
    huge.write_text("body:\n" + "  - log: x\n" * 200_000)
    result = run("validate", str(huge))
    assert result.exit_code == 2 and "too large" in result.stderr and "the limit is 1 MiB" in result.stderr


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads files whatever their permissions")
def test_a_file_without_read_permission_is_an_input_error(tmp_path):
    path = a_plan(tmp_path, "- log: x\n")
    path.chmod(0)
    result = run("validate", str(path))
    assert result.exit_code == 2 and "permission denied" in result.stderr


def test_bytes_that_are_not_utf8_are_reported_at_their_line(tmp_path):
    path = tmp_path / "p.yaml"
    path.write_bytes(b"body:\n  - log: caf\xe9\n")
    result = run("validate", str(path))
    assert result.exit_code == 2 and f"{path}:2:13: not UTF-8 text" in result.stderr


# -- output paths --------------------------------------------------------------------------------------------


def test_an_output_path_that_cannot_be_written_is_exit_2_before_the_run(tmp_path):
    path = a_plan(tmp_path, "- log: ran\n")
    result = run("run", str(path), "--render", "/proc/pycram/x.png")
    assert result.exit_code == 2 and "/proc/pycram/x.png" in result.stderr and "cannot write" in result.stderr
    assert "ran" not in result.stderr  # nothing ran
    os.mkfifo(tmp_path / "out.json")
    result = run("run", str(path), "--trace", str(tmp_path / "out.json"), timeout=5)
    assert result.exit_code == 2 and "out.json: trace: cannot write: it is a named pipe" in result.stderr


def test_operating_system_errors_on_output_paths_are_exit_2_naming_the_path(tmp_path, monkeypatch):
    # Path.is_dir()/exists() raise OSError (ENAMETOOLONG) for a 300-character name: that was exit 3
    monkeypatch.chdir(tmp_path)
    plan = a_plan(tmp_path, "- log: ran\n")
    long = "x" * 300
    cases = {
        ("run", str(plan), "--trace", f"{long}.json"): "cannot write the trace: file name too long",
        ("run", str(plan), "--render", f"{long}.png"): "cannot write the image: file name too long",
        ("run", str(plan), "--report", f"{long}.html"): "cannot write the report: file name too long",
        ("world", "render", str(tmp_path / "w.yaml"), "-o", f"{long}.png"): "cannot write the image: file name too long",
        ("validate", long): "file name too long",
        ("validate", f"{long}.yaml"): "file name too long",
    }
    for args, message in cases.items():
        result = run(*args)
        assert result.exit_code == 2, (args[:3], result.output)
        assert message in result.stderr and "ran" not in result.stderr, (args[:3], result.stderr)
    write(tmp_path, "p.vary.yaml", "objects: {box: {noise: [0.1, 0, 0]}}\n")
    for out, why in (("/proc/pycram", "it cannot be made there"), (long, "file name too long")):
        result = run("sweep", str(plan), "-n", "1", "--workers", "1", "--out", out)
        assert result.exit_code == 2, (out[:20], result.output)
        assert f"--out: cannot use '{out}' as the results folder: {why}" in result.stderr


# -- YAML: merge keys work; aliases, nesting and sizes are bounded ------------------------------------------


def test_yaml_merge_keys_share_object_fields(tmp_path):
    world = write(tmp_path, "w.yaml", """
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - &box {name: a, type: box, file: cube_small.urdf, position: [0, 0, 0.025]}
          - {<<: *box, name: b, position: [1, 0, 0.025]}
    """)
    result = run("validate", str(world))
    assert result.exit_code == 0, result.output
    b = parse_world(world).objects[2]
    assert (b.name, b.type, b.position) == ("b", "box", [1, 0, 0.025])
    world.write_text(world.read_text().replace("name: b,", "name: b, name: c,"))
    result = run("validate", str(world))  # a key given twice by the mapping itself is still an error
    assert result.exit_code == 2 and "duplicate key 'name'" in result.stderr


def test_an_alias_bomb_as_a_log_message_is_refused_quickly(tmp_path):
    levels = ["a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    levels += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 9)}]" for i in range(1, 9)]
    path = tmp_path / "bomb.yaml"
    path.write_text("params:\n" + "".join(f"  {line}\n" for line in levels) + "body:\n  - log: $a8\n")
    result = run("validate", str(path), timeout=5)
    assert result.exit_code == 2
    assert f"{path}:" in result.stderr and "more than 100000 values once its aliases are expanded" in result.stderr


def test_an_alias_bomb_in_a_parameter_is_refused(tmp_path):
    plan = write(tmp_path, "p.yaml", "params: {x: 1}\nbody: [{log: $x}]\n")
    value = "&a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]"
    for i in range(1, 6):
        value = f"&a{i} [{value}, " + ", ".join([f"*a{i - 1}"] * 9) + "]"
    result = run("run", str(plan), "-p", f"x={value}", timeout=5)
    assert result.exit_code == 2 and "-p x" in result.stderr and "aliases" in result.stderr


def test_a_plan_with_too_many_values_is_refused_at_once_naming_the_limit(tmp_path):
    # a plain 40 000-step plan (0.8 MB, no alias) was refused after 14 s, blaming aliases
    from pycram_cli.limits import MAX_YAML_NODES

    path = tmp_path / "long.yaml"
    path.write_text("body:\n" + "".join(f"  - log: step {i}\n" for i in range(40_000)))
    started = time.monotonic()
    result = run("validate", str(path))
    assert time.monotonic() - started < 2.0
    assert result.exit_code == 2
    assert f"more than {MAX_YAML_NODES} values (lists, mappings and scalars) in one file, the limit" in result.stderr
    assert "alias" not in result.stderr


def test_nesting_deeper_than_the_limit_is_an_input_error(tmp_path):
    path = tmp_path / "deep.yaml"
    path.write_text("body:\n  - log: " + "[" * 10_000 + "]" * 10_000 + "\n")
    result = run("validate", str(path))
    assert result.exit_code == 2 and "nested deeper than 100 levels" in result.stderr


def test_a_null_key_in_an_object_is_reported_at_the_key(tmp_path):
    world = write(tmp_path, "w.yaml", """
        objects:
          - name: box
            type: box
            file: cube_small.urdf
            ~: 3
    """)
    result = run("validate", str(world))
    assert result.exit_code == 2 and f"{world}:6:5: null: keys must be names, got null" in result.stderr


def test_keys_that_are_not_names_in_slots_and_arguments_are_exit_2_at_the_key(tmp_path):
    # a null, number or boolean key where a slot, argument or field name belongs crashed the suggestion (exit 3)
    plan = write(tmp_path, "p.yaml", """
        world: kitchen
        plans:
          sub: {params: [a], body: [{log: $a}]}
        body:
          - looking: {~: 1, target: [1, 1, 1]}
          - assert: {stable: {~: milk}}
          - stable: {1: milk}
          - if: {visible: {true: milk}}
            then: [{log: x}]
          - call: sub
            args: {~: 1}
          - action: transport
            object-type: milk
            target: {~: x, on: kitchen_island_surface}
          - try: [{log: a}]
            catch: {2.5: [{log: b}]}
          - ~: 1
    """)
    result = run("validate", str(plan))
    assert result.exit_code == 2, result.output
    assert "internal error" not in result.stderr
    for where, key, what in [("6:15", "null", "null"), ("7:23", "null", "null"), ("8:14", "1", "the number 1"),
                             ("9:20", "true", "true"), ("12:12", "null", "null"), ("15:14", "null", "null"),
                             ("17:13", "2.5", "the number 2.5"), ("18:5", "null", "null")]:
        assert f"{plan}:{where}: {key}: keys must be names, got {what}" in result.stderr, (where, result.stderr)
    vary = write(tmp_path, "v.vary.yaml", """
        plan: set_table
        objects:
          ~: {noise: [0.1, 0, 0]}
        params:
          1: [a, b]
    """)
    result = run("validate", str(vary))
    assert result.exit_code == 2 and "internal error" not in result.stderr
    assert f"{vary}:4:3: null: keys must be names" in result.stderr and f"{vary}:6:3: 1: keys must be names" in result.stderr


def test_a_non_finite_mass_is_refused(tmp_path):
    world = small_world(tmp_path).read_text().replace("position: [0.5, 0, 0.025]", "mass: .nan")
    (tmp_path / "w.yaml").write_text(world)
    result = run("validate", str(tmp_path / "w.yaml"))
    assert result.exit_code == 2 and "w.yaml:4:57: mass: not a finite number: '.nan'" in result.stderr


# -- `-p` values are parsed strictly ----------------------------------------------------------------------------


def test_a_malformed_parameter_value_is_exit_2_before_anything_runs(tmp_path):
    plan = write(tmp_path, "p.yaml", "params: {types: [milk]}\nbody: [{log: ran $types}]\n")
    result = run("run", str(plan), "-p", "types=[milk")
    assert result.exit_code == 2
    assert "-p types:1:6: types: malformed YAML" in result.stderr
    assert "quote a value meant as text" in result.stderr
    assert "ran" not in result.stderr  # nothing ran


# -- corrupt traces: checked against the trace's own schema (with its version) --------------------------------


def saved_trace(tmp_path: Path) -> tuple[Path, dict]:
    import json

    plan = a_plan(tmp_path, """
        - log: hello
        - try_all: [{fail: PerceptionFailure}, {log: b}]
    """)
    out = tmp_path / "t.json"
    assert run("run", str(plan), "--trace", str(out)).exit_code == 0
    data = json.loads(out.read_text())
    data["final_state"]["attachments"] = [{"parent": "floor", "child": "box", "parent_link": "planeLink",
                                           "child_link": "baseLink"}]
    return out, data


def test_a_trace_whose_attachment_lacks_parent_says_which_entry_and_what_is_missing(tmp_path):
    import json

    out, data = saved_trace(tmp_path)
    del data["final_state"]["attachments"][0]["parent"]
    out.write_text(json.dumps(data, indent=2))
    line = next(i for i, text in enumerate(out.read_text().splitlines(), 1) if '"child": "box"' in text) - 1
    for command in (["trace", "show", str(out)], ["trace", "diff", str(out), str(out)]):
        result = run(*command)
        assert result.exit_code == 2, result.output
        assert f"{out}:{line}:7: final_state.attachments[0]: an attachment needs 'parent'" in result.stderr


def test_corrupt_traces_are_input_errors_never_internal_ones(tmp_path):
    import json

    out, data = saved_trace(tmp_path)
    broken = {
        "a node without status": lambda d: d["root"]["children"][0].pop("status"),
        "a designator record that is a string": lambda d: d["root"]["children"][0].update(designator="x"),
        "children that are not a list": lambda d: d["root"].update(children=3),
        "a position of two numbers": lambda d: d["final_state"]["objects"]["box"].update(position=[1, 2]),
        "an unknown status": lambda d: d["root"].update(status="exploded"),
        "another version": lambda d: d.update(version=99),
        "a failure without type": lambda d: d["root"]["children"][1].update(failure={"message": "m"}),
    }
    for what, change in broken.items():
        copy = json.loads(json.dumps(data))
        change(copy)
        out.write_text(json.dumps(copy))
        result = run("trace", "show", str(out))
        assert result.exit_code == 2, (what, result.output)
        assert f"{out}:1:" in result.stderr, (what, result.stderr)
    out.write_text(json.dumps(data).replace('"status": "succeeded"', '"status": NaN', 1))
    result = run("trace", "show", str(out))
    assert result.exit_code == 2 and "not a finite number: NaN" in result.stderr
    out.write_text("[" * 100_000 + "]" * 100_000)
    assert run("trace", "show", str(out)).exit_code == 2
    out.write_text(json.dumps(data)[:1000])
    assert "not a JSON trace" in run("trace", "show", str(out)).stderr


def test_a_corrupt_replay_record_is_an_input_error_naming_the_entry(tmp_path):
    # `trace show --report` of a trace whose `replay` was corrupted: exit 3, or exit 0 with a wrong report
    import json

    out, data = saved_trace(tmp_path)
    del data["final_state"]["attachments"]
    report = tmp_path / "r.html"
    broken = {
        "replay.steps: expected a list of steps": lambda r: r.update(steps=3),
        "replay.steps[0].changed: expected an object, got a list": lambda r: r["steps"][0].update(changed=[1]),
        "replay.initial.box.position: expected a position: a list of 3 numbers":
            lambda r: r["initial"]["box"].update(position=[1, 2]),
        "replay.initial.box.orientation: expected a quaternion of unit length":
            lambda r: r["initial"]["box"].update(orientation=[0, 0, 0, 0]),
        "replay.steps[1].changed.fridge: no object 'fridge' in the trace's final state":
            lambda r: r["steps"][1]["changed"].update(fridge={"position": [0, 0, 0], "orientation": [0, 0, 0, 1]}),
        'replay.steps[0].path: no step of the trace has the path "body/9:log"':
            lambda r: r["steps"][0].update(path="body/9:log"),
        "replay: the replay record needs 'initial'": lambda r: r.pop("initial"),
        "replay.steps[0].physics[0].t: expected a number of seconds from 0 to 1e+06":
            lambda r: r["steps"][0].update(physics=[{"t": -1, "changed": {}}]),
        "replay.steps[0].physics[0].changed.box.position: expected a position: a list of 3 numbers":
            lambda r: r["steps"][0].update(physics=[{"t": 0.05, "changed": {"box": {"position": [0], "orientation": [0, 0, 0, 1]}}}]),
        "replay.steps[0].candidates: a candidate map needs two coordinates ('xy') for each outcome":
            lambda r: r["steps"][0].update(candidates={"kind": "base", "z": 0, "spacing": 0.05, "xy": [1, 2, 3],
                                                       "outcome": [0], "outcomes": ["ok"], "found": []}),
        "replay.steps[0].candidates.found: expected a list of poses [x, y, yaw]":
            lambda r: r["steps"][0].update(candidates={"kind": "base", "z": 0, "spacing": 0.05, "xy": [1, 2],
                                                       "outcome": [0], "outcomes": ["ok"], "found": "here"}),
    }
    for message, change in broken.items():
        copy = json.loads(json.dumps(data))
        change(copy["replay"])
        out.write_text(json.dumps(copy, indent=1))
        result = run("trace", "show", str(out), "--report", str(report))
        assert result.exit_code == 2, (message, result.output)
        assert re.search(rf"{re.escape(str(out))}:\d+:\d+: {re.escape(message)}", result.stderr), (message, result.stderr)
        assert not report.exists()


def test_a_trace_nested_too_deep_is_refused_at_its_line_and_column_with_the_documented_limit(tmp_path):
    from pycram_cli.plan.trace_schema import MAX_JSON_DEPTH

    out = tmp_path / "t.json"
    out.write_text('{"format": "pycram-trace",\n "x": ' + "[" * 10_000 + "]" * 10_000 + "}")
    result = run("trace", "show", str(out))
    assert result.exit_code == 2
    assert f"{out}:2:{7 + MAX_JSON_DEPTH - 1}: not a pycram trace: nested deeper than {MAX_JSON_DEPTH} levels" \
           in result.stderr
    readme = (REPO / "README.md").read_text()
    assert f"trace files: {MAX_JSON_DEPTH} levels of JSON" in readme


def test_trace_diff_json_never_prints_a_bare_nan_and_refuses_a_nan_tolerance(tmp_path):
    import json

    out, data = saved_trace(tmp_path)
    result = run("trace", "diff", str(out), str(out), "--atol", "nan")
    assert result.exit_code == 2 and "--atol" in result.stderr
    other = tmp_path / "other.json"
    data["final_state"]["objects"]["box"]["position"][0] += 1
    other.write_text(json.dumps(data))
    result = run("trace", "diff", str(out), str(other), "--json")
    assert result.exit_code == 1
    assert "NaN" not in result.stdout and json.loads(result.stdout)["same"] is False


# -- numbers outside what the runtime can do ------------------------------------------------------------------


def test_numbers_beyond_what_the_runtime_can_do_are_input_errors(tmp_path):
    plan = a_plan(tmp_path, """
        - wait: 1.0e+10
        - retry: 10000000000
          body: [{log: x}]
        - moving: {target: [1.0e+300, 0, 0]}
    """)
    result = run("validate", str(plan))
    assert result.exit_code == 2
    assert f"{plan}:4:11: wait: at most 86400 seconds (one day) can be waited for" in result.stderr
    assert f"{plan}:5:12: retry: at most 1000000000 retries" in result.stderr
    assert "numbers must be between -1e+06 and 1e+06" in result.stderr
    assert run("run", str(plan), "--pace", "nan").exit_code == 2


def test_sweep_numbers_are_finite_and_within_their_documented_maxima(tmp_path):
    from pycram_cli.limits import MAX_SWEEP_RUNS, MAX_WORKERS

    plan = a_plan(tmp_path, "- log: ran\n")
    write(tmp_path, "p.vary.yaml", "objects: {box: {noise: [0.1, 0, 0]}}\n")
    cases = {("--timeout", "nan"): "--timeout: expected a number of seconds above 0 and at most 86400",
             ("--timeout", "inf"): "--timeout: expected a number of seconds",
             ("--timeout", "1e300"): "--timeout: expected a number of seconds",
             ("-n", str(MAX_SWEEP_RUNS + 1)): f"-n: at most {MAX_SWEEP_RUNS} scenarios (the limit)",
             ("--workers", str(MAX_WORKERS + 1)): f"--workers: expected between 1 and {MAX_WORKERS} workers"}
    for option, message in cases.items():
        result = run("sweep", str(plan), "--out", str(tmp_path / "out"), *option)
        assert result.exit_code == 2 and message in result.stderr, (option, result.output)
        assert not (tmp_path / "out").exists()  # refused before the results folder is made


def test_a_camera_out_of_range_or_without_direction_is_refused_and_a_view_straight_down_is_drawn(tmp_path):
    import numpy as np
    from PIL import Image

    plan = a_plan(tmp_path, "- log: ran\n")
    image = str(tmp_path / "x.png")
    for camera, message in (("1e300,0,0:0,0,0", "camera eye: numbers must be between -1e+06 and 1e+06"),
                            ("1,1,1:1,1,1", "the camera's eye and target must differ")):
        for args in (("world", "render", str(tmp_path / "w.yaml"), "-o", image), ("run", str(plan), "--render", image)):
            result = run(*args, "--size", "32x24", f"--camera={camera}")
            assert result.exit_code == 2 and f"--camera: {message}" in result.stderr, (args[0], result.output)
    result = run("world", "render", str(tmp_path / "w.yaml"), "-o", image, "--size", "64x48",
                 "--camera=0.5,0,3:0.5,0,0")  # looking straight down, along the camera's up: was a blank image
    assert result.exit_code == 0, result.output
    assert np.asarray(Image.open(image)).std() > 1.0


def test_a_wait_or_a_slot_given_a_known_parameter_value_is_checked_before_the_run(tmp_path):
    # `wait: $t` with `-p t=1.0e+10` validated and then failed at run time (exit 1)
    path = write(tmp_path, "p.yaml", """
        world: kitchen
        params: {t: 1, far: [0, 0, 0]}
        body:
          - wait: $t
          - moving: {target: $far}
    """)
    result = run("run", str(path), "-p", "t=1.0e+10", "-p", "far=[1.0e+300, 0, 0]")
    assert result.exit_code == 2, result.output
    assert f"{path}:5:11: wait: at most 86400 seconds (one day) can be waited for, got 1e+10 ($t)" in result.stderr
    assert f"{path}:6:22: target: slot 'target': expected a position [x, y, z] (numbers must be between" \
           in result.stderr and "($far)" in result.stderr
    assert run("validate", str(path)).exit_code == 0  # the defaults are fine


def test_a_nan_wait_is_refused(tmp_path):
    plan = a_plan(tmp_path, "- wait: .nan\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2 and "wait: not a finite number: '.nan'" in result.stderr


# -- validation finds what the run would find out later -----------------------------------------------------


def test_object_link_and_joint_names_in_every_slot_are_checked_against_the_world(tmp_path):
    plan = write(tmp_path, "p.yaml", """
        world: kitchen
        params: {thing: fridge}
        body:
          - looking: {object: $thing}
          - accessing: {drawer-handle: sink_area_left_upper_drawer_handl, part-of: kitchen,
                        drawer-joint: sink_area_left_upper_drawer_main_joit}
          - accessing: {drawer-handle: sink_area_left_upper_drawer_handle, part-of: kitchn,
                        drawer-joint: sink_area_left_upper_drawer_main_joint}
          - for_each: [milk, fridge2]
            as: o
            do: [{looking: {object: $o}}]
          - supporting: {a: kitchen, b: milk, link: kitchen_island_surfac}
          - visible: {object: milk, from: wide_stereo_optical_fram}
          - move-arm-joints: {arms: {left: {l_elbow_flex_jont: 0.1}}}
    """)
    result = run("validate", str(plan))
    assert result.exit_code == 2
    expected = [
        "5:23: object: 'object': the world has no object 'fridge' ($thing)",
        "6:32: drawer-handle: 'drawer-handle': object 'kitchen' has no link 'sink_area_left_upper_drawer_handl' "
        "(did you mean 'sink_area_left_upper_drawer_handle'?)",
        "7:31: drawer-joint: 'drawer-joint': object 'kitchen' has no movable joint",
        "8:77: part-of: 'part-of': the world has no object 'kitchn' (did you mean 'kitchen'?)",
        "12:29: object: 'object': the world has no object 'fridge2' ($o)",
        "13:45: link: 'link': object 'kitchen' has no link 'kitchen_island_surfac'",
        "14:35: from: 'from': robot 'pr2' has no link 'wide_stereo_optical_fram'",
        "'l_elbow_flex_jont' is not a joint of the left arm (did you mean 'l_elbow_flex_joint'?)",
    ]
    for line in expected:
        assert line in result.stderr, (line, result.stderr)
    result = run("run", str(plan), "-p", "thing=milk")
    assert "no object 'fridge' ($thing)" not in result.stderr and result.exit_code == 2


def test_the_joint_of_open_and_close_actions_is_checked_against_the_handles_object(tmp_path):
    # `action: open` with `joint: nojoint` validated, then failed at run time (exit 1)
    plan = write(tmp_path, "p.yaml", """
        world: kitchen
        params: {j: sink_area_left_upper_drawer_main_joit}
        body:
          - action: open
            joint: nojoint
          - action: close
            joint: $j
            part-of: kitchen
          - action: open
            handle: sink_area_left_upper_drawer_handle
            joint: nojoint
          - action: open
            handle: sink_area_left_upper_drawer_handle
            part-of: milk
          - action: open
            joint: sink_area_left_upper_drawer_main_joint
    """)
    result = run("validate", str(plan))
    assert result.exit_code == 2
    expected = [
        "6:12: joint: 'joint': the world (the robot aside) has no movable joint 'nojoint'",
        "8:12: joint: 'joint': object 'kitchen' has no movable joint 'sink_area_left_upper_drawer_main_joit' ($j) "
        "(did you mean 'sink_area_left_upper_drawer_main_joint'?)",
        "12:12: joint: 'joint': object 'kitchen' has no movable joint 'nojoint'",
        "14:13: handle: 'handle': object 'milk' has no link 'sink_area_left_upper_drawer_handle'",
    ]
    for line in expected:
        assert f"{plan}:{line}" in result.stderr, (line, result.stderr)
    assert result.stderr.count("error:") == len(expected)  # the last step is right


def test_attachment_cycles_and_empty_names_in_worlds_are_refused(tmp_path):
    world = write(tmp_path, "w.yaml", """
        objects:
          - {name: milk, type: milk, file: objects/milk.obj, attach: [cereal]}
          - {name: cereal, type: cereal, file: objects/milk.obj, attach: [{to: milk}]}
          - {name: "", type: bowl, file: objects/bowl.obj}
    """)
    result = run("validate", str(world))
    assert result.exit_code == 2
    assert f"{world}:4:67: attach: attachments go round in a circle: milk -> cereal -> milk" in result.stderr
    assert f"{world}:5:12: name: the object's name must not be empty" in result.stderr


def test_a_location_on_line_100_is_printed_as_it_is(tmp_path):
    # rich read ":100:" as an emoji code and printed the location as "file💯3"
    plan = a_plan(tmp_path, "".join("- log: x\n" for _ in range(97)) + "- lgo: y\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2 and f"{plan}:100:5: lgo: unknown node type 'lgo'" in result.stderr


def test_a_broken_mesh_is_found_by_validation_not_by_the_run(tmp_path):
    (tmp_path / "empty.obj").write_text("")
    (tmp_path / "short.obj").write_text("v 1 2\nf 1 2 3\n")
    world = write(tmp_path, "w.yaml", """
        objects:
          - {name: a, type: box, file: empty.obj}
          - {name: b, type: box, file: short.obj}
    """)
    result = run("validate", str(world))
    assert result.exit_code == 2
    assert f"{world}:3:32: file: cannot read model file empty.obj: the mesh has no triangles" in result.stderr
    assert "a vertex needs three coordinates" in result.stderr


# -- model files (issue 29): what PyBullet cannot load is found by validate, named; odd names load ---------------


def world_with_model(tmp_path: Path, file: str) -> Path:
    return write(tmp_path, "w.yaml", f"""
        objects:
          - {{name: floor, type: environment, file: plane.urdf}}
          - name: thing
            type: box
            file: '{file}'
    """)


@pytest.mark.parametrize("model, message", [
    ('<robot name="x"></robot>', "the model has no <link>"),
    ('<model name="x"><link name="a"/></model>', "the root element is <model>, not <robot>"),
    ('<robot name="x"><link name="a"/><link name="b"/>'
     '<joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>'
     '<joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint></robot>', "the joints j1, j2 form a cycle"),
    ('<robot name="x"><link name="a"><visual><geometry><mesh filename="package://x/../../../etc/passwd"/></geometry>'
     '</visual></link></robot>', "mesh 'package://x/../../../etc/passwd' leaves its package 'x'"),
])
def test_a_model_file_pybullet_cannot_load_is_exit_2_at_validate_and_at_run_naming_file_and_element(tmp_path, model, message):
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "m.urdf").write_text(model)
    world = world_with_model(tmp_path, "x/m.urdf")
    for command in (("validate", str(world)), ("world", "show", str(world))):
        result = run(*command)
        assert result.exit_code == 2, result.output
        assert f"{world}:6:11: file: cannot read model file m.urdf: {message}" in result.stderr


def test_a_mesh_named_with_xml_metacharacters_validates_and_loads(tmp_path):
    import shutil
    shutil.copy(REPO / "resources" / "objects" / "milk.obj", tmp_path / 'm"i<l>k&.obj')
    world = world_with_model(tmp_path, "m\"i<l>k&.obj")
    assert run("validate", str(world)).exit_code == 0
    result = run("world", "show", str(world))
    assert result.exit_code == 0, result.output
    assert "thing" in result.output


def test_a_missing_mesh_is_a_validate_warning_naming_the_file(tmp_path):
    (tmp_path / "m.urdf").write_text('<robot name="x"><link name="a"><visual><geometry><mesh filename="gone.obj"/>'
                                     '</geometry></visual></link></robot>')
    world = world_with_model(tmp_path, "m.urdf")
    result = run("validate", str(world))
    assert result.exit_code == 0
    assert f"warning: {world}:4:5: object 'thing': mesh file not found, loaded without it: gone.obj" in result.stderr
