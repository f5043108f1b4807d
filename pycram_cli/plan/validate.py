"""Static checks of a parsed plan, all reported together with file, line and column.

Unknown node and designator types and unknown keys are found while parsing; here:
unknown or missing designator slots and ill-formed slot values, query arguments,
failure type names, undefined variables (or ones used before they are bound), calls
of undefined subplans, wrong argument counts or names, and — when a world is given —
object names that are not in it.

Scopes are function scopes: the plan's parameters are visible everywhere; a subplan's
parameters and everything bound in its body (`as`, `set`, `for_each`, `$failure` in
`catch`) are visible in the steps after the binding, in declaration order. What a branch of
par, pursue or try_all binds is visible in that branch only, unless bound with `scope: plan`.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..designators import DESIGNATORS, process_module_problems
from ..errors import InputError, Location, did_you_mean, raise_if_any
from ..failures import ALIASES, FAILURES, failure_class
from ..kinds import KINDS, Robots, param_kind
from ..paths import find_world
from ..reasoning import QUERIES
from ..robots import RobotDescription, bundled_descriptions, description_for
from ..yamlsource import LList, LMap
from .context import REFERENCE, Ref, UnboundVariable, attribute, references
from .params import type_problem
from .syntax import Node, Param, Plan, plain

if TYPE_CHECKING:
    from ..world import BulletWorld
    from ..worldfile.spec import WorldSpec


@dataclass(frozen=True)
class WorldFacts:
    """What validation knows of the world a plan runs in: its objects (with their links and movable joints)
    and its robot (with its description).

    Made from a world file (`of_spec`, nothing simulated: the models' names are read from the files)
    or from a loaded world (`of_world`).
    """

    objects: tuple[str, ...]
    robot: str | None = None
    robot_file: str = ""
    description: RobotDescription | None = None
    links: Mapping[str, tuple[str, ...]] = field(default_factory=dict)  # by object name (unknown: absent)
    joints: Mapping[str, tuple[str, ...]] = field(default_factory=dict)  # movable joints, by object name
    types: tuple[str, ...] = ()  # the objects' types (what `object-type` slots name)

    @classmethod
    def of_spec(cls, spec: WorldSpec) -> WorldFacts:
        robot = spec.robot
        links = {name: tuple(info.links) for name, info in spec.models.items()}
        joints = {name: tuple(j for j, info_joint in info.joints.items() if info_joint.movable)
                  for name, info in spec.models.items()}
        return cls(tuple(spec.object_names), robot.name if robot else None, robot.file.name if robot else "",
                   spec.robot_description, links, joints, _unique(o.type for o in spec.objects))

    @classmethod
    def of_world(cls, world: BulletWorld) -> WorldFacts:
        robot = world.robot
        return cls(tuple(o.name for o in world.objects), robot.name if robot else None,
                   robot.path.name if robot else "", description_for(robot) if robot is not None else None,
                   {o.name: tuple(o.link_names) for o in world.objects},
                   {o.name: tuple(j.name for j in o.movable_joints) for o in world.objects},
                   _unique(o.type for o in world.objects))

    @property
    def robots(self) -> Robots:
        return Robots((self.description,), True) if self.description is not None else Robots()


def _unique(names: Iterable[str]) -> tuple[str, ...]:
    return tuple(dict.fromkeys(names))


def _robots(facts: WorldFacts | None) -> Robots:
    """The world's robot; every bundled robot when the world is not known."""
    if facts is not None:
        return facts.robots
    return Robots(tuple(bundled_descriptions()), True)


class Validator:
    def __init__(self, plan: Plan, facts: WorldFacts | None = None, values: Mapping[str, Any] | None = None) -> None:
        self.plan = plan
        self.facts = facts
        self.robots = _robots(facts)
        self._robot_checked = False
        self.errors: list[InputError] = []
        self.globals = {p.name: p.where for p in plan.params}
        # the parameters' values, when known before the run (bound -p values, else the defaults)
        self.values = dict(values) if values is not None else {p.name: p.default for p in plan.params
                                                                if not p.required}
        self.defined: dict[str, Location] = {}
        self.later: dict[str, Location] = {}
        self.bound_count: dict[str, int] = {}
        self.known: dict[str, list[Any]] = {}  # locals whose possible values are known (for_each over a literal list)
        self.in_branch: dict[str, Location] = {}  # bound only inside a branch of a concurrent step

    def error(self, message: str, where: Location, key: str | None = None, suggestion: str | None = None) -> None:
        self.errors.append(InputError(message, where, key=key, suggestion=suggestion))

    # -- the whole plan --------------------------------------------------------------------
    def check(self) -> None:
        self._defaults(self.plan.params)
        for sub in self.plan.plans.values():
            self._defaults(sub.params)
            self._body(sub.body, {p.name: p.where for p in sub.params})
            if sub.has_returns:
                self.refs(sub.returns, sub.returns_where, "returns")
        self._body(self.plan.body, {})

    def _defaults(self, params: list[Param]) -> None:
        """The defaults of typed parameters must fit their types (and name what the world has)."""
        for param in params:
            if not param.required:
                problem = type_problem(param, param.default, self.robots)
                if problem:
                    self.error(f"the default of {problem}", param.default_where, key=param.name)
                elif self.values.get(param.name, param.default) == param.default:  # a value given (-p) replaces it
                    self.world_value(param, param.default, param.default_where, param.name, "the default of ")

    def world_value(self, param: Param, value: Any, where: Location, key: str, prefix: str = "",
                    origin: str = "") -> None:
        """A value of a typed parameter that names an object (type `object`) must name one of the world's."""
        kind = param_kind(param.type)
        facts = self.facts
        if kind is None or not kind.names_object or facts is None or not isinstance(value, str) or references(value):
            return
        if value not in facts.objects:
            self.error(f"{prefix}parameter '{param.name}' is an object: the world has no object '{value}'{origin}",
                       where, key=key, suggestion=did_you_mean(value, facts.objects))

    def object_type(self, slot_name: str, value: Any, where: Location) -> None:
        """With a world: an object type that is not the world's but close to one of them is a misspelling.

        A type far from every type of the world is let pass: a plan may look for what is not there
        (a `PerceptionFailure` it catches at run time), and a sweep's variations may bring it in.
        """
        facts = self.facts
        if facts is None or not facts.types:
            return
        values = self.possible(value) or []
        origin = "" if values == [value] else f" ({value})"
        for item in values:
            if not isinstance(item, str) or references(item) or item in facts.types:
                continue
            close = did_you_mean(item, facts.types)
            if close:
                self.error(f"'{slot_name}': the world has no object of type '{item}'{origin}", where,
                           key=str(slot_name), suggestion=close)

    def _body(self, steps: list[Node], params: dict[str, Location]) -> None:
        self.defined = dict(params)
        self.later = {}
        self.bound_count = {name: 1 for name in params}
        self.known = {}
        self.in_branch = {}
        for node in steps:
            for step in node.walk():
                for name, where in step.bindings():
                    self.later.setdefault(name, where)
                    self.bound_count[name] = self.bound_count.get(name, 0) + 1
        self.check_steps(steps)

    def check_steps(self, steps: Iterable[Node]) -> None:
        for node in steps:
            node.check(self)
            if node.bind:
                self.define(node.bind, node.bind_where)

    def define(self, name: str, where: Location, values: list[Any] | None = None) -> None:
        """`name` is bound from here on; `values`: every value it can take, when known before the run."""
        self.defined.setdefault(name, where)
        if values is not None and self.bound_count.get(name, 0) <= 1:
            self.known[name] = list(values)

    def possible(self, value: Any) -> list[Any] | None:
        """Every value `value` can have at run time when that is known now, else None.

        Literals are themselves; `$param.attr` of a plan parameter (not shadowed by a local) has the
        parameter's value; a `for_each` variable over a literal list has each item.
        """
        if not isinstance(value, str) or "$" not in value:
            return [value]
        match = REFERENCE.match(value)
        if not match:
            return None  # text with references inside: only known at run time
        ref = Ref.parse(match.group(1))
        if ref.name in self.known:
            bases = self.known[ref.name]
        elif ref.name in self.values and ref.name not in self.defined and not self.bound_count.get(ref.name):
            bases = [self.values[ref.name]]  # a parameter no step of this body rebinds
        else:
            return None
        found = []
        for base in bases:
            try:
                for attr in ref.attrs:
                    base = attribute(base, attr, ref)
            except UnboundVariable:
                continue
            found.append(base)
        return found

    def check_branches(self, branches: list[Node]) -> None:
        """The branches of a concurrent step: each sees what is bound before the step, and what it binds stays
        in it (CPL), except the bindings with `scope: plan`, which are seen after the step."""
        before = dict(self.defined)
        exported: dict[str, Location] = {}
        for branch in branches:
            self.defined = dict(before)
            self.check_steps([branch])
            for step in branch.walk():
                for name, where in step.bindings():
                    if name not in before:
                        self.in_branch.setdefault(name, where)
                for name, where in step.plan_bindings():
                    exported.setdefault(name, where)
        self.defined = before
        for name, where in exported.items():
            self.define(name, where)

    # -- references ---------------------------------------------------------------------------
    def refs(self, value: Any, where: Location, key: str | None = None) -> None:
        """Every `$name` inside `value` must be bound by now (located at the innermost value)."""
        if isinstance(value, LMap):
            for k, item in value.items():
                self.refs(item, value.loc(k, True), str(k))
            return
        if isinstance(value, LList):
            for index, item in enumerate(value):
                self.refs(item, value.loc(index), key)
            return
        for ref in references(value):
            if ref.name in self.defined or ref.name in self.globals or ref.name in self.plan.lost_names:
                continue
            if ref.name in self.in_branch:
                bound = self.in_branch[ref.name]
                self.error(f"variable ${ref.name} is bound inside a branch of a concurrent step (at line {bound.line}), "
                           "and a branch's bindings stay in that branch", where, key=key,
                           suggestion="add 'scope: plan' beside its 'as' to use it after the step")
            elif ref.name in self.later:
                bound = self.later[ref.name]
                self.error(f"variable ${ref.name} is used before it is bound (at line {bound.line})", where, key=key)
            else:
                known = [*self.defined, *self.globals]
                self.error(f"undefined variable ${ref.name}", where, key=key,
                           suggestion=_suggest(ref.name, known, "$"))

    # -- names -----------------------------------------------------------------------------------
    def failure_type(self, name: str, where: Location, key: str) -> None:
        if failure_class(name) is None:
            self.error(f"unknown failure type '{name}'", where, key=key,
                       suggestion=did_you_mean(name, [*FAILURES, *ALIASES]) or f"failure types: {', '.join(FAILURES)}")

    def check_call(self, name: str | None, args: Any, args_where: Location, where: Location) -> None:
        """A call of subplan `name` (at `where`) with `args` (a list, a mapping or None, at `args_where`)."""
        if name is None:
            return
        sub = self.plan.plans.get(name)
        if sub is None and name in self.plan.lost_plans:
            return
        if sub is None:
            self.error(f"undefined subplan '{name}'", where, key="call",
                       suggestion=did_you_mean(name, self.plan.plans)
                       or (f"subplans: {', '.join(self.plan.plans)}" if self.plan.plans else "define it under 'plans:'"))
            return
        names = [p.name for p in sub.params]
        required = [p.name for p in sub.params if p.required]
        signature = f"{name}({', '.join(names)})"
        given: list[str] = []
        if isinstance(args, LList):
            if len(args) > len(names):
                self.error(f"too many arguments: {signature} takes {len(names)}, got {len(args)}",
                           args_where, key="args")
            given = names[:len(args)]
        elif isinstance(args, LMap):
            for key in args:
                if key not in names:
                    self.error(f"{signature} has no parameter '{key}'", args.loc(key), key="args",
                               suggestion=did_you_mean(str(key), names))
            given = [k for k in args if k in names]
        for param, value, at in _arguments(sub.params, args, args_where):
            values = self.possible(value) if references(value) else [value]  # a variable's, when known now
            origin = "" if values == [value] else f" ({value})"
            for item in values or []:
                if isinstance(item, str) and references(item):
                    continue
                problem = type_problem(param, plain(item), self.robots)
                if problem:
                    self.error(f"{signature}: {problem}{origin}", at, key="args")
                else:
                    self.world_value(param, plain(item), at, "args", f"{signature}: ", origin)
        missing = [param for param in required if param not in given]
        if missing:
            self.error(f"missing argument{'s' if len(missing) > 1 else ''} {', '.join(missing)}: "
                       f"{signature} needs {len(required)}, got {len(given)}", args_where, key="args")

    def objects(self, head: str, slots: LMap) -> None:
        """With a world: the names in designator slots (objects, their links and joints) must be in it."""
        spec = DESIGNATORS.get(head)
        if spec is not None:
            self.need_robot(head, slots)
        if spec is not None:
            self._names(slots, [(s.name, s.kind, s.of) for s in spec.slots])

    def need_robot(self, head: str, slots: LMap) -> None:
        """With a world: designators and actions need a robot with a description (said once, at the first)."""
        if self.facts is not None and not self._robot_checked:
            self._robot_checked = True
            self._robot_for(head, slots)

    def _robot_for(self, head: str, slots: LMap) -> None:
        """With a world: designators need a robot with a description."""
        facts = self.facts
        if facts is None:
            return
        if facts.robot is None:
            self.error(f"the world has no robot to perform '{head}'", slots.where, key=head,
                       suggestion="add an object of type robot to the world file")
        elif facts.description is None:
            stem = facts.robot_file.rsplit(".", 1)[0]
            self.error(f"no robot description for '{facts.robot}' ({facts.robot_file}) to perform '{head}'",
                       slots.where, key=head, suggestion=f"write {stem}.yaml beside {facts.robot_file}, or name one "
                                                         "with 'description:' in the world file (see docs/robots.md)")

    def query_objects(self, name: str, args: LMap) -> None:
        """With a world: the names in query arguments (objects, their links, camera links) must be in it."""
        spec = QUERIES.get(name)
        if spec is not None:
            self._names(args, [(p.name, p.kind, p.of) for p in spec.params])

    def known_values(self, slot_name: str, kind: str, value: Any, where: Location) -> None:
        """A `$variable` in a slot whose values are known before the run (a plan parameter's, a `for_each` over a
        literal list) is checked like a literal of the slot's kind: what the run would find out later."""
        if not isinstance(value, str) or not references(value):
            return  # a literal: checked as one
        for item in self.possible(value) or []:
            if isinstance(item, str) and references(item):
                continue
            problem = KINDS[kind].check(item, self.robots)
            if problem:
                self.error(f"slot '{slot_name}': {problem} ({value})", where, key=str(slot_name))

    def _names(self, slots: LMap, kinds: list[tuple[str, str, str | None]]) -> None:
        """Object, link and joint names in slots, also those given by parameters and for_each lists."""
        for slot_name, kind, _ in kinds:
            if slot_name in slots:
                self.known_values(slot_name, kind, slots[slot_name], slots.loc(slot_name, True))
        facts = self.facts
        if facts is None:
            return
        names = list(facts.objects)
        for slot_name, kind, of in kinds:
            if slot_name not in slots:
                continue
            value = slots[slot_name]
            where = slots.loc(slot_name, True)
            values = self.possible(value) or []
            origin = "" if values == [value] else f" ({value})"
            for item in values:
                if not isinstance(item, str):
                    continue
                if KINDS[kind].names_object and item not in names:
                    self.error(f"'{slot_name}': the world has no object '{item}'{origin}", where, key=str(slot_name),
                               suggestion=did_you_mean(item, names))
                elif kind == "object-type":
                    self.object_type(slot_name, value, where)
                    break  # every value of the slot is checked at once
                elif kind == "camera" and facts.robot is not None and facts.robot in facts.links:
                    links = facts.links[facts.robot]
                    if item not in links:
                        self.error(f"'{slot_name}': robot '{facts.robot}' has no link '{item}'{origin}", where,
                                   key=str(slot_name), suggestion=did_you_mean(item, links))
                elif kind in ("link", "joint") and of is not None and of in slots:
                    self._part_names(slots, slot_name, item, kind, of, where, origin)

    def action_parts(self, slots: LMap, kinds: list[tuple[str, str, str | None]]) -> None:
        """With a world: the links and joints an action's slots name (`open`'s `handle` and `joint`) belong to the
        object its `of` slot names (`part-of`); without that slot, a joint must be a movable joint of the object
        that has the handle, else of some object of the world (the robot aside)."""
        facts = self.facts
        if facts is None:
            return
        for slot_name, kind, of in kinds:
            if kind not in ("link", "joint") or slot_name not in slots:
                continue
            where = slots.loc(slot_name, True)
            values = self.possible(slots[slot_name]) or []
            origin = "" if values == [slots[slot_name]] else f" ({slots[slot_name]})"
            for item in values:
                if not isinstance(item, str) or references(item):
                    continue
                if of is not None and of in slots:
                    self._part_names(slots, slot_name, item, kind, of, where, origin)
                elif kind == "joint":
                    self._joint_somewhere(slots, slot_name, item, where, origin)

    def _joint_somewhere(self, slots: LMap, slot_name: str, joint: str, where: Location, origin: str) -> None:
        facts = self.facts
        assert facts is not None
        owners = [name for name in facts.objects if name != facts.robot]
        handles = [h for h in self.possible(slots["handle"]) or [] if isinstance(h, str)] if "handle" in slots else []
        if handles:  # the joint is the one the handle is on: its object's
            owners = [name for name in owners if any(h in facts.links.get(name, ()) for h in handles)]
        if any(name not in facts.joints for name in owners):
            return  # an object whose model is not known: it may have the joint
        known = [j for name in owners for j in facts.joints[name]]
        if joint not in known:
            whose = f"object '{owners[0]}'" if len(owners) == 1 else "the world (the robot aside)"
            self.error(f"'{slot_name}': {whose} has no movable joint '{joint}'{origin}", where, key=str(slot_name),
                       suggestion=did_you_mean(joint, known))

    def _part_names(self, slots: LMap, slot_name: str, item: str, kind: str, of: str, where: Location,
                    origin: str) -> None:
        """A link or joint named in `slot_name` must belong to the object the slot `of` names."""
        facts = self.facts
        assert facts is not None
        table = facts.links if kind == "link" else facts.joints
        for owner in self.possible(slots[of]) or []:
            if not isinstance(owner, str) or owner not in table:
                continue  # not an object name (reported above), or an object whose model is not known
            known = table[owner]
            if item not in known:
                what = "link" if kind == "link" else "movable joint"
                self.error(f"'{slot_name}': object '{owner}' has no {what} '{item}'{origin}", where,
                           key=str(slot_name), suggestion=did_you_mean(item, known))


def _arguments(params: list[Param], args: Any, where: Location) -> list[tuple[Param, Any, Location]]:
    """The arguments of a call that go with typed parameters: (parameter, value, place)."""
    if isinstance(args, LList):
        return [(p, v, args.loc(i)) for i, (p, v) in enumerate(zip(params, args)) if p.type]
    if isinstance(args, LMap):
        by_name = {p.name: p for p in params}
        return [(by_name[k], v, args.loc(k, True)) for k, v in args.items() if k in by_name and by_name[k].type]
    return []


def _suggest(name: str, known: list[str], prefix: str = "") -> str | None:
    hint = did_you_mean(name, known)
    if hint:
        return hint.replace("'", f"'{prefix}", 1)
    return None


def check_plan(plan: Plan, world: BulletWorld | None = None, check_world_file: bool = True,
               errors: list[InputError] | None = None, facts: WorldFacts | None = None,
               values: Mapping[str, Any] | None = None) -> Plan:
    """Raise every static problem of `plan` (and the `errors` found before) together; return it when there is none.

    The world it runs in is known from `facts` (a world file) or `world` (a loaded world); without
    either, robot names (arms, grasps, poses) are checked against every bundled robot. `values`:
    the parameters' values for this run (default: their defaults), for names given by parameters.
    """
    if facts is None and world is not None:
        facts = WorldFacts.of_world(world)
    validator = Validator(plan, facts, values)
    validator.errors.extend(errors or [])
    if facts is not None and facts.description is not None:
        validator.errors.extend(process_module_problems(facts.description))
    if check_world_file and plan.world is not None:
        try:
            find_world(plan.world, plan.path.parent, plan.world_where, naming=plan.path)
        except InputError as exc:
            validator.errors.append(exc)
    validator.check()
    raise_if_any(validator.errors)
    return plan
