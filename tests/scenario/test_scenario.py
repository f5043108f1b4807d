"""The scenario layer: a plan, its world file and its parameters checked once, then run any number of times."""
from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.plan.trace import comparable, dumps
from pycram_cli.scenario import prepare
from pycram_cli.world import BulletWorld

PLAN = """\
world: kitchen
params: {object: milk, arm: left}
body:
  - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
  - pick-up: {object: $object, arm: $arm}
  - log: picked up $object
"""


@pytest.fixture
def plan(tmp_path: Path) -> Path:
    path = tmp_path / "pick.yaml"
    path.write_text(PLAN)
    return path


def test_every_problem_of_plan_world_and_parameters_is_reported_at_once_before_anything_is_simulated(tmp_path: Path):
    path = tmp_path / "bad.yaml"
    path.write_text(textwrap.dedent("""\
        world: kitchen
        params: {object: milk}
        body:
          - pick-up: {object: botle, arm: middle}
    """))
    worlds_before = len(BulletWorld._live)
    with pytest.raises((InputError, InputErrors)) as caught:
        prepare(path, params={"objekt": "bowl"})
    messages = [str(e) for e in as_list(caught.value)]
    assert any("has no parameter 'objekt' (did you mean 'object'?)" in m for m in messages)
    assert any(f"{path}:4:" in m and "the world has no object 'botle'" in m for m in messages)
    assert any(f"{path}:4:" in m and "pr2 has no arm 'middle'" in m for m in messages)
    assert len(BulletWorld._live) == worlds_before  # nothing was loaded


def test_parameters_are_bound_once_defaults_filled_in(plan: Path):
    scenario = prepare(plan, params={"object": "bowl"}, assignments=["arm=right"])
    assert scenario.params == {"object": "bowl", "arm": "right"}
    assert scenario.world_path.name == "kitchen.yaml"


def test_a_scenario_runs_again_and_again_with_the_same_trace(plan: Path):
    scenario = prepare(plan)
    first, second = scenario.run(), scenario.run()
    assert first.succeeded and second.succeeded
    assert dumps(comparable(first.trace)) == dumps(comparable(second.trace))


def test_two_scenarios_side_by_side_in_one_process_do_not_see_each_other(plan: Path):
    milk, bowl = prepare(plan), prepare(plan, params={"object": "bowl", "arm": "right"})
    world_a, world_b = milk.load_world(), bowl.load_world()
    try:
        a = milk.run(world_a)
        b = bowl.run(world_b)
        assert a.succeeded and b.succeeded
        assert a.trace["final_state"]["attachments"][0]["child"] == "milk"
        assert b.trace["final_state"]["attachments"][0]["child"] == "bowl"
        assert world_a.alive and world_b.alive  # a world given to run() is left open
        alone = milk.run()
        assert dumps(comparable(alone.trace)) == dumps(comparable(a.trace))
    finally:
        world_a.exit()
        world_b.exit()


def test_a_world_loaded_for_a_run_is_exited_afterwards(plan: Path):
    before = len(BulletWorld._live)
    prepare(plan).run()
    assert len(BulletWorld._live) == before
