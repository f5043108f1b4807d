"""The reasoning queries by name, for plans and the CLI: their parameters, static checks, and `run_query`.

    run_query(world, "visible", {"object": "bottle"})
    run_query(world, "reachable", {"target": [1.3, 0.6, 1.0], "arm": "left", "grasp": "front"})

Object arguments may be `Object`s or names; names are looked up in the world (a typo gets a
suggestion). The answer carries JSON-friendly `args`, `result` and `details`, and the Python
`value` (a bool, or a list of objects).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Mapping

from ..errors import InputError, Location, did_you_mean
from ..robots import description_for
from ..world import Object
from .contact import contact
from .reachability import GRASPS, ReachableAnswer, reachable, touching_at
from .stable import stable
from .supporting import support_points
from .visibility import occluding, visible

if TYPE_CHECKING:
    from ..world import BulletWorld


@dataclass(frozen=True)
class QueryParam:
    name: str
    kind: str  # object, target, camera, arm, grasp, distance, fraction, types
    required: bool
    doc: str
    default: Any = None


@dataclass(frozen=True)
class QuerySpec:
    name: str
    doc: str
    params: tuple[QueryParam, ...]

    def param(self, name: str) -> QueryParam | None:
        return next((q for q in self.params if q.name == name), None)

    @property
    def param_names(self) -> list[str]:
        return [q.name for q in self.params]


@dataclass(frozen=True)
class QueryAnswer:
    """One answered query. Truthy when the answer is yes (or a non-empty list)."""

    query: str
    args: dict[str, Any]
    result: Any
    details: dict[str, Any] = field(default_factory=dict)
    value: Any = None

    def __bool__(self) -> bool:
        return bool(self.value)

    def to_json(self) -> dict[str, Any]:
        return {"query": self.query, "args": self.args, "result": self.result, "details": self.details}


_OBJECT = "an object name"
_FROM = QueryParam("from", "camera", False, "camera: a link of the robot or a position [x, y, z] looking at the object",
                   "the robot's camera frame")
_ARM = QueryParam("arm", "arm", False, "the arm to reach with (left or right)", "left, then right: the first that reaches")
_GRASP = QueryParam("grasp", "grasp", False, "tool orientation: front, top, left, right, or a quaternion [x, y, z, w]",
                    "any orientation")
_REACH = QueryParam("threshold", "distance", False, "how close (m) the tool frame must come", 0.01)

QUERIES: dict[str, QuerySpec] = {q.name: q for q in (
    QuerySpec("stable", "Does the object stay put (within 1 mm and 1°) while the world is simulated for 2 s?", (
        QueryParam("object", "object", True, _OBJECT),)),
    QuerySpec("contact", "Are the two objects touching (within 5 mm)?", (
        QueryParam("a", "object", True, _OBJECT), QueryParam("b", "object", True, _OBJECT))),
    QuerySpec("visible", "Are at least 80 % of the object's pixels seen from the camera?", (
        QueryParam("object", "object", True, _OBJECT), _FROM,
        QueryParam("threshold", "fraction", False, "the fraction of pixels that must be seen", 0.8))),
    QuerySpec("occluding", "Which objects cover the object's pixels, seen from the camera?", (
        QueryParam("object", "object", True, _OBJECT), _FROM)),
    QuerySpec("reachable", "Can the robot bring its tool frame to the target (within 1 cm, and the grasp orientation)?", (
        QueryParam("target", "target", True, "an object name or a position [x, y, z]"), _ARM, _GRASP, _REACH)),
    QuerySpec("blocking", "Which objects would the robot touch when reaching for the target?", (
        QueryParam("target", "target", True, "an object name or a position [x, y, z]"), _ARM, _GRASP,
        QueryParam("exclude-type", "types", False, "object types to leave out (e.g. environment)", []), _REACH)),
    QuerySpec("supporting", "Does object a carry object b (b on top of a, touching)?", (
        QueryParam("a", "object", True, "the supporting object's name"),
        QueryParam("b", "object", True, "the supported object's name"),
        QueryParam("link", "link", False, "only count support by this link of a (e.g. kitchen_island_surface)"))),
)}


# -- static checks -----------------------------------------------------------------------------


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _is_vector(value: Any, size: int) -> bool:
    return isinstance(value, (list, tuple)) and len(value) == size and all(_is_number(v) for v in value)


def _check_value(param: QueryParam, value: Any) -> str | None:
    kind = param.kind
    if kind == "object":
        return None if isinstance(value, Object) or (isinstance(value, str) and value) else "expected an object name"
    if kind == "target":
        ok = isinstance(value, Object) or (isinstance(value, str) and value) or _is_vector(value, 3)
        return None if ok else "expected an object name or a position [x, y, z]"
    if kind == "camera":
        return None if (isinstance(value, str) and value) or _is_vector(value, 3) else \
            "expected a link name or a position [x, y, z]"
    if kind == "arm":
        return None if isinstance(value, str) and value else "expected an arm name (left or right)"
    if kind == "grasp":
        ok = (isinstance(value, str) and value) or _is_vector(value, 4)
        return None if ok else f"expected one of {', '.join(GRASPS)} or a quaternion [x, y, z, w]"
    if kind == "distance":
        return None if _is_number(value) and value > 0 else "expected a positive distance in metres"
    if kind == "fraction":
        return None if _is_number(value) and 0 <= value <= 1 else "expected a fraction between 0 and 1"
    if kind == "link":
        return None if isinstance(value, str) and value else "expected a link name"
    if kind == "types":
        ok = (isinstance(value, str) and value) or (isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value))
        return None if ok else "expected an object type or a list of types"
    return None


def check_query_args(name: str, args: Mapping[str, Any], is_reference: Callable[[Any], bool] | None = None) -> list[str]:
    """Problems with a query call found without a world: unknown query or parameter, missing or malformed values.

    Values for which `is_reference(value)` is true (plan variables) are not checked.
    """
    spec = QUERIES.get(name)
    if spec is None:
        hint = did_you_mean(name, QUERIES)
        return [f"unknown query '{name}'" + (f" ({hint})" if hint else f" (queries: {', '.join(QUERIES)})")]
    problems = []
    for key, value in args.items():
        param = spec.param(key)
        if param is None:
            hint = did_you_mean(key, spec.param_names)
            problems.append(f"query '{name}' has no parameter '{key}'"
                            + (f" ({hint})" if hint else f" (parameters: {', '.join(spec.param_names)})"))
            continue
        if is_reference is not None and is_reference(value):
            continue
        if value is None and not param.required:
            continue  # not given
        problem = _check_value(param, value)
        if problem:
            problems.append(f"query '{name}', parameter '{key}': {problem}, got {value!r}")
    for param in spec.params:
        if param.required and param.name not in args:
            problems.append(f"query '{name}' needs parameter '{param.name}' ({param.doc})")
    return problems


# -- running ------------------------------------------------------------------------------------


def _error(name: str, key: str | None, message: str, suggestion: str | None = None) -> InputError:
    return InputError(message, Location(f"query {name}"), key=key, suggestion=suggestion)


def _number(value: float | None) -> float | None:
    if value is None or not math.isfinite(value):
        return None
    return float(value)


def parse_vector(text: str, size: int) -> list[float] | None:
    """`"1.3,0.6,1.0"` -> [1.3, 0.6, 1.0]; None if `text` is not `size` comma-separated numbers."""
    parts = [s.strip() for s in text.split(",")]
    if len(parts) != size:
        return None
    try:
        values = [float(s) for s in parts]
    except ValueError:
        return None
    return values if all(math.isfinite(v) for v in values) else None


class _Call:
    """Resolves the arguments of one query against a world."""

    def __init__(self, world: "BulletWorld", spec: QuerySpec, args: Mapping[str, Any]) -> None:
        self.world = world
        self.spec = spec
        self.args = dict(args)
        self.resolved: dict[str, Any] = {}
        for key in self.args:
            if spec.param(key) is None:
                hint = did_you_mean(key, spec.param_names)
                raise _error(spec.name, key, f"query '{spec.name}' has no parameter '{key}'",
                             hint or f"parameters: {', '.join(spec.param_names)}")
        for param in spec.params:
            if param.required and param.name not in self.args:
                raise _error(spec.name, param.name, f"missing parameter '{param.name}' ({param.doc})")

    def get(self, key: str) -> Any:
        param = self.spec.param(key)
        assert param is not None
        return self.args.get(key, param.default)

    def object(self, key: str) -> Object:
        value = self.args[key]
        if isinstance(value, Object):
            if value.world is not self.world:
                raise _error(self.spec.name, key, f"object '{value.name}' is not in this world")
            self.resolved[key] = value.name
            return value
        if not isinstance(value, str) or not value:
            raise _error(self.spec.name, key, f"expected an object name, got {value!r}")
        found = self.world.get_object_by_name(value)
        if found is None:
            raise _error(self.spec.name, key, f"no object '{value}'",
                         did_you_mean(value, [o.name for o in self.world.objects]))
        self.resolved[key] = found.name
        return found

    def target(self, key: str = "target") -> Any:
        value = self.args[key]
        if isinstance(value, str):
            vector = parse_vector(value, 3)
            if vector is None:
                return self.object(key)
            value = vector
        if isinstance(value, Object):
            return self.object(key)
        if _is_vector(value, 3):
            self.resolved[key] = [float(v) for v in value]
            return [float(v) for v in value]
        if isinstance(value, (list, tuple)) and len(value) == 2 and all(isinstance(v, (list, tuple)) for v in value):
            if _is_vector(value[0], 3) and _is_vector(value[1], 4):
                self.resolved[key] = [[float(v) for v in value[0]], [float(v) for v in value[1]]]
                return (tuple(value[0]), tuple(value[1]))
        raise _error(self.spec.name, key, f"expected an object name or a position [x, y, z], got {value!r}")

    def robot(self) -> Object:
        robot = self.world.robot
        if robot is None:
            raise _error(self.spec.name, None, "the world has no robot (an object of type 'robot')")
        return robot

    def camera(self, obj: Object) -> Any:
        value = self.args.get("from")
        if value is None:
            robot = self.robot()
            desc = description_for(robot)
            if desc is None:
                raise _error(self.spec.name, "from", f"robot '{robot.name}' has no description naming its camera",
                             "give a camera with 'from'")
            self.resolved["from"] = desc.camera.frame
            return None
        if isinstance(value, str):
            vector = parse_vector(value, 3)
            if vector is None:
                robot = self.robot()
                if value not in robot.link_names:
                    raise _error(self.spec.name, "from", f"robot '{robot.name}' has no link '{value}'",
                                 did_you_mean(value, robot.link_names) or "or give a position x,y,z")
                self.resolved["from"] = value
                return value
            value = vector
        if _is_vector(value, 3):
            self.resolved["from"] = [float(v) for v in value]
            return [float(v) for v in value]
        raise _error(self.spec.name, "from", f"expected a link name or a position [x, y, z], got {value!r}")

    def arms(self) -> list[str]:
        robot = self.robot()
        desc = description_for(robot)
        if desc is None:
            raise _error(self.spec.name, "arm", f"robot '{robot.name}' has no description naming its arms")
        value = self.args.get("arm")
        if value is None:
            order = [a for a in ("left", "right") if a in desc.arms] + [a for a in desc.arms if a not in ("left", "right")]
            return order
        if value not in desc.arms:
            raise _error(self.spec.name, "arm", f"unknown arm {value!r}", f"arms: {', '.join(desc.arms)}")
        return [value]

    def grasp(self) -> Any:
        value = self.args.get("grasp")
        if value is None:
            self.resolved["grasp"] = None
            return None
        robot = self.robot()
        desc = description_for(robot)
        names = list(desc.grasps) if desc is not None else []
        if isinstance(value, str):
            vector = parse_vector(value, 4)
            if vector is None:
                if value not in names:
                    raise _error(self.spec.name, "grasp", f"unknown grasp {value!r}",
                                 f"grasps: {', '.join(names) or 'none'}, or a quaternion x,y,z,w")
                self.resolved["grasp"] = value
                return value
            value = vector
        if _is_vector(value, 4):
            norm = math.sqrt(sum(v * v for v in value))
            if abs(norm - 1.0) > 1e-3:
                raise _error(self.spec.name, "grasp", f"a grasp quaternion must have unit length, got norm {norm:.4g}")
            self.resolved["grasp"] = [float(v) for v in value]
            return [float(v) for v in value]
        raise _error(self.spec.name, "grasp", f"expected one of {', '.join(names)} or a quaternion [x, y, z, w], got {value!r}")

    def number(self, key: str) -> float:
        param = self.spec.param(key)
        assert param is not None
        value = self.args.get(key)
        if value is None:
            value = param.default
        problem = _check_value(param, value)
        if problem:
            raise _error(self.spec.name, key, f"{problem}, got {value!r}")
        self.resolved[key] = float(value)
        return float(value)

    def types(self, key: str) -> list[str]:
        value = self.args.get(key) or []
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, (list, tuple)) or not all(isinstance(v, str) for v in value):
            raise _error(self.spec.name, key, f"expected a list of object types, got {value!r}")
        self.resolved[key] = list(value)
        return list(value)


def _reach(call: _Call, target: Any, grasp: Any, threshold: float) -> tuple[str, str, ReachableAnswer, dict[str, Any]]:
    """Try the arms in order; the first that reaches wins, else the one that came closest."""
    robot = call.robot()
    desc = description_for(robot)
    assert desc is not None
    tried: dict[str, Any] = {}
    best: tuple[str, str, ReachableAnswer] | None = None
    for arm in call.arms():
        tool = desc.arm(arm).tool_frame
        answer = reachable(target, robot, tool, grasp=grasp, threshold=threshold)
        tried[arm] = _number(answer.position_error)
        if answer.reachable:
            return arm, tool, answer, tried
        if best is None or answer.position_error < best[2].position_error:
            best = (arm, tool, answer)
    assert best is not None
    return (*best, tried)


def _stable(call: _Call) -> QueryAnswer:
    obj = call.object("object")
    answer = stable(obj)
    return QueryAnswer("stable", call.resolved, answer.stable,
                       {"displacement": answer.displacement, "rotation": answer.rotation,
                        "simulated": answer.simulated}, answer.stable)


def _contact(call: _Call) -> QueryAnswer:
    a, b = call.object("a"), call.object("b")
    if a is b:
        raise _error("contact", "b", f"contact needs two different objects, got '{a.name}' twice")
    answer = contact(a, b, links=True)
    return QueryAnswer("contact", call.resolved, answer.in_contact,
                       {"distance": _number(answer.distance), "links": [list(pair) for pair in answer.links]},
                       answer.in_contact)


def _visible(call: _Call) -> QueryAnswer:
    obj = call.object("object")
    camera = call.camera(obj)
    threshold = call.number("threshold")
    answer = visible(obj, camera, threshold=threshold)
    return QueryAnswer("visible", call.resolved, answer.visible,
                       {"fraction": answer.fraction, "pixels": answer.pixels, "total": answer.total,
                        "camera": call.resolved["from"]}, answer.visible)


def _occluding(call: _Call) -> QueryAnswer:
    obj = call.object("object")
    camera = call.camera(obj)
    found = occluding(obj, camera)
    return QueryAnswer("occluding", call.resolved, [o.name for o in found],
                       {"count": len(found), "camera": call.resolved["from"]}, found)


def _reachable(call: _Call) -> QueryAnswer:
    target = call.target()
    grasp = call.grasp()
    threshold = call.number("threshold")
    arm, tool, answer, tried = _reach(call, target, grasp, threshold)
    call.resolved["arm"] = arm
    details = {"arm": arm, "gripper_link": tool, "position_error": _number(answer.position_error),
               "orientation_error": _number(answer.orientation_error), "joint_positions": answer.joint_positions,
               "arms_tried": tried}
    return QueryAnswer("reachable", call.resolved, answer.reachable, details, answer.reachable)


def _blocking(call: _Call) -> QueryAnswer:
    target = call.target()
    grasp = call.grasp()
    threshold = call.number("threshold")
    excluded = call.types("exclude-type")
    arm, tool, answer, _ = _reach(call, target, grasp, threshold)
    call.resolved["arm"] = arm
    found = touching_at(call.robot(), answer.joint_positions, target, excluded)
    details = {"arm": arm, "gripper_link": tool, "reachable": answer.reachable,
               "position_error": _number(answer.position_error), "excluded_types": excluded}
    return QueryAnswer("blocking", call.resolved, [o.name for o in found], details, found)


def _supporting(call: _Call) -> QueryAnswer:
    a, b = call.object("a"), call.object("b")
    if a is b:
        raise _error("supporting", "b", f"supporting needs two different objects, got '{a.name}' twice")
    link = call.get("link")
    if link is not None:
        if link not in a.link_names:
            raise _error("supporting", "link", f"'{a.name}' has no link '{link}'", did_you_mean(str(link), a.link_names))
        call.resolved["link"] = link
    points = [(on, point) for on, point in support_points(a, b) if link is None or on == link]
    details = {"contacts": [{"link": on, "point": list(point)} for on, point in points]}
    return QueryAnswer("supporting", call.resolved, bool(points), details, bool(points))


_RUNNERS: dict[str, Callable[[_Call], QueryAnswer]] = {
    "stable": _stable, "contact": _contact, "visible": _visible, "occluding": _occluding,
    "reachable": _reachable, "blocking": _blocking, "supporting": _supporting,
}


def run_query(world: "BulletWorld", name: str, args: Mapping[str, Any]) -> QueryAnswer:
    """Answer query `name` with `args` (parameter name -> value) in `world`. Bad input raises InputError."""
    spec = QUERIES.get(name)
    if spec is None:
        hint = did_you_mean(name, QUERIES)
        raise InputError(f"unknown query '{name}'", Location("query"),
                         suggestion=hint or f"queries: {', '.join(QUERIES)}")
    call = _Call(world, spec, args)
    return _RUNNERS[name](call)
