"""A carried object keeps the orientation it was grasped in: the PR2 has no carry pose, and parking an arm that holds
a milk carton taken from the front used to lay it on its side. An arm that holds something and has no `carry` pose
holds its tool where `park` puts it, turned as it was at the grasp; a robot whose description has a `carry` pose
(the Fetch) carries in it, as its description asks.
"""
from __future__ import annotations

import pytest

from pycram_cli.paths import plans_dir, worlds_dir
from pycram_cli.plan import load_plan, run_plan
from pycram_cli.world.pose import quat_to_matrix
from pycram_cli.worldfile.loader import load_world

PLAN = "world: kitchen\nbody:\n  - action: pick-up\n    object: milk\n    grasp: {grasp}\n  - action: park-arms\n"


@pytest.mark.parametrize("grasp", ["front", "top"])
def test_the_pr2_carries_the_milk_upright_whichever_way_it_took_it(tmp_path, grasp):
    plan = tmp_path / "carry.yaml"
    plan.write_text(PLAN.format(grasp=grasp))
    world = load_world(worlds_dir() / "kitchen.yaml")
    try:
        result = run_plan(load_plan(plan), world)
        assert result.status == "succeeded", result.failure
        milk = world.get_object_by_name("milk")
        assert milk in world.robot.attachments
        assert quat_to_matrix(milk.get_orientation())[2, 2] == pytest.approx(1.0, abs=1e-3)  # its z axis still up
    finally:
        world.exit()
