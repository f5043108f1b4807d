"""Shell completion: the `shell_complete` callbacks of arguments and options.

Plan and world names come from the working folder's `plans/` and `worlds/` and the bundled ones
(as names resolve), object and link names from the world file a command will use (`--world`,
else the default world), read as YAML without simulating anything. A callback never fails: on
any problem it completes nothing (or file names). Enable completion in a shell with

    eval "$(_PYCRAM_COMPLETE=bash_source pycram)"      # bash (zsh: zsh_source, fish: fish_source)
"""
from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

import click
from click.shell_completion import CompletionItem

from ..errors import PycramError
from ..paths import available, find_world
from ..worldfile.extends import merged
from ..yamlsource import LMap, load_yaml

#: what a file name looks like, as opposed to a plan's or world's name: complete files
_FILE_HINTS = ("/", ".", "~")


def _matching(names: Iterable[tuple[str, str]], incomplete: str) -> list[CompletionItem]:
    """The (name, help) pairs that start with `incomplete`, each once, in order."""
    seen: set[str] = set()
    items = []
    for name, help_text in names:
        if name.startswith(incomplete) and name not in seen:
            seen.add(name)
            items.append(CompletionItem(name, help=help_text or None))
    return items


def _description(path: Path) -> str:
    try:
        data = load_yaml(path)
    except (PycramError, OSError):
        return ""
    text = data.get("description") if isinstance(data, LMap) else None
    return text.strip().splitlines()[0] if isinstance(text, str) and text.strip() else ""


def _named(kinds: Iterable[str], incomplete: str) -> list[CompletionItem]:
    """Names of plans or worlds (local first); file names when `incomplete` looks like a path or nothing matches."""
    if incomplete.startswith(_FILE_HINTS) or "/" in incomplete:
        return [CompletionItem(incomplete, type="file")]
    items = _matching(((found.name, _description(found.path)) for kind in kinds for found in available(kind)),
                      incomplete)
    return items or [CompletionItem(incomplete, type="file")]


def plan_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """PLAN: the names of the local and bundled plans."""
    return _named(["plans"], incomplete)


def world_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """WORLD (`--world`): the names of the local and bundled worlds."""
    return _named(["worlds"], incomplete)


def plan_or_world_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """`validate`'s FILE|NAME: plans, then worlds."""
    return _named(["plans", "worlds"], incomplete)


def chosen_world(ctx: click.Context) -> Path | None:
    """The world file the command will use: its `--world` (or WORLD argument), else the default world."""
    value: Any = ctx.params.get("world_file")
    try:
        return find_world(value if isinstance(value, str) else None)
    except PycramError:
        return None


def world_objects(ctx: click.Context) -> list[tuple[str, str]]:
    """(name, type) of the objects of the chosen world, read from its file (nothing is simulated)."""
    path = chosen_world(ctx)
    if path is None:
        return []
    try:
        data = load_yaml(path)
        data = merged(data, path, []) if isinstance(data, LMap) else data  # a world it extends: its objects too
    except (PycramError, OSError):
        return []
    objects = data.get("objects") if isinstance(data, LMap) else None
    if not isinstance(objects, list):
        return []
    return [(item["name"], str(item.get("type", ""))) for item in objects
            if isinstance(item, dict) and isinstance(item.get("name"), str)]


def object_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """An object of the chosen world (`--world`, else the default world), its type as help."""
    return _matching(world_objects(ctx), incomplete)


def link_names(ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    """The links of the chosen world's objects (read from their model files, nothing simulated)."""
    from ..worldfile.spec import parse_world  # why: reading the models is only needed here, and is slow to import

    path = chosen_world(ctx)
    try:
        spec = parse_world(path) if path is not None else None
    except PycramError:
        return []
    if spec is None:
        return []
    return _matching(((link, f"a link of {name}") for name, model in spec.models.items() for link in model.links),
                     incomplete)
