"""`pycram validate FILE...`: check world and plan files without running anything."""
from __future__ import annotations

from pathlib import Path
from typing import Callable

import click

from ..errors import InputError, InputErrors, Location, as_list
from ..yamlsource import LMap, load_yaml
from . import console

# kind of file -> checker; a file's kind is told by its top-level keys
CHECKERS: dict[str, Callable[[Path], object]] = {}


def checker(kind: str) -> Callable[[Callable[[Path], object]], Callable[[Path], object]]:
    def register(func: Callable[[Path], object]) -> Callable[[Path], object]:
        CHECKERS[kind] = func
        return func

    return register


@checker("world")
def _check_world(path: Path) -> object:
    from ..worldfile.spec import parse_world

    return parse_world(path)


def kind_of(path: Path) -> str:
    data = load_yaml(path)
    if isinstance(data, LMap) and "objects" in data:
        return "world"
    if isinstance(data, LMap) and ("body" in data or "plan" in data) and "plan" in CHECKERS:
        return "plan"
    if isinstance(data, LMap) and "plan" in CHECKERS:
        return "plan"
    raise InputError("not a world file (no 'objects') nor a plan file (no 'body')", Location(str(path), 1, 1))


@click.command()
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
def validate(files: tuple[Path, ...]) -> None:
    """Check world and plan FILES; report every problem with file, line and key."""
    problems: list[InputError] = []
    for path in files:
        try:
            kind = kind_of(path)
            CHECKERS[kind](path)
            console.success(f"{path}: valid {kind} file")
        except (InputError, InputErrors) as exc:
            problems.extend(as_list(exc))
    if problems:
        raise InputErrors(problems)
