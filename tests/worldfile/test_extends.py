"""`extends:` makes a world from another one (bundled or local): its objects, some changed by name, then new ones."""
from __future__ import annotations

from pathlib import Path

import pytest

from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.paths import worlds_dir
from pycram_cli.worldfile.spec import parse_world

KITCHEN = ["floor", "pr2", "kitchen", "milk", "cereal", "bowl", "spoon", "bottle"]


def problems(path: Path) -> list[tuple[str, int, str, str | None]]:
    with pytest.raises((InputError, InputErrors)) as err:
        parse_world(path)
    return [(Path(p.location.file).name, p.location.line, p.message, p.suggestion) for p in as_list(err.value)]


def test_a_world_extending_the_bundled_kitchen_adds_and_changes_objects(tmp_path: Path):
    world = tmp_path / "mine.yaml"
    world.write_text("extends: kitchen\nobjects:\n"
                     "  - {name: mug, type: mug, file: objects/mug.urdf, position: [1.3, 1.2, 0.851]}\n"
                     "  - {name: milk, position: [1.3, 1.1, 0.851]}\n")
    spec = parse_world(world)
    assert spec.object_names == [*KITCHEN, "mug"]
    milk = spec.objects[KITCHEN.index("milk")]
    assert (milk.type, milk.file.name, milk.position) == ("milk", "milk.obj", [1.3, 1.1, 0.851])
    assert spec.robot is not None and spec.robot.name == "pr2" and spec.robot_description is not None
    assert spec.description == parse_world(worlds_dir() / "kitchen.yaml").description  # inherited
    assert spec.path == world


def test_files_are_found_beside_the_file_that_names_them(tmp_path: Path):
    (tmp_path / "base").mkdir()
    (tmp_path / "base" / "box.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    (tmp_path / "base" / "room.yaml").write_text("objects:\n  - {name: box, type: box, file: box.obj}\n")
    (tmp_path / "mine.yaml").write_text("extends: base/room.yaml\ngravity: [0, 0, -1]\n"
                                        "objects:\n  - {name: box, position: [1, 0, 0]}\n")
    spec = parse_world(tmp_path / "mine.yaml")
    assert spec.objects[0].file == (tmp_path / "base" / "box.obj").resolve() and spec.gravity == [0, 0, -1]


def test_a_local_world_named_as_a_bundled_one_extends_the_bundled_one(tmp_path: Path, monkeypatch):
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "kitchen.yaml").write_text("extends: kitchen\nobjects:\n  - {name: bottle, position: [1.35, 0.3, 0.851]}\n")
    monkeypatch.chdir(tmp_path)
    assert parse_world(Path("worlds/kitchen.yaml")).object_names == KITCHEN


def test_problems_with_extends_are_located_with_suggestions(tmp_path: Path):
    world = tmp_path / "mine.yaml"
    world.write_text("extends: kitchn\nobjects: []\n")
    assert problems(world) == [("mine.yaml", 1, "world file not found: 'kitchn'", "did you mean 'kitchen'?")]
    world.write_text("extends: kitchen\nobjects:\n  - {name: botle, position: [1, 1, 1]}\n")
    assert problems(world) == [("mine.yaml", 3, "the world it extends has no object 'botle' to change, and a new "
                                "object needs type and file", "did you mean 'bottle'?")]


def test_worlds_extending_each_other_in_a_circle_are_an_input_error(tmp_path: Path):
    (tmp_path / "a.yaml").write_text("extends: b.yaml\n")
    (tmp_path / "b.yaml").write_text("extends: a.yaml\n")
    found = problems(tmp_path / "a.yaml")
    assert [(name, line) for name, line, _, _ in found] == [("b.yaml", 1)]
    assert "extend each other in a circle" in found[0][2]

