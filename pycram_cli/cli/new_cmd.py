"""`pycram new plan NAME`: write a commented starting plan that validates (and runs) on its world.

The plan is written with action designators, so it needs no poses or arm names of its own:
the robot parks its arms while it drives to where it sees the object and an arm reaches it,
looks at it, detects it and picks it up. The object is a typed parameter whose default is an
object of the world (the milk when there is one).
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import click

from ..errors import InputError, Location
from ..files import check_writable
from ..paths import find_world
from ..plan.params import value_text
from ..worldfile.spec import WorldSpec, parse_world
from . import console
from .files import check_output, write_output
from .options import world_option

PLAN_FORMATS = {".yaml": "YAML", ".yml": "YAML"}
NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")
#: object types a robot does not pick up
NOT_PICKED = ("robot", "environment")

TEMPLATE = """\
# {name}: a starting plan, written by `pycram new plan`.
#   pycram validate {path}    # check it (nothing runs)
#   pycram run {path} -p object={other}    # run it, here on another object
# Step types: docs/plans.md; actions and their slots: `pycram designators --actions`.
description: Pick up the {object} (a starting plan)   # `pycram plans` shows it
{world_row}# a world's name (pycram worlds) or a file relative to this one
params:                               # typed parameters: checked before anything runs, set with -p
  object:
    type: object                      # the kind of value: position, object, arm, list, number, ...
    default: {object_value}
    description: the object to pick up
body:
  - par:                              # at the same time: park the arms while driving
      - action: park-arms
      - action: navigate              # to where the camera sees the object and an arm reaches it
        target: {{reachable-for: $object, visible-for: $object}}
  - action: look-at                   # turn the head to it
    target: $object
  - action: detect                    # see it (a PerceptionFailure when it is not in sight)
    object: $object
    as: seen                          # what was detected, as $seen
  - action: pick-up                   # grasp it with an arm that reaches it and lift it
    object: $seen
  - log: "holding $seen"
"""


@click.group("new")
def new() -> None:
    """Write a starting file: a commented plan (pycram new plan NAME)."""


def plan_name(value: str) -> str:
    """NAME or NAME.yaml -> NAME; an InputError for a name that is no file name."""
    stem = value[: -len(Path(value).suffix)] if Path(value).suffix in PLAN_FORMATS else value
    if not NAME.match(stem) or stem in (".", ".."):
        raise InputError(f"'{value}' is not a plan name (letters, digits, _, - and .)", Location("NAME"),
                         suggestion="e.g. pycram new plan fetch_bowl")
    return stem


def world_line(value: str | None, world: Path, output: Path) -> str:
    """How the plan names its world: a name as given (`kitchen`), else the file relative to the plan's folder."""
    if value is None:
        return "kitchen"
    if "/" not in value and os.sep not in value and Path(value).suffix not in PLAN_FORMATS:
        return value
    if Path(value).is_absolute():
        return value
    return os.path.relpath(world.resolve(), (output.parent if str(output.parent) else Path(".")).resolve())


def objects_to_pick(spec: WorldSpec) -> list[str]:
    """The objects a robot may pick up, the milk first when the world has it: neither robots nor environments."""
    if spec.robot is None:
        raise InputError(f"the world {spec.path.name} has no robot to run a plan", Location("--world"),
                         suggestion="add an object of type robot to it, or choose another world (pycram worlds)")
    movable = [o.name for o in spec.objects if o.type not in NOT_PICKED]
    if not movable:
        raise InputError(f"the world {spec.path.name} has no object to pick up", Location("--world"))
    return sorted(movable, key=lambda name: name != "milk")


@new.command("plan")
@click.argument("name", metavar="NAME")
@world_option
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="The file to write (default: plans/NAME.yaml in the working folder).")
@click.option("--force", is_flag=True, help="Overwrite the file if it exists.")
def new_plan(name: str, world_file: str | None, output: Path | None, force: bool) -> None:
    """Write plans/NAME.yaml: a commented plan (park the arms while driving, look, detect, pick up) that validates."""
    stem = plan_name(name)
    if output is None and not Path("plans").is_dir():
        raise InputError("cannot write the plan: folder 'plans' does not exist", Location(f"plans/{stem}.yaml"),
                         suggestion="create it with mkdir plans, or write elsewhere with -o FILE")
    output = output if output is not None else Path("plans") / f"{stem}.yaml"
    check_output(output, PLAN_FORMATS, "plan")
    if output.exists() and not force:
        raise InputError("the file exists already", Location(str(output)),
                         suggestion="give --force to overwrite it, or -o another file")
    check_writable(output)
    world = find_world(world_file)
    spec = parse_world(world)
    picked, *others = objects_to_pick(spec)
    line = world_line(world_file, world, output)
    text = TEMPLATE.format(name=stem, path=output, object=picked, object_value=value_text(picked),
                           other=value_text(others[0]) if others else "NAME",
                           world_row=f"world: {value_text(line)} ".ljust(38))
    write_output(output, text, "plan")
    console.success(f"{output}: a new plan on {spec.path.name}; check it with `pycram validate {output}`, "
                    f"run it with `pycram run {output}`")
