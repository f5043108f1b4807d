"""Where a run failed: the failed steps, what they name, the place meant for their object, and a camera on both."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pycram_cli.report.failures import Focus, failed_leaves, failure_camera, focus

REPO = Path(__file__).resolve().parents[2]
FAILING = {"jobs": [{"type": "milk", "target": [-0.65, 1.0, 0.862], "arm": "left", "look": [1.3, 0.8, 0.95]}]}


def _tree(*leaves):
    return {"path": "body", "status": "failed", "children": list(leaves)}


def test_the_focus_of_a_failed_check_is_its_object_and_where_an_earlier_step_put_it():
    place = {"path": "body/0:place", "status": "succeeded",
             "designator": {"slots": {"object": "milk"}, "resolved": {"object": "milk", "target": [1, 2, 0.9], "arm": "left"}}}
    other = {"path": "body/1:place", "status": "succeeded",
             "designator": {"resolved": {"object": "bowl", "target": [5, 5, 0.9]}}}
    check = {"path": "body/2:assert", "status": "failed", "failure": {"type": "ReasoningFailure", "message": "m"},
             "condition": {"not": {"query": {"name": "stable", "args": {"object": "milk"}, "result": False}}}}
    root = _tree(place, other, check)
    assert failed_leaves(root) == [check]
    assert focus(root, check, {"milk", "bowl"}) == Focus(("milk",), (1.0, 2.0, 0.9), "body/0:place")
    # a step that names its place itself is its own target; one that names nothing known has no focus
    assert focus(root, place, {"milk"}) == Focus(("milk",), (1.0, 2.0, 0.9), "body/0:place")
    assert focus(root, check, {"bowl"}) == Focus((), None, None)


def test_a_failed_runs_camera_frames_the_object_and_its_target():
    from pycram_cli.scenario import prepare

    scenario = prepare(REPO / "plans" / "set_table.yaml", params=FAILING)
    world = scenario.load_world()
    try:
        result = scenario.run(world)
        assert result.status == "failed"
        camera = failure_camera(world, result.trace, 4 / 3)
        assert camera is not None
        milk = world.get_object_by_name("milk")
        lo, hi = milk.get_aabb()
        points = [tuple((a + b) / 2 for a, b in zip(lo, hi)), (-0.65, 1.0, 0.862)]
        eye, target = np.array(camera.eye), np.array(camera.target)
        forward = (target - eye) / np.linalg.norm(target - eye)
        for point in points:  # both within the camera's field of view, in front of it
            to = np.array(point) - eye
            angle = math.degrees(math.acos(float(np.dot(to, forward) / np.linalg.norm(to))))
            assert angle < camera.vertical_fov_deg / 2, (point, angle)
        assert eye[2] > 0.5  # from above, not from the floor
    finally:
        world.exit()


def test_render_of_a_failed_run_frames_the_failure_unless_a_view_is_named(tmp_path):
    import json

    from click.testing import CliRunner
    from PIL import Image

    from pycram_cli.cli.main import cli

    images = {}
    for name, extra in (("failure", []), ("overview", ["--camera", "overview"])):
        out = tmp_path / f"{name}.png"
        result = CliRunner().invoke(cli, ["run", "set_table", "-p", f"jobs={json.dumps(FAILING['jobs'])}",
                                          "--render", str(out), "--size", "320x240", *extra])
        assert result.exit_code == 1 and out.is_file(), result.output
        images[name] = np.asarray(Image.open(out).convert("RGB")).astype(int)
    assert np.abs(images["failure"] - images["overview"]).mean() > 20  # another view: close on the failure
