"""plans/set_table_actions.yaml: the chapter-5 demo written with action designators, with no base pose, arm or
look target in it, sets the table on the PR2 and on the Fetch unchanged, and on random arrangements of the
breakfast things along the counter, where the motion-level set_table (fixed poses) mostly cannot."""
from __future__ import annotations

import re

import pytest
from arrangements import arrange, arrangement
from shipped_runs import group

from pycram_cli.paths import plans_dir
from pycram_cli.reasoning import stable, supporting
from pycram_cli.scenario import prepare

PLAN = plans_dir() / "set_table_actions.yaml"
THINGS = ("bowl", "milk", "cereal", "spoon")
#: the 20 seeded arrangements the README speaks of; set_table_actions succeeds on all of them (measured on cdcd405)
SEEDS = range(20)
#: the arrangements the suite runs set_table_actions on: the five of the 20 whose location searches try the most
#: candidate poses (the sum of `tried` over the run's 16 locate steps, on cdcd405: seed 19 141, 1 117, 2 110, 8 101,
#: 9 98; the others 65-92). They are also the longest runs; an easier arrangement exercises nothing these do not
HARD_SEEDS = (19, 1, 2, 8, 9)


def set_on_the_island(world) -> None:
    kitchen = world.get_object_by_name("kitchen")
    for name in THINGS:
        obj = world.get_object_by_name(name)
        assert supporting(kitchen, obj, "kitchen_island_surface"), f"{name} is not on the island"
        assert stable(obj), f"{name} is not stable"
    assert not world.robot.attachments


def test_the_plan_names_no_base_pose_arm_or_look_target():
    text = "\n".join(line.split("#")[0] for line in PLAN.read_text().splitlines())
    assert "action: transport" in text
    for word in ("moving", "target: [", "arm:", "left", "right", "looking", "look", "pick-up:", "place:", "grasp"):
        assert not re.search(rf"\b{re.escape(word)}", text), word


@pytest.mark.parametrize("world_name", [pytest.param("kitchen", marks=group("set_table_actions")),
                                        pytest.param("kitchen_fetch", marks=group("set_table_actions", "kitchen_fetch"))])
def test_it_sets_the_table_on_the_pr2_and_on_the_fetch(world_name, shipped_runs):
    """The run the golden tests compare too (tests/shipped_runs.py)."""
    run = shipped_runs("set_table_actions", None if world_name == "kitchen" else world_name)
    result, world = run.result, run.world
    assert result.status == "succeeded", result.failure
    set_on_the_island(world)
    # the spoon was in the closed drawer: search opened it, and transport tried to close it again (the PR2
    # does; the Fetch's arm cannot follow the handle the last centimetres, and leaves it open)
    text = str(result.trace)
    assert "action open" in text and "action close" in text
    if world_name == "kitchen":
        assert world.get_object_by_name("kitchen").get_joint_position("sink_area_left_upper_drawer_main_joint") < 0.01


@group("set_table_actions", "kitchen_fetch")
def test_the_fetch_run_matches_its_golden_trace(pycram_golden, shipped_runs):
    pycram_golden(PLAN, world="kitchen_fetch", name="set_table_actions-fetch",
                  trace=shipped_runs("set_table_actions", "kitchen_fetch").result.trace)


def run_arranged(scenario, seed: int):
    """The scenario's plan on its world with the breakfast things of arrangement `seed`; the result and the world."""
    world = scenario.load_world()
    try:
        arrange(world, arrangement(seed, world))
        return scenario.run(world=world), world
    except BaseException:
        world.exit()
        raise


@pytest.mark.parametrize("seed", HARD_SEEDS)
def test_it_sets_the_table_on_random_arrangements_along_the_counter(seed):
    """On the hardest five of the README's 20 seeded arrangements ("every time"). One test a seed, so that the
    suite's workers share them out."""
    result, world = run_arranged(prepare(PLAN), seed)
    try:
        assert result.succeeded, (seed, result.failure)
        set_on_the_island(world)
    finally:
        world.exit()


def test_the_motion_level_plan_sets_the_table_on_one_of_those_arrangements():
    """For comparison: set_table, with its fixed poses, succeeds on one of the 20 (the README says "once")."""
    succeeded = []
    scenario = prepare("set_table")
    for seed in SEEDS:
        result, world = run_arranged(scenario, seed)
        world.exit()
        if result.succeeded:
            succeeded.append(seed)
    assert len(succeeded) == 1, succeeded


#: the breakfast things and the Fetch as a sweep scenario of an earlier variation file drew them (seed 1954524034)
FLIP_SCENARIO = {"milk": [1.28697, 1.099578, 0.851], "cereal": [1.296054, 0.527185, 0.851],
                 "bowl": [1.299713, 0.702549, 0.851], "fetch": ([-0.000407, 0.716549, 0.0], -0.134534)}


def test_the_fetch_lowers_the_cereal_straight_onto_the_island(tmp_path):
    """In this arrangement the Fetch lowered the cereal from a nearly stretched-out arm; inverse kinematics took the
    other branch, the joint path swung the box 8° off upright and 3.5 cm aside before it touched the island, and it
    was left rocking ("not stable where it was placed"). A short straight move now keeps to its line."""
    import math

    import yaml
    from click.testing import CliRunner

    from pycram_cli.cli.main import cli
    from pycram_cli.paths import worlds_dir

    data = yaml.safe_load((worlds_dir() / "kitchen_fetch.yaml").read_text())
    kept = []
    for entry in data["objects"]:
        if entry["name"] == "bottle":
            continue  # not in that scenario
        if entry["name"] == "fetch":
            position, yaw = FLIP_SCENARIO["fetch"]
            entry["position"], entry["orientation"] = position, [0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]
        elif entry["name"] in FLIP_SCENARIO:
            entry["position"] = FLIP_SCENARIO[entry["name"]]
        kept.append(entry)
    data["objects"] = kept
    world = tmp_path / "kitchen_fetch_flip.yaml"
    world.write_text(yaml.safe_dump(data, sort_keys=False))
    result = CliRunner().invoke(cli, ["run", str(PLAN), "--world", str(world)])
    assert result.exit_code == 0, result.output[-2000:]


def replay(*args: str):
    from click.testing import CliRunner

    from pycram_cli.cli.main import cli

    vary = plans_dir() / "set_table.vary.yaml"
    return CliRunner().invoke(cli, ["run", str(PLAN), "--vary", str(vary), *args])


def test_a_pose_searched_again_costs_the_location_no_patience():
    """Sweep scenario 16 of the action demo puts the cereal at the island's far end, where the first poses tested
    reach it only along a way the arm's joint-space search finds. They are searched again once a few wait; that second
    test is the same candidate's, not another's, so it must not use up the location's patience: counted twice, the
    place ran out of candidates ("no pose for reachable-for (-0.875, 1.45, 0.862)") with 422 untried."""
    result = replay("--scenario", "1462206085")
    assert result.exit_code == 0, result.output[-2000:]
    assert "succeeded" in result.output


def test_a_grasp_whose_way_in_brushes_a_neighbour_is_not_taken():
    """Sweep scenario 24 on the Fetch: the bottle stands beside the cereal, and the open gripper's straight way in
    from the pre-grasp pose (a grasp from the right) brushes it 22 % of the way in. Pick-up moves in until the first
    touch, so the fingers stopped short and closed on nothing, three times; the grasp planning (and the location
    test that asks it) now walks that way in, and the Fetch takes the cereal from another pose."""
    result = replay("--world", "kitchen_fetch", "--scenario", "192017152")
    assert result.exit_code == 0, result.output[-2000:]
    assert "closed on nothing" not in result.output


def test_a_place_the_hand_cannot_back_off_from_is_not_chosen():
    """Sweep scenario 34 on the Fetch: the place chosen for the milk put the Fetch's elbow within a degree of its limit,
    so the hand could not back off along its approach after letting go; the park then started with the palm on the
    milk and every way from there pushed into it. The place location now tests the whole of letting go (the gripper
    opens, the hand backs off as far as the arm reaches, a way to rest from there) and chooses another pose."""
    result = replay("--world", "kitchen_fetch", "--scenario", "2370723418")
    assert result.exit_code == 0, result.output[-2000:]
    assert "inside milk" not in result.output
