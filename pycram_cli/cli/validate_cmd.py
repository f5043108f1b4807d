"""`pycram validate FILE...`: check world and plan files as `run` would, without running anything.

A plan is checked against its world file (`--world`, else its own `world:`): object names,
the robot's description (its arms, grasps and poses), and its parameters' defaults.
"""
from __future__ import annotations

from pathlib import Path

import click

from ..errors import InputError, InputErrors, Location, as_list
from ..paths import find_plan, find_world
from ..scenario import prepare
from ..worldfile.spec import parse_world
from ..yamlsource import LMap, load_yaml
from . import console


def _resolve(value: str) -> Path:
    """A file path, or the name of a plan or world (the working folder's `plans/`/`worlds/`, then the bundled ones)."""
    path = Path(value)
    if path.exists() or path.suffix in (".yaml", ".yml") and path.parent != Path("."):
        return path
    try:
        return find_plan(value)
    except InputError:
        try:
            return find_world(value)
        except InputError:
            return path  # reported as not found, with the path as given


def kind_of(path: Path) -> str:
    """A file's kind, told by its top-level keys: a world has `objects`, a plan has `body`."""
    data = load_yaml(path)
    if isinstance(data, LMap) and "objects" in data:
        return "world"
    if isinstance(data, LMap) and "body" in data:
        return "plan"
    raise InputError("not a world file (no 'objects') nor a plan file (no 'body')", Location(str(path), 1, 1))


@click.command()
@click.argument("files", metavar="FILE|NAME...", nargs=-1, required=True)
@click.option("--world", "world_file", metavar="WORLD", help="Check plans against this world (default: each plan's own).")
def validate(files: tuple[str, ...], world_file: str | None) -> None:
    """Check world and plan FILES (or bundled names) as `run` would; report every problem with file, line and key."""
    problems: list[InputError] = []
    for value in files:
        path = _resolve(value)
        try:
            kind = kind_of(path)
            if kind == "world":
                parse_world(path)
            else:
                prepare(path, world_file)
            console.success(f"{path}: valid {kind} file")
        except (InputError, InputErrors) as exc:
            problems.extend(as_list(exc))
    if problems:
        raise InputErrors(problems)
