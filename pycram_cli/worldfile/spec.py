"""The YAML world format, checked without starting a simulation.

    extends: kitchen                  # optional: a world's name or file; `objects` then add to and change its own
    gravity: [0, 0, -9.81]
    objects:
      - name: milk
        type: milk
        file: objects/milk.obj        # against this file's folder, then bundled resources/, then pybullet_data
        position: [1.3, 1.0, 0.851]
        orientation: [0, 0, 0, 1]     # quaternion x, y, z, w
        color: [1, 1, 1]              # optional, meshes
        joints: {joint_name: value}   # optional initial joint positions
        attach: [{to: pr2, parent_link: r_gripper_tool_frame}]   # optional; this object follows `to`
        fixed: false                  # optional; robots and environments are fixed by default
        mass: 0.5                     # optional, kg, meshes
        description: my_robot.yaml    # optional, robots: the robot description (default: beside the URDF, bundled)
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError, InputErrors, Location, as_list, did_you_mean, raise_if_any
from ..files import probe
from ..paths import resources_dir
from ..robots import RobotDescription, find_description
from ..robots.description import check_against_model
from ..schema import check_keys, describe, expect, is_number, names_only, number_list, quaternion, string_entry
from ..world.model_files import MESH_SUFFIXES, ModelInfo, describe_model, simulator_models_dir
from ..world.pose import UP_TURNS, quat_multiply
from ..yamlsource import LList, LMap, load_yaml
from .extends import EXTENDS, folder_of, merged

WORLD_KEYS = ("description", "extends", "gravity", "objects")
WORLD_REQUIRED = ("objects",)
OBJECT_KEYS = ("name", "type", "file", "position", "orientation", "up", "color", "joints", "attach", "fixed", "mass",
               "description")
OBJECT_REQUIRED = ("name", "type", "file")
ATTACH_KEYS = ("to", "parent_link", "child_link")
ATTACH_REQUIRED = ("to",)
MODEL_SUFFIXES = {".urdf", *MESH_SUFFIXES}


@dataclass
class AttachSpec:
    to: str
    parent_link: str | None
    child_link: str | None


@dataclass
class ObjectSpec:
    name: str
    type: str
    file: Path
    position: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0])
    orientation: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0, 1.0])
    color: list[float] | None = None
    joints: dict[str, float] = field(default_factory=dict)
    attach: list[AttachSpec] = field(default_factory=list)
    fixed: bool | None = None
    mass: float | None = None
    description: Path | None = None  # an explicit robot description file
    up: str = "z"  # the model's axis that points up (its orientation already includes the turn)
    file_text: str = ""
    where: Location = field(default_factory=Location)


@dataclass
class WorldSpec:
    path: Path
    gravity: list[float]
    objects: list[ObjectSpec]
    description: str = ""
    robot: ObjectSpec | None = None  # the world's robot: the first object of type robot
    robot_description: RobotDescription | None = None
    models: dict[str, ModelInfo] = field(default_factory=dict)  # each object's links and joints, by object name

    @property
    def object_names(self) -> list[str]:
        return [o.name for o in self.objects]


def search_dirs(base: Path) -> list[Path]:
    dirs = [base, resources_dir()]
    data = simulator_models_dir()
    if data is not None:
        dirs.append(data)
    return dirs


class Unreadable(Exception):
    """Something is at a file's place, but it cannot be read as a file (a pipe, a device, a name too long)."""


def resolve_file(name: str, base: Path) -> Path | None:
    """The regular file `name` names (absolute, or in the search folders); None when there is none.

    Raises Unreadable (with the reason) when something is there that is not a readable regular file.
    """
    try:
        expanded = Path(os.path.expanduser(name))
    except (RuntimeError, ValueError):
        expanded = Path(name)
    candidates = [expanded] if expanded.is_absolute() else [folder / expanded for folder in search_dirs(base)]
    for candidate in candidates:
        problem = probe(candidate)
        if problem is None:
            return candidate if expanded.is_absolute() else candidate.resolve()
        if problem != "not found" and not problem.startswith("it is a folder"):
            raise Unreadable(problem)
    return None


def _short(text: str, limit: int = 80) -> str:
    """A name as shown in a message: long ones cut in the middle."""
    return text if len(text) <= limit else f"{text[:40]}...{text[-30:]}"


def _known_files(base: Path) -> list[str]:
    names: list[str] = []
    for folder in search_dirs(base)[:2]:
        if folder.is_dir():
            for path in folder.rglob("*"):
                if path.suffix.lower() in MODEL_SUFFIXES and "cache" not in path.parts:
                    names.append(str(path.relative_to(folder)))
    return names


def parse_world(path: Path) -> WorldSpec:
    """Read and check a world file; every problem is reported together (InputErrors)."""
    path = Path(path)
    data = load_yaml(path)
    fname = str(path)
    errors: list[InputError] = []
    if not isinstance(data, LMap):
        raise InputError("a world file must be a mapping with 'objects' (and optionally 'gravity')", Location(fname, 1, 1))
    check_keys(data, WORLD_KEYS, () if EXTENDS in data else WORLD_REQUIRED, "the world", errors)
    data = merged(data, path, errors)
    gravity = [0.0, 0.0, -9.81]
    if "gravity" in data:
        gravity = number_list(data["gravity"], 3, data.loc("gravity", True), "gravity", errors) or gravity
    description = data.get("description", "")
    if "description" in data:
        expect(description, str, data.loc("description", True), "description", errors)
    objects: list[ObjectSpec] = []
    raw = data.get("objects", [])
    if not isinstance(raw, LList):
        if "objects" in data:
            errors.append(InputError("expected a list of objects", data.loc("objects", True), key="objects"))
        raw = LList()
        raw.where, raw.item_where = data.where, []
    models: dict[str, ModelInfo] = {}
    first_seen: dict[str, Location] = {}
    for index, item in enumerate(raw):
        folder = folder_of(item, path.parent) if isinstance(item, LMap) else path.parent
        spec = _parse_object(item, raw.loc(index), folder, errors, models)
        if spec is None:
            continue
        if spec.name in first_seen:
            errors.append(InputError(f"duplicate object name '{spec.name}' (first defined at line "
                                     f"{first_seen[spec.name].line})", spec.where, key="name",
                                     suggestion="give every object a unique name"))
            continue
        first_seen[spec.name] = spec.where
        objects.append(spec)
    _check_attachments(objects, models, errors)
    robot = next((o for o in objects if o.type == "robot"), None)
    robot_description = _robot_description(robot, models.get(robot.name), errors) if robot is not None else None
    raise_if_any(errors)
    return WorldSpec(path, gravity, objects, description if isinstance(description, str) else "", robot,
                     robot_description, {o.name: models[o.name] for o in objects if o.name in models})


def _robot_description(robot: ObjectSpec, model: ModelInfo | None, errors: list[InputError]) -> RobotDescription | None:
    """The robot's description, checked against its model; problems are reported at the description's file."""
    if model is None:
        return None
    try:
        desc = find_description(robot.file, robot.description)
        if desc is not None:
            raise_if_any(check_against_model(desc, model, robot.file))
        return desc
    except (InputError, InputErrors) as exc:
        errors.extend(as_list(exc))
        return None


# long: every key of an object entry checked in turn, all problems collected at once
def _parse_object(item: Any, where: Location, base: Path, errors: list[InputError],
                  models: dict[str, ModelInfo]) -> ObjectSpec | None:
    if not isinstance(item, LMap):
        errors.append(InputError("each object must be a mapping with name, type and file", where))
        return None
    check_keys(item, OBJECT_KEYS, OBJECT_REQUIRED, f"object '{item.get('name', '?')}'", errors)
    usable = all(key in item and expect(item[key], str, item.loc(key, True), key, errors) for key in OBJECT_REQUIRED)
    if not usable:
        return None
    empty = [key for key in OBJECT_REQUIRED if not item[key].strip()]
    for key in empty:
        errors.append(InputError(f"the object's {key} must not be empty", item.loc(key, True), key=key))
    if empty:
        return None
    name, file_text = item["name"], item["file"]
    spec = ObjectSpec(name=name, type=item["type"], file=Path(file_text), file_text=file_text, where=item.where)
    try:
        resolved = resolve_file(file_text, base)
    except Unreadable as exc:
        errors.append(InputError(f"cannot read '{_short(file_text)}': {exc}", item.loc("file", True), key="file"))
        return spec
    if resolved is None:
        errors.append(InputError(f"file not found: '{_short(file_text)}' (looked in {base}, the bundled resources and "
                                 "pybullet_data)",
                                 item.loc("file", True), key="file",
                                 suggestion=did_you_mean(file_text, _known_files(base))))
    elif resolved.suffix.lower() not in MODEL_SUFFIXES:
        errors.append(InputError(f"unsupported file type '{resolved.suffix}' (expected .urdf, .stl or .obj)",
                                 item.loc("file", True), key="file"))
        resolved = None
    else:
        spec.file = resolved
    if "position" in item:
        spec.position = number_list(item["position"], 3, item.loc("position", True), "position", errors) or spec.position
    if "orientation" in item:
        orientation = quaternion(item["orientation"], item.loc("orientation", True), "orientation", errors)
        spec.orientation = orientation or spec.orientation
    if "up" in item:
        up = item["up"]
        if not isinstance(up, str) or up not in UP_TURNS:
            errors.append(InputError(f"up: expected the model's axis that points up ({', '.join(UP_TURNS)}), got "
                                     f"{describe(up)}", item.loc("up", True), key="up",
                                     suggestion=did_you_mean(str(up), list(UP_TURNS)) if isinstance(up, str) else None))
        else:
            spec.up = up
            spec.orientation = list(quat_multiply(spec.orientation, UP_TURNS[up]))
    if "color" in item:
        color = number_list(item["color"], (3, 4), item.loc("color", True), "color", errors)
        if color is not None and not all(0 <= c <= 1 for c in color):
            errors.append(InputError("color values must be between 0 and 1 (r, g, b[, a])", item.loc("color", True), key="color"))
        spec.color = color
    if "fixed" in item and expect(item["fixed"], bool, item.loc("fixed", True), "fixed", errors):
        spec.fixed = item["fixed"]
    if "mass" in item and expect(item["mass"], float, item.loc("mass", True), "mass", errors):
        if item["mass"] <= 0:
            errors.append(InputError("mass must be positive (kg)", item.loc("mass", True), key="mass"))
        else:
            spec.mass = float(item["mass"])
    info: ModelInfo | None = None
    if resolved is not None:
        try:
            info = describe_model(resolved)
            models[name] = info
        except Exception as exc:  # any parse failure is the user's file
            errors.append(InputError(f"cannot read model file {resolved.name}: {exc}", item.loc("file", True), key="file"))
    if "description" in item and expect(item["description"], str, item.loc("description", True), "description", errors):
        try:
            found = resolve_file(item["description"], base)
            if found is None:
                errors.append(InputError(f"robot description not found: '{_short(item['description'])}' (looked in "
                                         f"{base} and the bundled resources)", item.loc("description", True),
                                         key="description"))
            else:
                spec.description = found
        except Unreadable as exc:
            errors.append(InputError(f"cannot read robot description '{_short(item['description'])}': {exc}",
                                     item.loc("description", True), key="description"))
    if "joints" in item:
        spec.joints = _parse_joints(item["joints"], item.loc("joints", True), info, errors)
    if "attach" in item:
        spec.attach = _parse_attach(item["attach"], item.loc("attach", True), errors)
    return spec


def _parse_joints(value: Any, where: Location, info: ModelInfo | None, errors: list[InputError]) -> dict[str, float]:
    if not isinstance(value, LMap):
        errors.append(InputError("expected a mapping of joint name to value", where, key="joints"))
        return {}
    joints: dict[str, float] = {}
    for joint, position in names_only(value, errors).items():
        at = value.loc(joint)
        if not is_number(position):
            errors.append(InputError(f"joint '{joint}': expected a number", value.loc(joint, True), key="joints"))
            continue
        if info is not None:
            known = info.joints.get(str(joint))
            movable = [n for n, j in info.joints.items() if j.movable]
            if known is None or not known.movable:
                what = "no joint" if known is None else "no movable joint"
                errors.append(InputError(f"the model has {what} '{joint}'", at, key="joints",
                                         suggestion=did_you_mean(str(joint), movable)))
                continue
            if known.limited and not (known.lower - 1e-9 <= position <= known.upper + 1e-9):
                limits = f"[{known.lower:g}, {known.upper:g}]"
                errors.append(InputError(f"joint '{joint}': {position:g} is outside its limits {limits}",
                                         value.loc(joint, True), key="joints"))
                continue
        joints[str(joint)] = float(position)
    return joints


def _parse_attach(value: Any, where: Location, errors: list[InputError]) -> list[AttachSpec]:
    items = value if isinstance(value, list) else [value]
    result: list[AttachSpec] = []
    for index, entry in enumerate(items):
        at = value.loc(index) if isinstance(value, LList) else where
        if isinstance(entry, str):
            result.append(AttachSpec(entry, None, None))
            continue
        if not isinstance(entry, LMap):
            errors.append(InputError("expected an object name or a mapping {to, parent_link, child_link}", at, key="attach"))
            continue
        if string_entry(entry, ATTACH_KEYS, ATTACH_REQUIRED, ATTACH_KEYS, "attach", errors):
            spec = AttachSpec(entry["to"], entry.get("parent_link"), entry.get("child_link"))
            spec.where = entry.where  # type: ignore[attr-defined]  # place in the file: no field, kept out of eq/asdict
            result.append(spec)
    for spec in result:
        if not hasattr(spec, "where"):
            spec.where = where  # type: ignore[attr-defined]  # place in the file: no field, kept out of eq/asdict
    return result


def _check_attachments(objects: list[ObjectSpec], models: dict[str, ModelInfo], errors: list[InputError]) -> None:
    names = [o.name for o in objects]
    _check_attachment_cycles(objects, errors)
    for obj in objects:
        for att in obj.attach:
            where = att.where  # type: ignore[attr-defined]  # place in the file: no field, kept out of eq/asdict
            if att.to not in names or att.to == obj.name:
                errors.append(InputError(f"'{obj.name}' cannot attach to '{att.to}': "
                                         + ("an object cannot attach to itself" if att.to == obj.name else "no such object"),
                                         where, key="attach",
                                         suggestion=did_you_mean(att.to, [n for n in names if n != obj.name])))
                continue
            for link, owner in ((att.parent_link, att.to), (att.child_link, obj.name)):
                info = models.get(owner)
                if link is not None and info is not None and link not in info.links:
                    errors.append(InputError(f"object '{owner}' has no link '{link}'", where, key="attach",
                                             suggestion=did_you_mean(link, info.links)))


def _check_attachment_cycles(objects: list[ObjectSpec], errors: list[InputError]) -> None:
    """An object cannot follow itself through others (milk attached to cereal and cereal to milk)."""
    parents = {o.name: [a.to for a in o.attach if a.to != o.name] for o in objects}
    by_name = {o.name: o for o in objects}
    reported: set[frozenset[str]] = set()
    for start in parents:
        path = [start]
        seen = {start}
        stack = [(start, iter(parents.get(start, [])))]
        while stack:
            name, followers = stack[-1]
            following = next(followers, None)
            if following is None:
                stack.pop()
                seen.discard(path.pop())
                continue
            if following == start:
                cycle = frozenset(path)
                if cycle not in reported:
                    reported.add(cycle)
                    loop = " -> ".join([*path, start])
                    obj = by_name[path[-1]]
                    att = next(a for a in obj.attach if a.to == start)
                    errors.append(InputError(f"attachments go round in a circle: {loop} (each object would follow "
                                             "itself)", att.where, key="attach",  # type: ignore[attr-defined]  # place in the file: no field, kept out of eq/asdict
                                             suggestion="attach each object to one that does not follow it"))
                continue
            if following in seen or following not in parents:
                continue
            seen.add(following)
            path.append(following)
            stack.append((following, iter(parents.get(following, []))))
