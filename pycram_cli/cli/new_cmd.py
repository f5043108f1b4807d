"""`pycram new plan|world|vary NAME`: write a commented starting file that validates.

`new plan` writes a plan, `new world` a world that extends another (bundled or local) one, `new vary`
the variation file of a plan for `pycram sweep`. Each goes to the working folder's `plans/` or
`worlds/` (made when missing, and said so), never over a file without `--force`.

The plan is written with action designators, so it needs no poses or arm names of its own:
the robot parks its arms while it drives to where it sees the object and an arm reaches it,
looks at it, detects it and picks it up. The object is a typed parameter whose default is an
object of the world (the milk when there is one).
"""
from __future__ import annotations

import os
import re
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import click

from ..errors import InputError, Location
from ..files import check_writable
from ..paths import find_plan, find_world
from ..plan import Plan, parse_plan
from ..plan.params import plan_world, value_text
from ..scenario.variation_files import SUFFIX
from ..worldfile.spec import WorldSpec, parse_world
from . import console
from .complete import plan_names, world_names
from .files import check_output, write_output
from .options import world_option

F = TypeVar("F", bound=Callable[..., object])

PLAN_FORMATS = {".yaml": "YAML", ".yml": "YAML"}
VARY_FORMATS = {".yaml": "YAML"}  # a variation file beside its plan is PLAN.vary.yaml
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
{body}"""

#: the steps of a new plan, each kept only when the robot has what it needs (its description says)
DRIVE_AND_LOOK = """  - par:                              # at the same time: park the arms while driving
      - action: park-arms
      - action: navigate              # to where the camera sees the object and an arm reaches it
        target: {reachable-for: $object, visible-for: $object}
"""
DRIVE = """  - par:                              # at the same time: park the arms while driving
      - action: park-arms
      - action: navigate              # to where an arm reaches the object
        target: {reachable-for: $object}
"""
LOOK = """  - action: look-at                   # point the camera at it
    target: $object
  - action: detect                    # see it (a PerceptionFailure when it is not in sight)
    object: $object
    as: seen                          # what was detected, as $seen
"""
TAKE = """  - action: pick-up                   # grasp it with an arm that reaches it and lift it
    object: {what}
  - log: "holding {what}"
"""


def plan_body(spec: WorldSpec) -> str:
    """What the world's robot can do of driving, looking and taking: a robot bolted down does not drive, one without a
    camera does not look; one without arms takes nothing (an input error)."""
    desc = spec.robot_description
    mobile = desc is None or desc.mobile
    camera = desc is None or desc.camera is not None
    if desc is not None and not desc.arms:
        raise InputError(f"the robot '{desc.name}' has no arms: a plan cannot pick anything up with it",
                         Location(str(desc.path)), suggestion="describe its arms (docs/robots.md), or choose another "
                                                              "world (pycram worlds)")
    body = (DRIVE_AND_LOOK if camera else DRIVE) if mobile else ""
    body += LOOK if camera else ""
    return body + TAKE.format(what="$seen" if camera else "$object")


@click.group("new", short_help="Write a starting file: a commented plan, a world made from another, variations for sweeps.")
def new() -> None:
    """Write a starting file: a commented plan (pycram new plan NAME), a world made from another one
    (pycram new world NAME --from kitchen) or a plan's variations for sweeps (pycram new vary PLAN)."""


def plan_name(value: str, what: str = "plan") -> str:
    """NAME or NAME.yaml -> NAME; an InputError for a name that is no file name."""
    stem = value[: -len(Path(value).suffix)] if Path(value).suffix in PLAN_FORMATS else value
    if not NAME.match(stem) or stem in (".", ".."):
        raise InputError(f"'{value}' is not a {what} name (letters, digits, _, - and .)", Location("NAME"),
                         suggestion=f"e.g. pycram new {what} {'fetch_bowl' if what == 'plan' else 'my_kitchen'}")
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


def default_output(folder: str, file_name: str) -> Path:
    """`folder/file_name` in the working folder; the folder is made when missing (and said so on stderr)."""
    path = Path(folder)
    if not path.is_dir():
        if path.exists() or path.is_symlink():
            raise InputError(f"'{folder}' is not a folder", Location(f"{folder}/{file_name}"),
                             suggestion="write elsewhere with -o FILE")
        try:
            path.mkdir()
        except OSError as exc:
            raise InputError(f"cannot make the folder '{folder}': {exc.strerror or exc}",
                             Location(f"{folder}/{file_name}"), suggestion="write elsewhere with -o FILE") from None
        console.info(f"made the folder {folder}/ (it did not exist)")
    return path / file_name


def prepared_output(output: Path | None, folder: str, file_name: str, kinds: dict[str, str], what: str,
                    force: bool) -> Path:
    """The file to write, checked: `-o FILE` (its folder must exist) or `folder/file_name`; never an existing
    file without `force`."""
    output = output if output is not None else default_output(folder, file_name)
    check_output(output, kinds, what)
    if output.exists() and not force:
        raise InputError("the file exists already", Location(str(output)),
                         suggestion="give --force to overwrite it, or -o another file")
    check_writable(output)
    return output


def output_option(default: str) -> Callable[[F], F]:
    return click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
                        help=f"The file to write (default: {default} in the working folder, made when missing).")


force_option = click.option("--force", is_flag=True, help="Overwrite the file if it exists.")


@new.command("plan")
@click.argument("name", metavar="NAME")
@world_option
@output_option("plans/NAME.yaml")
@force_option
def new_plan(name: str, world_file: str | None, output: Path | None, force: bool) -> None:
    """Write plans/NAME.yaml: a commented plan (park the arms while driving, look, detect, pick up) that validates."""
    stem = plan_name(name)
    world = find_world(world_file)
    spec = parse_world(world)
    picked, *others = objects_to_pick(spec)
    output = prepared_output(output, "plans", f"{stem}.yaml", PLAN_FORMATS, "plan", force)
    line = world_line(world_file, world, output)
    text = TEMPLATE.format(name=stem, path=output, object=picked, object_value=value_text(picked),
                           other=value_text(others[0]) if others else "NAME",
                           world_row=f"world: {value_text(line)} ".ljust(38), body=plan_body(spec))
    write_output(output, text, "plan")
    console.success(f"{output}: a new plan on {spec.path.name}; check it with `pycram validate {output}`, "
                    f"run it with `pycram run {output}`")


WORLD_TEMPLATE = """\
# {name}: a world made from {base}, written by `pycram new world`.
#   pycram validate {path}    # check it (nothing is simulated)
#   pycram world show {path}  # its objects, where they are, their joints
#   pycram world render {path} -o {name}.png    # a picture of it
# Keys: the README's *Worlds*; `pycram schema world` for editors.
description: {description}
extends: {base_value}{extends_pad}# a world's name (pycram worlds) or a file relative to this one
objects:                              # what this world adds to {base} or changes in it
{change}  # A new object: a name {base} does not have, its type (what `detecting` finds) and its model (a
  # URDF, OBJ or STL file: beside this file, in pycram's resources, or in pybullet_data):
  # - name: mug
  #   type: mug
  #   file: objects/mug.urdf          # pybullet_data's mug
  #   position: {new_position}    # x, y, z in metres (z: where its bottom rests)
  #   orientation: [0, 0, 0, 1]       # a quaternion x, y, z, w
"""

CHANGE_TEMPLATE = """\
  - name: {object_pad}# an object of {base}, by name: the keys given here replace its own
    position: {position}    # where it starts (move it: x, y, z in metres)
"""


@new.command("world")
@click.argument("name", metavar="NAME")
@click.option("--from", "base", metavar="WORLD", default=None, shell_complete=world_names,
              help="The world to start from: a world's name (pycram worlds) or file (default: kitchen).")
@output_option("worlds/NAME.yaml")
@force_option
def new_world(name: str, base: str | None, output: Path | None, force: bool) -> None:
    """Write worlds/NAME.yaml: a world that extends another (--from, default kitchen), with its objects to change or add."""
    stem = plan_name(name, "world")
    base_path = find_world(base, where=Location("--from") if base is not None else None)
    spec = parse_world(base_path)
    output = prepared_output(output, "worlds", f"{stem}.yaml", PLAN_FORMATS, "world", force)
    line = world_line(base, base_path, output)
    if Path(line).stem == stem and "/" not in line:  # worlds/kitchen.yaml from kitchen: the bundled one
        line = Path(line).stem
    movable = [o for o in spec.objects if o.type not in NOT_PICKED]
    changed = sorted(movable, key=lambda o: o.name != "milk")[:1]
    change = "".join(CHANGE_TEMPLATE.format(object_pad=o.name.ljust(30), base=spec.path.stem,
                                            position=value_text(o.position).ljust(20))
                     for o in changed)
    near = list(changed[0].position) if changed else [0.0, 0.0, 0.0]
    new_position = value_text([round(near[0], 3), round(near[1] + 0.2, 3), round(near[2], 3)]).ljust(20)
    text = WORLD_TEMPLATE.format(name=stem, path=output, base=spec.path.stem, base_value=value_text(line),
                                 extends_pad=" " * max(1, 29 - len(value_text(line))),
                                 description=value_text(f"{spec.path.stem}, with my changes"),
                                 change=change if change else "  []\n", new_position=new_position)
    write_output(output, text, "world")
    console.success(f"{output}: a new world made from {spec.path.name}; check it with `pycram validate {output}`, "
                    f"use it with `--world {output}` or a plan's `world: {stem}`")


VARY_TEMPLATE = """\
# Variations of the plan {plan} for `pycram sweep`, written by `pycram new vary`.
#   pycram validate {path}    # check it against the plan and its world
#   pycram sweep {plan_arg} -n 20{vary_arg}    # run 20 varied scenarios
# Keys: the README's *Sweeps*; `pycram schema vary` for editors.
description: {object} and the robot start a little off their places
plan: {plan_value}# the plan these variations are for
separation: 0.1                       # varied objects start at least this far apart (m, x-y)
objects:                              # how each object's start differs from the world file's
  {object}: {{noise: [0.05, 0.05, 0]}}    # uniform within ± these (m, per axis); `yaw: 0.3` turns it by up to ± 0.3 rad
{others}robot: {{noise: [0.05, 0.05, 0], yaw: 0.1}}   # the robot's start, the same way
{params}"""


def plan_object_first(plan: Plan, movable: list[str]) -> list[str]:
    """The objects to vary, the one the plan works on first: the default of its first `object` parameter."""
    chosen = next((p.default for p in plan.params if p.type == "object" and p.default in movable), None)
    return sorted(movable, key=lambda name: name != chosen) if chosen is not None else movable


@new.command("vary")
@click.argument("plan", metavar="PLAN", shell_complete=plan_names)
@output_option("plans/PLAN.vary.yaml")
@force_option
def new_vary(plan: str, output: Path | None, force: bool) -> None:
    """Write plans/PLAN.vary.yaml: how a sweep varies PLAN's scenarios (objects and robot a little off their places)."""
    plan_path = find_plan(plan)
    parsed = parse_plan(plan_path)
    spec = parse_world(plan_world(parsed))
    picked, *others = plan_object_first(parsed, objects_to_pick(spec))
    by_name = "/" not in plan and os.sep not in plan and Path(plan).suffix not in PLAN_FORMATS
    output = prepared_output(output, "plans", f"{plan_path.stem}{SUFFIX}", VARY_FORMATS, "variation file", force)
    found_beside = output.resolve() == plan_path.with_name(f"{plan_path.stem}{SUFFIX}").resolve()
    plan_value = plan if by_name else plan_path.stem if found_beside else os.path.relpath(
        plan_path.resolve(), output.parent.resolve())
    lines = []
    if others:
        lines.append(f"  # {others[0]}: {{present: 0.5}}".ljust(38) + "# in a scenario with this probability\n")
        lines.append(f"  # {others[-1]}: {{region: {{box: [[X1, Y1, Z], [X2, Y2, Z]]}}}}    # anywhere in a box\n")
    params = ""
    if parsed.params:
        first = parsed.params[0]
        shown = value_text([first.default]) if not first.required else "[VALUE, ...]"
        params = (f"# params: {{{first.name}: {shown}}}    # the plan's parameters: values to choose from, "
                  "or {range: [LOW, HIGH]}\n")
    text = VARY_TEMPLATE.format(plan=plan_path.name, path=output, plan_arg=plan, plan_value=value_text(plan_value).ljust(32),
                                vary_arg="" if found_beside else f" --vary {output}", object=picked,
                                others="".join(lines), params=params)
    write_output(output, text, "variation file")
    console.success(f"{output}: variations of {plan_path.name}; check them with `pycram validate {output}`")
