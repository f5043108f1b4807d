"""A command as a contributor writes one: `pycram types`, in one module of its own.

Registering it takes this file (as pycram_cli/cli/types_cmd.py) and one line in `COMMANDS`
(`"types": ("types_cmd", "types", "List the object types of a world, with how many of each.")`);
help, completion and docs/reference.md pick it up from there.
"""
from __future__ import annotations

from collections import Counter

import click

from pycram_cli.cli import console
from pycram_cli.cli.options import json_option
from pycram_cli.paths import find_world
from pycram_cli.worldfile.spec import parse_world

HELP = "List the object types of a world, with how many of each."


@click.command("types", help=HELP)
@click.option("--world", "world_file", metavar="WORLD", help="World file or bundled world name (default: kitchen).")
@click.option("--at-least", metavar="N", type=click.IntRange(1), default=1, show_default=True,
              help="Only types with at least N objects.")
@json_option
def types(world_file: str | None, at_least: int, as_json: bool) -> None:
    counts = Counter(o.type for o in parse_world(find_world(world_file)).objects)
    found = {kind: n for kind, n in sorted(counts.items()) if n >= at_least}
    if as_json:
        console.emit_json(found)
    else:
        for kind, n in found.items():
            console.plain(f"{kind}  {n}")
