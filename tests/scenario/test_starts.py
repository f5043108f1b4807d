"""A drawn scenario whose objects start inside each other or in the air is drawn again; a variation file that
cannot draw a possible start is said so, by the sweep (not counted) and by `pycram run --scenario` (exit 2)."""
from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.paths import plans_dir
from pycram_cli.scenario import prepare
from pycram_cli.scenario.starts import REDRAWS, ImpossibleStart, impossible
from pycram_cli.scenario.variation_files import read_variations
from pycram_cli.scenario.variations import scenario_seed
from pycram_cli.scenario.worlds import LoadedWorlds


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture
def boxes(tmp_path: Path) -> Path:
    """Two 5 cm boxes on the floor; the plan only waits and checks the moved box is still."""
    write(tmp_path, "boxes.yaml", """\
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
          - {name: other, type: box, file: cube_small.urdf, position: [0.52, 0, 0.025]}
    """)
    write(tmp_path, "still.yaml", """\
        world: boxes.yaml
        body:
          - wait: 0.2
          - assert: {stable: {object: box}}
            message: "the box moves"
    """)
    return tmp_path


def vary(folder: Path, z: float, half: float = 0.06) -> Path:
    """`box` anywhere within ±half of `other` (so that it often lands inside it), at height z."""
    return write(folder, "still.vary.yaml", f"""\
        objects:
          box: {{region: {{box: [[{0.52 - half}, {-half}, {z}], [{0.52 + half}, {half}, {z}]]}}}}
    """)


def run(*args: object):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_a_draw_inside_another_object_is_drawn_again_and_the_record_says_why(boxes):
    scenario = prepare(boxes / "still.yaml")
    variations = read_variations(vary(boxes, 0.025), scenario.world, scenario.plan)
    worlds = LoadedWorlds(scenario)
    try:
        redrawn = 0
        for index in range(12):
            seed = scenario_seed(0, index)
            first = variations.sample(seed, index)
            first_problems = impossible(worlds.world_for(first), first)
            variant, world = worlds.possible(variations, seed, index)
            assert impossible(world, variant) == []  # what runs can start
            if first_problems:
                redrawn += 1
                assert variant.varied["redrawn"][0] == "; ".join(first_problems)
                assert "box starts" in first_problems[0] and "inside other" in first_problems[0]
            else:
                assert variant.varied == first.varied  # a possible first draw is kept as it was
        assert redrawn >= 3  # the region is mostly inside `other`: the test would notice no redraw
        again, _ = worlds.possible(variations, scenario_seed(0, 5), 5)
        assert again.varied == worlds.possible(variations, scenario_seed(0, 5), 5)[0].varied  # the seed decides
    finally:
        worlds.close()


def test_a_draw_in_the_air_is_not_supported(boxes):
    scenario = prepare(boxes / "still.yaml")
    variations = read_variations(vary(boxes, 0.3, half=0.01), scenario.world, scenario.plan)
    worlds = LoadedWorlds(scenario)
    try:
        variant = variations.sample(1, 0)
        problems = impossible(worlds.world_for(variant), variant)
        assert problems and "box is not supported" in problems[0] and "above other" in problems[0]
        with pytest.raises(ImpossibleStart) as caught:
            worlds.possible(variations, 1, 0)
        assert len(caught.value.reasons) == REDRAWS + 1
    finally:
        worlds.close()


def test_a_sweep_does_not_count_scenarios_that_cannot_start_and_says_so(boxes, tmp_path):
    vary(boxes, 0.3, half=0.01)
    result = run("sweep", boxes / "still.yaml", "-n", 2, "--workers", 1, "--out", tmp_path / "out", "--json")
    assert result.exit_code == 0, result.output
    summary = json.loads(result.output)
    assert summary["runs"] == 0 and summary["statuses"] == {"invalid": 2}
    assert summary["starts"]["invalid"] == 2 and "not supported" in summary["starts"]["invalid_example"]
    records = [json.loads(line) for line in (tmp_path / "out" / "results.jsonl").read_text().splitlines()]
    assert all(r["failure"]["type"] == "ImpossibleStart" and len(r["varied"]["redrawn"]) == REDRAWS + 1
               for r in records)


def test_a_swept_scenario_replayed_alone_is_the_redrawn_one(boxes, tmp_path):
    vary(boxes, 0.025)
    result = run("sweep", boxes / "still.yaml", "-n", 6, "--workers", 1, "--out", tmp_path / "out")
    assert result.exit_code == 0, result.output
    assert "drawn again: their first draw could not start (e.g. box starts" in result.output
    records = [json.loads(line) for line in (tmp_path / "out" / "results.jsonl").read_text().splitlines()]
    redrawn = next(r for r in records if r["varied"].get("redrawn"))
    alone = run("run", boxes / "still.yaml", "--scenario", redrawn["seed"], "--json")
    assert alone.exit_code in (0, 1), alone.output
    assert json.loads(alone.output)["status"] == redrawn["status"]


def test_run_scenario_with_no_possible_draw_is_an_input_error(boxes):
    vary(boxes, 0.3, half=0.01)
    result = run("run", boxes / "still.yaml", "--scenario", 7)
    assert result.exit_code == 2
    assert "--scenario" in result.output and "no possible start" in result.output
    assert "not supported" in result.output and "Traceback" not in result.output


def test_the_demo_variations_start_every_scenario_possible():
    """The demo's file puts the bowl within centimetres of the cereal: a draw where they overlap is drawn again."""
    scenario = prepare("set_table")
    variations = read_variations(plans_dir() / "set_table.vary.yaml", scenario.world, scenario.plan)
    worlds = LoadedWorlds(scenario)
    try:
        redrawn = 0
        for index in range(20):
            variant, world = worlds.possible(variations, scenario_seed(0, index), index)
            assert impossible(world, variant) == []
            redrawn += bool(variant.varied.get("redrawn"))
        assert redrawn >= 2
    finally:
        worlds.close()
