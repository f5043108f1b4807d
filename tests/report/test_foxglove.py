"""`pycram run --mcap` and `pycram trace show --mcap`: the replay as an MCAP file for Foxglove, read back here with
the MCAP project's own reader, message by message."""
from __future__ import annotations

import base64
import io
import json
import re
from collections import defaultdict
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from mcap.reader import make_reader
from PIL import Image

from pycram_cli.cli.main import cli
from pycram_cli.report.foxglove import STEP_NS
from pycram_cli.report.foxglove_scene import stl_bytes

FAILING = "jobs=[{type: milk, target: [-0.65, 1.0, 0.862], arm: left, look: [1.3, 0.8, 0.95]}]"


def run(*args: str):
    return CliRunner().invoke(cli, [str(a) for a in args])


def read(path: Path) -> dict[str, list[tuple[int, dict]]]:
    """topic -> [(log time, message)], with every channel's schema a Foxglove JSON schema."""
    found: dict[str, list[tuple[int, dict]]] = defaultdict(list)
    with path.open("rb") as stream:
        for schema, channel, message in make_reader(stream).iter_messages(log_time_order=True):
            assert channel.message_encoding == "json" and schema.encoding == "jsonschema"
            assert schema.name.startswith("foxglove.")
            assert json.loads(schema.data)["title"] == schema.name
            found[channel.topic].append((message.log_time, json.loads(message.data)))
    return found


@pytest.fixture(scope="module")
def set_table(tmp_path_factory):
    folder = tmp_path_factory.mktemp("mcap")
    result = run("run", "set_table", "--mcap", folder / "run.mcap", "--trace", folder / "run.json")
    assert result.exit_code == 0, result.output
    assert f"wrote {folder / 'run.mcap'} (MCAP replay" in result.stderr
    return folder / "run.mcap", json.loads((folder / "run.json").read_text())


def test_the_file_is_as_small_as_the_readme_says(set_table):
    assert set_table[0].stat().st_size < 300_000  # README: "set_table's: under 0.3 MB"


def test_every_body_is_a_scene_entity_at_the_start(set_table):
    topics = read(set_table[0])
    [(time, update)] = topics["/scene"]
    assert time == 0
    bodies = defaultdict(set)
    for entity in update["entities"]:
        meta = {pair["key"]: pair["value"] for pair in entity["metadata"]}
        if "link" in meta:
            assert entity["frame_locked"] and entity["frame_id"] == f"{meta['body']}/{meta['link']}"
            bodies[meta["body"]].add(meta["link"])
    trace = set_table[1]
    assert set(bodies) == set(trace["replay"]["initial"]) == {"floor", "pr2", "kitchen", "milk", "cereal", "bowl",
                                                             "spoon", "bottle"}
    assert len(bodies["pr2"]) > 20 and "l_gripper_l_finger_link" in bodies["pr2"]  # every drawn link, not only the base
    milk = next(e for e in update["entities"] if e["id"] == "milk/" + next(iter(bodies["milk"])))
    [model] = milk["models"]  # the milk's mesh, as the model has it, embedded as an STL model
    assert model["media_type"] == "model/stl"
    stl = base64.b64decode(model["data"])
    triangles = int.from_bytes(stl[80:84], "little")
    assert triangles > 10 and len(stl) == 84 + 50 * triangles
    labels = {e["texts"][0]["text"] for e in update["entities"] if e.get("texts")}
    assert labels == {"pr2", "milk", "cereal", "bowl", "spoon", "bottle"}  # the scenery is not labelled


def test_one_log_message_per_step_and_every_frame_after_each(set_table):
    topics = read(set_table[0])
    assert "/failures" not in topics  # nothing failed
    steps = set_table[1]["replay"]["steps"]
    logs = topics["/plan"]
    assert len(logs) == len(steps) == 67
    assert [time for time, _ in logs] == [k * STEP_NS for k in range(1, len(steps) + 1)]
    for (_, log), step in zip(logs, steps):
        assert log["message"].startswith(step["path"]) and log["level"] == 2 and log["file"] == "set_table.yaml"
    assert "object-type=bowl" in logs[0][1]["message"] and logs[0][1]["line"] > 0
    transforms = topics["/tf"]
    assert [time for time, _ in transforms] == [k * STEP_NS for k in range(len(steps) + 1)]
    frames = {t["child_frame_id"] for t in transforms[0][1]["transforms"]}
    assert all({t["child_frame_id"] for t in message["transforms"]} == frames for _, message in transforms)
    # after the last step, the milk's frame is where the run left it
    milk = next(t for t in transforms[-1][1]["transforms"] if t["child_frame_id"].startswith("milk/"))
    final = set_table[1]["final_state"]["objects"]["milk"]["position"]
    assert np.allclose([milk["translation"][axis] for axis in "xyz"], final, atol=1e-3)
    start = next(t for t in transforms[0][1]["transforms"] if t["child_frame_id"] == milk["child_frame_id"])
    assert not np.allclose([start["translation"][a] for a in "xyz"], final, atol=0.1)  # it was moved


def _rotation(q: dict) -> np.ndarray:
    x, y, z, w = q["x"], q["y"], q["z"], q["w"]
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def _nodes(node: dict, into: dict) -> dict:
    into[node["path"]] = node
    for child in node.get("children") or []:
        _nodes(child, into)
    return into


def test_the_camera_images_are_what_the_robot_saw_when_it_detected(set_table):
    topics = read(set_table[0])
    steps = set_table[1]["replay"]["steps"]
    detecting = [k for k, step in enumerate(steps, start=1) if step["path"].endswith(":detecting")]
    assert detecting and [time // STEP_NS for time, _ in topics["/camera/image"]] == detecting
    assert [t for t, _ in topics["/camera/calibration"]] == [t for t, _ in topics["/camera/tf"]] == \
        [t for t, _ in topics["/camera/image"]]
    nodes = _nodes(set_table[1]["root"], {})
    for (time, message), (_, calibration), (_, frames) in zip(topics["/camera/image"], topics["/camera/calibration"],
                                                             topics["/camera/tf"]):
        assert message["format"] == "png"
        image = np.asarray(Image.open(io.BytesIO(base64.b64decode(message["data"]))).convert("RGB")).astype(int)
        assert image.shape[1] == 320 and len(np.unique(image.reshape(-1, 3) // 16, axis=0)) > 20  # a scene, not blank
        assert (calibration["width"], calibration["height"]) == (image.shape[1], image.shape[0])
        [frame] = frames["transforms"]
        assert frame["child_frame_id"] == message["frame_id"] == calibration["frame_id"]
        assert frame["parent_frame_id"] == "world" and re.fullmatch(r"pr2/\w+/optical", frame["child_frame_id"])
        # the point the head looked at (the step before) projects near the middle of the picture
        looked = nodes[steps[time // STEP_NS - 2]["path"]]
        assert looked["type"] == "looking"
        target = np.array(looked["designator"]["resolved"]["target"])
        origin = np.array([frame["translation"][a] for a in "xyz"])
        local = _rotation(frame["rotation"]).T @ (target - origin)
        assert local[2] > 0.3  # in front of the camera
        fx, _, cx, _, fy, cy = calibration["K"][:6]
        u, v = fx * local[0] / local[2] + cx, fy * local[1] / local[2] + cy
        assert abs(u - cx) < 0.15 * calibration["width"] and abs(v - cy) < 0.15 * calibration["height"], (u, v)


def test_the_metadata_names_the_run(set_table):
    with set_table[0].open("rb") as stream:
        [record] = list(make_reader(stream).iter_metadata())
    assert record.name == "pycram"
    assert record.metadata == {"plan": "set_table.yaml", "world": "kitchen.yaml", "status": "succeeded", "steps": "67",
                               "not drawn": ""}


def test_the_real_pr2_in_the_real_kitchen_is_drawn_with_its_own_meshes(real_kitchen, tmp_path):
    """../shared/models (skipped when absent): every body, the robot's detailed meshes as models, nothing left out."""
    path = tmp_path / "real.mcap"
    job = "jobs=[{type: milk, target: [-0.8, 1.0, 0.862], arm: left, look: [1.3, 0.8, 0.95]}]"
    result = run("run", "set_table", "--world", tmp_path / "real_kitchen.yaml", "-p", job, "--mcap", path)
    assert result.exit_code == 0, result.output
    [(_, update)] = read(path)["/scene"]
    bodies = {pair["value"] for e in update["entities"] for pair in e["metadata"] if pair["key"] == "body"}
    assert bodies == {w.name for w in real_kitchen.objects}
    robot_models = [m for e in update["entities"] if e["id"].startswith("pr2/") for m in e.get("models", [])]
    assert len(robot_models) > 30
    collada = [m for m in robot_models if m["media_type"] == "model/vnd.collada+xml"]
    assert collada and all(b"<COLLADA" in base64.b64decode(m["data"])[:2000] and not m["override_color"]
                           for m in collada)  # embedded as the model has it, with its own materials
    with path.open("rb") as stream:
        [record] = list(make_reader(stream).iter_metadata())
    assert record.metadata["not drawn"] == "" and record.metadata["status"] == "succeeded"


def test_a_failure_is_an_error_in_the_log(tmp_path):
    path = tmp_path / "fail.mcap"
    result = run("run", "set_table", "-p", FAILING, "--mcap", path)
    assert result.exit_code == 1
    logs = read(path)["/plan"]
    *before, (_, last) = logs
    assert last["level"] == 4 and "ReasoningFailure: milk is not stable where it was placed" in last["message"]
    assert all(log["level"] == 2 for _, log in before)
    # in the 3D view: the failure written above the milk, where it ended up, marked by a red sphere
    [(time, update)] = read(path)["/failures"]
    assert time == len(logs) * STEP_NS
    [marker] = update["entities"]
    assert marker["texts"][0]["text"] == "ReasoningFailure: milk is not stable where it was placed"
    [sphere] = marker["spheres"]
    milk = next(t for t in read(path)["/tf"][-1][1]["transforms"] if t["child_frame_id"].startswith("milk/"))
    assert np.allclose([sphere["pose"]["position"][a] for a in "xyz"], [milk["translation"][a] for a in "xyz"],
                       atol=0.15)  # the middle of its box, lying on its side, and its frame
    assert marker["texts"][0]["pose"]["position"]["z"] > sphere["pose"]["position"]["z"]


def test_trace_show_writes_the_same_file_byte_for_byte(set_table, tmp_path):
    trace = tmp_path / "run.json"
    trace.write_text(json.dumps(set_table[1]))
    again = tmp_path / "again.mcap"
    result = run("trace", "show", trace, "--mcap", again)
    assert result.exit_code == 0, result.output
    assert again.read_bytes() == set_table[0].read_bytes()


@pytest.mark.parametrize("args, message", [
    (["run", "set_table", "--mcap", "{tmp}/run.mcp"], "cannot tell the MCAP file's format from '.mcp' (expected .mcap)"),
    (["run", "set_table", "--mcap", "{tmp}/missing/run.mcap"], "folder '{tmp}/missing' does not exist"),
    (["run", "set_table", "--mcap", "{tmp}"], "is a directory"),
    (["run", "set_table", "--mcap", "{tmp}/a.mcap", "--trace", "{tmp}/a.mcap"], "name the same file"),
])
def test_bad_mcap_paths_are_refused_before_the_run(tmp_path, args, message):
    result = run(*[a.format(tmp=tmp_path) for a in args])
    assert result.exit_code == 2
    assert message.format(tmp=tmp_path) in result.stderr
    assert "Traceback" not in result.output and "plan" not in result.stderr.split("error:")[0]


def test_a_corrupt_replay_record_is_refused_and_nothing_written(set_table, tmp_path):
    broken = json.loads(json.dumps(set_table[1]))
    broken["replay"]["steps"][0]["changed"] = [1]
    trace = tmp_path / "broken.json"
    trace.write_text(json.dumps(broken, indent=1))
    result = run("trace", "show", trace, "--mcap", tmp_path / "run.mcap")
    assert result.exit_code == 2 and "replay.steps[0].changed: expected an object, got a list" in result.stderr
    assert not (tmp_path / "run.mcap").exists()


def test_stl_bytes_is_a_binary_stl_with_unit_normals():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)
    data = stl_bytes(vertices, np.array([[0, 1, 2]]))
    assert len(data) == 84 + 50
    normal = np.frombuffer(data[84:96], dtype="<f4")
    assert np.allclose(normal, [0, 0, 1])
    assert np.allclose(np.frombuffer(data[96:132], dtype="<f4").reshape(3, 3), vertices)
