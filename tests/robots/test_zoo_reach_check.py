"""bench/zoo.py's independent reach check (plain PyBullet): the ways it holds an object come from the object's box, the
gripper's width and the object knowledge, and it finds the poses pick-up itself finds.

Zoo seed 12's gripper opens 9.4 cm: the 19 cm wide cereal box is held only across its 7 cm depth, through its narrow
sides or from above; its arm reaches the box's top with the torso raised (as pycram's planner does: see
tests/locations/test_torso_reach.py).
"""
from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import pytest

from pycram_cli.robots.zoo import generate, write_world

BENCH = Path(__file__).resolve().parents[2] / "bench" / "zoo.py"


@pytest.fixture(scope="module")
def check():
    spec = importlib.util.spec_from_file_location("bench_zoo", BENCH)
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench_zoo"] = module  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def scene(check, tmp_path_factory):
    made = check._Scene(write_world(generate(12), Path(tmp_path_factory.mktemp("zoo12"))))
    yield made
    made.close()


def test_the_cereal_is_held_only_across_its_depth(scene):
    grasps = scene.grasps("cereal")
    approaches = {tuple(round(v) for v in g.approach) for g in grasps}
    assert approaches == {(0, 1, 0), (0, -1, 0), (0, 0, -1)}  # never through the wide face (along x)
    for grasp in grasps:  # the pre-grasp pose is APPROACH back along the approach
        assert math.dist(grasp.pre, grasp.position) == pytest.approx(0.10)


def test_the_bowl_is_held_by_its_rim_from_above(scene):
    grasps = scene.grasps("bowl")
    (lo, hi), _ = scene.boxes["bowl"]
    assert grasps and all(g.approach == (0.0, 0.0, -1.0) for g in grasps)
    assert all(g.position[2] < hi[2] and math.hypot(g.position[0] - (lo[0] + hi[0]) / 2,
                                                     g.position[1] - (lo[1] + hi[1]) / 2) > 0.06 for g in grasps)


def test_it_takes_the_cereal_as_the_planner_does(scene):
    assert scene.takes("cereal")


def _opens(check, tmp_path, seed: int, fraction: float) -> bool:
    made = check._Scene(write_world(generate(seed), tmp_path))
    try:
        return made.opens(check.DRAWER_HANDLE, check.DRAWER_JOINT, fraction)
    finally:
        made.close()


def test_a_long_arm_pulls_the_spoons_drawer_as_far_as_search_needs(check, scene):
    # seed 12 (whose robot sets the table) holds the handle closed and pulled 75 % open from one base pose
    assert scene.opens(check.DRAWER_HANDLE, check.DRAWER_JOINT, check.OPEN_FRACTION)


def test_a_short_arm_behind_its_base_pulls_the_drawer_only_part_of_the_way(check, tmp_path):
    # seed 7: a 5-joint arm whose shoulder stands behind the base's front: the drawer open 75 % would reach into the
    # base before the hand comes back that far; half way it can
    assert not _opens(check, tmp_path, 7, check.OPEN_FRACTION)
    assert _opens(check, tmp_path, 7, 0.5)
