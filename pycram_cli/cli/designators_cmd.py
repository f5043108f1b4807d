"""`pycram designators [TYPE]`: the reference for every motion designator and its slots, from their declarations."""
from __future__ import annotations

import click

from ..designators import DESIGNATORS, Designator
from ..errors import InputError, Location, did_you_mean
from ..kinds import KINDS
from . import console
from .options import json_option


def _as_dict(spec: Designator) -> dict[str, object]:
    return {
        "type": spec.name, "doc": spec.doc, "resource": spec.resource, "process_module": spec.module,
        "one_of": list(spec.one_of), "needs": list(spec.needs),
        "slots": [{"name": s.name, "required": s.required, "kind": s.kind, "kind_doc": KINDS[s.kind].doc,
                   "default": s.default, "doc": s.doc} for s in spec.slots],
    }


@click.command("designators")
@click.argument("type_name", metavar="[TYPE]", required=False)
@json_option
def designators(type_name: str | None, as_json: bool) -> None:
    """List every motion designator type with its slots (or just TYPE)."""
    if type_name is not None and type_name not in DESIGNATORS:
        raise InputError(f"unknown designator type '{type_name}'", Location("TYPE"),
                         suggestion=did_you_mean(type_name, DESIGNATORS) or f"known types: {', '.join(DESIGNATORS)}")
    specs = [DESIGNATORS[type_name]] if type_name else list(DESIGNATORS.values())
    if as_json:
        console.emit_json([_as_dict(s) for s in specs])
        return
    for spec in specs:
        rows = []
        for slot in spec.slots:
            need = "required" if slot.required else ("one of" if slot.name in spec.one_of else "optional")
            rows.append((slot.name, need, KINDS[slot.kind].doc, slot.default or "-", slot.doc))
        console.table(f"{spec.name} — {spec.doc}", ["slot", "", "value", "default", "meaning"], rows)
        if spec.one_of:
            console.plain(f"  give at least one of: {', '.join(spec.one_of)}")
        console.plain("")


COMMANDS = [designators]
