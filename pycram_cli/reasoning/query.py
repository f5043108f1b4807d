"""Declaring a reasoning query once: its parameters, how it runs, and the sentence that says its answer.

    declare_query(QuerySpec("stable", "Does the object stay put ...?",
                            (QueryParam("object", "object", required=True, positional=True, doc="an object name"),),
                            run=_stable, describe=_say_stable))

Plans (`stable: {object: milk}`), plan validation, `pycram query` (its arguments, options and
help) and the docs are all generated from the declarations in `QUERIES`. Parameter kinds are
the ones designator slots use (`pycram_cli.kinds`). Object arguments may be `Object`s or
names; names are looked up in the world (a typo gets a suggestion). The answer carries
JSON-friendly `args`, `result` and `details`, and the Python `value` (a bool, or objects).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Mapping

from ..errors import InputError, Location, did_you_mean
from ..kinds import KINDS, NOTHING_KNOWN, Robots, parse_vector
from ..robots import RobotDescription, description_for
from ..schema import is_vector
from ..world import Object

if TYPE_CHECKING:
    from ..world import BulletWorld


@dataclass(frozen=True)
class QueryParam:
    """One parameter: its kind (`pycram_cli.kinds`), whether it is positional on the command line, its option."""

    name: str
    kind: str
    required: bool = False
    doc: str = ""
    default: Any = None  # the value used when it is not given
    default_doc: str = ""  # how the default is found, for people
    positional: bool = False
    multiple: bool = False  # a repeatable option collecting a list
    of: str | None = None  # for a link or joint: the parameter naming the object it belongs to

    @property
    def option(self) -> str:
        return f"--{self.name}"


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
    """A query: name, what it asks, its parameters, how it runs and how its answer reads."""

    name: str
    doc: str
    params: tuple[QueryParam, ...]
    run: Callable[["Call"], QueryAnswer]
    describe: Callable[[QueryAnswer], str]

    def param(self, name: str) -> QueryParam | None:
        return next((q for q in self.params if q.name == name), None)

    @property
    def param_names(self) -> list[str]:
        return [q.name for q in self.params]

    @property
    def positional(self) -> list[QueryParam]:
        return [q for q in self.params if q.positional]

    @property
    def options(self) -> list[QueryParam]:
        return [q for q in self.params if not q.positional]

    def usage(self) -> str:
        args = " ".join(q.name.upper() for q in self.positional)
        options = " ".join(f"[{q.option} {q.name.upper()}]" for q in self.options)
        return f"{self.name} {args} {options}".rstrip()


#: every query by name, filled by `declare_query` (explicit imports in `reasoning/__init__.py`)
QUERIES: dict[str, QuerySpec] = {}


def declare_query(spec: QuerySpec) -> QuerySpec:
    """Register a query; its name must be new and every parameter's kind known."""
    if spec.name in QUERIES:
        raise ValueError(f"query '{spec.name}' is declared twice")
    for param in spec.params:
        if param.kind not in KINDS:
            raise ValueError(f"query '{spec.name}', parameter '{param.name}': unknown kind '{param.kind}'")
    QUERIES[spec.name] = spec
    return spec


def unknown_query(name: str) -> InputError:
    hint = did_you_mean(name, QUERIES)
    return InputError(f"unknown query '{name}'", Location("query"), suggestion=hint or f"queries: {', '.join(QUERIES)}")


# -- static checks ---------------------------------------------------------------------------------


def check_query_args(name: str, args: Mapping[str, Any], is_reference: Callable[[Any], bool] | None = None,
                     robots: Robots = NOTHING_KNOWN) -> list[str]:
    """Problems with a query call found without a world: unknown query or parameter, missing or malformed values.

    Values for which `is_reference(value)` is true (plan variables) are not checked; `robots`
    says what is known of the robot (its arms and grasps) when checking robot-dependent values.
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
        problem = KINDS[param.kind].check(value, robots)
        if problem:
            problems.append(f"query '{name}', parameter '{key}': {problem}, got {value!r}")
    for param in spec.params:
        if param.required and param.name not in args:
            problems.append(f"query '{name}' needs parameter '{param.name}' ({param.doc})")
    return problems


# -- running -----------------------------------------------------------------------------------------


def finite(value: float | None) -> float | None:
    """A number for JSON: None instead of inf or nan."""
    if value is None or not math.isfinite(value):
        return None
    return float(value)


class Call:
    """One call of a query: resolves its arguments against a world and records the resolved values."""

    def __init__(self, world: "BulletWorld", spec: QuerySpec, args: Mapping[str, Any]) -> None:
        self.world = world
        self.spec = spec
        self.args = dict(args)
        self.resolved: dict[str, Any] = {}
        for key in self.args:
            if spec.param(key) is None:
                hint = did_you_mean(key, spec.param_names)
                raise self.error(key, f"query '{spec.name}' has no parameter '{key}'",
                                 hint or f"parameters: {', '.join(spec.param_names)}")
        for param in spec.params:
            if param.required and param.name not in self.args:
                raise self.error(param.name, f"missing parameter '{param.name}' ({param.doc})")

    def error(self, key: str | None, message: str, suggestion: str | None = None) -> InputError:
        return InputError(message, Location(f"query {self.spec.name}"), key=key, suggestion=suggestion)

    def get(self, key: str) -> Any:
        param = self.spec.param(key)
        if param is None:
            raise KeyError(f"query '{self.spec.name}' declares no parameter '{key}'")
        value = self.args.get(key)
        return param.default if value is None else value

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
                raise self.error("from", f"robot '{desc.name}' has no camera", "give a camera with --from LINK|x,y,z")
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


def run_query(world: "BulletWorld", name: str, args: Mapping[str, Any]) -> QueryAnswer:
    """Answer query `name` with `args` (parameter name -> value) in `world`. Bad input raises InputError."""
    spec = QUERIES.get(name)
    if spec is None:
        raise unknown_query(name)
    return spec.run(Call(world, spec, args))
