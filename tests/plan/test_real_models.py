"""The same plans run on the real ROS descriptions (../shared/models): the real PR2 in the real IAI kitchen.

Robot knowledge is data matched by the URDF's robot name, so the real PR2 gets the same description
as ours and the process modules drive it unchanged. Skipped when ../shared/models is absent.
"""
from __future__ import annotations

import math

import pytest

from pycram_cli.paths import plans_dir
from pycram_cli.plan import load_plan, run_plan
from pycram_cli.reasoning import stable, supporting
from pycram_cli.world.pose import angle_between
from pycram_cli.worldfile.loader import load_world


def test_set_table_places_the_breakfast_with_the_real_pr2_in_the_real_kitchen(real_kitchen):
    jobs = [{"type": "milk", "target": [-0.8, 1.0, 0.862], "arm": "left", "look": [1.3, 0.8, 0.95]},
            {"type": "bowl", "target": [-0.8, 1.2, 0.862], "arm": "right", "look": [1.3, 0.8, 0.95]},
            {"type": "breakfast_cereal", "target": [-1.0, 1.0, 0.862], "arm": "right", "look": [1.3, 0.8, 0.95]}]
    result = run_plan(load_plan(plans_dir() / "set_table.yaml"), real_kitchen, {"jobs": jobs})
    assert result.status == "succeeded", result.failure
    for name in ("milk", "bowl", "cereal"):
        obj = real_kitchen.get_object_by_name(name)
        assert obj.get_position()[0] < -0.6, name  # on the island
        assert stable(obj), name


# -- the design's own world: the real PR2, the real IAI kitchen and the design's object meshes ---------------------
# The meshes (../shared/models/objects) have their origin at their middle, as most downloaded meshes do; they stand
# where the design's listing 5.1 puts them (x, y), let down onto the counter — the spoon into the drawer, where the
# design keeps it.

LISTING = {  # name: (type, mesh, x, y)
    "milk": ("milk", "milk.stl", 1.3, 1.0),
    "spoon": ("spoon", "spoon.stl", 1.4, 0.8),
    "cereal": ("breakfast_cereal", "breakfast_cereal.stl", 1.3, 0.6),
    "bowl": ("bowl", "bowl.stl", 1.3, 0.8),
}
DRAWER_FLOOR = 0.7324  # the real drawer is hollow: five convex parts, its floor's top here


@pytest.fixture
def design_world(tmp_path, shared_models):
    objects = shared_models / "objects"
    lines = ["gravity: [0, 0, -9.81]", "objects:",
             f"  - {{name: floor, type: environment, file: {objects / 'plane.urdf'}}}",
             f"  - {{name: pr2, type: robot, file: {shared_models / 'pr2' / 'pr2.urdf'}}}",  # no torso height given
             f"  - {{name: kitchen, type: environment, file: {shared_models / 'kitchen' / 'kitchen.urdf'}}}"]
    for name, (kind, mesh, x, y) in LISTING.items():
        z = DRAWER_FLOOR + 0.03 if name == "spoon" else 1.0  # the listing's height (the spoon: in the drawer)
        lines.append(f"  - {{name: {name}, type: {kind}, file: {objects / mesh}, position: [{x}, {y}, {z}]}}")
    path = tmp_path / "design_kitchen.yaml"
    path.write_text("\n".join(lines) + "\n")
    world = load_world(path)
    kitchen = world.get_object_by_name("kitchen")
    for name in LISTING:  # let each down onto what is under it, touching it
        obj = world.get_object_by_name(name)
        x, y, z = obj.get_position()
        obj.set_position([x, y, z - world.distance(obj, kitchen, 1.0) + 0.0002])
    yield world
    world.exit()


BREAKFAST = [{"type": "bowl", "target": [-0.8, 1.2, 0.862], "arm": "right", "look": [1.3, 0.8, 0.95]},
             {"type": "milk", "target": [-0.8, 1.0, 0.862], "arm": "left", "look": [1.3, 0.8, 0.95]},
             {"type": "breakfast_cereal", "target": [-1.0, 1.0, 0.862], "arm": "right", "look": [1.3, 0.8, 0.95]}]


def test_the_design_world_takes_the_robot_descriptions_torso_height(design_world):
    assert design_world.robot.get_joint_position("torso_lift_joint") == pytest.approx(0.3)


def test_set_table_sets_milk_bowl_and_cereal_with_the_designs_meshes_in_the_real_kitchen(design_world):
    result = run_plan(load_plan(plans_dir() / "set_table.yaml"), design_world, {"jobs": BREAKFAST})
    assert result.status == "succeeded", result.failure
    kitchen = design_world.get_object_by_name("kitchen")
    for name in ("milk", "bowl", "cereal"):
        obj = design_world.get_object_by_name(name)
        assert obj.get_position()[0] < -0.6, name  # on the island
        assert supporting(kitchen, obj, link="kitchen_island_surface"), name
        assert stable(obj), name


def test_the_whole_demo_sets_the_breakfast_and_stands_the_designs_spoon_on_the_island_still_rocking(design_world):
    """set_table as shipped (all four jobs): milk, bowl and cereal are set; the spoon is taken from the drawer by its
    handle and stood on the island, but the plan's last assert fails: the design's spoon.stl is an open, arched
    surface (no volume), which PyBullet collides as its convex hull resting on three points (the bottom of its bowl
    and the two corners of its handle's end, 1.6 cm apart). Let go, it rocks by 1-4° every 0.05 s for longer than a
    placed object is left to settle (1 s), and `stable` rightly says no; lying in the drawer, untouched since the
    world was loaded, it rocks just the same. (Placed alone, from another pose, it sometimes happens to come to rest.)"""
    spoon = design_world.get_object_by_name("spoon")
    assert not stable(spoon)  # as loaded, untouched, in the drawer
    result = run_plan(load_plan(plans_dir() / "set_table.yaml"), design_world)
    assert result.status == "failed"
    assert result.failure["type"] == "ReasoningFailure" and "spoon is not stable" in result.failure["message"]
    assert result.failure["path"].startswith("body/0:for_each/item 3/")  # the spoon's job, the last
    kitchen = design_world.get_object_by_name("kitchen")
    for name in ("milk", "bowl", "cereal", "spoon"):
        obj = design_world.get_object_by_name(name)
        assert obj.get_position()[0] < -0.6, name  # on the island
        assert supporting(kitchen, obj, link="kitchen_island_surface"), name
    for name in ("milk", "bowl", "cereal"):
        assert stable(design_world.get_object_by_name(name)), name


def test_stable_says_the_designs_spoon_rocks_rather_than_that_it_moved(design_world):
    """Lying in the drawer as loaded, the design's spoon swings by 8.2° and 5.2° in its first two seconds of a plain
    simulation (bench/stable_tolerance.py): `stable` says it is not at rest and rocks, with how far."""
    answer = stable(design_world.get_object_by_name("spoon"))
    assert not answer and answer.motion == "rocks"
    assert answer.amplitude is not None and answer.amplitude[1] > math.radians(1.0)


def test_the_design_meshes_settled_by_physics_are_set_as_well_as_upright_ones(design_world):
    """Real objects rest tilted: after 3 s of physics the design's meshes lean by 1-3° (the bowl most). The unchanged
    demo still sets the milk, the bowl and the cereal; the spoon rocks for ever (see above) and fails the last assert."""
    before = {name: design_world.get_object_by_name(name).get_orientation() for name in LISTING}
    design_world.simulate(3.0)
    tilts = [angle_between(before[name], design_world.get_object_by_name(name).get_orientation()) for name in LISTING]
    assert max(tilts) > math.radians(1.0)  # settled, not as placed
    run_plan(load_plan(plans_dir() / "set_table.yaml"), design_world)
    kitchen = design_world.get_object_by_name("kitchen")
    set_ = [name for name in LISTING
            if supporting(kitchen, design_world.get_object_by_name(name), link="kitchen_island_surface")
            and stable(design_world.get_object_by_name(name))]
    assert len(set_) >= 3, set_
