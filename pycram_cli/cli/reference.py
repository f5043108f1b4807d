"""The reference of designators, queries and value kinds, generated from their declarations.

    python -m pycram_cli.cli.reference                              # print it
    python -m pycram_cli.cli.reference --write docs/reference.md    # write it (from the checkout's top)

`tests/cli/test_reference.py` fails when docs/reference.md is not what the declarations say.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..designators import DESIGNATORS
from ..designators.actions import ACTIONS
from ..kinds import KIND_ALIASES, KINDS, LOCATION_KEYS
from ..reasoning import QUERIES


def _cell(text: object) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def render() -> str:
    """The whole reference as Markdown."""
    lines = ["# Reference: designators, queries and values", "",
             "Generated from the declarations by `python -m pycram_cli.cli.reference --write docs/reference.md`; "
             "do not edit by hand.",
             "`pycram designators` and `pycram query --help` show the same.", "", "## Motion designators", ""]
    for spec in DESIGNATORS.values():
        needs = f" Needs a robot with: {', '.join(spec.needs)}." if spec.needs else ""
        lines += [f"### `{spec.name}`", "", f"{spec.doc} Performed by the `{spec.module}` process module "
                  f"(drives: {spec.resource or 'nothing'}).{needs}", "",
                  "| slot | | value | default | meaning |", "|---|---|---|---|---|"]
        for slot in spec.slots:
            need = "required" if slot.required else ("one of" if slot.name in spec.one_of else "optional")
            lines.append(f"| `{slot.name}` | {need} | {_cell(KINDS[slot.kind].doc)} | {_cell(slot.default_text or '-')} | "
                         f"{_cell(slot.doc)} |")
        if spec.one_of:
            lines += ["", f"Give at least one of: {', '.join(f'`{s}`' for s in spec.one_of)}."]
        lines.append("")
    lines += ["## Action designators", "",
              "Written in a plan as `- action: TYPE` with the slots beside it (`pick-up` and `place` are motion "
              "designators too: `- pick-up: {...}` is the motion). Slots left open are inferred; `as:` binds what the "
              "action gives.", ""]
    for action in ACTIONS.values():
        needs = f" Needs a robot with: {', '.join(action.needs)}." if action.needs else ""
        gives = f" Gives: {action.returns}." if action.returns else ""
        lines += [f"### action `{action.name}`", "", f"{action.doc}{gives}{needs}", "",
                  "| slot | | value | default | meaning |", "|---|---|---|---|---|"]
        for slot in action.slots:
            need = "required" if slot.required else ("one of" if slot.name in action.one_of else "optional")
            lines.append(f"| `{slot.name}` | {need} | {_cell(KINDS[slot.kind].doc)} | {_cell(slot.default_text or '-')} | "
                         f"{_cell(slot.doc)} |")
        if action.one_of:
            lines += ["", f"Give at least one of: {', '.join(f'`{s}`' for s in action.one_of)}."]
        lines.append("")
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
