"""The same plans run on the real ROS descriptions (../shared/models): the real PR2 in the real IAI kitchen.

Robot knowledge is data matched by the URDF's robot name, so the real PR2 gets the same description
as ours and the process modules drive it unchanged. Skipped when ../shared/models is absent.
"""
from __future__ import annotations

import pytest

from pycram_cli.paths import default_world, plans_dir
from pycram_cli.plan import load_plan, run_plan
from pycram_cli.reasoning import stable
from pycram_cli.worldfile.loader import load_world


@pytest.fixture
def real_world(tmp_path, shared_models):
    text = default_world().read_text()
    text = text.replace("file: robots/pr2/pr2.urdf", f"file: {shared_models / 'pr2' / 'pr2.urdf'}")
    text = text.replace("file: environments/kitchen/kitchen.urdf", f"file: {shared_models / 'kitchen' / 'kitchen.urdf'}")
    path = tmp_path / "real_kitchen.yaml"
    path.write_text(text)
    world = load_world(path)
    yield world
    world.exit()


def test_set_table_places_the_breakfast_with_the_real_pr2_in_the_real_kitchen(real_world):
    jobs = [{"type": "milk", "target": [-0.8, 1.0, 0.862], "arm": "left", "look": [1.3, 0.8, 0.95]},
            {"type": "bowl", "target": [-0.8, 1.2, 0.862], "arm": "right", "look": [1.3, 0.8, 0.95]},
            {"type": "breakfast_cereal", "target": [-1.0, 1.0, 0.862], "arm": "right", "look": [1.3, 0.8, 0.95]}]
    result = run_plan(load_plan(plans_dir() / "set_table.yaml"), real_world, {"jobs": jobs})
    assert result.status == "succeeded", result.failure
    for name in ("milk", "bowl", "cereal"):
        obj = real_world.get_object_by_name(name)
        assert obj.get_position()[0] < -0.6, name  # on the island
        assert stable(obj), name
