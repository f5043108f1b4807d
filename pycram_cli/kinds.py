"""Parameter kinds: how a value of a designator slot or a query parameter is written and checked.

One set of kinds serves designator slots and query parameters alike. A kind knows

* `doc`: how the value is written, for people (the `pycram designators` table, query help);
* `check(value, robots)`: the problem with a literal value, or None, found without running
  anything. Robot-dependent kinds (arms, grasps, poses) ask `robots`, what is known of the
  robot the value is meant for: the world's robot, every bundled robot when no world is
  known, or nothing;
* `from_text(text)`: the value a command-line string stands for (`1.3,0.6,1` is a position);
* `names_object`: whether a literal string names an object of the world (checked against
  the world's objects when one is known);
* `schema`: the JSON Schema of a literal value (for editors: `pycram schema`), as loose as
  `check` without a robot or a world (arms, grasps and objects are any name there); without
  descriptions, so that an editor shows the slot's own when the pointer rests on a value.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from .errors import did_you_mean, not_a_name
from .limits import MAX_MAGNITUDE
from .schema import is_number, is_vector, number_problem


def arm_words(name: str | None) -> str:
    """An arm's name in a sentence, without the article: "left arm", and "arm" for an arm called `arm` (a Fetch),
    or none (None: the robot's only arm)."""
    if name is None:
        return "arm"
    return name if name == "arm" or name.endswith(("arm", "_arm", "-arm")) else f"{name} arm"


def arm_phrase(name: str) -> str:
    """How an arm is named in a sentence: "the left arm", and "the arm" for an arm called `arm` (a Fetch)."""
    return f"the {arm_words(name)}"


def gripper_words(arm: str) -> str:
    """An arm's gripper in a sentence, without the article: "left gripper", and "gripper" for an arm called `arm`."""
    return "gripper" if arm == "arm" or arm.endswith(("arm", "_arm", "-arm")) else f"{arm} gripper"

if TYPE_CHECKING:
    from .robots import RobotDescription


@dataclass(frozen=True)
class Robots:
    """What static checks know of the robot a value is meant for.

    `descriptions` holds the world's robot (one), every bundled robot (when the plan names
    no world), or nothing; with `known` false the robot-dependent checks are skipped.
    """

    descriptions: tuple[RobotDescription, ...] = ()
    known: bool = False

    @property
    def label(self) -> str:
        names = [d.name for d in self.descriptions]
        return names[0] if len(names) == 1 else " or ".join(names) if names else "the robot"

    def _union(self, values: Callable[[RobotDescription], Iterable[str]]) -> list[str]:
        seen: list[str] = []
        for desc in self.descriptions:
            for value in values(desc):
                if value not in seen:
                    seen.append(value)
        return seen

    def arms(self) -> list[str]:
        return self._union(lambda d: d.arms)

    def grasps(self) -> list[str]:
        return self._union(lambda d: d.grasps)

    def poses(self, arm: str | None = None) -> list[str]:
        return self._union(lambda d: [p for a in d.arms.values() if arm in (None, a.name) for p in a.poses])


NOTHING_KNOWN = Robots()


#: how a position is written on the command line (shown when one cannot be read)
POSITION_FORMS = "1.3,0.6,1.0 or [1.3,0.6,1.0] or '1.3, 0.6, 1.0' or 1.3 0.6 1.0 (three arguments, where that is unambiguous)"


def parse_vector(text: str, size: int) -> list[float] | None:
    """`"1.3,0.6,1.0"` (also `[1.3, 0.6, 1.0]`, `(1.3, 0.6, 1.0)`) -> [1.3, 0.6, 1.0]; None unless `text` is `size`
    comma-separated finite numbers."""
    text = text.strip()
    if len(text) >= 2 and (text[0], text[-1]) in (("[", "]"), ("(", ")")):
        text = text[1:-1]
    parts = [s.strip() for s in text.split(",")]
    if len(parts) != size:
        return None
    try:
        values = [float(s) for s in parts]
    except ValueError:
        return None
    return values if all(math.isfinite(v) for v in values) else None


def _quaternion_problem(value: Any) -> str | None:
    if not is_vector(value, 4):
        return "expected a quaternion [x, y, z, w]" + (" (got 3 numbers)" if is_vector(value, 3) else "")
    norm = math.sqrt(sum(v * v for v in value))
    return None if abs(norm - 1) <= 1e-3 else f"quaternion must have unit length, got norm {norm:.4g}"


def _name(value: Any) -> bool:
    return isinstance(value, str) and bool(value)


def _is_object(value: Any) -> bool:
    """An Object of a world (duck-typed: this module sits below the world layer)."""
    return hasattr(value, "world") and hasattr(value, "id") and hasattr(value, "name")


def _one_of(value: Any, allowed: Sequence[str], what: str, robots: Robots) -> str | None:
    if not robots.known or not robots.descriptions:
        return None
    if value in allowed:
        return None
    return f"{robots.label} has no {what} '{value}' ({_hint(value, allowed, what)})"


def _hint(value: Any, allowed: Sequence[str], what: str) -> str:
    """`did you mean 'x'?` when a name is close, else the list of names."""
    close = did_you_mean(str(value), allowed)
    return close or f"{what}s: {', '.join(allowed) if allowed else 'none'}"


# -- the checks --------------------------------------------------------------------------------


def _range_hint(value: Any) -> str:
    """' (numbers must be ...)' when `value` holds a number that is not usable, else ''."""
    items = value if isinstance(value, (list, tuple)) else [value]
    problem = next((number_problem(v) for v in items if number_problem(v)), None)
    return f" ({problem})" if problem else ""


def _position(value: Any, robots: Robots) -> str | None:
    return None if is_vector(value, 3) else "expected a position [x, y, z]" + _range_hint(value)


def _place_position(value: Any, robots: Robots) -> str | None:
    return None if is_vector(value, 3) or is_vector(value, 2) else "expected a position [x, y] or [x, y, z]"


def _quaternion(value: Any, robots: Robots) -> str | None:
    return _quaternion_problem(value)


def _object(value: Any, robots: Robots) -> str | None:
    return None if _name(value) or _is_object(value) else "expected an object name"


def _target(value: Any, robots: Robots) -> str | None:
    if _name(value) or _is_object(value) or is_vector(value, 3):
        return None
    if isinstance(value, (list, tuple)) and len(value) == 2 and is_vector(value[0], 3) and is_vector(value[1], 4):
        return None  # a pose (position, orientation), from Python
    return "expected an object name or a position [x, y, z]" + _range_hint(value)


def _arm(value: Any, robots: Robots) -> str | None:
    if not _name(value):
        return "expected an arm name" + (f" ({', '.join(robots.arms())})" if robots.known and robots.arms() else "")
    return _one_of(value, robots.arms(), "arm", robots)


def _grasp(value: Any, robots: Robots) -> str | None:
    if isinstance(value, (list, tuple)):
        return _quaternion_problem(value)
    if not _name(value):
        grasps = robots.grasps()
        return f"expected {('one of ' + ', '.join(grasps)) if grasps else 'a grasp name'} or a quaternion [x, y, z, w]"
    return _one_of(value, robots.grasps(), "grasp", robots)


def _number(value: Any, robots: Robots) -> str | None:
    return None if is_number(value) else "expected a number" + _range_hint(value)


def _distance(value: Any, robots: Robots) -> str | None:
    return None if is_number(value) and value > 0 else "expected a positive distance in metres" + _range_hint(value)


def _fraction(value: Any, robots: Robots) -> str | None:
    return None if is_number(value) and 0 <= value <= 1 else "expected a fraction between 0 and 1"


def _plain_name(value: Any, robots: Robots) -> str | None:
    return None if _name(value) else "expected a name"


def _types(value: Any, robots: Robots) -> str | None:
    ok = _name(value) or (isinstance(value, (list, tuple)) and all(_name(v) for v in value))
    return None if ok else "expected an object type or a list of types"


def _list(value: Any, robots: Robots) -> str | None:
    return None if isinstance(value, (list, tuple)) else "expected a list"


def _mapping(value: Any, robots: Robots) -> str | None:
    return None if isinstance(value, Mapping) else "expected a mapping"


def _string(value: Any, robots: Robots) -> str | None:
    return None if isinstance(value, str) else "expected text (quote it if it looks like a number or a list)"


def _boolean(value: Any, robots: Robots) -> str | None:
    return None if isinstance(value, bool) else "expected true or false"


def _camera(value: Any, robots: Robots) -> str | None:
    return None if _name(value) or is_vector(value, 3) else ("expected a link name or a position [x, y, z]"
                                                             + _range_hint(value))


def _arm_config(value: Any, robots: Robots, arm: str | None = None) -> str | None:
    if isinstance(value, str) and value:
        poses = robots.poses(arm)
        if robots.known and robots.descriptions and value not in poses:
            whose = f"{arm_phrase(arm)} of {robots.label}" if arm else robots.label
            return f"{whose} has no pose '{value}' ({_hint(value, poses, 'pose')})"
        return None
    joints = _arm_joints(robots, arm)
    if isinstance(value, (list, tuple)) and value and all(is_number(v) for v in value):
        if joints is not None and len(value) != len(joints):
            return f"the {arm_words(arm)} has {len(joints)} joints ({', '.join(joints)}), got {len(value)} values"
        return None
    if isinstance(value, Mapping) and value and all(isinstance(k, str) and is_number(v) for k, v in value.items()):
        unknown = [k for k in value if joints is not None and k not in joints]
        if unknown:
            return f"'{unknown[0]}' is not a joint of the {arm_words(arm)} ({_hint(unknown[0], joints or [], 'joint')})"
        return None
    return "expected a named pose (e.g. park), a list of joint values, or a mapping joint: value" + _range_hint(
        list(value.values()) if isinstance(value, Mapping) else value)


def _arm_joints(robots: Robots, arm: str | None) -> list[str] | None:
    """The joints of `arm` when one robot is known and has that arm, else None (not checked)."""
    if arm is None or not robots.known or len(robots.descriptions) != 1:
        return None
    arms = robots.descriptions[0].arms
    return list(arms[arm].joints) if arm in arms else None


def _arm_configs(value: Any, robots: Robots) -> str | None:
    if not isinstance(value, Mapping) or not value:
        return "expected a mapping of arm name to configuration, e.g. {left: park}"
    for arm, config in value.items():
        problem = _arm(arm, robots) or _arm_config(config, robots, str(arm))
        if problem:
            return f"{arm}: {problem}"
    return None


# -- locations ---------------------------------------------------------------------------------

#: the keys of a location mapping, what each takes, and what it means (docs and checks)
LOCATION_KEYS: dict[str, str] = {
    "reachable-for": "an object or a position [x, y, z]: base poses from which an arm reaches it",
    "visible-for": "an object: base poses from which the robot's camera sees it",
    "arm": "with reachable-for (or accessing): the arm that must reach",
    "grasp": "with reachable-for: the grasp it must reach with",
    "on": "a surface: a link (kitchen_island_surface) or an object: a free spot on it",
    "for": "with on: the object that must fit there (inferred when placing)",
    "near": "with on: a position [x, y, z] the spot should be close to",
    "accessing": "a handle link: base poses from which an arm opens its drawer or door",
}
#: a location asks for one of these
LOCATION_GOALS = ("reachable-for", "visible-for", "on", "accessing")
#: the only goals that may go together
LOCATION_GOALS_TOGETHER = frozenset({"reachable-for", "visible-for"})
#: the keys that go with each goal
LOCATION_WITH = {"arm": ("reachable-for", "accessing"), "grasp": ("reachable-for",), "for": ("on",), "near": ("on",)}
#: the kind of each key's value (`on` names a link or an object: any name, as the `link` kind checks)
LOCATION_KEY_KINDS = {"reachable-for": "target", "visible-for": "object", "arm": "arm", "grasp": "grasp", "on": "link",
                      "for": "object", "near": "position", "accessing": "link"}


def location_mapping(value: Any) -> Any:
    """A location mapping with YAML 1.1's reading of an unquoted `on` key (true) put back to "on"."""
    if isinstance(value, Mapping) and True in value:
        return {("on" if key is True else key): item for key, item in value.items()}
    return value


def location_goals(value: Mapping[str, Any]) -> list[str]:
    return [key for key in LOCATION_GOALS if key in value]


def _location(value: Any, robots: Robots) -> str | None:
    value = location_mapping(value)
    if not isinstance(value, Mapping):
        return ("expected a location mapping such as {reachable-for: milk}, {visible-for: milk}, "
                "{on: kitchen_island_surface, for: milk} or {accessing: HANDLE_LINK}")
    for key in value:
        unnamed = not_a_name(key)
        if unnamed is not None:
            return f"{unnamed[0]} in a location"
        if key not in LOCATION_KEYS:
            return f"a location has no key '{key}' ({_hint(key, list(LOCATION_KEYS), 'key')})"
    goals = location_goals(value)
    if not goals:
        return f"a location needs one of {', '.join(LOCATION_GOALS)}"
    if len(goals) > 1 and not set(goals) <= LOCATION_GOALS_TOGETHER:
        return f"{' and '.join(goals)} do not go together (only {' and '.join(sorted(LOCATION_GOALS_TOGETHER))} do)"
    for key, goes_with in LOCATION_WITH.items():
        if key in value and not any(goal in value for goal in goes_with):
            return f"'{key}' goes with {' or '.join(goes_with)}"
    for key, item in value.items():
        if _is_reference_text(item):
            continue
        problem = KINDS[LOCATION_KEY_KINDS[key]].check(item, robots)
        if problem:
            return f"{key}: {problem}"
    return None


def _is_reference_text(value: Any) -> bool:
    """A plan variable (`$obj`): only known when the step runs."""
    return isinstance(value, str) and value.startswith("$")


def _link_name(value: Any) -> list[tuple[str, str, str]]:
    """A link name as a slot value (the slot's own name is the key)."""
    return [("", value, "link")] if isinstance(value, str) and value and not _is_reference_text(value) else []


def location_names(value: Any) -> list[tuple[str, str, str]]:
    """(key, name, what) for every literal name a location mapping gives: `object`, `link`, or `object or link`."""
    value = location_mapping(value)
    if not isinstance(value, Mapping):
        return []
    found = []
    for key, what in (("reachable-for", "object"), ("visible-for", "object"), ("for", "object"),
                      ("on", "object or link"), ("accessing", "link")):
        item = value.get(key)
        if isinstance(item, str) and item and not _is_reference_text(item) and parse_vector(item, 3) is None:
            found.append((key, item, what))
    return found


# -- reading values from the command line ---------------------------------------------------------


def _text(text: str) -> Any:
    return text


def looks_like_numbers(text: str) -> bool:
    """Text meant as numbers (`1.3,0.6`, `[1, 2, x]`), never an object's name: a bracket, or commas between
    items that start like numbers."""
    stripped = text.strip()
    if stripped[:1] in "[(" and stripped:
        return True
    parts = [part.strip() for part in stripped.split(",")]
    return len(parts) > 1 and all(part[:1].isdigit() or part[:1] in "+-." for part in parts if part)


def _vector_or_name(size: int) -> Callable[[str], Any]:
    def read(text: str) -> Any:
        vector = parse_vector(text, size)
        return vector if vector is not None else text

    return read


def _float_or_text(text: str) -> Any:
    try:
        return float(text)
    except ValueError:
        return text


# -- JSON Schemas of the written forms (for editors: `pycram schema`) --------------------------------

JsonSchema = Mapping[str, Any]

_NUMBER: JsonSchema = {"type": "number", "minimum": -MAX_MAGNITUDE, "maximum": MAX_MAGNITUDE}
_NAME: JsonSchema = {"type": "string", "minLength": 1}


def _vector_schema(size: int) -> JsonSchema:
    return {"type": "array", "items": _NUMBER, "minItems": size, "maxItems": size}


def _either(*schemas: JsonSchema) -> JsonSchema:
    return {"anyOf": list(schemas)}


_POSITION = _vector_schema(3)
_QUATERNION = _vector_schema(4)
_ARM_CONFIG = _either(_NAME, {"type": "array", "items": _NUMBER, "minItems": 1},
                      {"type": "object", "additionalProperties": _NUMBER, "minProperties": 1})


def _location_schema(kinds: Mapping[str, Kind]) -> JsonSchema:
    """A location mapping: its keys (each value of its kind, or a `$variable`), one goal, what goes with what."""
    variable = {"type": "string", "pattern": r"^\$"}  # a $variable, known when the step runs
    together = [[a, b] for i, a in enumerate(LOCATION_GOALS) for b in LOCATION_GOALS[i + 1:]
                if not {a, b} <= LOCATION_GOALS_TOGETHER]
    return {
        "type": "object",
        "properties": {key: {"description": doc, "anyOf": [kinds[LOCATION_KEY_KINDS[key]].schema or {}, variable]}
                       for key, doc in LOCATION_KEYS.items()},
        "additionalProperties": False,
        "anyOf": [{"required": [goal]} for goal in LOCATION_GOALS],
        "allOf": [*({"not": {"required": pair}} for pair in together),
                  *({"if": {"required": [key]}, "then": {"anyOf": [{"required": [goal]} for goal in goals]}}
                    for key, goals in LOCATION_WITH.items())],
    }


@dataclass(frozen=True)
class Kind:
    name: str
    doc: str
    check: Callable[[Any, Robots], str | None]
    from_text: Callable[[str], Any] = field(default=_text)
    names_object: bool = False
    #: the names of objects and links inside a value (location mappings): (key, name, `object`/`link`/`object or link`)
    names_in: Callable[[Any], list[tuple[str, str, str]]] | None = None
    #: the JSON Schema of a literal value (None: any value)
    schema: JsonSchema | None = None


KINDS: dict[str, Kind] = {k.name: k for k in (
    Kind("position", "[x, y, z] in metres, world frame", _position, _vector_or_name(3), schema=_POSITION),
    Kind("place-position", "[x, y] or [x, y, z] in metres, world frame (z: the height of the surface)", _place_position,
         lambda text: parse_vector(text, 3) or parse_vector(text, 2) or text,
         schema={"type": "array", "items": _NUMBER, "minItems": 2, "maxItems": 3}),
    Kind("quaternion", "[x, y, z, w], unit length", _quaternion, _vector_or_name(4), schema=_QUATERNION),
    Kind("object", "an object name (or a $variable bound to an object)", _object, names_object=True, schema=_NAME),
    Kind("target", "an object name or a position [x, y, z]", _target, _vector_or_name(3), names_object=True,
         schema=_either(_NAME, _POSITION, {"type": "array", "prefixItems": [_POSITION, _QUATERNION], "minItems": 2,
                                           "maxItems": 2})),  # a pose from Python
    Kind("arm", "an arm of the robot (its description names them, e.g. left or right)", _arm, schema=_NAME),
    Kind("grasp", "a grasp of the robot (e.g. front, top, left, right) or a quaternion [x, y, z, w]", _grasp,
         _vector_or_name(4), schema=_either(_NAME, _QUATERNION)),
    Kind("number", "a number", _number, _float_or_text, schema=_NUMBER),
    Kind("distance", "a positive distance in metres", _distance, _float_or_text,
         schema={**_NUMBER, "exclusiveMinimum": 0}),
    Kind("fraction", "a fraction between 0 and 1", _fraction, _float_or_text,
         schema={"type": "number", "minimum": 0, "maximum": 1}),
    Kind("joint", "a joint name of the part-of object", _plain_name, schema=_NAME),
    Kind("link", "a link name", _plain_name, names_in=_link_name, schema=_NAME),
    Kind("object-type", "an object type, e.g. milk", _plain_name, schema=_NAME),
    Kind("types", "an object type or a list of types", _types, schema=_either(_NAME, {"type": "array", "items": _NAME})),
    Kind("camera", "a link of the robot or a position [x, y, z]", _camera, _vector_or_name(3),
         schema=_either(_NAME, _POSITION)),
    Kind("arm-config", "a named pose (park), joint values in order, or {joint: value}", _arm_config,
         schema=_ARM_CONFIG),
    Kind("arm-configs", "{arm: configuration}, each a named pose, joint values, or {joint: value}", _arm_configs,
         schema={"type": "object", "additionalProperties": _ARM_CONFIG, "minProperties": 1}),
    Kind("list", "a list of any values, e.g. [milk, bowl]", _list, schema={"type": "array"}),
    Kind("mapping", "a mapping of any values, e.g. {target: [0, 0, 0], orientation: [0, 0, 0, 1]}", _mapping,
         schema={"type": "object"}),
    Kind("string", "text", _string, schema={"type": "string"}),
    Kind("boolean", "true or false", _boolean, schema={"type": "boolean"}),
)}
KINDS["location"] = Kind(
    "location", "a mapping: {reachable-for: OBJECT|[x, y, z], arm?, grasp?}, {visible-for: OBJECT} (or both), "
    "{on: SURFACE, for: OBJECT?, near: [x, y, z]?}, or {accessing: HANDLE_LINK}", _location, names_in=location_names,
    schema=_location_schema(KINDS))

#: other names a plan parameter's `type:` may use for a kind
KIND_ALIASES: dict[str, str] = {"orientation": "quaternion"}


def kind(name: str) -> Kind:
    return KINDS[name]


def param_kind(name: Any) -> Kind | None:
    """The kind a plan parameter's `type:` names (a kind's name or an alias), or None."""
    if not isinstance(name, str):
        return None
    return KINDS.get(KIND_ALIASES.get(name, name))


def param_kind_names() -> list[str]:
    """Every name a plan parameter's `type:` may use."""
    return [*KINDS, *KIND_ALIASES]
