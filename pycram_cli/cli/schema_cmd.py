"""`pycram schema world|plan|vary [-o FILE]`: the JSON Schema of a kind of file, for editors.

The schema is generated from the declarations validation uses (`editor_schema.py`); the
bundled copies in `resources/schemas/` are what the shipped YAML files' modelines name.
"""
from __future__ import annotations

from pathlib import Path

import click

from ..errors import InputError, Location, did_you_mean
from . import console
from .editor_schema import FILE_KINDS, build, render
from .files import check_output, write_output
from .options import json_option


@click.command("schema")
@click.argument("kind", metavar="world|plan|vary")
@click.option("-o", "--output", type=click.Path(path_type=Path), metavar="FILE",
              help="Write the schema to FILE (its folder must exist) instead of printing it.")
@json_option
def schema(kind: str, output: Path | None, as_json: bool) -> None:
    """Print the JSON Schema of world, plan or variation files, for editors (completion, checks as you type).

    KIND is world, plan or vary. The output is JSON either way; with -o and --json, stdout says
    which file was written. For VS Code's YAML extension, name the schema on a YAML file's first line:
    `# yaml-language-server: $schema=PATH` (see the README's "Editor support").
    """
    if kind not in FILE_KINDS:
        raise InputError(f"unknown kind of file '{kind}'", Location("schema"),
                         suggestion=did_you_mean(kind, FILE_KINDS) or f"kinds: {', '.join(FILE_KINDS)}")
    if output is None:
        console.emit_json(build(kind))
        return
    check_output(output, {".json": "JSON"}, "schema")
    text = render(kind)
    write_output(output, text, f"JSON Schema of {kind} files, {len(text) // 1000} kB")
    if as_json:
        console.emit_json({"schema": kind, "file": str(output)})
