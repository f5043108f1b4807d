"""`pycram designators [TYPE]`: the reference for every motion and action designator and its slots, from their
declarations. `pick-up` and `place` are both: motion designators (`- pick-up: {...}` in a plan) and actions
(`- action: pick-up`); `--motions` and `--actions` show one level only."""
from __future__ import annotations

import click
from click.shell_completion import CompletionItem

from ..designators import DESIGNATORS, Designator
from ..designators.actions import ACTIONS, Action
from ..errors import InputError, Location, did_you_mean
from ..kinds import KINDS
from ..robots import RobotDescription, bundled_descriptions
from ..signature import Param
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


def _as_dict(spec: Designator | Action, robots: list[RobotDescription]) -> dict[str, object]:
    head: dict[str, object] = {"type": spec.name, "level": "action", "doc": spec.doc, "returns": spec.returns,
                               "written": f"action: {spec.name}"} if isinstance(spec, Action) else {
        "type": spec.name, "level": "motion", "doc": spec.doc, "resource": spec.resource, "process_module": spec.module}
    return {
        **head, "one_of": list(spec.one_of), "needs": list(spec.needs),
        "slots": [{"name": s.name, "required": s.required, "kind": s.kind, "kind_doc": KINDS[s.kind].doc,
                   "default": s.default_text or None, "doc": s.doc, **({"values_per_robot": _per_robot(s.kind, robots)}
                                                          if _per_robot(s.kind, robots) else {})}
                  for s in spec.slots],
    }


def type_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """TYPE: every motion designator and action, each with its doc."""
    docs = {**{name: spec.doc for name, spec in ACTIONS.items()}, **{name: spec.doc for name, spec in DESIGNATORS.items()}}
    return [CompletionItem(name, help=doc) for name, doc in docs.items() if name.startswith(incomplete)]


@click.command("designators")
@click.argument("type_name", metavar="[TYPE]", required=False, shell_complete=type_names)
@click.option("--motions", "only", flag_value="motions", help="Only the motion designators.")
@click.option("--actions", "only", flag_value="actions", help="Only the action designators.")
@json_option
def designators(type_name: str | None, only: str | None, as_json: bool) -> None:
    """List every motion designator and action designator with its slots (or just TYPE).

    In a plan a motion designator is a step `- TYPE: {SLOT: value}`; an action is `- action: TYPE` with its
    slots beside it. pick-up and place are both.
    """
    motions = [] if only == "actions" else list(DESIGNATORS.values())
    actions = [] if only == "motions" else list(ACTIONS.values())
    if type_name is not None:
        motions = [s for s in motions if s.name == type_name]
        actions = [s for s in actions if s.name == type_name]
        if not motions and not actions:
            known = ([] if only == "actions" else list(DESIGNATORS)) + ([] if only == "motions" else list(ACTIONS))
            raise InputError(f"unknown designator type '{type_name}'", Location("TYPE"),
                             suggestion=did_you_mean(type_name, known) or f"known types: {', '.join(dict.fromkeys(known))}")
    specs: list[Designator | Action] = [*motions, *actions]
    robots = bundled_descriptions()
    if as_json:
        console.emit_json([_as_dict(s, robots) for s in specs])
        return
    for spec in specs:
        rows = [_slot_row(spec, slot, robots) for slot in spec.slots]
        title = f"action {spec.name} — {spec.doc}" if isinstance(spec, Action) else f"{spec.name} — {spec.doc}"
        if console.out.is_terminal:
            console.table(title, ["slot", "", "value", "default", "meaning"], rows)
        else:  # piped: one field a line, as `pycram plans` and `pycram worlds` print
            console.plain(title)
            for name, need, value, default, meaning in rows:
                console.plain(f"  {name}  {need}: {meaning}")
                console.plain(f"    value: {value}")
                if default != "-":
                    console.plain(f"    default: {default}")
        if spec.one_of:
            console.plain(f"  give at least one of: {', '.join(spec.one_of)}")
        console.plain("")


def _slot_row(spec: Designator | Action, slot: Param, robots: list[RobotDescription]) -> tuple[str, str, str, str, str]:
    """(name, required/optional/one of, what value it takes, default, meaning) of one slot."""
    need = "required" if slot.required else ("one of" if slot.name in spec.one_of else "optional")
    value = KINDS[slot.kind].doc
    per_robot = _per_robot(slot.kind, robots)
    if per_robot:
        value += "; " + "; ".join(f"{robot}: {', '.join(names) or 'none'}" for robot, names in per_robot.items())
    return (slot.name, need, value, slot.default_text or "-", slot.doc)
