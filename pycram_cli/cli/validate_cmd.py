"""`pycram validate FILE...`: check world, plan and variation files as `run` and `sweep` would, running nothing.

A plan is checked against its world file (`--world`, else its own `world:`): object names,
the robot's description (its arms, grasps and poses), and its parameters' defaults, or the
values `-p` gives them (as `run -p` would set them: every value must fit its declared type). A
variation file is checked against its plan (its `plan:`, else the plan it is named after:
`set_table.vary.yaml` goes with `set_table.yaml`) and that plan's world.
"""
from __future__ import annotations

from pathlib import Path

import click

from ..designators import process_module_problems
from ..errors import InputError, InputErrors, Location, as_list, raise_if_any
from ..paths import find_plan, find_world
from ..scenario import prepare
from ..scenario.variation_files import SUFFIX, parse_variations
from ..world import BulletWorld
from ..worldfile.loader import load_spec
from ..worldfile.spec import WorldSpec, parse_world
from ..worldfile.starts import unsupported
from ..yamlsource import LMap, load_yaml
from . import console
from .complete import plan_or_world_names, world_names


def _resolve(value: str) -> Path:
    """A file path, or the name of a plan or world (the working folder's `plans/`/`worlds/`, then the bundled ones)."""
    path = Path(value)
    try:
        there = path.exists()
    except (OSError, ValueError):  # a name too long, a NUL character: reading it says what is wrong
        return path
    if there or path.suffix in (".yaml", ".yml") and path.parent != Path("."):
        return path
    try:
        return find_plan(value)
    except InputError:
        try:
            return find_world(value)
        except InputError:
            return path  # reported as not found, with the path as given


def kind_of(path: Path) -> str:
    """A file's kind, told by its top-level keys: a world has a list of `objects`, a plan has `body`,
    variations have `objects` by name, `robot` or `params` (or the name NAME.vary.yaml)."""
    data = load_yaml(path)
    if isinstance(data, LMap) and "body" in data:
        return "plan"
    if isinstance(data, LMap) and (path.name.endswith(SUFFIX) or isinstance(data.get("objects"), LMap)
                                   or (("robot" in data or "params" in data) and "objects" not in data)):
        return "variation"
    if isinstance(data, LMap) and "objects" in data:
        return "world"
    raise InputError("not a world file (no 'objects'), a plan file (no 'body') nor a variation file",
                     Location(str(path), 1, 1))


def warn_missing_meshes(world: WorldSpec) -> None:
    """A warning for each mesh file a world's models name but that is not found: the run loads them without it."""
    for spec in world.objects:
        info = world.models.get(spec.name)
        for uri in info.missing if info is not None else ():
            console.warning(f"{spec.where}: object '{spec.name}': mesh file not found, loaded "
                            f"without it: {uri} (in {spec.file})")


def warn_unsupported(spec: WorldSpec, sim: BulletWorld) -> None:
    """A warning for each free object with nothing just below its centre of mass (off a table's edge, in the air):
    it falls as soon as anything is simulated. A warning, not an error: a world may mean it."""
    for item in spec.objects:
        obj = sim.get_object_by_name(item.name)
        if obj is None or obj.fixed or obj is sim.robot or any(obj in o.attachments for o in sim.objects):
            continue
        problem = unsupported(sim, obj)
        if problem:
            console.warning(f"{item.where}: {problem}: it falls as soon as anything is simulated")


def check_variations(path: Path, world_file: str | None, params: tuple[str, ...] = ()) -> None:
    """A variation file against its plan and world."""
    data = load_yaml(path)
    named = data.get("plan") if isinstance(data, LMap) and isinstance(data.get("plan"), str) else None
    if named is not None:
        try:
            plan = find_plan(named, path.parent)
        except InputError as exc:
            raise InputError(exc.message, data.loc("plan", True), key="plan", suggestion=exc.suggestion) from None
    elif path.name.endswith(SUFFIX) and path.with_name(path.name[: -len(SUFFIX)] + ".yaml").is_file():
        plan = path.with_name(path.name[: -len(SUFFIX)] + ".yaml")
    else:
        raise InputError("which plan are these variations for? name it with 'plan:' (or call the file "
                         "PLAN.vary.yaml beside PLAN.yaml)", Location(str(path), 1, 1), key="plan")
    scenario = prepare(plan, world_file, assignments=params)
    parse_variations(path, scenario.world, scenario.plan)


@click.command()
@click.argument("files", metavar="FILE|NAME...", nargs=-1, required=True, shell_complete=plan_or_world_names)
@click.option("--world", "world_file", metavar="WORLD", shell_complete=world_names,
              help="Check plans against this world (default: each plan's own).")
@click.option("-p", "--param", "params", multiple=True, metavar="NAME=VALUE",
              help="Check plans with this parameter value, as `run -p` sets it (read as YAML). Repeatable.")
def validate(files: tuple[str, ...], world_file: str | None, params: tuple[str, ...]) -> None:
    """Check world, plan and variation FILES (or bundled names) as `run` and `sweep` would; report every problem
    with file, line and key."""
    problems: list[InputError] = []
    kinds: list[str] = []
    for value in files:
        path = _resolve(value)
        try:
            kind = kind_of(path)
            kinds.append(kind)
            if kind == "world":
                world = parse_world(path)
                if world.robot_description is not None:
                    raise_if_any(process_module_problems(world.robot_description))
                warn_missing_meshes(world)
                sim = load_spec(world)  # loaded too: what starts inside what is found here, not at run
                try:
                    warn_unsupported(world, sim)
                finally:
                    sim.exit()
            elif kind == "variation":
                check_variations(path, world_file, params)
            else:
                warn_missing_meshes(prepare(path, world_file, assignments=params).world)
            console.success(f"{path}: valid {kind} file")
        except (InputError, InputErrors) as exc:
            problems.extend(as_list(exc))
    if params and kinds and all(kind == "world" for kind in kinds):
        problems.append(InputError("sets a plan parameter, but no plan or variation file is given", Location("-p")))
    if problems:
        raise InputErrors(problems)
