"""Objects from elsewhere: a Y-up mesh from pybullet_data, an origin that is not the model's bottom.

A world object says which of its model's axes points up (`up: y` for pybullet_data's duck), or
its `orientation` does; either way the object keeps that side up when it is placed again. An
object that starts inside another body is an input error naming both, the depth and the height
that frees it; a duck stood on its feet can be carried to the island.
"""
from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.errors import InputError
from pycram_cli.paths import worlds_dir
from pycram_cli.worldfile.loader import load_world


def kitchen_with(tmp_path: Path, entry: str) -> Path:
    """The bundled kitchen world with one more object (YAML lines of one list item)."""
    text = (worlds_dir() / "kitchen.yaml").read_text().replace(
        "# yaml-language-server: $schema=../resources/schemas/world.schema.json\n", "")
    path = tmp_path / "world.yaml"
    path.write_text(text.rstrip("\n") + "\n" + entry)
    return path


DUCK_ON_ITS_SIDE = """  - name: duck
    type: duck
    file: duck_vhacd.urdf
    position: [1.35, 0.25, 0.851]
"""
DUCK_UPRIGHT = """  - name: duck
    type: duck
    file: duck_vhacd.urdf
    up: y
    position: [1.35, 0.25, 0.847]
"""


def test_an_object_that_starts_inside_another_is_an_input_error_naming_both(tmp_path: Path) -> None:
    world = kitchen_with(tmp_path, DUCK_ON_ITS_SIDE)
    result = CliRunner().invoke(cli, ["validate", str(world)])
    assert result.exit_code == 2, result.output
    assert "duck starts 27 mm inside kitchen (sink_area_surface)" in result.stderr
    assert "raise it to z = 0.879" in result.stderr
    assert f"{world}:" in result.stderr
    with pytest.raises(InputError):
        load_world(world)


def test_up_names_the_models_axis_that_points_up(tmp_path: Path) -> None:
    world = load_world(kitchen_with(tmp_path, DUCK_UPRIGHT))
    try:
        duck = world.get_object_by_name("duck")
        lo, hi = duck.get_aabb()
        assert hi[2] - lo[2] > 0.08  # standing: taller than it is when lying on its side
        assert duck.upright == pytest.approx((0.7071068, 0.0, 0.0, 0.7071068))
    finally:
        world.exit()


def test_a_misspelt_up_axis_is_an_input_error_with_a_suggestion(tmp_path: Path) -> None:
    world = kitchen_with(tmp_path, DUCK_UPRIGHT.replace("up: y", "up: Y"))
    result = CliRunner().invoke(cli, ["validate", str(world)])
    assert result.exit_code == 2
    assert "up: expected the model's axis that points up" in result.stderr and "did you mean 'y'" in result.stderr


def test_the_duck_stood_on_its_feet_is_carried_to_the_island_where_it_stands_stably(tmp_path: Path) -> None:
    world = kitchen_with(tmp_path, DUCK_UPRIGHT)
    plan = tmp_path / "plan.yaml"
    plan.write_text("world: world.yaml\nbody:\n  - action: transport\n    object: duck\n"
                    "    target: {on: kitchen_island_surface}\n")
    result = CliRunner().invoke(cli, ["run", str(plan), "--trace", str(tmp_path / "trace.json")])
    assert result.exit_code == 0, result.output
    assert "succeeded" in result.output
