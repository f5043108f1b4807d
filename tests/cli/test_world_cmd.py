"""`pycram world show|render` and `pycram validate` from a user's point of view."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys

from click.testing import CliRunner

from pycram_cli.cli.main import cli


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def small_world(tmp_path, data_dir):
    path = tmp_path / "w.yaml"
    path.write_text(f"objects:\n  - {{name: floor, type: environment, file: plane.urdf}}\n"
                    f"  - {{name: arm, type: robot, file: {data_dir}/arm.urdf, joints: {{slide: 0.1}}}}\n"
                    f"  - {{name: cube, type: box, file: {data_dir}/cube.obj, position: [0.5, 0, 0]}}\n")
    return path


def test_world_show_lists_objects_with_type_file_position_and_joints(tmp_path, data_dir):
    result = run("world", "show", str(small_world(tmp_path, data_dir)))
    assert result.exit_code == 0, result.output
    for text in ("floor", "environment", "plane.urdf", "cube", "(0.500, 0.000, 0.000)"):
        assert text in result.output
    assert re.search(r"slide +0\.100 m +\[0\.000, 0\.200\]", result.output)
    assert "links     4: base, upper, slider, hand" in result.output


def test_world_show_json_is_machine_readable(tmp_path, data_dir):
    result = run("world", "show", str(small_world(tmp_path, data_dir)), "--json")
    data = json.loads(result.stdout)
    assert [o["name"] for o in data["objects"]] == ["floor", "arm", "cube"]
    assert data["robot"] == "arm"
    assert data["objects"][1]["movable_joints"]["slide"] == 0.1


def test_world_show_fits_80_columns_and_names_every_movable_joint_with_limits_and_every_link():
    result = subprocess.run([sys.executable, "-m", "pycram_cli.cli.main", "world", "show"], capture_output=True,
                            text=True, env={**os.environ, "COLUMNS": "80"})
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert max(len(line) for line in lines) <= 80, "\n".join(line for line in lines if len(line) > 80)
    # one block per object; the kitchen's drawers by joint (value, limits) and handle link, as `accessing` needs them
    assert "kitchen  environment, fixed" in lines
    joint = next(line for line in lines if "sink_area_left_upper_drawer_main_joint" in line)
    assert re.search(r"0\.000 m +\[0\.000, 0\.480\]", joint)
    assert "sink_area_left_upper_drawer_handle" in result.stdout
    # the robot's links (for `--from`) and its continuous joints, which have no limits
    assert "wide_stereo_optical_frame" in result.stdout
    assert re.search(r"r_forearm_roll_joint +-?\d\.\d{3} rad +continuous", result.stdout)


def test_world_show_json_lists_joints_with_limits_and_links():
    data = json.loads(run("world", "show", "--json").stdout)
    kitchen = next(o for o in data["objects"] if o["name"] == "kitchen")
    assert {"name": "sink_area_left_upper_drawer_main_joint", "type": "prismatic", "value": 0.0, "lower": 0.0,
            "upper": 0.48} in kitchen["joints"]
    assert "sink_area_left_upper_drawer_handle" in kitchen["links"]
    pr2 = next(o for o in data["objects"] if o["name"] == "pr2")
    roll = next(j for j in pr2["joints"] if j["name"] == "r_forearm_roll_joint")
    assert roll["type"] == "continuous" and roll["lower"] is None and roll["upper"] is None


def test_world_render_writes_a_png(tmp_path, data_dir):
    out = tmp_path / "scene.png"
    result = run("world", "render", str(small_world(tmp_path, data_dir)), "-o", str(out), "--size", "64x48",
                 "--camera", "2,2,2:0,0,0")
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_camera_is_an_input_error(tmp_path, data_dir):
    result = run("world", "render", str(small_world(tmp_path, data_dir)), "--camera", "1,2")
    assert result.exit_code == 2 and "expected EYE:TARGET" in result.output


def test_validate_reports_every_problem_and_exits_2_without_traceback(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n    postion: [0, 0, 0]\n")
    result = subprocess.run([sys.executable, "-m", "pycram_cli.cli.main", "validate", str(bad)],
                            capture_output=True, text=True)
    assert result.returncode == 2
    assert f"{bad}:5:5: postion: unknown key 'postion'" in result.stderr
    assert "Traceback" not in result.stderr + result.stdout


def test_validate_accepts_a_good_world(tmp_path, data_dir):
    result = run("validate", str(small_world(tmp_path, data_dir)))
    assert result.exit_code == 0 and "valid world file" in result.output


def test_a_missing_world_file_is_an_input_error():
    result = run("world", "show", "no_such_world.yaml")
    assert result.exit_code == 2 and "world file not found" in result.output


def test_pybullet_console_noise_stays_off_the_terminal(tmp_path, data_dir):
    result = subprocess.run([sys.executable, "-m", "pycram_cli.cli.main", "world", "show",
                             str(small_world(tmp_path, data_dir))], capture_output=True, text=True)
    assert result.returncode == 0
    assert "pybullet build time" not in result.stdout + result.stderr
    assert "b3Printf" not in result.stdout + result.stderr


def test_world_render_format_follows_the_extension_and_views_are_named(tmp_path, data_dir):
    world = small_world(tmp_path, data_dir)
    out = tmp_path / "scene.jpg"
    result = run("world", "render", str(world), "-o", str(out), "--size", "80x60", "--camera", "robot")
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:3] == b"\xff\xd8\xff"  # JPEG
    assert f"wrote {out} (80x60 JPEG)" in result.stderr and result.stdout == ""
    for view in ("overview", "target"):
        assert run("world", "render", str(world), "-o", str(tmp_path / f"{view}.png"), "--size", "32x32",
                   "--camera", view).exit_code == 0


def test_world_render_output_problems_are_input_errors_naming_the_file(tmp_path, data_dir):
    world = small_world(tmp_path, data_dir)
    for out, message in ((tmp_path / "scene.gif", "cannot tell the image's format from '.gif'"),
                         (tmp_path / "no" / "such" / "scene.png", "does not exist"),
                         (tmp_path, "is a directory")):
        result = run("world", "render", str(world), "-o", str(out))
        assert result.exit_code == 2, result.output
        assert str(out) in result.stderr and message in result.stderr
    result = run("world", "render", str(world), "--camera", "robt")
    assert result.exit_code == 2 and "did you mean 'robot'?" in result.stderr
