"""The `project` step: alternatives tried in prospection on a varied copy of the scene, the best run for real,
the world untouched by the projections, the choice a function of the seed, and its problems located."""
from __future__ import annotations

import json
import textwrap
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.plan import load_plan, run_plan
from pycram_cli.plan.trace import comparable
from pycram_cli.worldfile.loader import load_world

COUNTER = "- moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}"


def write(folder: Path, text: str, name: str = "plan.yaml") -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


def find(node: dict[str, Any], path_end: str) -> dict[str, Any]:
    if node["path"].endswith(path_end):
        return node
    for child in node.get("children", []):
        try:
            return find(child, path_end)
        except KeyError:
            pass
    raise KeyError(path_end)


def state(world: Any) -> list[tuple[Any, ...]]:
    """Every object's pose and joint positions, exactly."""
    return [(o.name, o.get_pose(), tuple(sorted(o.get_joint_positions().items()))) for o in world.objects]


@pytest.fixture(scope="module")
def kitchen():
    world = load_world("kitchen")
    yield world
    world.exit()


def run(tmp_path: Path, kitchen: Any, text: str) -> Any:
    plan = load_plan(write(tmp_path, text), kitchen)
    saved = kitchen.save_state()
    try:
        return run_plan(plan, kitchen)
    finally:
        kitchen.reset_to(saved)


def test_projections_leave_the_world_bitwise_as_it_was(tmp_path, kitchen):
    """The chosen alternative changes nothing, the other one picks the milk up in every projection: after the
    step the world is exactly as before it."""
    plan = load_plan(write(tmp_path, f"""\
        world: kitchen
        body:
          - project:
              alternatives:
                look: [{{log: "looking only"}}]
                grab: [{COUNTER[2:]}, {{pick-up: {{object: milk, arm: left}}}}]
              runs: 3
              vary: {{milk: {{noise: [0.02, 0.02, 0], yaw: 0.3}}}}
              choose: first-success
        """), kitchen)
    saved = kitchen.save_state()
    try:
        before = state(kitchen)
        result = run_plan(plan, kitchen)
        assert result.succeeded, result.failure
        assert state(kitchen) == before
        record = find(result.trace["root"], "0:project")["projection"]
        assert record["choice"] == "look"
        assert record["alternatives"]["grab"]["succeeded"] == 3  # the projections did pick the milk up
    finally:
        kitchen.reset_to(saved)


def test_the_most_successful_alternative_runs_for_real_and_the_table_is_in_the_trace(tmp_path, kitchen):
    result = run(tmp_path, kitchen, f"""\
        world: kitchen
        body:
          {COUNTER}
          - project:
              alternatives:
                front: [{{pick-up: {{object: cereal, arm: right, grasp: front}}}}]
                top: [{{pick-up: {{object: cereal, arm: right, grasp: top}}}}]
              runs: 2
            as: choice
          - log: "took it with $choice.name"
        """)
    assert result.succeeded, result.failure
    project = find(result.trace["root"], "1:project")
    table = project["projection"]["alternatives"]
    assert table["front"]["succeeded"] == 0 and table["front"]["failures"] == {"GripperFailure": 2}
    assert table["top"] == {**table["top"], "runs": 2, "succeeded": 2, "rate": 1.0}
    assert project["projection"]["choice"] == "top"
    assert [c["path"].rsplit("/", 1)[1] for c in project["children"]] == ["projected front", "projected top",
                                                                          "chosen top"]
    assert find(result.trace["root"], "2:log")["message"] == "took it with top"


def test_the_same_seed_gives_the_same_choice_and_trace_and_another_seed_other_scenes(tmp_path, kitchen):
    text = f"""\
        world: kitchen
        body:
          {COUNTER}
          - project:
              alternatives:
                left-side: [{{pick-up: {{object: cereal, arm: left, grasp: left}}}}]
                left-top: [{{pick-up: {{object: cereal, arm: left, grasp: top}}}}]
              runs: 3
              vary: {{cereal: {{noise: [0.02, 0.02, 0], yaw: 0.5}}}}
              seed: SEED
        """
    first = run(tmp_path, kitchen, text.replace("SEED", "1"))
    again = run(tmp_path, kitchen, text.replace("SEED", "1"))
    other = run(tmp_path, kitchen, text.replace("SEED", "2"))
    assert comparable(first.trace) == comparable(again.trace)
    outcomes = lambda r: find(r.trace["root"], "1:project")["projection"]["alternatives"]  # noqa: E731
    assert outcomes(first) == outcomes(again)
    assert comparable(first.trace) != comparable(other.trace) or outcomes(first) != outcomes(other)


def test_when_none_succeeds_often_enough_the_step_fails_with_the_table(tmp_path, kitchen):
    result = run(tmp_path, kitchen, f"""\
        world: kitchen
        body:
          {COUNTER}
          - project:
              alternatives:
                left: [{{pick-up: {{object: cereal, arm: left, grasp: front}}}}]
                right: [{{pick-up: {{object: cereal, arm: right, grasp: front}}}}]
              runs: 2
              at-least: 0.5
        """)
    assert not result.succeeded
    assert result.failure["type"] == "ProjectionFailure"
    assert "no alternative succeeded in at least 50 % of 2 projected runs" in result.failure["message"]
    assert "left: 0 of 2 (2 GripperFailure); right: 0 of 2 (2 GripperFailure)" in result.failure["message"]


def test_a_projection_that_hits_an_internal_error_is_recorded_and_the_step_goes_on(tmp_path, kitchen, monkeypatch):
    from pycram_cli.plan import leaves

    original = leaves.LogStep.execute

    def explode(self, ex, tn):  # a bug in one step, only inside the first alternative's projections
        if "projected broken" in tn.path:
            raise RuntimeError("boom")
        return original(self, ex, tn)

    monkeypatch.setattr(leaves.LogStep, "execute", explode)
    result = run(tmp_path, kitchen, """\
        world: kitchen
        body:
          - project:
              alternatives:
                broken: [{log: "a step with a bug"}]
                fine: [{wait: 0}]
              runs: 2
        """)
    assert result.succeeded, result.failure
    table = find(result.trace["root"], "0:project")["projection"]["alternatives"]
    assert table["broken"]["succeeded"] == 0 and table["broken"]["failures"] == {"InternalError": 2}
    assert table["fine"]["succeeded"] == 2


@pytest.mark.parametrize("score, chosen, why", [
    ("{max: rate - 0.1 * steps}", "short", "the highest rate - 0.1 * steps (0.9)"),  # both always succeed
    ("{max: steps}", "long", "the highest steps (3)"),
    ("{min: failed + steps}", "short", "the lowest failed + steps (1)"),
])
def test_an_expression_over_the_outcomes_chooses(tmp_path, kitchen, score, chosen, why):
    result = run(tmp_path, kitchen, f"""\
        world: kitchen
        body:
          - project:
              alternatives:
                long: [{{log: one}}, {{log: two}}, {{log: three}}]
                short: [{{log: one}}]
              runs: 2
              choose: {score}
        """)
    assert result.succeeded, result.failure
    projection = find(result.trace["root"], "0:project")["projection"]
    assert projection["choice"] == chosen and projection["why"] == why
    assert projection["choose"] == score.strip("{}").replace(": ", ": ", 1)


@pytest.mark.parametrize("body, message", [
    ("project: [a, b]", "project: expected a mapping with 'alternatives'"),
    ("project: {runs: 3}", "a 'project' step needs 'alternatives'"),
    ("project: {alternatives: {a: [{log: x}]}, runs: 0}", "runs: expected a whole number from 1 to"),
    ("project: {alternatives: {a: [{log: x}]}, choose: best}", "choose: expected one of most-successful, "
                                                                "first-success, fewest-steps, or {max: EXPRESSION}"),
    ("project: {alternatives: {a: [{log: x}]}, choose: {max: rat - steps}}", "unknown name 'rat' (did you mean "
                                                                             "'rate'?)"),
    ("project: {alternatives: {a: [{log: x}]}, choose: {max: \"__import__('os').getcwd()\"}}",
     "only numbers, rate, succeeded, failed, runs, steps, + - * / and min, max, abs() are allowed"),
    ("project: {alternatives: {a: [{log: x}]}, choose: {max: rate +}}", "not an arithmetic expression"),
    ("project: {alternatives: {a: [{log: x}]}, choose: {best: rate}}", "expected {max: EXPRESSION} or "
                                                                       "{min: EXPRESSION}"),
    ("project: {alternatives: {a: [{log: x}]}, at-least: 2}", "at-least: expected a success rate from 0 to 1"),
    ("project: {alternatives: {a: [{log: x}]}, vary: {milk: {noise: -1}}}", "noise: expected a number"),
    ("project: {alternatives: {a: [{log: x}]}, vary: {milk: {turn: 1}}}", "unknown key 'turn' in a varied object"),
    ("project: {alternatives: {a: [{log: x}]}, vary: {milc: {yaw: 0.1}}}", "unknown object 'milc' in the world "
                                                                          "(did you mean 'milk'?)"),
    ("project: {alternatives: {a: [{pick-up: {object: milc}}]}}", "milc"),
    ("project: {alternatives: {a: [{log: x}]}, rnus: 3}", "unknown key 'rnus' in 'project'"),
    ("project: {alternatives: {a: [{log: x}]}, timeout: 0}", "timeout: expected seconds above 0 and at most 86400"),
])
def test_problems_are_input_errors_with_their_place(tmp_path, body, message):
    path = write(tmp_path, f"world: kitchen\nbody:\n  - {body}\n")
    result = CliRunner().invoke(cli, ["validate", str(path)])
    assert result.exit_code == 2, result.output
    assert message in result.output and f"{path.name}:3:" in result.output
    assert "Traceback" not in result.output


def test_what_an_alternative_binds_stays_in_it(tmp_path):
    path = write(tmp_path, """\
        world: kitchen
        body:
          - project:
              alternatives:
                a: [{seq: [{log: x}], as: inner}]
          - log: "$inner"
        """)
    result = CliRunner().invoke(cli, ["validate", str(path)])
    assert result.exit_code == 2 and "bound inside a branch" in result.output


def test_trace_show_prints_the_table(tmp_path):
    path = write(tmp_path, """\
        world: kitchen
        body:
          - project:
              alternatives:
                quick: [{wait: 0}]
                failing: [{fail: PerceptionFailure, message: "nothing seen"}]
              runs: 2
        """)
    trace = tmp_path / "t.json"
    ran = CliRunner().invoke(cli, ["run", str(path), "--trace", str(trace), "-q"])
    assert ran.exit_code == 0, ran.output
    shown = CliRunner().invoke(cli, ["trace", "show", str(trace)])
    assert "projected: failing 0/2 (2 PerceptionFailure), quick 2/2 → quick (the most successful (2 of 2 runs))" \
        in shown.output
    assert json.loads(trace.read_text())["status"] == "succeeded"
