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
