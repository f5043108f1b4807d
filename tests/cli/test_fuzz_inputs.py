"""Malformed variants of the shipped worlds and plans (issue 18): every one is exit 2 with a located message —
never a traceback, another exit code, a hang or a memory blow-up.

A few hundred variants are made from worlds/kitchen.yaml and every plan in plans/ by mutations
that make a file invalid by construction: a structural key misspelt or removed, a value of the
wrong type, a key that is not a name (null, a number, true), a number that is not finite, a key given twice, an alias bomb, nesting beyond the
limit, bytes that are not UTF-8, an object name the world does not have, an empty name. They run
in-process through `pycram validate` (click's CliRunner), all within a time and a memory bound
(about 7 s and a few MB).
"""
from __future__ import annotations

import copy
import random
import re
import resource
import time
from pathlib import Path
from typing import Any, Callable

import yaml
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.designators import DESIGNATORS
from pycram_cli.plan import NODE_TYPES
from pycram_cli.reasoning import QUERIES
from pycram_cli.worldfile.spec import OBJECT_KEYS, OBJECT_REQUIRED

REPO = Path(__file__).resolve().parents[2]
SOURCES = [REPO / "worlds" / "kitchen.yaml",
           *sorted(p for p in (REPO / "plans").glob("*.yaml") if not p.name.endswith(".vary.yaml"))]  # plans only
VARIANTS = 300
SEED = 18
TIME_LIMIT = 60.0  # seconds for all of them (about 7 s on the development machine)
MEMORY_LIMIT = 300 * 1024  # kB the process may grow by (ru_maxrss is in kB on Linux)

HEADS = set(NODE_TYPES) | set(DESIGNATORS) | set(QUERIES)
STEP_KEYS = {"as", "on", "recover", "body", "then", "else", "do", "catch", "args", "message", "failure"}
LIST_KEYS = {"body", "then", "else", "do", "recover"}
Path_ = tuple[Any, ...]


def is_step(value: Any) -> bool:
    return isinstance(value, dict) and any(key in HEADS for key in value)


def head_of(step: dict) -> str:
    return next(key for key in step if key in HEADS)


def sites(data: Any, world: bool) -> dict[str, list[Path_]]:
    """Where each kind of mutation applies (paths into the data), for a world or a plan file."""
    found: dict[str, list[Path_]] = {k: [] for k in ("key", "required", "type", "number", "name", "scalar",
                                                     "mapping")}

    def walk(value: Any, path: Path_, structural: bool) -> None:
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            found["number"].append(path)
        if isinstance(value, (str, int, float)) and not isinstance(value, bool):
            found["scalar"].append(path)
        if isinstance(value, list):
            for index, item in enumerate(value):
                walk(item, path + (index,), structural and (is_step(item) or bool(path) and path[-1] == "objects"))
            return
        if not isinstance(value, dict):
            return
        found["mapping"].append(path)  # a mapping whose keys are names (free-form values are not walked)
        if world:
            if path == ():
                found["key"] += [path + ("objects",)]
                found["required"].append(path + ("objects",))
            elif len(path) == 2 and path[0] == "objects":
                found["key"] += [path + (k,) for k in value if k in OBJECT_KEYS]
                found["required"] += [path + (k,) for k in OBJECT_REQUIRED]
                found["type"] += [path + (k,) for k in value if k in ("name", "position", "orientation", "joints",
                                                                      "attach", "fixed", "file", "type")]
                found["name"].append(path + ("name",))
        else:
            if path == ():
                found["mapping"] += [path + (k,) for k in ("params", "plans") if isinstance(value.get(k), dict)]
                found["key"] += [path + (k,) for k in value if k in ("world", "params", "plans", "body")]
                found["required"].append(path + ("body",))
                found["type"].append(path + ("body",))
            elif len(path) == 2 and path[0] == "plans" and isinstance(value, dict):
                found["key"] += [path + (k,) for k in value if k in ("params", "body", "returns")]
                found["required"].append(path + ("body",))
            if is_step(value):
                head = head_of(value)
                found["key"].append(path + (head,))
                found["key"] += [path + (k,) for k in value if k in STEP_KEYS and k != "args"]
                found["type"] += [path + (k,) for k in value if k in LIST_KEYS or k in ("as",)]
                slots = value[head]
                spec = DESIGNATORS.get(head) or QUERIES.get(head)
                if isinstance(slots, dict) and spec is not None:
                    found["key"] += [path + (head, k) for k in slots]
                    found["type"].append(path + (head,))
                    required = [s.name for s in getattr(spec, "slots", ())] + \
                               [q.name for q in getattr(spec, "params", ())]
                    required = [n for n in required if _required(spec, n)]
                    found["required"] += [path + (head, n) for n in required if n in slots]
                    found["name"] += [path + (head, k) for k, v in slots.items()
                                      if k in ("object", "part-of", "a", "b") and isinstance(v, str)
                                      and not v.startswith("$")]
        for key, item in value.items():
            if key in ("params", "set", "args", "returns", "log") or key == "for_each" and not isinstance(item, list):
                _numbers_only(item, path + (key,), found)
                continue
            walk(item, path + (key,), structural)

    walk(data, (), True)
    return found


def _required(spec: Any, name: str) -> bool:
    for item in (*getattr(spec, "slots", ()), *getattr(spec, "params", ())):
        if item.name == name:
            return bool(item.required)
    return False


def _numbers_only(value: Any, path: Path_, found: dict[str, list[Path_]]) -> None:
    """Inside free-form values (parameters, messages) only non-finite numbers are surely invalid."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        found["number"].append(path)
    elif isinstance(value, dict):
        for key, item in value.items():
            _numbers_only(item, path + (key,), found)
    elif isinstance(value, list):
        for index, item in enumerate(value):
            _numbers_only(item, path + (index,), found)


def get(data: Any, path: Path_) -> Any:
    for part in path:
        data = data[part]
    return data


def put(data: Any, path: Path_, value: Any) -> None:
    get(data, path[:-1])[path[-1]] = value


MARK = "__PYCRAM_FUZZ__"


def bomb() -> str:
    value = "&b0 [x, x, x, x, x, x, x, x, x, x]"
    for level in range(1, 6):
        value = f"&b{level} [{value}, " + ", ".join([f"*b{level - 1}"] * 9) + "]"
    return value


# -- the mutations: each takes (data, path, rng) and returns the file's bytes -------------------------------------

def dump(data: Any, replace: str | None = None) -> bytes:
    text = yaml.safe_dump(data, sort_keys=False, default_flow_style=False, allow_unicode=True, width=1000)
    if replace is not None:
        text = text.replace(f"'{MARK}'", replace).replace(MARK, replace)
    return text.encode()


def misspell_key(data: Any, path: Path_, rng: random.Random) -> bytes:
    parent = get(data, path[:-1])
    key = path[-1]
    renamed = {(f"{k}x" if k == key else k): v for k, v in parent.items()}
    if path[:-1]:
        put(data, path[:-1], renamed)
        return dump(data)
    return dump(renamed)


def remove_key(data: Any, path: Path_, rng: random.Random) -> bytes:
    del get(data, path[:-1])[path[-1]]
    return dump(data)


def wrong_type(data: Any, path: Path_, rng: random.Random) -> bytes:
    value = get(data, path)
    if isinstance(value, (list, dict)):
        replacement: Any = rng.choice([5, True, "text"]) if not isinstance(value, dict) or rng.random() < 0.5 else 7
    elif isinstance(value, bool):
        replacement = "maybe"
    elif isinstance(value, str):
        replacement = rng.choice([[1, 2], {"nested": "mapping"}, 3.5])
    else:
        replacement = "text"
    if path[-1] == "as":
        replacement = rng.choice(["$x", 5, "two words"])
    put(data, path, replacement)
    return dump(data)


def key_not_a_name(data: Any, path: Path_, rng: random.Random) -> bytes:
    mapping = get(data, path)
    value = rng.choice([1, "x", [1, 1, 1], next(iter(mapping.values()), "x")])
    mapping[rng.choice([None, 1, True, 2.5])] = value
    return dump(data)


def non_finite(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, MARK)
    return dump(data, rng.choice([".nan", ".inf", "-.inf", "1.0e+400"]))


def alias_bomb(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, MARK)
    return dump(data, bomb())


def too_deep(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, MARK)
    depth = rng.choice([150, 1000, 5000])
    return dump(data, "[" * depth + "]" * depth)


def not_utf8(data: Any, path: Path_, rng: random.Random) -> bytes:
    put(data, path, MARK)
    return dump(data).replace(MARK.encode(), b"caf\xe9\xff")


def unknown_name(data: Any, path: Path_, rng: random.Random) -> bytes:
    if path[0] == "objects":  # a world: an empty name, or one another object has
        others = [o["name"] for i, o in enumerate(data["objects"]) if i != path[1]]
        put(data, path, rng.choice(["", "  ", rng.choice(others)]))
    else:  # a plan: an object the world does not have
        put(data, path, rng.choice(["fridge", "", "kitchn", "milk_2"]))
    return dump(data)


def duplicate_key(data: Any, path: Path_, rng: random.Random) -> bytes:
    lines = dump(data).decode().splitlines()
    candidates = [i for i, line in enumerate(lines) if re.match(r"^\s*[A-Za-z_][\w-]*: \S", line)]
    index = rng.choice(candidates)
    lines.insert(index + 1, lines[index])
    return ("\n".join(lines) + "\n").encode()


def whole_file(data: Any, path: Path_, rng: random.Random) -> bytes:
    return rng.choice([b"- just\n- a list\n", b"42\n", b"", b"{\n", b"? [a, b]\n: 1\n", b"\x00\x01\x02", b"~: 1\n"])


MUTATIONS: dict[str, tuple[str, Callable[[Any, Path_, random.Random], bytes]]] = {
    "misspelt key": ("key", misspell_key),
    "missing key": ("required", remove_key),
    "wrong type": ("type", wrong_type),
    "key not a name": ("mapping", key_not_a_name),
    "non-finite number": ("number", non_finite),
    "alias bomb": ("scalar", alias_bomb),
    "nesting too deep": ("scalar", too_deep),
    "not UTF-8": ("scalar", not_utf8),
    "unknown or empty name": ("name", unknown_name),
    "duplicate key": ("scalar", duplicate_key),
    "not a mapping": ("scalar", whole_file),
}


def variants(count: int, seed: int) -> list[tuple[str, str, bytes]]:
    rng = random.Random(seed)
    originals = {path: yaml.safe_load(path.read_text()) for path in SOURCES}
    places = {path: sites(data, path.parent.name == "worlds") for path, data in originals.items()}
    made = []
    while len(made) < count:
        source = rng.choice(SOURCES)
        name = rng.choice(list(MUTATIONS))
        kind, mutate = MUTATIONS[name]
        if not places[source][kind]:
            continue
        path = rng.choice(places[source][kind])
        made.append((f"{source.name}: {name} at {'/'.join(map(str, path)) or 'the top'}", source.name,
                     mutate(copy.deepcopy(originals[source]), path, rng)))
    return made


def test_the_shipped_files_are_valid_to_start_with():
    result = CliRunner().invoke(cli, ["validate", *map(str, SOURCES)])
    assert result.exit_code == 0, result.output


def test_hundreds_of_malformed_variants_are_each_exit_2_with_a_located_message(tmp_path):
    made = variants(VARIANTS, SEED)
    kinds = {label.split(": ")[1].split(" at ")[0] for label, _, _ in made}
    assert kinds == set(MUTATIONS)
    runner = CliRunner()
    memory_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    started = time.monotonic()
    slowest = (0.0, "")
    for index, (label, name, content) in enumerate(made):
        path = tmp_path / f"v{index}-{name}"  # beside no world file: plans name the bundled kitchen
        path.write_bytes(content)
        begun = time.monotonic()
        result = runner.invoke(cli, ["validate", str(path)])
        took = time.monotonic() - begun
        slowest = max(slowest, (took, label))
        assert result.exit_code == 2, f"{label}: exit {result.exit_code}\n{result.output}"
        assert "Traceback" not in result.output and "internal error" not in result.output, f"{label}\n{result.output}"
        assert re.search(rf"{re.escape(str(path))}(:\d+:\d+)?: ", result.stderr), f"{label}: no location\n" \
                                                                                   f"{result.stderr}"
        assert took < 5.0, f"{label} took {took:.1f} s"
    elapsed = time.monotonic() - started
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - memory_before
    print(f"\n{len(made)} variants in {elapsed:.1f} s (slowest {slowest[0]:.2f} s: {slowest[1]}); "
          f"peak memory grew by {grown / 1024:.0f} MB")
    assert elapsed < TIME_LIMIT
    assert grown < MEMORY_LIMIT
