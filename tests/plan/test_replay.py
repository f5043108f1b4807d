"""The replay record: the world after every step, deterministic, outside the comparable trace."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from pycram_cli.plan import trace as traces
from pycram_cli.plan.replay import Recorder, changes, focus_points, world_state
from pycram_cli.scenario import prepare
from pycram_cli.scenario.golden import golden_path

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def set_table():
    return prepare(REPO / "plans" / "set_table.yaml").run(replay=True)


def _leaves(node):
    children = node.get("children") or []
    if not children:
        yield node
    for child in children:
        yield from _leaves(child)


def test_every_finished_leaf_is_a_step_in_execution_order(set_table):
    replay = set_table.trace[traces.REPLAY_KEY]
    steps = replay["steps"]
    finished = {n["path"]: n for n in _leaves(set_table.trace["root"]) if n["status"] not in ("pending", "skipped")}
    assert [s["path"] for s in steps if s["path"] in finished] == [s["path"] for s in steps]
    assert len(steps) >= set_table.steps == 67
    starts = [finished[s["path"]]["timing"]["started"] for s in steps]
    assert starts == sorted(starts)
    assert replay["world_file"].endswith("kitchen.yaml")


def test_the_initial_state_and_the_changes_give_the_final_state(set_table):
    replay = set_table.trace[traces.REPLAY_KEY]
    state = json.loads(json.dumps(replay["initial"]))
    for step in replay["steps"]:
        for name, change in step["changed"].items():
            state[name].update({k: v for k, v in change.items() if k != "joints"})
            state[name].setdefault("joints", {}).update(change.get("joints", {}))
    final = set_table.trace["final_state"]["objects"]
    for name, entry in final.items():
        assert state[name]["position"] == pytest.approx(entry["position"], abs=1e-6)
    assert state["kitchen"]["joints"]["sink_area_left_upper_drawer_main_joint"] == pytest.approx(0.3)
    # the moving steps moved the robot, the place steps the objects
    moving = [s for s in replay["steps"] if s["path"].endswith("moving")]
    assert moving and all("position" in s["changed"].get("pr2", {}) for s in moving[:1])


def test_the_golden_trace_ignores_the_replay(set_table):
    assert traces.REPLAY_KEY not in traces.comparable(set_table.trace)
    golden = traces.load(golden_path(REPO / "plans" / "set_table.yaml", REPO / "tests" / "golden"))
    assert traces.diff(golden, set_table.trace) == []


def test_the_replay_is_the_same_byte_for_byte_on_every_run(set_table):
    again = prepare(REPO / "plans" / "set_table.yaml").run(replay=True)
    assert traces.dumps(again.trace[traces.REPLAY_KEY]) == traces.dumps(set_table.trace[traces.REPLAY_KEY])


def test_changes_keep_only_what_moved():
    before = {"a": {"position": [0, 0, 0], "orientation": [0, 0, 0, 1], "joints": {"j": 0.1, "k": 0.2}},
              "b": {"position": [1, 0, 0], "orientation": [0, 0, 0, 1]}}
    after = {"a": {"position": [0, 0, 0], "orientation": [0, 0, 0, 1], "joints": {"j": 0.1, "k": 0.5}},
             "b": {"position": [1, 0, 1], "orientation": [0, 0, 0, 1]}}
    assert changes(before, after) == {"a": {"joints": {"k": 0.5}},
                                      "b": {"position": [1, 0, 1], "orientation": [0, 0, 0, 1]}}
    assert changes(after, after) == {}


def test_recorder_passes_every_event_on(world, data_dir):
    from pycram_cli import Object
    from pycram_cli.plan.trace import TraceNode

    Object("cube", "box", data_dir / "cube.obj")
    seen = []

    class Inner:
        def started(self, node):
            seen.append(("started", node.path))

        def finished(self, node):
            seen.append(("finished", node.path))

        def log(self, node, message):
            seen.append(("log", message))

    recorder = Recorder(world, Inner())
    node = TraceNode("body/0:log", "log")
    recorder.started(node)
    recorder.log(node, "hi")
    recorder.finished(node)
    assert seen == [("started", "body/0:log"), ("log", "hi"), ("finished", "body/0:log")]
    assert recorder.record()["steps"] == [{"path": "body/0:log", "status": "pending", "changed": {}}]
    assert set(world_state(world)) == {"cube"}


def test_focus_points_are_the_objects_and_places_a_step_names(set_table):
    from pycram_cli import load_world

    world = load_world()
    try:
        info = {"designator": {"resolved": {"object": "milk", "arm": "left", "target": [1.0, 2.0, 0.9]}}}
        points = focus_points(world, info)
        assert len(points) == 2 and points[1] == (1.0, 2.0, 0.9)
        assert points[0][0] == pytest.approx(1.3, abs=0.01)
        assert focus_points(world, {"query": {"args": {"a": "kitchen", "b": "bowl"}}})[0][1] == pytest.approx(0.8, abs=0.01)
        assert focus_points(world, {"message": "hi"}) == []
    finally:
        world.exit()


def _replay_of_a_retry(tmp_path, retries: int):
    plan = tmp_path / f"retry{retries}.yaml"
    plan.write_text(f"""
world: kitchen
body:
  - par:
      - retry: {retries}
        body:
          - moving: {{target: [0.5, 0.7, 0]}}
          - moving: {{target: [0.6, 0.75, 0]}}
          - fail: PerceptionFailure
      - seq: [{{looking: {{target: [1.3, 0.8, 0.9]}}}}, {{looking: {{target: [1.3, 0.6, 0.9]}}}}]
  - log: done
""")
    return prepare(plan).run(replay=True).trace


def test_the_replay_of_folded_attempts_is_folded_too_and_stays_exact(tmp_path):
    # retry: 1000000000 of a failing body grew the replay record by one entry per step of every attempt
    small, large = _replay_of_a_retry(tmp_path, 20), _replay_of_a_retry(tmp_path, 200)
    for trace in (small, large):
        steps = trace[traces.REPLAY_KEY]["steps"]
        folded = [s for s in steps if s.get("folded")]
        assert len(folded) == 1 and folded[0]["path"] == "body/0:par/0:retry/folded attempts"
        tree = {n["path"] for n in _nodes(trace["root"])}
        assert all(s["path"] in tree for s in steps)  # the report finds every step in the tree
        _replays_to_the_final_state(trace)
    assert len(small[traces.REPLAY_KEY]["steps"]) == len(large[traces.REPLAY_KEY]["steps"])  # bounded
    count = next(s for s in large[traces.REPLAY_KEY]["steps"] if s.get("folded"))["folded"]
    attempts = next(n for n in _nodes(large["root"]) if n["type"] == "folded")["folded"]["steps"]
    assert attempts > 190 and count == 3 * attempts  # every step of every folded attempt


def _nodes(node):
    yield node
    for child in node.get("children") or []:
        yield from _nodes(child)


def _replays_to_the_final_state(trace):
    replay = trace[traces.REPLAY_KEY]
    state = json.loads(json.dumps(replay["initial"]))
    for step in replay["steps"]:
        for name, change in step["changed"].items():
            state[name].update({k: v for k, v in change.items() if k != "joints"})
            state[name].setdefault("joints", {}).update(change.get("joints", {}))
    for name, entry in trace["final_state"]["objects"].items():
        assert state[name]["position"] == pytest.approx(entry["position"], abs=1e-6)
    return state


def test_folding_steps_keeps_the_state_after_them_when_other_branches_interleave():
    from pycram_cli.plan.replay import fold_steps

    pose = lambda x: {"position": [x, 0.0, 0.0], "orientation": [0.0, 0.0, 0.0, 1.0]}  # noqa: E731
    initial = {"a": pose(0.0), "b": pose(0.0)}
    steps = [{"path": "r/attempt 4/0:x", "status": "succeeded", "changed": {"a": pose(1.0)}},
             {"path": "other/0:y", "status": "succeeded", "changed": {"a": pose(2.0), "b": pose(5.0)}},
             {"path": "r/attempt 4/1:x", "status": "failed", "changed": {"b": pose(3.0)}},
             {"path": "other/1:y", "status": "succeeded", "changed": {}}]
    fold_steps(steps, initial, "r/folded attempts", "r/attempt 4")
    assert [s["path"] for s in steps] == ["other/0:y", "r/folded attempts", "other/1:y"]
    assert steps[1]["folded"] == 2
    # after it: a where the other branch put it last (2.0), b where the attempt put it (3.0)
    assert steps[1]["changed"] == {"a": pose(2.0), "b": pose(3.0)}


FAILING_MILK = {"jobs": [{"type": "milk", "target": [-0.65, 1.0, 0.862], "arm": "left", "look": [1.3, 0.8, 0.95]}]}


@pytest.fixture(scope="module")
def milk_over_the_edge():
    """The README's failing example: the milk placed over the island's edge tips over while place settles it."""
    return prepare(REPO / "plans" / "set_table.yaml", params=FAILING_MILK).run(replay=True)


def _tilt(orientation) -> float:
    """Degrees between an object's z axis and the vertical."""
    import math
    x, y, z, w = orientation
    return math.degrees(math.acos(max(-1.0, min(1.0, 1 - 2 * (x * x + y * y)))))


def test_physics_inside_a_step_is_recorded_at_20_frames_per_simulated_second(milk_over_the_edge):
    assert milk_over_the_edge.status == "failed"
    steps = milk_over_the_edge.trace[traces.REPLAY_KEY]["steps"]
    with_physics = [s for s in steps if s.get("physics")]
    assert [s["path"].rsplit("/", 1)[1] for s in with_physics] == ["0:place"]  # only place lets physics run
    frames = with_physics[0]["physics"]
    times = [f["t"] for f in frames]
    assert times == sorted(times) and times[0] == pytest.approx(0.05) and len(frames) >= 20 * times[-1] - 1
    milk = [f["changed"]["milk"] for f in frames if "milk" in f["changed"]]
    tilts = [_tilt(m["orientation"]) for m in milk]
    heights = [m["position"][2] for m in milk]
    # the fall itself: standing at first, lying at the end, and frames in between
    assert tilts[0] < 5 and tilts[-1] > 60 and any(15 < t < 60 for t in tilts)
    assert heights[0] > 0.85 and heights[-1] < 0.5
    # only what moved: the robot's joints in the first frame only (physics holds them), resting objects rarely
    assert all("pr2" not in f["changed"] for f in frames[1:])
    assert sum(len(f["changed"]) for f in frames) < 3 * len(frames)


def test_physics_frames_are_bounded_per_step(world, data_dir):
    from pycram_cli import Object
    from pycram_cli.limits import MAX_PHYSICS_FRAMES
    from pycram_cli.plan.trace import TraceNode

    world.set_gravity((0, 0, -9.81))
    Object("cube", "box", data_dir / "cube.obj", position=(0, 0, 50))  # falls for the whole time
    recorder = Recorder(world)
    world.simulate(10.0)  # 200 frames at 20 per second: thinned to every 8th
    recorder.finished(TraceNode("body/0:wait", "wait"))
    recorder.close()
    frames = recorder.record()["steps"][0]["physics"]
    assert MAX_PHYSICS_FRAMES // 2 <= len(frames) <= MAX_PHYSICS_FRAMES
    gaps = {round(b["t"] - a["t"], 4) for a, b in zip(frames, frames[1:])}
    assert len(gaps) == 1  # evenly spaced after thinning
    heights = [f["changed"]["cube"]["position"][2] for f in frames]
    assert heights == sorted(heights, reverse=True)
    world.simulate(0.5)  # no longer watched
    assert len(recorder.record()["steps"]) == 1


def test_the_physics_frames_are_the_same_on_every_run_and_outside_the_comparable_trace(milk_over_the_edge):
    again = prepare(REPO / "plans" / "set_table.yaml", params=FAILING_MILK).run(replay=True)
    assert traces.dumps(again.trace[traces.REPLAY_KEY]) == traces.dumps(milk_over_the_edge.trace[traces.REPLAY_KEY])
    assert "physics" not in json.dumps(traces.comparable(milk_over_the_edge.trace))


def test_what_stable_simulates_on_the_prospection_copy_is_recorded_apart(milk_over_the_edge):
    steps = milk_over_the_edge.trace[traces.REPLAY_KEY]["steps"]
    check = steps[-1]
    assert check["path"].endswith("12:assert") and check["status"] == "failed"
    frames = check["prospection"]  # stable(milk) tried it out on the copy: the milk goes on moving there
    assert frames and all(set(f["changed"]) == {"milk"} for f in frames)  # only what the step names
    assert [f["t"] for f in frames] == sorted(f["t"] for f in frames)
    assert "milk" not in check["changed"] and "physics" not in check  # the world itself did not move


def test_a_project_steps_runs_are_replayed_apart_the_first_of_each_alternative_only(tmp_path):
    """Projected runs are not the run: none of their steps is among the replay's, and the replay (and its
    final state) is the real run's; each alternative's first MAX_PROJECTED_REPLAYS runs are kept apart, each a
    replay of its own from its varied start, with its own tree."""
    from pycram_cli.limits import MAX_PROJECTED_REPLAYS

    plan = tmp_path / "project.yaml"
    plan.write_text(f"""
world: kitchen
body:
  - project:
      alternatives:
        look: [{{looking: {{target: [1.3, 0.8, 0.9]}}}}]
        drive: [{{moving: {{target: [0.5, 0.7, 0]}}}}]
      runs: {MAX_PROJECTED_REPLAYS + 2}
      vary: {{milk: {{noise: [0.02, 0.02, 0]}}}}
      choose: first-success
  - log: done
""")
    trace = prepare(plan).run(replay=True).trace
    replay = trace["replay"]
    assert [step["path"] for step in replay["steps"]] == ["body/0:project/chosen look/0:looking", "body/1:log"]
    assert _replays_to_the_final_state(trace)
    kept = replay["projections"]["body/0:project"]
    assert list(kept) == ["look", "drive"]
    assert list(kept["drive"]) == [str(run) for run in range(MAX_PROJECTED_REPLAYS)]
    drive = kept["drive"]["3"]
    assert drive["root"]["path"] == "body/0:project/projected drive 3" and drive["root"]["status"] == "succeeded"
    assert [step["path"] for step in drive["steps"]] == ["body/0:project/projected drive 3/0:moving"]
    assert drive["steps"][0]["changed"]["pr2"]["position"][:2] == [0.5, 0.7]
    assert drive["initial"]["milk"]["position"] != replay["initial"]["milk"]["position"]  # its own varied start
    assert traces.comparable(trace) == traces.comparable(prepare(plan).run().trace)  # the same run, recorded or not
    docs = (REPO / "docs" / "plans.md").read_text()
    assert f"the first {MAX_PROJECTED_REPLAYS} runs of each alternative" in docs  # as the docs say
    assert f"(the first {MAX_PROJECTED_REPLAYS} of each alternative)" in docs
