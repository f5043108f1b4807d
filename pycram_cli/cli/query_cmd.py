"""`pycram query QUERY ARGS`: ask a reasoning question about a world.

    pycram query visible bottle
    pycram query contact kitchen milk
    pycram query reachable 1.3,0.6,1.0 --arm left
    pycram query blocking milk --arm left --exclude-type environment --json

Arguments, options and help are generated from the query declarations (`reasoning.QUERIES`),
so a newly declared query is asked like any other. Exit 0 whatever the answer; 2 on bad input.
"""
from __future__ import annotations

from typing import Any

import click
from click.shell_completion import CompletionItem

from ..errors import InputError, Location, did_you_mean
from ..jsonable import jsonable
from ..kinds import KINDS, parse_vector
from .. import locations  # noqa: F401 - registers pick-up's planning, which reachable asks about objects
from ..reasoning import QUERIES, QuerySpec, run_query
from ..reasoning.query import unknown_query
from . import console
from .complete import object_names
from .options import open_world, world_option

FIXED_OPTIONS = ("--world", "--json", "--help")


def _queries_help() -> str:
    lines = []
    for spec in QUERIES.values():
        lines.append(f"  {spec.usage()}")
        lines.append(f"      {spec.doc}")
        for param in spec.params:
            default = f" (default: {param.default_doc or param.default})" if (param.default_doc or param.default not in (None, [])) else ""
            name = param.name.upper() if param.positional else param.option
            lines.append(f"      {name}: {param.doc or KINDS[param.kind].doc}{default}")
    return "\n".join(lines)


class QueryCommand(click.Command):
    """Help generated from the query declarations at the moment it is shown."""

    def format_help_text(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        text = ("Ask a reasoning question about a world (default: the bundled kitchen).\n\n\b\nQueries:\n"
                + _queries_help()
                + "\n\n\bPositions are x,y,z and quaternions x,y,z,w (no spaces), e.g. reachable 1.3,0.6,1.0."
                "\n\n\b\nExamples:\n  pycram query visible bottle\n  pycram query contact kitchen milk\n"
                "  pycram query reachable milk --arm right --grasp front\n"
                "  pycram query blocking milk --arm left --exclude-type environment --json\n\n"
                "Exit status: 0 whatever the answer, 2 on bad input.")
        formatter.write_paragraph()
        with formatter.indentation():
            formatter.write_text(text)


def build_args(query: str, tokens: tuple[str, ...]) -> dict[str, Any]:
    """The query's parameters from the command line: positional ARGS in declaration order, then options."""
    spec = QUERIES.get(query)
    if spec is None:
        raise unknown_query(query)
    where = Location(f"query {query}")
    usage = f"usage: pycram query {spec.usage()}"
    options = {param.option: param for param in spec.options}
    positional: list[str] = []
    args: dict[str, Any] = {}
    index = 0
    while index < len(tokens):
        token = tokens[index]
        index += 1
        if not token.startswith("--") or parse_vector(token, 3) is not None or parse_vector(token, 4) is not None:
            if token.startswith("-") and parse_vector(token, 3) is None and parse_vector(token, 4) is None:
                raise InputError(f"no such option: {token}", where, suggestion=_option_hint(token, spec))
            positional.append(token)
            continue
        name, eq, inline = token.partition("=")
        param = options.get(name)
        if param is None:
            applies_elsewhere = any(name in {p.option for p in other.options} for other in QUERIES.values())
            message = f"option {name} does not apply to '{query}'" if applies_elsewhere else f"no such option: {name}"
            raise InputError(message, where, suggestion=_option_hint(name, spec) or usage)
        if eq:
            text = inline
        elif index < len(tokens):
            text = tokens[index]
            index += 1
        else:
            raise InputError(f"option {name} needs a value ({KINDS[param.kind].doc})", where, key=param.name)
        value = KINDS[param.kind].from_text(text)
        if param.multiple:
            args.setdefault(param.name, []).append(value)
        elif param.name in args:
            raise InputError(f"option {name} is given twice", where, key=param.name)
        else:
            args[param.name] = value
    names = [param.name for param in spec.positional]
    if len(positional) != len(names):
        what = "missing" if len(positional) < len(names) else "too many"
        raise InputError(f"{what} arguments: expected {len(names)} ({', '.join(names)}), got {len(positional)}",
                         where, suggestion=usage)
    for param, text in zip(spec.positional, positional):
        args[param.name] = KINDS[param.kind].from_text(text)
    return args


def query_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """QUERY: the declared queries, each with its one-line doc."""
    return [CompletionItem(name, help=spec.doc) for name, spec in QUERIES.items() if name.startswith(incomplete)]


def _option_hint(token: str, spec: QuerySpec) -> str | None:
    allowed = [p.option for p in spec.options]
    return did_you_mean(token, [*allowed, *FIXED_OPTIONS]) or (f"its options: {', '.join(allowed)}" if allowed else None)


@click.command("query", cls=QueryCommand, context_settings={"ignore_unknown_options": True},
               short_help="Ask a reasoning question (stable, visible, reachable, ...) about a world.")
@click.argument("query_name", metavar="QUERY", shell_complete=query_names)
@click.argument("tokens", metavar="ARGS...", nargs=-1, type=click.UNPROCESSED, shell_complete=object_names)
@world_option
@click.option("--json", "as_json", is_flag=True, help="Machine-readable output on stdout.")
def query(query_name: str, tokens: tuple[str, ...], world_file: str | None, as_json: bool) -> None:
    spec = QUERIES.get(query_name)
    if spec is None:
        raise unknown_query(query_name)
    args = build_args(query_name, tokens)
    with open_world(world_file) as (world, path):
        answer = run_query(world, query_name, args)
    if as_json:
        payload = answer.to_json()
        payload["world"] = str(path)
        console.emit_json(jsonable(payload, nonfinite=None))
    else:
        console.plain(spec.describe(answer))
