"""The plans shipped in plans/ do what they promise on the kitchen world."""
from __future__ import annotations

import pytest
from shipped_runs import group

from pycram_cli.paths import plans_dir
from pycram_cli.plan import load_plan, plan_world, run_plan
from pycram_cli.reasoning import stable, supporting
from pycram_cli.worldfile.loader import load_world


def run(name: str, params: dict | None = None):
    plan = load_plan(plans_dir() / f"{name}.yaml")
    world = load_world(plan_world(plan))
    return world, run_plan(plan, world, params or {})


def find(node: dict, path_part: str) -> list[dict]:
    found = [node] if path_part in node["path"] else []
    for child in node.get("children", []):
        found += find(child, path_part)
    return found


@pytest.fixture
def set_table(shipped_runs):
    """set_table's run, shared with its golden test (tests/shipped_runs.py): these tests only read it."""
    run = shipped_runs("set_table")
    return run.world, run.result


@group("set_table")
def test_set_table_succeeds_with_all_four_objects_stable_at_their_targets(set_table):
    world, result = set_table
    assert result.status == "succeeded", result.failure
    kitchen = world.get_object_by_name("kitchen")
    targets = {"bowl": (-0.8, 1.2, 0.862), "milk": (-0.8, 1.0, 0.862), "cereal": (-1.0, 1.0, 0.862),
               "spoon": (-0.8, 1.4, 0.862)}
    for name, target in targets.items():
        obj = world.get_object_by_name(name)
        assert obj.get_position() == pytest.approx(target, abs=0.002), name
        assert stable(obj), name
        assert supporting(kitchen, obj, link="kitchen_island_surface"), name
    assert world.robot.attachments == {}


@group("set_table")
def test_set_table_opens_the_drawer_for_the_spoon(set_table):
    world, result = set_table
    assert result.trace["final_state"]["objects"]["kitchen"]["joints"] == {"sink_area_left_upper_drawer_main_joint": 0.3}
    assert [n["status"] for n in find(result.trace["root"], ":accessing")] == ["succeeded"]


@group("set_table")
def test_set_table_moves_the_blocking_cereal_first_by_calling_itself(set_table):
    _, result = set_table
    blocking = find(result.trace["root"], "move_object/4:blocking")
    assert blocking[0]["query"]["result"] == ["cereal"]  # the bowl's grasp is blocked by the cereal
    nested = [n for n in find(result.trace["root"], "call move_object")
              if n["path"].count("call move_object") == 2 and n["path"].endswith("call move_object")]
    assert [n["call"]["args"]["job"]["type"] for n in nested] == ["breakfast_cereal"]
    # the cereal job of the main loop finds it already on the table and skips it
    skipped = [n for n in find(result.trace["root"], "body/0:for_each/item 2/1:if") if n["path"].endswith("1:if")]
    assert skipped[0]["condition"]["holds"] is True
    assert skipped[0]["condition"]["query"]["args"]["link"] == "kitchen_island_surface"


def test_set_table_fails_with_a_reasoning_failure_when_a_placed_object_is_not_stable():
    # its middle 1.7 cm beyond the island's edge (x -0.667): let go there, it tips over
    jobs = [{"type": "milk", "target": [-0.65, 1.0, 0.862], "arm": "left", "look": [1.3, 0.8, 0.95]}]
    world, result = run("set_table", {"jobs": jobs})
    try:
        assert result.status == "failed"
        assert result.failure["type"] == "ReasoningFailure"
        assert "milk is not stable" in result.failure["message"]
        assert result.failure["path"].endswith(":assert")
    finally:
        world.exit()


@group("fetch_spoon")
def test_fetch_spoon_recovers_from_not_seeing_the_spoon_by_opening_the_drawer(shipped_runs):
    run = shipped_runs("fetch_spoon")
    world, result = run.world, run.result
    assert result.status == "succeeded", result.failure
    attempts = find(result.trace["root"], "body/1:retry/attempt")
    assert [a["status"] for a in attempts if a["path"].endswith(("attempt 1", "attempt 2"))] == ["failed", "succeeded"]
    assert attempts[0]["failure"]["type"] == "PerceptionFailure"
    assert [n["status"] for n in find(result.trace["root"], "recover 1/1:accessing")] == ["succeeded"]
    assert world.get_object_by_name("spoon").get_position() == pytest.approx((-0.8, 1.4, 0.862), abs=0.002)


@group("grasp_alternatives")
def test_grasp_alternatives_fall_through_and_cancel_the_losers(shipped_runs):
    run = shipped_runs("grasp_alternatives")
    world, result = run.world, run.result
    assert result.status == "succeeded", result.failure
    root = result.trace["root"]
    order = find(root, "body/2:try_in_order/")
    assert [(n["status"], n.get("failure", {}).get("type")) for n in order] == [
        ("failed", "GripperFailure"), ("succeeded", None)]
    assert [n["status"] for n in find(root, "body/3:try_all/")] == ["succeeded", "cancelled"]
    assert [n["status"] for n in find(root, "body/1:pursue/")] == ["succeeded", "cancelled"]
    for name in ("bowl", "milk"):
        assert stable(world.get_object_by_name(name))
