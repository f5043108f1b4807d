"""Malformed variants of the bundled robot descriptions and variation files (issue 29), made as the world and plan
fuzzer makes its variants (test_fuzz_inputs.py): a key misspelt or removed, a value of the wrong type, a key that
is not a name, NaN and huge numbers, an alias bomb, nesting beyond the limit, bytes that are not UTF-8, a key
given twice, a file that is not a mapping. A mutation may leave a file valid (a pose value changed to another
number), so each variant is exit 0, or exit 2 with a located message — never a traceback, an internal error
(exit 3), a hang or a memory blow-up. They run in-process through `pycram validate`, within a time bound.
"""
from __future__ import annotations

import copy
import os
import random
import re
import resource
import time
from pathlib import Path
from typing import Any, Callable

import yaml
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from test_fuzz_inputs import (MARK, alias_bomb, dump, duplicate_key, key_not_a_name, misspell_key, non_finite, not_utf8,
                              put, remove_key, too_deep, whole_file, wrong_type)

REPO = Path(__file__).resolve().parents[2]
ROBOTS = REPO / "resources" / "robots"
DESCRIPTIONS = [ROBOTS / "pr2" / "pr2.yaml", ROBOTS / "fetch" / "fetch.yaml"]
VARIATIONS = [REPO / "plans" / "set_table.vary.yaml"]
DESCRIPTION_VARIANTS = 80  # about 15 s on the development machine
VARIATION_VARIANTS = 120  # about 10 s
TIME_LIMIT = 60.0  # seconds for the variants of one kind of file
MEMORY_LIMIT = 300 * 1024  # kB
Path_ = tuple[Any, ...]


def sites(data: Any) -> dict[str, list[Path_]]:
    """Where each kind of mutation applies: every key, every mapping, every number, every value."""
    found: dict[str, list[Path_]] = {k: [] for k in ("key", "mapping", "number", "scalar", "text", "type")}

    def walk(value: Any, path: Path_) -> None:
        if path:
            found["type"].append(path)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            found["number"].append(path)
        if isinstance(value, dict):
            found["mapping"].append(path)
            for key, item in value.items():
                found["key"].append(path + (key,))
                walk(item, path + (key,))
        elif isinstance(value, list):
            for index, item in enumerate(value):
                walk(item, path + (index,))
        else:
            found["scalar"].append(path)
            if isinstance(value, str):
                found["text"].append(path)

    walk(data, ())
    return found


def huge_number(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, MARK)
    return dump(data, rng.choice(["1.0e+300", "-1.0e+300", "123456789012345678901234567890", "1e-320"]))


#: files that are there but cannot be read as a file: a device, a folder, a named pipe (`fifo`, made by the tests)
SPECIAL_FILES = ["/dev/zero", "/dev/null", "/"]


def special_file(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, rng.choice([*SPECIAL_FILES, str(fifo)]))
    return dump(data)


fifo = Path("/nonexistent")


def make_fifo(folder: Path) -> None:
    """The named pipe `special_file` names, in `folder`."""
    global fifo
    fifo = folder / "pipe.urdf"
    os.mkfifo(fifo)


def emptied(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, rng.choice([{}, [], ""]))
    return dump(data)


MUTATIONS: dict[str, tuple[str, Callable[[Any, Path_, random.Random], bytes]]] = {
    "special file": ("text", special_file),
    "emptied": ("type", emptied),
    "misspelt key": ("key", misspell_key),
    "missing key": ("key", remove_key),
    "wrong type": ("type", wrong_type),
    "key not a name": ("mapping", key_not_a_name),
    "non-finite number": ("number", non_finite),
    "huge number": ("number", huge_number),
    "alias bomb": ("scalar", alias_bomb),
    "nesting too deep": ("scalar", too_deep),
    "not UTF-8": ("scalar", not_utf8),
    "duplicate key": ("scalar", duplicate_key),
    "not a mapping": ("scalar", whole_file),
}


def variants(sources: dict[Path, Any], count: int, seed: int) -> list[tuple[str, Path, bytes]]:
    rng = random.Random(seed)
    places = {path: sites(data) for path, data in sources.items()}
    made = []
    while len(made) < count:
        source = rng.choice(list(sources))
        name = rng.choice(list(MUTATIONS))
        kind, mutate = MUTATIONS[name]
        if not places[source][kind]:
            continue
        path = rng.choice(places[source][kind])
        made.append((f"{source.name}: {name} at {'/'.join(map(str, path)) or 'the top'}", source,
                     mutate(copy.deepcopy(sources[source]), path, rng)))
    return made


def check_all(made: list[tuple[str, list[str], list[Path]]]) -> None:
    """Each (label, validate arguments, files a message may name): exit 0, or exit 2 located; within the bounds."""
    runner = CliRunner()
    memory_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    started = time.monotonic()
    exits = {0: 0, 2: 0}
    for label, args, files in made:
        begun = time.monotonic()
        result = runner.invoke(cli, ["validate", *args])
        took = time.monotonic() - begun
        assert result.exit_code in (0, 2), f"{label}: exit {result.exit_code}\n{result.output}"
        assert "Traceback" not in result.output and "internal error" not in result.output, f"{label}\n{result.output}"
        if result.exit_code == 2:
            located = "|".join(re.escape(str(f)) for f in files)
            assert re.search(rf"error: ({located})(:\d+:\d+)?: ", result.stderr), f"{label}: no location\n{result.stderr}"
        exits[result.exit_code] += 1
        assert took < 5.0, f"{label} took {took:.1f} s"
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - memory_before
    assert time.monotonic() - started < TIME_LIMIT
    assert grown < MEMORY_LIMIT
    assert exits[2] > len(made) // 2, exits  # most mutations break the file: the fuzzer does test something


def test_malformed_robot_descriptions_are_exit_2_with_a_location_or_valid(tmp_path):
    make_fifo(tmp_path)
    sources = {}
    for path in DESCRIPTIONS:
        data = yaml.safe_load(path.read_text())
        data["urdf"] = str(path.with_name(data["urdf"]))  # the variants are written elsewhere
        sources[path] = data
    made = []
    for index, (label, source, content) in enumerate(variants(sources, DESCRIPTION_VARIANTS, 29)):
        description = tmp_path / f"d{index}.yaml"
        description.write_bytes(content)
        world = tmp_path / f"w{index}.yaml"
        world.write_text("objects:\n  - {name: floor, type: environment, file: plane.urdf}\n"
                         f"  - {{name: robot, type: robot, file: robots/{source.stem}/{source.stem}.urdf, "
                         f"description: {description.name}}}\n"
                         "  - {name: cube, type: box, file: cube_small.urdf, position: [0.6, 0, 0.8]}\n")
        plan = tmp_path / f"p{index}.yaml"
        plan.write_text(f"world: {world.name}\nbody:\n  - move-arm-joints: {{left-arm: [0, 0, 0, 0, 0, 0, 0]}}\n"
                        "  - pick-up: {object: cube}\n  - looking: {target: [1, 0, 1]}\n")
        made.append((label, [str(world), str(plan)], [description, world, plan]))
    check_all(made)


def test_malformed_variation_files_are_exit_2_with_a_location_or_valid(tmp_path):
    make_fifo(tmp_path)
    sources = {path: yaml.safe_load(path.read_text()) for path in VARIATIONS}
    for data in sources.values():
        data["objects"]["milk"]["swap"] = ["keep", {"type": "milk", "file": "objects/milk.obj", "color": [1, 1, 1],
                                                    "mass": 0.5}]
        data["objects"]["cereal"]["region"] = {"on": "kitchen/sink_area_surface", "margin": 0.02}
        data["params"] = {"jobs": [[{"object": "milk", "target": "left"}]]} if "params" not in data else data["params"]
    made = []
    for index, (label, source, content) in enumerate(variants(sources, VARIATION_VARIANTS, 29)):
        folder = tmp_path / f"v{index}"
        folder.mkdir()
        path = folder / source.name
        path.write_bytes(content)
        made.append((label, [str(path)], [path]))
    check_all(made)


def test_the_fuzzed_sources_are_valid_to_start_with():
    """The mutations start from valid files (else every variant would fail for the same reason)."""
    worlds = [REPO / "worlds" / "kitchen.yaml", REPO / "worlds" / "kitchen_fetch.yaml"]  # the PR2's and the Fetch's
    result = CliRunner().invoke(cli, ["validate", *map(str, worlds), *map(str, VARIATIONS)])
    assert result.exit_code == 0, result.output
