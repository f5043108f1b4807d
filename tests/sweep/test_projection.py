"""`pycram run PLAN --project N [--require P]`: the plan projected N times on drawn scenarios before it acts,
the success rate and failures by cause printed, and the run refused when the rate is below P."""
from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.sweep.projection import Projection, project


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture
def boxes(tmp_path: Path) -> Path:
    """A box on the floor; the plan drops it when `drop` is set, and fails when it is far from the origin."""
    write(tmp_path, "boxes.yaml", """\
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
    """)
    write(tmp_path, "near.yaml", """\
        world: boxes.yaml
        params: {drop: false}
        body:
          - if: $drop
            then: [{fail: ManipulationFailure, message: "dropped the box"}]
          - assert: {stable: {object: box}}
            message: "the box moves"
    """)
    write(tmp_path, "near.vary.yaml", """\
        objects:
          box: {region: {box: [[0.2, -0.3, 0.025], [0.8, 0.3, 0.025]]}}
    """)
    return tmp_path


def run(*args: object):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_a_projection_that_succeeds_lets_the_plan_run(boxes):
    result = run("run", boxes / "near.yaml", "--project", 3, "--require", 1.0)
    assert result.exit_code == 0, result.output
    assert "projected near.yaml 3 times on scenarios of near.vary.yaml: succeeded 3 of 3, 100.0 %" in result.output
    assert "plan near.yaml succeeded" in result.output


def test_a_projection_below_the_required_rate_refuses_to_act_and_says_why(boxes):
    result = run("run", boxes / "near.yaml", "-p", "drop=true", "--project", 3, "--require", 0.5)
    assert result.exit_code == 1
    assert "succeeded 0 of 3, 0.0 %" in result.output
    assert "3  ManipulationFailure at body/0:if/then/0:fail" in result.output and "dropped the box" in result.output
    assert "replay: pycram run" in result.output and "--scenario" in result.output
    assert "not running near.yaml: the projected success rate 0.0 % is below the required 50.0 %" in result.output
    assert "plan near.yaml" not in result.output  # nothing ran for real


def test_json_holds_the_projection_with_the_run_or_instead_of_it(boxes):
    ran = run("run", boxes / "near.yaml", "--project", 2, "--json")
    assert ran.exit_code == 0, ran.output
    data = json.loads(ran.stdout)
    assert data["status"] == "succeeded" and data["projection"]["runs"] == 2
    refused = run("run", boxes / "near.yaml", "-p", "drop=true", "--project", 2, "--require", 0.1, "--json")
    assert refused.exit_code == 1
    data = json.loads(refused.stdout)
    assert data["status"] == "not run" and data["projection"]["succeeded"] == 0


def test_the_same_seed_gives_the_same_projection_in_process_and_on_two_workers(boxes):
    alone = project(Projection(str(boxes / "near.yaml"), runs=8, workers=1))
    pooled = project(Projection(str(boxes / "near.yaml"), runs=8, workers=2))
    assert pooled["workers"] == 2 and alone["workers"] == 1
    strip = lambda s: {k: v for k, v in s.items() if k not in ("time", "workers")}  # noqa: E731
    assert strip(alone) == strip(pooled)


@pytest.mark.parametrize("args, message", [
    (["--require", "0.5"], "--require: sets the success rate --project must reach, but no --project N is given"),
    (["--project", "2", "--scenario", "1"], "--project: projects the plan over scenarios, and --scenario runs one"),
    (["--project", "2", "--require", "1.5"], "--require: expected a finite number from 0 to 1"),
])
def test_projection_options_that_cannot_go_together_are_input_errors(boxes, args, message):
    result = run("run", boxes / "near.yaml", *args)
    assert result.exit_code == 2 and message in result.output and "Traceback" not in result.output


def test_without_a_variation_file_the_error_says_how_to_write_one(boxes):
    (boxes / "near.vary.yaml").unlink()
    result = run("run", boxes / "near.yaml", "--project", 2)
    assert result.exit_code == 2
    assert "projecting the plan needs a variation file" in result.output and "pycram new vary near" in result.output


# -- a `project` step's runs on local workers (LocalProjector) ---------------------------------------------------
COUNTER = "{target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}"


@pytest.fixture(scope="module")
def kitchen():
    from pycram_cli.worldfile.loader import load_world

    world = load_world("kitchen")
    yield world
    world.exit()


def run_step(tmp_path: Path, kitchen, text: str, projector=None):
    from pycram_cli.plan import load_plan, run_plan

    plan = load_plan(write(tmp_path, "step.yaml", text), kitchen)
    saved = kitchen.save_state()
    try:
        return run_plan(plan, kitchen, projector=projector)
    finally:
        kitchen.reset_to(saved)


def projection_of(result) -> dict:
    return next(c for c in result.trace["root"]["children"] if c["path"].endswith(":project"))["projection"]


def test_the_same_seed_gives_the_same_choice_table_and_trace_in_process_and_on_one_or_two_workers(tmp_path, kitchen):
    from pycram_cli.plan.trace import comparable
    from pycram_cli.sweep.projection import LocalProjector

    text = f"""\
        world: kitchen
        body:
          - moving: {COUNTER}
          - project:
              alternatives:
                left-side: [{{pick-up: {{object: cereal, arm: left, grasp: left}}}}]
                right-top: [{{pick-up: {{object: cereal, arm: right, grasp: top}}}}]
              runs: 3
              vary: {{cereal: {{noise: [0.03, 0.03, 0], yaw: 0.6}}}}
              seed: 4
        """
    here = run_step(tmp_path, kitchen, text)
    one, two = LocalProjector(workers=1, startup=0), LocalProjector(workers=2, startup=0)
    on_one, on_two = run_step(tmp_path, kitchen, text, one), run_step(tmp_path, kitchen, text, two)
    assert (one.used, two.used) == (1, 2)
    assert here.succeeded and on_two.succeeded, on_two.failure
    assert projection_of(here) == projection_of(on_one) == projection_of(on_two)
    assert comparable(here.trace) == comparable(on_one.trace) == comparable(on_two.trace)


def test_runs_go_to_the_workers_only_when_they_save_more_time_than_starting_them_costs():
    from pycram_cli.sweep.projection import LocalProjector

    projector = LocalProjector(workers=2, startup=0.15)
    assert projector.parallel(3, 0.3) == 2          # 0.9 s here, 0.15 + 0.45 s on two workers
    assert projector.parallel(3, 0.05) == 1         # 0.15 s here, 0.3 s there
    assert projector.parallel(1, 10.0) == 1         # one run: nothing to share
    assert LocalProjector(workers=8).usable(3) == 3  # never more workers than runs


def test_quick_runs_stay_in_this_process(tmp_path, kitchen):
    from pycram_cli.sweep.projection import LocalProjector

    projector = LocalProjector(workers=2)
    result = run_step(tmp_path, kitchen, """\
        world: kitchen
        body:
          - project:
              alternatives: {a: [{log: x}], b: [{log: y}]}
              runs: 3
        """, projector)
    assert result.succeeded and projector.used == 1


def test_on_workers_a_run_with_an_internal_error_or_whose_worker_dies_is_recorded_and_the_step_goes_on(
        tmp_path, kitchen, monkeypatch):
    import os

    from pycram_cli.plan import leaves
    from pycram_cli.sweep.projection import LocalProjector

    original = leaves.LogStep.execute

    def broken(self, ex, tn):  # inherited by the forked workers
        if "projected bug" in tn.path:
            raise RuntimeError("boom")
        if "projected crash" in tn.path:
            os._exit(9)  # the worker process dies with the run
        return original(self, ex, tn)

    monkeypatch.setattr(leaves.LogStep, "execute", broken)
    result = run_step(tmp_path, kitchen, """\
        world: kitchen
        body:
          - project:
              alternatives:
                bug: [{log: "a step with a bug"}]
                crash: [{log: "a step that kills its process"}]
                fine: [{wait: 0}]
              runs: 2
        """, LocalProjector(workers=2, startup=0))
    assert result.succeeded, result.failure
    table = projection_of(result)["alternatives"]
    assert table["bug"]["failures"] == {"InternalError": 2}
    assert table["crash"]["failures"] == {"InternalError": 2}
    assert "the worker process died (exit code 9)" in table["crash"]["outcomes"][0]["failure"]
    assert table["fine"]["succeeded"] == 2 and projection_of(result)["choice"] == "fine"


@pytest.mark.parametrize("workers", [1, 2])
def test_a_run_past_the_timeout_is_recorded_and_the_step_goes_on(tmp_path, kitchen, workers):
    import time as clock

    from pycram_cli.sweep.projection import LocalProjector

    began = clock.perf_counter()
    result = run_step(tmp_path, kitchen, """\
        world: kitchen
        body:
          - project:
              alternatives:
                slow: [{wait: 30}]
                quick: [{wait: 0}]
              runs: 2
              timeout: 0.3
        """, LocalProjector(workers=workers, startup=0))
    assert clock.perf_counter() - began < 10
    projection = projection_of(result)
    assert projection["alternatives"]["slow"]["failures"] == {"Timeout": 2}
    assert projection["alternatives"]["slow"]["outcomes"][0]["failure"] == "Timeout: ran past the 0.3 s timeout"
    assert projection["choice"] == "quick" and projection["timeout"] == 0.3


def test_a_worker_stuck_past_the_timeout_is_stopped_and_its_run_recorded(tmp_path, kitchen, monkeypatch):
    import time as clock

    from pycram_cli.plan import leaves
    from pycram_cli.sweep.projection import LocalProjector

    original = leaves.LogStep.execute

    def stuck(self, ex, tn):  # no cancellation check: only killing the worker ends it
        if "projected stuck" in tn.path:
            clock.sleep(60)
        return original(self, ex, tn)

    monkeypatch.setattr(leaves.LogStep, "execute", stuck)
    began = clock.perf_counter()
    result = run_step(tmp_path, kitchen, """\
        world: kitchen
        body:
          - project:
              alternatives:
                quick: [{wait: 0}]
                stuck: [{log: "never ends"}]
              runs: 2
              timeout: 0.3
        """, LocalProjector(workers=2, startup=0, grace=0.2))
    assert clock.perf_counter() - began < 10
    for row in projection_of(result)["alternatives"]["stuck"]["outcomes"]:
        assert row["status"] == "timeout"
        assert row["failure"] == "Timeout: ran past the 0.3 s timeout (the worker was stopped)"
    assert projection_of(result)["choice"] == "quick"
