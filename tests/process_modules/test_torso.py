"""`moving-torso`: the torso joint the robot description names, within its limits."""
from __future__ import annotations

import pytest

from pycram_cli.designators import check_designator, perform
from pycram_cli.failures import ManipulationFailure
from pycram_cli.kinds import Robots
from pycram_cli.paths import worlds_dir
from pycram_cli.robots import bundled_descriptions
from pycram_cli.worldfile.loader import load_world


@pytest.mark.parametrize("world_name, joint", [("kitchen.yaml", "torso_lift_joint"), ("kitchen_fetch.yaml", "torso_lift_joint")])
def test_moving_the_torso_sets_the_described_joint(world_name, joint):
    world = load_world(worlds_dir() / world_name)
    try:
        done = perform(world, "moving-torso", {"position": 0.1})
        assert world.robot.get_joint_position(joint) == pytest.approx(0.1)
        assert done.resolved == {"position": 0.1}
        assert perform(world, "moving-torso", {}).resolved == {"position": 0.3}  # the description's default
        with pytest.raises(ManipulationFailure, match="outside its limits"):
            perform(world, "moving-torso", {"position": 2.0})
    finally:
        world.exit()


def test_a_robot_without_a_torso_cannot_move_one():
    pr2 = next(d for d in bundled_descriptions() if d.name == "pr2")
    no_torso = type(pr2)(**{**pr2.__dict__, "torso_joint": None})
    problems = check_designator("moving-torso", {}, robots=Robots((no_torso,), True))
    assert [p.message for p in problems] == ["robot 'pr2' cannot perform 'moving-torso': it has no torso (no torso: in its description)"]
