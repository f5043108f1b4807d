"""Declaring a reasoning query once: its parameters, how it runs, and the sentence that says its answer.

    declare_query(QuerySpec("stable", "Does the object stay put ...?",
                            parameters(Param("object", "object", required=True, positional=True, doc="an object name")),
                            run=_stable, describe=_say_stable))

Plans (`stable: {object: milk}`), plan validation, `pycram query` (its arguments, options and
help) and the docs are all generated from the declarations in `QUERIES`. Parameters are the
`Param`s of a `Signature` (`pycram_cli.signature`), the shape designator slots have; their
defaults are filled in before a query's runner sees them (`Call.args`). Object arguments may be `Object`s or
names; names are looked up in the world (a typo gets a suggestion). The answer carries
JSON-friendly `args`, `result` and `details`, and the Python `value` (a bool, or objects).
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..errors import InputError, Location, did_you_mean, setting
from ..kinds import KINDS, NOTHING_KNOWN, Robots, parse_vector
from ..robots import RobotDescription, description_for
from ..schema import is_vector
from ..signature import Param, Problem, Registry, Signature
from ..world import Object

if TYPE_CHECKING:
    from ..world import BulletWorld


def parameters(*params: Param) -> Signature:
    """A query's signature: its parameters, called so in messages, which name the query and the value given (a
    query's problems also show inside conditions, away from its arguments)."""
    return Signature(params, noun="parameter", names_value=True)


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


@dataclass(frozen=True)
class QuerySpec:
    """A query: name, what it asks, its parameters (its signature), how it runs and how its answer reads."""

    name: str
    doc: str
    signature: Signature
    run: Callable[[Call], QueryAnswer]
    describe: Callable[[QueryAnswer], str]

    @property
    def params(self) -> tuple[Param, ...]:
        return self.signature.params

    def param(self, name: str) -> Param | None:
        return self.signature.param(name)

    @property
    def param_names(self) -> list[str]:
        return self.signature.names

    @property
    def positional(self) -> list[Param]:
        return [q for q in self.params if q.positional]

    @property
    def options(self) -> list[Param]:
        return [q for q in self.params if not q.positional]

    def usage(self) -> str:
        args = " ".join(q.name.upper() for q in self.positional)
        options = " ".join(f"[{q.option} {q.name.upper()}]" for q in self.options)
        return f"{self.name} {args} {options}".rstrip()


#: every query by name, filled by `declare_query` (explicit imports in `reasoning/__init__.py`)
QUERIES: Registry[QuerySpec] = Registry("query", "queries")


def declare_query(spec: QuerySpec) -> QuerySpec:
    """Register a query; its name must be new and every parameter's kind known."""
    return QUERIES.declare(spec)


def unknown_query(name: str) -> InputError:
    problem = QUERIES.unknown(name)
    return InputError(problem.message, Location("query"), suggestion=problem.suggestion)


# -- static checks ---------------------------------------------------------------------------------


def check_query_args(name: str, args: Mapping[str, Any], is_reference: Callable[[Any], bool] | None = None,
                     robots: Robots = NOTHING_KNOWN) -> list[Problem]:
    """Problems with a query call found without a world: unknown query or parameter, missing or malformed values.

    Values for which `is_reference(value)` is true (plan variables) are not checked, nor an optional one given as
    None (not given); `robots` says what is known of the robot (its arms and grasps) for robot-dependent values.
    """
    spec = QUERIES.get(name)
    if spec is None:
        return [QUERIES.unknown(name)]

    def skip(param: Param, value: Any) -> bool:
        return (is_reference is not None and is_reference(value)) or (value is None and not param.required)

    return spec.signature.check(args, robots, f"query '{name}'", skip)


# -- running -----------------------------------------------------------------------------------------


def finite(value: float | None) -> float | None:
    """A number for JSON: None instead of inf or nan."""
    if value is None or not math.isfinite(value):
        return None
    return float(value)


#: how an object parameter is documented
AN_OBJECT = "an object name"


def mm(value: float | None) -> str:
    """A distance in an answer's sentence: millimetres, "-" when unknown."""
    if value is None:
        return "-"
    millimetres = value * 1000
    return f"{millimetres:.2f} mm" if abs(millimetres) < 10 else f"{millimetres:.1f} mm"


def degrees(value: float | None) -> str:
    """An angle (radians) in an answer's sentence."""
    return "-" if value is None else f"{math.degrees(value):.2f}°"


def place(value: Any) -> str:
    """A position `(x, y, z)` or a name, in an answer's sentence."""
    if isinstance(value, list) and value and isinstance(value[0], (int, float)):
        return "(" + ", ".join(f"{v:g}" for v in value) + ")"
    return str(value)


class Call:
    """One call of a query: resolves its arguments against a world and records the resolved values."""

    def __init__(self, world: BulletWorld, spec: QuerySpec, args: Mapping[str, Any]) -> None:
        self.world = world
        self.spec = spec
        self.resolved: dict[str, Any] = {}
        for key in args:
            if spec.param(key) is None:
                unknown = spec.signature.unknown(f"query '{spec.name}'", key)
                raise self.error(key, unknown.message, unknown.suggestion)
        for param in spec.params:
            if param.required and param.name not in args:
                raise self.error(param.name, f"missing parameter '{param.name}' ({param.doc})")
        self.args = spec.signature.bind(args)  # the declared defaults filled in

    def error(self, key: str | None, message: str, suggestion: str | None = None) -> InputError:
        return InputError(message, Location(f"query {self.spec.name}"), key=key, suggestion=suggestion)

    def get(self, key: str) -> Any:
        """The value given for `key`, or its declared default."""
        if self.spec.param(key) is None:
            raise KeyError(f"query '{self.spec.name}' declares no parameter '{key}'")
        return self.args.get(key)

    def checked(self, key: str) -> Any:
        """The value of `key` (or its default), checked against its kind; recorded as resolved."""
        param = self.spec.param(key)
        value = self.get(key)
        assert param is not None
        problem = KINDS[param.kind].check(value, self.robots())
        if problem:
            raise self.error(key, f"{problem}, got {value!r}")
        self.resolved[key] = value
        return value

    def robots(self) -> Robots:
        robot = self.world.robot
        desc = description_for(robot) if robot is not None else None
        return Robots((desc,), True) if desc is not None else NOTHING_KNOWN

    # -- objects and places -------------------------------------------------------------------
    def object(self, key: str) -> Object:
        value = self.args[key]
        if isinstance(value, Object):
            if value.world is not self.world:
                raise self.error(key, f"object '{value.name}' is not in this world")
            self.resolved[key] = value.name
            return value
        if not isinstance(value, str) or not value:
            raise self.error(key, f"expected an object name, got {value!r}")
        found = self.world.get_object_by_name(value)
        if found is None:
            raise self.error(key, f"no object '{value}'", did_you_mean(value, [o.name for o in self.world.objects]))
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
        if is_vector(value, 3):
            self.resolved[key] = [float(v) for v in value]
            return [float(v) for v in value]
        if isinstance(value, (list, tuple)) and len(value) == 2 and is_vector(value[0], 3) and is_vector(value[1], 4):
            self.resolved[key] = [[float(v) for v in value[0]], [float(v) for v in value[1]]]
            return (tuple(value[0]), tuple(value[1]))
        raise self.error(key, f"expected an object name or a position [x, y, z], got {value!r}")

    # -- the robot -------------------------------------------------------------------------------
    def robot(self) -> Object:
        robot = self.world.robot
        if robot is None:
            raise self.error(None, "the world has no robot (an object of type 'robot')")
        return robot

    def description(self, what: str, key: str | None = None) -> RobotDescription:
        """The robot's description; without one, an input error saying what was needed and how to give it."""
        robot = self.robot()
        desc = description_for(robot)
        if desc is None:
            raise self.error(key, f"robot '{robot.name}' has no description naming its {what}",
                             f"write {robot.path.with_suffix('.yaml').name} beside {robot.path.name}, or name one "
                             "with 'description:' in the world file (see docs/robots.md)")
        return desc

    def camera(self) -> Any:
        """None (the robot's camera), a robot link, or a position; recorded as resolved `from`."""
        value = self.args.get("from")
        if value is None:
            desc = self.description("camera", "from")
            if desc.camera is None:
                raise self.error("from", f"robot '{desc.name}' has no camera", f"give a camera: {setting('from')} LINK|x,y,z")
            self.resolved["from"] = desc.camera.frame
            return None
        if isinstance(value, str):
            vector = parse_vector(value, 3)
            if vector is None:
                robot = self.robot()
                if value not in robot.link_names:
                    raise self.error("from", f"robot '{robot.name}' has no link '{value}'",
                                     did_you_mean(value, robot.link_names) or "or give a position x,y,z")
                self.resolved["from"] = value
                return value
            value = vector
        if is_vector(value, 3):
            self.resolved["from"] = [float(v) for v in value]
            return [float(v) for v in value]
        raise self.error("from", f"expected a link name or a position [x, y, z], got {value!r}")

    def arms(self) -> list[str]:
        """The arm asked for, or every arm of the robot in the description's order."""
        desc = self.description("arms", "arm")
        if not desc.arms:
            raise self.error("arm", f"robot '{desc.name}' has no arms")
        value = self.args.get("arm")
        if value is None:
            return list(desc.arms)
        if value not in desc.arms:
            raise self.error("arm", f"robot '{desc.name}' has no arm {value!r}", f"arms: {', '.join(desc.arms)}")
        return [value]

    def grasp(self) -> Any:
        value = self.args.get("grasp")
        if value is None:
            self.resolved["grasp"] = None
            return None
        if isinstance(value, str):
            vector = parse_vector(value, 4)
            if vector is None:
                names = list(self.description("grasps", "grasp").grasps)
                if value not in names:
                    raise self.error("grasp", f"unknown grasp {value!r}",
                                     f"grasps: {', '.join(names) or 'none'}, or a quaternion x,y,z,w")
                self.resolved["grasp"] = value
                return value
            value = vector
        if is_vector(value, 4):
            norm = math.sqrt(sum(v * v for v in value))
            if abs(norm - 1.0) > 1e-3:
                raise self.error("grasp", f"a grasp quaternion must have unit length, got norm {norm:.4g}")
            self.resolved["grasp"] = [float(v) for v in value]
            return [float(v) for v in value]
        raise self.error("grasp", f"expected a grasp name or a quaternion [x, y, z, w], got {value!r}")

    def number(self, key: str) -> float:
        value = float(self.checked(key))
        self.resolved[key] = value
        return value

    def types(self, key: str) -> list[str]:
        value = self.args.get(key) or []
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, (list, tuple)) or not all(isinstance(v, str) for v in value):
            raise self.error(key, f"expected a list of object types, got {value!r}")
        self.resolved[key] = list(value)
        return list(value)


def run_query(world: BulletWorld, name: str, args: Mapping[str, Any]) -> QueryAnswer:
    """Answer query `name` with `args` (parameter name -> value) in `world`. Bad input raises InputError."""
    spec = QUERIES.get(name)
    if spec is None:
        raise unknown_query(name)
    return spec.run(Call(world, spec, args))
