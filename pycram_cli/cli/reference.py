"""The reference of commands, designators, queries and value kinds, generated from their declarations.

The commands come from `main.COMMANDS` and each click command's own usage and options, so a new command
needs no entry here.

    python -m pycram_cli.cli.reference                              # print it
    python -m pycram_cli.cli.reference --write docs/reference.md    # write it (from the checkout's top)

`tests/cli/test_reference.py` fails when docs/reference.md is not what the declarations say.
"""
from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

import click

from ..designators import DESIGNATORS
from ..designators.actions import ACTIONS
from ..kinds import KIND_ALIASES, KINDS, LOCATION_KEYS
from ..reasoning import QUERIES
from ..signature import Param
from .main import COMMANDS, cli


def _cell(text: object) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _slots(slots: Sequence[Param], one_of: Sequence[str]) -> list[str]:
    """A designator's or action's slots as a table, and which of them to give at least one of."""
    lines = ["| slot | | value | default | meaning |", "|---|---|---|---|---|"]
    for slot in slots:
        need = "required" if slot.required else ("one of" if slot.name in one_of else "optional")
        lines.append(f"| `{slot.name}` | {need} | {_cell(KINDS[slot.kind].doc)} | {_cell(slot.default_text or '-')} | "
                     f"{_cell(slot.doc)} |")
    if one_of:
        lines += ["", f"Give at least one of: {', '.join(f'`{s}`' for s in one_of)}."]
    return [*lines, ""]


def _command(command: click.Command, path: str, help_text: str, parent: click.Context) -> list[str]:
    """One command's section: its one-line help, usage and options; a group's subcommands after it."""
    ctx = click.Context(command, info_name=path.split()[-1], parent=parent)
    usage = " ".join([path, *command.collect_usage_pieces(ctx)])
    lines = [f"### `{path}`", "", help_text, "", f"    {usage}", ""]
    options = [record for param in command.params
               if isinstance(param, click.Option) and (record := param.get_help_record(ctx)) is not None]
    if options:
        lines += ["| option | meaning |", "|---|---|"]
        lines += [f"| `{_cell(names)}` | {_cell(meaning)} |" for names, meaning in options]
        lines.append("")
    if isinstance(command, click.Group):
        for name in command.list_commands(ctx):
            sub = command.get_command(ctx, name)
            if sub is not None and not sub.hidden:
                lines += _command(sub, f"{path} {name}", sub.get_short_help_str(limit=300), ctx)
    return lines


def commands() -> list[str]:
    """The Commands section: every command of `COMMANDS`, in the order `pycram --help` lists them."""
    root = click.Context(cli, info_name="pycram")
    lines = ["## Commands", "", "`pycram --help` lists these; `pycram COMMAND --help` says the same of each.", ""]
    for name, (_, _, help_text) in COMMANDS.items():
        command = cli.get_command(root, name)
        assert command is not None, f"COMMANDS names {name!r} but its module has no such command"
        lines += _command(command, f"pycram {name}", help_text, root)
    return lines


def render() -> str:
    """The whole reference as Markdown."""
    lines = ["# Reference: commands, designators, queries and values", "",
             "Generated from the declarations by `python -m pycram_cli.cli.reference --write docs/reference.md`; "
             "do not edit by hand.",
             "`pycram designators` and `pycram query --help` show the same.", "", *commands(),
             "## Motion designators", ""]
    for spec in DESIGNATORS.values():
        needs = f" Needs a robot with: {', '.join(spec.needs)}." if spec.needs else ""
        lines += [f"### `{spec.name}`", "", f"{spec.doc} Performed by the `{spec.module}` process module "
                  f"(drives: {spec.resource or 'nothing'}).{needs}", "", *_slots(spec.slots, spec.one_of)]
    lines += ["## Action designators", "",
              "Written in a plan as `- action: TYPE` with the slots beside it (`pick-up` and `place` are motion "
              "designators too: `- pick-up: {...}` is the motion). Slots left open are inferred; `as:` binds what the "
              "action gives.", ""]
    for action in ACTIONS.values():
        needs = f" Needs a robot with: {', '.join(action.needs)}." if action.needs else ""
        gives = f" Gives: {action.returns}." if action.returns else ""
        lines += [f"### action `{action.name}`", "", f"{action.doc}{gives}{needs}", "",
                  *_slots(action.slots, action.one_of)]
    lines += ["## Location designators", "", "A slot of kind `location` is a mapping with these keys "
              "(`pycram locate` resolves one from the command line):", "", "| key | takes |", "|---|---|"]
    lines += [f"| `{key}` | {_cell(doc)} |" for key, doc in LOCATION_KEYS.items()]
    lines.append("")
    lines += ["## Reasoning queries", "", "In a plan: `QUERY: {PARAMETER: value, ...}`; on the command line: "
              "`pycram query QUERY ARGS [--OPTION VALUE]`.", ""]
    for query in QUERIES.values():
        lines += [f"### `{query.name}`", "", query.doc, "", f"    pycram query {query.usage()}", "",
                  "| parameter | | value | default | meaning |", "|---|---|---|---|---|"]
        for param in query.params:
            where = "positional" if param.positional else f"`{param.option}`"
            default = param.default_text or "-"
            lines.append(f"| `{param.name}` | {where}{', required' if param.required else ''} | "
                         f"{_cell(KINDS[param.kind].doc)} | {_cell(default)} | {_cell(param.doc)} |")
        lines.append("")
    aliases = ", ".join(f"`{alias}` for `{name}`" for alias, name in KIND_ALIASES.items())
    lines += ["## Value kinds", "", "Slots, query parameters and typed plan parameters (`type:`, see docs/plans.md) "
              f"take these kinds of value; a plan parameter's `type:` may also use {aliases}.", "",
              "| kind | written as |", "|---|---|"]
    lines += [f"| `{kind.name}` | {_cell(kind.doc)} |" for kind in KINDS.values()]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pycram_cli.cli.reference", description=__doc__.splitlines()[0])
    parser.add_argument("--write", type=Path, metavar="FILE", help="write the reference to FILE")
    args = parser.parse_args(argv)
    if args.write:
        args.write.write_text(render())
        print(f"wrote {args.write}")
    else:
        sys.stdout.write(render())
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
