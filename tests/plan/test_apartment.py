"""A second environment: the IAI apartment (../shared/models/apartment), set by the same action-level plan.

Nothing of the plan changes but its parameters: the table is the apartment's `table_area_main`, a
link of the apartment. The breakfast things stand on the kitchen island's countertop; the PR2
finds them, where to stand, which arm and grasp, and free spots on the table. The apartment's
floor is a link of its own model (not a separate floor object): the robot stands on it. Skipped
when ../shared/models is absent.
"""
from __future__ import annotations

from pathlib import Path

from pycram_cli.paths import plans_dir, worlds_dir
from pycram_cli.plan import load_plan, run_plan
from pycram_cli.reasoning import stable, supporting
from pycram_cli.worldfile.loader import load_world

BREAKFAST = """  - {name: bowl, type: bowl, file: objects/bowl.obj, position: [2.45, 2.3, 0.951], color: [0.85, 0.2, 0.2]}
  - {name: milk, type: milk, file: objects/milk.obj, position: [2.45, 2.55, 0.951], color: [0.95, 0.95, 0.98]}
  - {name: cereal, type: breakfast_cereal, file: objects/breakfast_cereal.obj, position: [2.45, 2.8, 0.951]}
  - {name: spoon, type: spoon, file: objects/spoon.obj, position: [2.45, 3.0, 0.951]}
"""


def apartment_world(folder: Path, shared_models: Path) -> Path:
    """The bundled kitchen's PR2 (its pose and joints) in the apartment, the breakfast on the island's countertop."""
    kitchen = (worlds_dir() / "kitchen.yaml").read_text()
    robot = kitchen[kitchen.index("  - name: pr2"):kitchen.index("  - name: kitchen")]
    robot = robot.replace("position: [0.0, 0.7, 0.0]", "position: [1.6, 2.5, 0.0]")
    text = ("gravity: [0, 0, -9.81]\nobjects:\n" + robot
            + f"  - {{name: apartment, type: environment, file: {shared_models / 'apartment' / 'apartment.urdf'}}}\n"
            + BREAKFAST)
    path = folder / "apartment.yaml"
    path.write_text(text)
    return path


def test_the_action_demo_sets_the_breakfast_on_the_apartments_table(tmp_path: Path, shared_models: Path) -> None:
    world = load_world(apartment_world(tmp_path, shared_models))
    try:
        params = {"table": "table_area_main", "furniture": "apartment"}
        result = run_plan(load_plan(plans_dir() / "set_table_actions.yaml"), world, params)
        apartment = world.get_object_by_name("apartment")
        set_ = [name for name in ("bowl", "milk", "cereal", "spoon")
                if supporting(apartment, world.get_object_by_name(name), link="table_area_main")
                and stable(world.get_object_by_name(name))]
        assert len(set_) >= 3, (set_, result.failure)
    finally:
        world.exit()
