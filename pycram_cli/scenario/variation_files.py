"""Reading a variation file: found beside its plan or named, checked like worlds and plans, into `Variations`.

What: `variation_file` (which file a command draws from), `read_variations` / `parse_variations` (every problem at
once, with file:line:column and key: unknown objects and surfaces, regions, swaps whose models do not load, parameter
values of the wrong kind). Why apart from `variations.py`: what a file may say and how it is checked is its own job;
the drawing of scenarios (`Variations.sample`) needs none of it.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ..errors import InputError, Location, did_you_mean, raise_if_any
from ..files import probe
from ..kinds import Robots, param_kind
from ..plan import Plan, WorldFacts
from ..plan.params import type_problem
from ..plan.syntax import Param, plain
from ..schema import check_keys, describe, expect, is_number, names_only, number_list, string_entry
from ..world.model_files import MESH_SUFFIXES, describe_model
from ..worldfile.loader import load_spec
from ..worldfile.spec import ObjectSpec, Unreadable, WorldSpec, resolve_file
from ..yamlsource import LList, LMap, load_yaml
from .variations import KEEP, ParamDraw, Region, Swap, Variations, Varied, is_fixed

#: the keys a variation file, an object, the robot, a region, a swap and a parameter may have
TOP_KEYS = ("description", "plan", "separation", "objects", "robot", "params")
OBJECT_KEYS = ("noise", "region", "yaw", "present", "swap")
ROBOT_KEYS = ("noise", "region", "yaw")
REGION_KEYS = ("box", "on", "margin")
SWAP_KEYS = ("type", "file", "color", "mass")
SWAP_REQUIRED = ("type", "file")
PARAM_KEYS = ("range", "choose")
#: a variation file's name ends so; the one beside `plan.yaml` is `plan.vary.yaml`
SUFFIX = ".vary.yaml"


def beside(plan_path: Path) -> Path | None:
    """The variation file that goes with a plan by name (`set_table.yaml` -> `set_table.vary.yaml`), if any."""
    candidate = plan_path.with_name(plan_path.stem + SUFFIX)
    return candidate if probe(candidate) is None else None  # no OSError for a name made too long


def variation_file(plan_path: Path, vary: str | Path | None, flag: str, who: str | None = None) -> Path:
    """The variation file `who` (default: the option `flag`: `--project`, `--scenario`) draws from: `vary` when given,
    else the one beside the plan; none: an InputError at `flag` saying how to write one."""
    if vary is not None:
        return Path(vary).resolve()
    found = beside(plan_path)
    if found is not None:
        return found
    stem = plan_path.stem
    local = (Path.cwd() / "plans").resolve() == plan_path.parent.resolve()
    where = "it goes beside the plan" if local else f"then give --vary plans/{stem}{SUFFIX}"
    raise InputError(f"{who or flag} needs a variation file, and none named {stem}{SUFFIX} is beside the plan: give --vary "
                     "FILE", Location(flag), suggestion=f"`pycram new vary {stem}` writes plans/{stem}{SUFFIX}; {where}")


def read_variations(path: str | Path, world: WorldSpec, plan: Plan | None = None) -> Variations:
    """`parse_variations`, then the surfaces its regions stand on read from the world loaded once."""
    variations = parse_variations(path, world, plan)
    if variations.needs_surfaces():
        sim = load_spec(world)
        try:
            variations.bind_surfaces(sim)
        finally:
            sim.exit()
    return variations


# long: every key of the file checked in turn, all problems collected at once
def parse_variations(path: str | Path, world: WorldSpec, plan: Plan | None = None) -> Variations:
    """Read and check a variation file against the world (and the plan's parameters); all problems at once."""
    path = Path(path)
    data = load_yaml(path)
    fname = str(path)
    errors: list[InputError] = []
    if not isinstance(data, LMap):
        raise InputError("a variation file must be a mapping with 'objects', 'robot' and/or 'params'",
                         Location(fname, 1, 1))
    check_keys(data, TOP_KEYS, (), "the variations", errors)
    result = Variations(path, world, [])
    if "description" in data and expect(data["description"], str, data.loc("description", True), "description", errors):
        result.description = data["description"]
    if "plan" in data and expect(data["plan"], str, data.loc("plan", True), "plan", errors):
        result.plan, result.plan_where = data["plan"], data.loc("plan", True)
    if "separation" in data and expect(data["separation"], float, data.loc("separation", True), "separation", errors):
        if data["separation"] < 0:
            errors.append(InputError("separation must not be negative (m)", data.loc("separation", True),
                                     key="separation"))
        else:
            result.separation = float(data["separation"])
    by_name = {o.name: o for o in world.objects}
    if "objects" in data:
        objects = data["objects"]
        if not isinstance(objects, LMap):
            errors.append(InputError(f"expected a mapping of object name to its variations, got {describe(objects)}",
                                     data.loc("objects", True), key="objects"))
        else:
            for name, value in names_only(objects, errors).items():
                spec = by_name.get(name)
                if spec is None:
                    errors.append(InputError(f"the world {world.path.name} has no object '{name}'", objects.loc(name),
                                             key="objects", suggestion=did_you_mean(str(name), list(by_name))))
                    continue
                if spec is world.robot:
                    errors.append(InputError(f"'{name}' is the robot: vary its start pose under 'robot:'",
                                             objects.loc(name), key="objects"))
                    continue
                if is_fixed(spec) and isinstance(value, LMap) and set(value) - {"present"}:
                    errors.append(InputError(f"'{name}' is a fixed {spec.type}: only free objects move or change "
                                             "model in a sweep", objects.loc(name), key="objects"))
                    continue
                item = _parse_varied(str(name), value, objects.loc(name, True), OBJECT_KEYS, world, errors)
                if item is not None:
                    result.objects.append(item)
    if "robot" in data:
        if world.robot is None:
            errors.append(InputError(f"the world {world.path.name} has no robot (an object of type robot)",
                                     data.loc("robot"), key="robot"))
        else:
            result.robot = _parse_varied(world.robot.name, data["robot"], data.loc("robot", True), ROBOT_KEYS, world,
                                         errors)
            if result.robot is not None and result.robot.region is not None and result.robot.region.on is not None:
                errors.append(InputError("the robot stands on the floor: give it a region 'box', not 'on'",
                                         data.loc("robot", True), key="region"))
    if "params" in data:
        result.params = _parse_params(data["params"], data.loc("params", True), plan, WorldFacts.of_spec(world).robots,
                                      errors, world.object_names)
    for item in result.objects + ([result.robot] if result.robot else []):
        if item.region is not None and item.region.on is not None:
            owner = item.region.on[0]
            if owner in by_name and any(v.name == owner and (v.present < 1.0 or v.swaps) for v in result.objects):
                errors.append(InputError(f"'{item.name}' stands on '{owner}', which may be absent or swapped",
                                         data.loc("objects"), key="region"))
    raise_if_any(errors)
    return result


def _parse_varied(name: str, value: Any, where: Location, keys: tuple[str, ...], world: WorldSpec,
                  errors: list[InputError]) -> Varied | None:
    if not isinstance(value, LMap):
        errors.append(InputError(f"expected a mapping with some of {', '.join(keys)}, got {describe(value)}", where,
                                 key=name))
        return None
    count = len(errors)
    check_keys(value, keys, (), f"the variations of '{name}'", errors)
    item = Varied(name)
    if "noise" in value and "region" in value:
        errors.append(InputError("give either 'noise' (around its position) or 'region' (anywhere in it), not both",
                                 value.loc("region"), key="region"))
    if "noise" in value:
        noise = value["noise"]
        at = value.loc("noise", True)
        if is_number(noise):
            item.noise = (float(noise), float(noise), 0.0)
        else:
            numbers = number_list(noise, 3, at, "noise", errors)
            if numbers is not None:
                item.noise = (numbers[0], numbers[1], numbers[2])
        if item.noise is not None and any(n < 0 for n in item.noise):
            errors.append(InputError("noise must not be negative (m, the half-width of a uniform draw)", at, key="noise"))
    if "region" in value:
        item.region = _parse_region(value["region"], value.loc("region", True), world, errors)
    if "yaw" in value and expect(value["yaw"], float, value.loc("yaw", True), "yaw", errors):
        if not 0 <= value["yaw"] <= math.pi + 1e-3:
            errors.append(InputError("yaw must be between 0 and π (rad, the half-width of a uniform draw)",
                                     value.loc("yaw", True), key="yaw"))
        else:
            item.yaw = float(value["yaw"])
    if "present" in value and expect(value["present"], float, value.loc("present", True), "present", errors):
        if not 0 <= value["present"] <= 1:
            errors.append(InputError("present is a probability, between 0 and 1", value.loc("present", True),
                                     key="present"))
        else:
            item.present = float(value["present"])
    if "swap" in value:
        item.swaps = _parse_swaps(value["swap"], value.loc("swap", True), world, errors)
    return item if len(errors) == count else None


def _parse_region(value: Any, where: Location, world: WorldSpec, errors: list[InputError]) -> Region | None:
    if not isinstance(value, LMap):
        errors.append(InputError("expected {box: [[x, y, z], [x, y, z]]} or {on: object/link, margin: m}", where,
                                 key="region"))
        return None
    if True in value and "on" not in value:  # YAML 1.1 reads a bare `on:` key as true
        value["on"] = value.pop(True)
        value.key_where["on"], value.value_where["on"] = value.key_where.pop(True), value.value_where.pop(True)
    check_keys(value, REGION_KEYS, (), "region", errors)
    region = Region()
    if ("box" in value) == ("on" in value):
        errors.append(InputError("a region is either a 'box' or 'on' a surface link", value.loc(), key="region"))
        return None
    if "box" in value:
        box = value["box"]
        at = value.loc("box", True)
        if not isinstance(box, list) or len(box) != 2:
            errors.append(InputError(f"expected two corners [[x, y, z], [x, y, z]], got {describe(box)}", at, key="box"))
            return None
        corners = [number_list(c, 3, box.loc(i) if isinstance(box, LList) else at, "box", errors)
                   for i, c in enumerate(box)]
        if corners[0] is None or corners[1] is None:
            return None
        lo = tuple(min(a, b) for a, b in zip(corners[0], corners[1]))
        hi = tuple(max(a, b) for a, b in zip(corners[0], corners[1]))
        region.box = (lo, hi)  # type: ignore[assignment]
    else:
        text = value["on"]
        at = value.loc("on", True)
        if not expect(text, str, at, "on", errors):
            return None
        owner, sep, link = text.partition("/")
        spec = next((o for o in world.objects if o.name == owner), None)
        if not sep or not link:
            errors.append(InputError(f"expected object/link, got '{text}'", at, key="on",
                                     suggestion="e.g. kitchen/sink_area_surface"))
            return None
        if spec is None:
            errors.append(InputError(f"the world has no object '{owner}'", at, key="on",
                                     suggestion=did_you_mean(owner, [o.name for o in world.objects])))
            return None
        links = _links_of(spec)
        if link not in links:
            surfaces = [name for name in links if "surface" in name]
            errors.append(InputError(f"object '{owner}' has no link '{link}'", at, key="on",
                                     suggestion=did_you_mean(link, links)
                                     or (f"its surfaces: {', '.join(surfaces)}" if surfaces else None)))
            return None
        region.on = (owner, link)
    if "margin" in value and expect(value["margin"], float, value.loc("margin", True), "margin", errors):
        if value["margin"] < 0:
            errors.append(InputError("margin must not be negative (m)", value.loc("margin", True), key="margin"))
        region.margin = float(value["margin"])
    return region


def _links_of(spec: ObjectSpec) -> list[str]:
    try:
        return list(describe_model(spec.file).links)
    except Exception:  # noqa: BLE001 - the world file's own check reports unreadable models
        return []


def _parse_swaps(value: Any, where: Location, world: WorldSpec, errors: list[InputError]) -> list[Swap | None]:
    if not isinstance(value, LList) or not value:
        errors.append(InputError("expected a list of models: keep, or {type, file[, color, mass]}", where, key="swap"))
        return []
    swaps: list[Swap | None] = []
    base = world.path.parent
    for index, entry in enumerate(value):
        at = value.loc(index)
        if entry == KEEP:
            swaps.append(None)
            continue
        if not isinstance(entry, LMap):
            errors.append(InputError(f"expected 'keep' or a mapping {{type, file}}, got {describe(entry)}", at,
                                     key="swap"))
            continue
        if not string_entry(entry, SWAP_KEYS, SWAP_REQUIRED, SWAP_REQUIRED, "swap", errors):
            continue
        swap = _parse_swap(entry, base, errors)
        if swap is not None:
            swaps.append(swap)
    return swaps


def _parse_swap(entry: LMap, base: Path, errors: list[InputError]) -> Swap | None:
    """One model a swap puts in, checked as a world file's object is: its type, its model file (found, a regular
    file PyBullet can load), a colour within 0..1 and a positive mass."""
    if not entry["type"].strip():
        errors.append(InputError("the swapped object's type must not be empty", entry.loc("type", True), key="type"))
        return None
    if entry["type"] in ("robot", "environment"):
        errors.append(InputError("a swapped object stays a free object (not a robot or environment)",
                                 entry.loc("type", True), key="type"))
        return None
    found = _swap_model(entry, base, errors)
    if found is None:
        return None
    color = None
    if "color" in entry:
        color = number_list(entry["color"], (3, 4), entry.loc("color", True), "color", errors)
        if color is not None and not all(0 <= c <= 1 for c in color):
            errors.append(InputError("color values must be between 0 and 1 (r, g, b[, a])", entry.loc("color", True),
                                     key="color"))
            return None
    mass = None
    if "mass" in entry and expect(entry["mass"], float, entry.loc("mass", True), "mass", errors):
        if not entry["mass"] > 0:
            errors.append(InputError("mass must be positive (kg)", entry.loc("mass", True), key="mass"))
            return None
        mass = float(entry["mass"])
    return Swap(entry["type"], found, color, mass)


def _swap_model(entry: LMap, base: Path, errors: list[InputError]) -> Path | None:
    """The model file a swap names, found and readable as a model (an error at its `file:` otherwise)."""
    where = entry.loc("file", True)
    try:
        found = resolve_file(entry["file"], base)
    except Unreadable as exc:
        errors.append(InputError(f"cannot read '{entry['file']}': {exc}", where, key="file"))
        return None
    if found is None or found.suffix.lower() not in {".urdf", *MESH_SUFFIXES}:
        errors.append(InputError(f"model file not found: '{entry['file']}' (looked beside the world, in the bundled "
                                 "resources and pybullet_data)", where, key="file"))
        return None
    try:
        describe_model(found)
    except Exception as exc:  # noqa: BLE001 - any parse failure is the user's file, as in a world file
        errors.append(InputError(f"cannot read model file {found.name}: {exc}", where, key="file"))
        return None
    return found


def _no_such_object(declared: Param, value: Any, objects: list[str] | None) -> str | None:
    """A drawn value of an `object` parameter that names no object of the world: why, else None."""
    kind = param_kind(declared.type)
    if objects is None or kind is None or not kind.names_object or not isinstance(value, str) or value in objects:
        return None
    return f"parameter '{declared.name}' is an object: the world has no object '{value}'"


# long: every parameter entry checked in turn, all problems collected at once
def _parse_params(value: Any, where: Location, plan: Plan | None, robots: Robots,
                  errors: list[InputError], objects: list[str] | None = None) -> list[ParamDraw]:
    if not isinstance(value, LMap):
        errors.append(InputError("expected a mapping of parameter name to [choices] or {range: [lo, hi]}", where,
                                 key="params"))
        return []
    known = [p.name for p in plan.params] if plan is not None else None
    draws: list[ParamDraw] = []
    for name, spec in names_only(value, errors).items():
        at = value.loc(name, True)
        if known is not None and name not in known:
            errors.append(InputError(f"plan '{plan.name}' has no parameter '{name}'", value.loc(name), key=str(name),  # type: ignore[union-attr]
                                     suggestion=did_you_mean(str(name), known)
                                     or (f"its parameters: {', '.join(known)}" if known else "it takes no parameters")))
            continue
        declared = plan.param(str(name)) if plan is not None else None

        def typed(values: list[Any], places: list[Location], declared: Any = declared, name: Any = name) -> bool:
            """The drawn values fit the parameter's declared type (as `-p` values must)."""
            problems = [(type_problem(declared, v, robots), at) for v, at in zip(values, places)] if declared else []
            errors.extend(InputError(problem, at, key=str(name)) for problem, at in problems if problem)
            if declared is not None and not any(problem for problem, _ in problems):
                problems = [(_no_such_object(declared, v, objects), at) for v, at in zip(values, places)]
                errors.extend(InputError(problem, at, key=str(name), suggestion=did_you_mean(str(v), objects or []))
                              for (problem, at), v in zip(problems, values) if problem)
            return not any(problem for problem, _ in problems)

        if isinstance(spec, LList):
            if not spec:
                errors.append(InputError("expected at least one value to choose from", at, key=str(name)))
                continue
            if typed([plain(v) for v in spec], [spec.loc(i) for i in range(len(spec))]):
                draws.append(ParamDraw(str(name), choices=[plain(v) for v in spec]))
            continue
        if isinstance(spec, LMap):
            count = len(errors)
            check_keys(spec, PARAM_KEYS, (), f"parameter '{name}'", errors)
            if ("range" in spec) == ("choose" in spec):
                errors.append(InputError("give either 'range: [lo, hi]' or 'choose: [values]'", spec.loc(),
                                         key=str(name)))
                continue
            if "choose" in spec:
                choices = spec["choose"]
                if not isinstance(choices, list) or not choices:
                    errors.append(InputError("expected a non-empty list of values", spec.loc("choose", True),
                                             key="choose"))
                    continue
                places = [choices.loc(i) if isinstance(choices, LList) else spec.loc("choose", True)
                          for i in range(len(choices))]
                if typed([plain(v) for v in choices], places):
                    draws.append(ParamDraw(str(name), choices=[plain(v) for v in choices]))
                continue
            bounds = number_list(spec["range"], 2, spec.loc("range", True), "range", errors)
            if bounds is None or len(errors) != count:
                continue
            if bounds[0] > bounds[1]:
                errors.append(InputError("expected [lo, hi] with lo <= hi", spec.loc("range", True), key="range"))
                continue
            integer = all(isinstance(b, int) and not isinstance(b, bool) for b in spec["range"])
            ends = spec.loc("range", True)
            if not (typed([spec["range"][0]], [ends]) and typed([spec["range"][1]], [ends])):
                continue
            draws.append(ParamDraw(str(name), range=(bounds[0], bounds[1]), integer=integer))
            continue
        errors.append(InputError(f"expected [choices] or {{range: [lo, hi]}}, got {describe(spec)}", at, key=str(name),
                                 suggestion=f"a fixed value is a plan parameter: -p {name}=VALUE"))
    return draws
