"""Surfaces in worlds nobody here wrote: two tables of one model (pybullet_data's, both `baseLink`) — a bare link
name that several objects have must say whose (`table_b/baseLink`), and the demo plan says whose; an object set off
a table's edge is a warning of `validate`; a plan parameter given with -p replaces its default's world check."""
from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.errors import InputError
from pycram_cli.locations.spec import find_surface
from pycram_cli.paths import worlds_dir
from pycram_cli.scenario import prepare
from pycram_cli.reasoning import supporting
from pycram_cli.worldfile.loader import load_world


def tables_world(folder: Path, spoon_y: float = -0.4) -> Path:
    """The bundled PR2 between two pybullet_data tables; the breakfast on table_a, which is to be set on table_b."""
    kitchen = (worlds_dir() / "kitchen.yaml").read_text()
    robot = kitchen[kitchen.index("  - name: pr2"):kitchen.index("  - name: kitchen")]
    robot = robot.replace("position: [0.0, 0.7, 0.0]", "position: [0.0, 0.0, 0.0]")
    path = folder / "tables.yaml"
    things = [
        "{name: floor, type: environment, file: plane.urdf}",
        "{name: table_a, type: environment, file: table/table.urdf, position: [1.5, 0, 0]}",
        "{name: table_b, type: environment, file: table/table.urdf, position: [-1.6, 0.5, 0], "
        "orientation: [0, 0, 0.7071068, 0.7071068]}",
        "{name: bowl, type: bowl, file: objects/bowl.obj, position: [0.95, -0.2, 0.626]}",
        "{name: milk, type: milk, file: objects/milk.obj, position: [0.95, 0.05, 0.626]}",
        f"{{name: spoon, type: spoon, file: objects/spoon.obj, position: [0.95, {spoon_y}, 0.626]}}",
    ]
    path.write_text("objects:\n" + robot + "".join(f"  - {thing}\n" for thing in things))
    return path


def run(*args: object):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_a_link_several_objects_have_must_say_whose(tmp_path):
    world = load_world(tables_world(tmp_path))
    try:
        with pytest.raises(InputError) as caught:
            find_surface(world, "baseLink")
        assert "'baseLink' is a link of table_a and table_b: say whose" in caught.value.message
        assert caught.value.suggestion == "e.g. on: table_b/baseLink"
        surface = find_surface(world, "table_b/baseLink")
        assert surface.obj.name == "table_b" and surface.link == "baseLink"
        assert surface.name == "table_b/baseLink"  # as traces and messages say it: whose, since both have one
        assert find_surface(world, "table_b").name == "table_b"
        with pytest.raises(InputError, match="'table_b' has no link 'top'"):
            find_surface(world, "table_b/top")
        with pytest.raises(InputError, match="no object 'table_c'"):
            find_surface(world, "table_c/baseLink")
    finally:
        world.exit()


def test_validate_says_whose_link_is_meant(tmp_path):
    world = tables_world(tmp_path)
    plan = tmp_path / "plan.yaml"
    plan.write_text("body:\n  - action: place\n    object: milk\n    target: {on: baseLink}\n")
    result = run("validate", plan, "--world", world)
    assert result.exit_code == 2
    assert "plan.yaml:4:" in result.output and "'baseLink' is a link of table_a and table_b: say whose" in result.output
    assert "e.g. table_b/baseLink" in result.output
    plan.write_text("body:\n  - action: place\n    object: milk\n    target: {on: table_b/baseLink}\n")
    assert run("validate", plan, "--world", world).exit_code == 0


def test_the_demo_sets_the_other_table_not_the_one_the_things_stand_on(tmp_path):
    """Before the plan said whose surface, `on: baseLink` meant table_a's, where the things already stood."""
    scenario = prepare("set_table_actions", tables_world(tmp_path),
                       params={"table": "baseLink", "furniture": "table_b", "objects": ["milk", "bowl"]})
    world = scenario.load_world()
    try:
        result = scenario.run(world)
        assert result.succeeded, result.failure
        table_b = world.get_object_by_name("table_b")
        assert all(supporting(table_b, world.get_object_by_name(name), link="baseLink") for name in ("milk", "bowl"))
    finally:
        world.exit()


def test_a_parameter_given_with_p_replaces_its_defaults_world_check(tmp_path):
    world = tables_world(tmp_path)
    given = run("validate", "set_table_actions", "--world", world, "-p", "table=baseLink", "-p", "furniture=table_b")
    assert given.exit_code == 0, given.output
    default = run("validate", "set_table_actions", "--world", world)
    assert default.exit_code == 2 and "the default of parameter 'furniture' is an object: the world has no object " \
                                      "'kitchen'" in default.output


def test_an_object_off_a_tables_edge_is_a_warning_of_validate(tmp_path):
    result = run("validate", tables_world(tmp_path, spoon_y=-0.55))
    assert result.exit_code == 0
    assert "tables.yaml:" in result.output and "spoon is not supported: its centre of mass is" in result.output
    assert "above floor: it falls as soon as anything is simulated" in result.output
    assert "not supported" not in run("validate", tables_world(tmp_path)).output
