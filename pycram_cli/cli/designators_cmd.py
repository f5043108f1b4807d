"""`pycram designators [TYPE]`: the reference for every motion designator and its slots, from their declarations."""
from __future__ import annotations

import click

from ..designators import DESIGNATORS, Designator
from ..errors import InputError, Location, did_you_mean
from ..kinds import KINDS
from ..robots import RobotDescription, bundled_descriptions
from . import console
from .options import json_option


def _robot_values(kind: str, desc: RobotDescription) -> list[str] | None:
    """The names a robot-dependent slot takes on one robot (None for kinds that do not depend on the robot)."""
    if kind == "arm":
        return list(desc.arms)
    if kind == "grasp":
        return list(desc.grasps)
    if kind in ("arm-config", "arm-configs"):
        return sorted({pose for arm in desc.arms.values() for pose in arm.poses})
    return None


def _per_robot(kind: str, robots: list[RobotDescription]) -> dict[str, list[str]]:
    values = {desc.name: _robot_values(kind, desc) for desc in robots}
    return {name: v for name, v in values.items() if v is not None}


def _as_dict(spec: Designator, robots: list[RobotDescription]) -> dict[str, object]:
    return {
        "type": spec.name, "doc": spec.doc, "resource": spec.resource, "process_module": spec.module,
        "one_of": list(spec.one_of), "needs": list(spec.needs),
        "slots": [{"name": s.name, "required": s.required, "kind": s.kind, "kind_doc": KINDS[s.kind].doc,
                   "default": s.default, "doc": s.doc, **({"values_per_robot": _per_robot(s.kind, robots)}
                                                          if _per_robot(s.kind, robots) else {})}
                  for s in spec.slots],
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
    robots = bundled_descriptions()
    if as_json:
        console.emit_json([_as_dict(s, robots) for s in specs])
        return
    for spec in specs:
        rows = []
        for slot in spec.slots:
            need = "required" if slot.required else ("one of" if slot.name in spec.one_of else "optional")
            value = KINDS[slot.kind].doc
            per_robot = _per_robot(slot.kind, robots)
            if per_robot:
                value += "; " + "; ".join(f"{robot}: {', '.join(names) or 'none'}" for robot, names in per_robot.items())
            rows.append((slot.name, need, value, slot.default or "-", slot.doc))
        console.table(f"{spec.name} — {spec.doc}", ["slot", "", "value", "default", "meaning"], rows)
        if spec.one_of:
            console.plain(f"  give at least one of: {', '.join(spec.one_of)}")
        console.plain("")
