"""Variation files: checked with file:line:column, drawn from a seed alone, applied to worlds that
are kept loaded and give byte-identical traces to freshly loaded ones."""
from __future__ import annotations

import json
import os
import time
import math
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.paths import plans_dir
from pycram_cli.plan import trace as traces
from pycram_cli.scenario import prepare
from pycram_cli.scenario.variation_files import parse_variations, read_variations
from pycram_cli.scenario.variations import scenario_seed
from pycram_cli.scenario.worlds import LoadedWorlds

SET_TABLE_VARY = plans_dir() / "set_table.vary.yaml"


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture(scope="module")
def kitchen():
    return prepare("set_table")


def problems(path, scenario) -> list[InputError]:
    with pytest.raises((InputError, InputErrors)) as caught:
        parse_variations(path, scenario.world, scenario.plan)
    return as_list(caught.value)


def test_every_problem_is_reported_at_its_place_with_its_key(tmp_path, kitchen):
    path = write(tmp_path, "bad.vary.yaml", """\
        objects:
          milkk: {noise: 0.1}
          cereal:
            region: {on: kitchen/sink_surface}
            yaw: 5
          bowl:
            present: 2
            colour: red
          kitchen: {noise: 0.1}
        robot:
          noise: [0.1, 0.1]
        params:
          jobz: [a, b]
          counter: 3
        colour: blue
    """)
    found = {(e.location.line, e.location.column, e.key) for e in problems(path, kitchen)}
    assert found == {(2, 3, "objects"), (4, 18, "on"), (5, 10, "yaw"), (7, 14, "present"), (8, 5, "colour"),
                     (9, 3, "objects"), (11, 10, "noise"), (13, 3, "jobz"), (14, 12, "counter"), (15, 1, "colour")}
    messages = "\n".join(e.format() for e in problems(path, kitchen))
    assert f"{path}:2:3: objects: the world kitchen.yaml has no object 'milkk' (did you mean 'milk'?)" in messages
    assert "object 'kitchen' has no link 'sink_surface' (did you mean 'sink_area_surface'?)" in messages
    assert "plan 'set_table' has no parameter 'jobz' (did you mean 'jobs'?)" in messages


def test_drawn_parameter_values_must_fit_the_parameters_declared_types(tmp_path):
    scenario = prepare("set_table_actions")  # objects: a list, table: a link
    path = write(tmp_path, "typed.vary.yaml", """\
        params:
          objects: [[milk], milk]
          table: {range: [0, 1]}
    """)
    found = [(e.location.line, e.location.column, e.key, e.message) for e in problems(path, scenario)]
    assert found == [(2, 21, "objects", "parameter 'objects' is a list: expected a list, got the string 'milk'"),
                     (3, 18, "table", "parameter 'table' is a link: expected a name, got 0")]


def test_drawn_values_of_an_object_parameter_must_name_objects_of_the_world(tmp_path):
    plan = write(tmp_path, "fetch.yaml", "world: kitchen\nparams: {object: {type: object, default: milk}}\n"
                                         "body: [{log: $object}]\n")
    path = write(tmp_path, "fetch.vary.yaml", "params:\n  object: [milk, bowwl]\n")
    found = [(e.location.line, e.message, e.suggestion) for e in problems(path, prepare(plan))]
    assert found == [(2, "parameter 'object' is an object: the world has no object 'bowwl'", "did you mean 'bowl'?")]


def test_bad_variation_files_exit_2_in_validate_and_sweep(tmp_path):
    path = write(tmp_path, "set_table.vary.yaml", "plan: set_table\nobjects:\n  milk: {noise: -1}\n")
    result = CliRunner().invoke(cli, ["validate", str(path)])
    assert result.exit_code == 2
    assert f"{path}:3:17: noise: noise must not be negative" in result.stderr
    result = CliRunner().invoke(cli, ["sweep", "set_table", "--vary", str(path), "-n", "2", "--out",
                                      str(tmp_path / "out")])
    assert result.exit_code == 2 and "noise must not be negative" in result.stderr
    assert not (tmp_path / "out").exists()
    assert CliRunner().invoke(cli, ["validate", str(SET_TABLE_VARY)]).exit_code == 0


def test_a_scenario_is_a_function_of_its_seed(kitchen, tmp_path):
    path = write(tmp_path, "v.yaml", """\
        separation: 0.1
        objects:
          milk: {region: {on: kitchen/sink_area_surface, margin: 0.1}, yaw: 1.0}
          cereal: {noise: [0.05, 0.02, 0]}
          bowl: {region: {box: [[1.2, 0.7, 0.851], [1.4, 0.9, 0.851]]}}
          bottle: {present: 0.5}
          spoon: {swap: [keep, {type: fork, file: objects/spoon.obj}]}
        robot: {noise: [0.1, 0.1, 0], yaw: 0.2}
        params:
          counter: [{target: [0.6, 0.7, 0], orientation: [0, 0, 0, 1]}, {target: [0.7, 0.7, 0], orientation: [0, 0, 0, 1]}]
    """)
    variations = read_variations(path, kitchen.world, kitchen.plan)
    assert scenario_seed(0, 0) == 1940278583 and scenario_seed(0, 1) != scenario_seed(1, 0)
    a, b = variations.sample(12345), variations.sample(12345)
    assert a == b and variations.sample(12346) != a
    top = variations.surfaces[("kitchen", "sink_area_surface")]
    bottles = swaps = 0
    for seed in range(60):
        variant = variations.sample(seed)
        milk = variant.poses["milk"][0]
        assert top[0][0] + 0.1 <= milk[0] <= top[1][0] - 0.1 and top[0][1] + 0.1 <= milk[1] <= top[1][1] - 0.1
        assert milk[2] == top[1][2]
        assert abs(variant.poses["cereal"][0][0] - 1.3) <= 0.05 and variant.poses["cereal"][0][2] == 0.851
        assert 1.2 <= variant.poses["bowl"][0][0] <= 1.4
        assert abs(variant.varied["robot"]["yaw"]) <= 0.2 and variant.params["counter"]["target"][0] in (0.6, 0.7)
        bottles += "bottle" not in variant.absent
        swaps += "spoon" in variant.swaps
        free = [variant.poses[n][0] for n in ("milk", "cereal", "bowl")]
        assert all(math.dist(p[:2], q[:2]) >= 0.1 for i, p in enumerate(free) for q in free[i + 1:])
        spec = variant.world_spec(kitchen.world)
        assert ("bottle" in spec.object_names) == ("bottle" not in variant.absent)
        assert [o.type for o in spec.objects if o.name == "spoon"] == ["fork" if "spoon" in variant.swaps else "spoon"]
    assert 15 < bottles < 45 and 15 < swaps < 45


def _comparable(result) -> str:
    return json.dumps(traces.normalised(traces.comparable(result.trace)), sort_keys=True)


def test_worlds_kept_loaded_give_the_traces_of_fresh_worlds(kitchen):
    """The sweep's determinism: a world reset after other runs is a freshly loaded world, to the byte."""
    variations = read_variations(SET_TABLE_VARY, kitchen.world, kitchen.plan)
    variants = [variations.sample(scenario_seed(0, i), i) for i in (0, 1, 3)]
    fresh = [_comparable(kitchen.varied(v).run()) for v in variants]
    assert len(set(fresh)) == 3
    worlds = LoadedWorlds(kitchen)
    try:
        again = [_comparable(worlds.run(v)[0]) for v in reversed(variants)]
    finally:
        worlds.close()
    assert again[::-1] == fresh
    assert any(v.absent for v in variants) and any(not v.absent for v in variants)  # two structures, two worlds
    assert worlds.loads == 2


# -- swaps checked as world objects are (issue 29) ----------------------------------------------------------


@pytest.mark.parametrize("entry, key, message", [
    ("{type: milk, file: objects/milk.obj, mass: -1}", "mass", "mass must be positive (kg)"),
    ("{type: milk, file: objects/milk.obj, mass: 0}", "mass", "mass must be positive (kg)"),
    ("{type: '', file: objects/milk.obj}", "type", "the swapped object's type must not be empty"),
    ("{type: milk, file: objects/milk.obj, color: [2, 0, 0]}", "color", "color values must be between 0 and 1"),
    ("{type: milk, file: pipe.obj}", "file", "named pipe"),
    ("{type: milk, file: zero.obj}", "file", "not a regular file"),
    ("{type: milk, file: garbage.urdf}", "file", "cannot read model file garbage.urdf"),
    ("{type: milk, file: nolinks.urdf}", "file", "the model has no <link>"),
])
def test_a_swap_is_checked_as_a_world_object_is(tmp_path, kitchen, entry, key, message):
    os.mkfifo(tmp_path / "pipe.obj")
    (tmp_path / "zero.obj").symlink_to("/dev/zero")
    (tmp_path / "garbage.urdf").write_text("<robot name='x'><link name=")
    (tmp_path / "nolinks.urdf").write_text("<robot name='x'/>")
    world = tmp_path / "kitchen.yaml"
    world.write_text(kitchen.world.path.read_text())  # swapped files are looked for beside the world
    path = write(tmp_path, "set_table.vary.yaml", f"plan: set_table\nobjects:\n  milk:\n    swap:\n      - {entry}\n")
    started = time.monotonic()
    result = CliRunner().invoke(cli, ["validate", str(path), "--world", str(world)])
    assert time.monotonic() - started < 30
    assert result.exit_code == 2, result.output
    assert f"{path}:5:" in result.stderr and f"{key}: " in result.stderr and message in result.stderr, result.stderr
