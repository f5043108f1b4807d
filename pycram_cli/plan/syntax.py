"""Reading a plan file into a tree of nodes, each remembering its place in the file.

A plan file:

    description: ...            # optional
    world: kitchen              # bundled world name, or a path relative to the plan file
    params: {object: milk}      # parameters with defaults (a list entry without default is required)
                                # or declared: {target: {type: position, default: [1, 0.5, 0.9]}}
    plans:                      # subplans, called with `call:`
      fetch:
        params: [object]
        body: [...]
        returns: $obj           # optional: the value of a call
    body: [...]                 # the steps run by `pycram run`

A step is a mapping with exactly one *head* key naming its node type (`seq`, `par`,
`retry`, `moving`, `stable`, `log`, ...) plus the keys that node type allows. Node types
register themselves with `@node_type`; motion designators and reasoning queries are node
families found by name in their own registries. This module knows no node type: the
built-in ones are registered by `language.py`, which imports their modules (composites,
decorators, leaves) and offers `parse_plan`. Parsing only builds the tree and reports
malformed steps; `validate.py` checks names, variables and calls across the whole plan.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

from ..errors import InputError, Location, did_you_mean, raise_if_any
from ..kinds import param_kind, param_kind_names
from ..limits import MAX_PLAN_DEPTH
from ..schema import check_keys, describe, key_error, names_only
from ..yamlsource import LList, LMap, load_yaml, where_of
from .context import IDENTIFIER, references
from .runtime import Record, Runtime

if TYPE_CHECKING:  # for annotations only: these modules import this one
    from .resources import ResourceAnalysis
    from .validate import Validator

PLAN_KEYS = ("description", "world", "params", "plans", "body")
PLAN_REQUIRED = ("body",)
SUBPLAN_KEYS = ("description", "params", "body", "returns")
SUBPLAN_REQUIRED = ("body",)
COMMON_KEYS = ("as", "scope")
#: where a step's binding goes: its branch's frame (the default) or the plan invocation's (`scope: plan`)
SCOPES = ("branch", "plan")


class Node:
    """One step of a plan. Subclasses register with `@node_type(head)`."""

    HEAD: ClassVar[str] = ""
    KEYS: ClassVar[tuple[str, ...]] = ()      # keys allowed beside the head
    REQUIRED: ClassVar[tuple[str, ...]] = ()  # keys that must be given beside the head
    BINDS: ClassVar[bool] = False             # whether `as: name` is allowed
    LEAF: ClassVar[bool] = False              # leaf steps pass the turn to other branches when they succeed
    DOC: ClassVar[str] = ""

    def __init__(self, head: str, where: Location) -> None:
        self.head = head
        self.where = where
        self.bind: str | None = None
        self.bind_where: Location = where
        self.scope: str | None = None  # `scope: plan` binds in the plan invocation's frame, not the branch's

    # -- parsing ----------------------------------------------------------------
    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        raise NotImplementedError

    @classmethod
    def allowed_keys(cls, head: str) -> tuple[str, ...]:
        return cls.KEYS + (("as", "scope") if cls.BINDS else ())

    # -- structure ----------------------------------------------------------------
    def label(self) -> str:
        """How the node is named in paths and trees: `par`, `moving`, `call fetch`."""
        return self.head

    def parts(self) -> list[tuple[str, list[Node]]]:
        """The node's static lists of child steps, named (for validation and resource analysis)."""
        return []

    def walk(self) -> Iterable[Node]:
        yield self
        for _, steps in self.parts():
            for step in steps:
                yield from step.walk()

    def bindings(self) -> list[tuple[str, Location]]:
        """The variables this node itself binds, with their places (`as:`; subclasses add theirs)."""
        return [(self.bind, self.bind_where)] if self.bind else []

    def plan_bindings(self) -> list[tuple[str, Location]]:
        """The variables this node binds with `scope: plan` (seen after the branch it runs in)."""
        return self.bindings() if self.scope == "plan" else []

    def resources(self, analysis: ResourceAnalysis) -> frozenset[str]:
        """The robot's resources this node itself uses, not counting its child steps (see resources.py)."""
        return frozenset()

    # -- checking and running -----------------------------------------------------
    def check(self, validator: Validator) -> None:
        """Static checks (references, names); the default checks the child steps in order."""
        for _, steps in self.parts():
            validator.check_steps(steps)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        """Run the node: `ex` is the runtime of its thread, `tn` its entry in the trace (see runtime.py)."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.label()} at {self.where}>"


NODE_TYPES: dict[str, type[Node]] = {}
FAMILIES: list[tuple[str, Callable[[], Iterable[str]], type[Node]]] = []


def node_type(head: str) -> Callable[[type[Node]], type[Node]]:
    """Register a node class under its head key."""

    def register(cls: type[Node]) -> type[Node]:
        cls.HEAD = head
        NODE_TYPES[head] = cls
        return cls

    return register


def node_family(name: str, heads: Callable[[], Iterable[str]]) -> Callable[[type[Node]], type[Node]]:
    """Register a node class for a family of heads (designator types, query names)."""

    def register(cls: type[Node]) -> type[Node]:
        FAMILIES.append((name, heads, cls))
        return cls

    return register


def node_class(head: str) -> type[Node] | None:
    """The registered node class for a head, or None."""
    if head in NODE_TYPES:
        return NODE_TYPES[head]
    for _, heads, cls in FAMILIES:
        if head in set(heads()):
            return cls
    return None


def all_heads() -> list[str]:
    """Every registered head (for suggestions)."""
    names = list(NODE_TYPES)
    for _, heads, _cls in FAMILIES:
        names.extend(heads())
    return names


#: the keys of a declared parameter: `target: {type: position, default: [1, 0.5, 0.9], description: ...}`
PARAM_DECLARATION_KEYS = ("type", "default", "description")


@dataclass
class Param:
    """A plan's or subplan's parameter: its default (none when required) and, when declared, its type.

    `type` names a kind of value (`kinds.py`: position, object, arm, list, ...); values given for a
    typed parameter (its default, `-p`, sweep variations, literal call arguments) are checked
    against it before anything runs.
    """

    name: str
    default: Any = None
    required: bool = False
    where: Location = field(default_factory=Location)
    type: str | None = None
    description: str = ""
    default_where: Location = field(default_factory=Location)


@dataclass
class Subplan:
    name: str
    params: list[Param]
    body: list[Node]
    returns: Any = None
    has_returns: bool = False
    description: str = ""
    where: Location = field(default_factory=Location)
    returns_where: Location = field(default_factory=Location)


@dataclass
class Plan:
    path: Path
    body: list[Node]
    params: list[Param] = field(default_factory=list)
    plans: dict[str, Subplan] = field(default_factory=dict)
    world: str | None = None
    world_where: Location = field(default_factory=Location)
    description: str = ""
    where: Location = field(default_factory=Location)
    lost_names: set[str] = field(default_factory=set)
    lost_plans: set[str] = field(default_factory=set)

    @property
    def name(self) -> str:
        return self.path.stem

    def param(self, name: str) -> Param | None:
        return next((p for p in self.params if p.name == name), None)


class Parser:
    """Turns YAML (with locations) into nodes, collecting every problem."""

    def __init__(self) -> None:
        self.errors: list[InputError] = []
        self.depth = 0  # steps nested around the one being read
        # names bound by steps (or subplans defined) that could not be parsed: later checks
        # treat them as known, so that one mistake is not reported again at every use
        self.lost_names: set[str] = set()
        self.lost_plans: set[str] = set()

    def error(self, message: str, where: Location, key: str | None = None, suggestion: str | None = None) -> None:
        self.errors.append(InputError(message, where, key=key, suggestion=suggestion))

    def names_only(self, mapping: LMap) -> LMap:
        """Report the keys of a mapping of names (slots, arguments) that are not names, and leave them out."""
        return names_only(mapping, self.errors)

    # -- steps ---------------------------------------------------------------------
    def named_steps(self, mapping: LMap, key: str, what: str, example: str) -> list[tuple[str, Location, list[Node]]]:
        """`mapping[key]`, a mapping of names to lists of steps (`catch`, `alternatives`), as (name, where, steps)
        in order; reports anything else as "expected a mapping of `what`" with `example` as the suggestion."""
        given = mapping.get(key)
        if not isinstance(given, LMap) or not given:
            self.error(f"expected a mapping of {what}, got {describe(given)}", mapping.loc(key, True), key=key,
                       suggestion=example)
            return []
        return [(str(name), given.loc(name), self.steps(given[name], given.loc(name, True), str(name)))
                for name in self.names_only(given)]

    def steps(self, value: Any, where: Location, key: str) -> list[Node]:
        """A list of steps; a single step mapping is accepted as a list of one."""
        if isinstance(value, LMap):
            node = self.step(value, where_of(value, where))
            return [node] if node is not None else []
        if not isinstance(value, LList):
            self.error(f"expected a list of steps, got {describe(value)}", where, key=key)
            return []
        if not value:
            self.error("expected at least one step, got an empty list", where_of(value, where), key=key)
        result = []
        for index, item in enumerate(value):
            node = self.step(item, value.loc(index))
            if node is not None:
                result.append(node)
        return result

    def step(self, value: Any, where: Location) -> Node | None:
        if self.depth >= MAX_PLAN_DEPTH:
            self.error(f"steps nested more than {MAX_PLAN_DEPTH} levels deep (the limit)", where,
                       suggestion="move inner steps into a subplan and call it")
            return None
        self.depth += 1
        try:
            node = self._step(value, where)
        finally:
            self.depth -= 1
        if node is None and isinstance(value, LMap):
            for key in ("as",):
                if isinstance(value.get(key), str):
                    self.lost_names.add(value[key])
        return node

    def _step(self, value: Any, where: Location) -> Node | None:
        if isinstance(value, LMap) and any(key is True for key in value):
            value = yaml11_on(value)
        if not isinstance(value, LMap):
            hint = None
            if isinstance(value, str):
                hint = (f"write a step as a mapping, e.g. {{{value}: ...}}" if node_class(value)
                        else did_you_mean(value, all_heads()))
            self.error(f"a step must be a mapping with one node type, got {describe(value)}", where, suggestion=hint)
            return None
        heads = [(key, cls) for key in value if isinstance(key, str) and (cls := node_class(key)) is not None]
        if len(heads) > 1:
            names = " and ".join(f"'{k}'" for k, _ in heads)
            self.error(f"a step has exactly one node type, found {names}", value.loc(heads[1][0]), key=heads[1][0],
                       suggestion="put them in separate steps of a list")
            return None
        if not heads:
            self._unknown_head(value)
            return None
        head, cls = heads[0]
        allowed = cls.allowed_keys(head)
        self.names_only(value)
        for key in value:
            if key == head or key in allowed:
                continue
            if key in COMMON_KEYS:
                self.error(f"'{head}' does not produce a value to bind with '{key}'", value.loc(key), key=str(key))
            else:
                self.error(f"unknown key '{key}' in {_article(head)} '{head}' step", value.loc(key), key=str(key),
                           suggestion=did_you_mean(str(key), allowed)
                           or (f"'{head}' takes: {', '.join(allowed)}" if allowed else f"'{head}' takes no other keys"))
        for key in cls.REQUIRED:
            if key not in value:
                self.error(f"{_article(head)} '{head}' step needs '{key}'", value.loc(head), key=key)
        node = cls.parse(head, value, self)
        if node is None:
            return None
        if "as" in value and cls.BINDS:
            node.bind = self.identifier(value["as"], value.loc("as", True), "as")
            node.bind_where = value.loc("as", True)
        if "scope" in value and "scope" in allowed:
            node.scope = self.scope(value, head)
        return node

    def scope(self, step: LMap, head: str) -> str | None:
        """`scope: plan | branch` of a binding step (it needs something to bind: `as`, or `set`'s names)."""
        value = step["scope"]
        if value not in SCOPES:
            self.error(f"expected scope: plan or scope: branch, got {describe(value)}", step.loc("scope", True),
                       key="scope", suggestion=did_you_mean(str(value), SCOPES))
            return None
        if "as" not in step and head != "set":
            self.error(f"'scope' says where '{head}' binds its value: it needs 'as'", step.loc("scope"), key="scope")
            return None
        return str(value)

    def _unknown_head(self, value: LMap) -> None:
        heads = all_heads()
        unknown = [k for k in value if k not in COMMON_KEYS]
        if not unknown:
            self.error("a step needs a node type (e.g. seq, par, moving, log)", value.where)
            return
        key = unknown[0]
        if (error := key_error(value, key)) is not None:
            self.errors.append(error)
            return
        self.error(f"unknown node type '{key}'", value.loc(key), key=str(key),
                   suggestion=did_you_mean(str(key), heads) or "see docs/plans.md for the node types")

    # -- values ------------------------------------------------------------------------
    def identifier(self, value: Any, where: Location, key: str) -> str | None:
        if isinstance(value, str) and value.startswith("$"):
            self.error(f"write a variable name without '$' here, got '{value}'", where, key=key,
                       suggestion=f"{key}: {value[1:]}")
            return None
        if not isinstance(value, str) or not IDENTIFIER.match(value):
            self.error(f"expected a variable name (letters, digits, _ and -), got {describe(value)}", where, key=key)
            return None
        return value

    def string(self, value: Any, where: Location, key: str) -> str | None:
        if not isinstance(value, str):
            self.error(f"expected a string, got {describe(value)}", where, key=key)
            return None
        return value

    def names(self, value: Any, where: Location, key: str) -> list[tuple[str, Location]]:
        """A name or a list of names, each with its place."""
        items = value if isinstance(value, LList) else [value]
        result = []
        for index, item in enumerate(items):
            at = value.loc(index) if isinstance(value, LList) else where
            if isinstance(item, str) and item:
                result.append((item, at))
            else:
                self.error(f"expected a name, got {describe(item)}", at, key=key)
        return result

    # -- parameters ----------------------------------------------------------------------
    def params(self, value: Any, where: Location, context: str) -> list[Param]:
        """`params` as a mapping name: default, or a list whose items are `name` (required) or `{name: default}`.

        A default that is a mapping of `type` (a kind of value) and optionally `default` and
        `description` is a declaration: `target: {type: position, default: [1, 0.5, 0.9]}`; without
        `default` the parameter is required. Any other mapping is a plain default.
        """
        result: list[Param] = []
        if isinstance(value, LMap):
            entries = [(k, value[k], True, value.loc(k), value.loc(k, True)) for k in value]
        elif isinstance(value, LList):
            entries = []
            for index, item in enumerate(value):
                at = value.loc(index)
                if isinstance(item, str):
                    entries.append((item, None, False, at, at))
                elif isinstance(item, LMap) and len(item) == 1:
                    (name, default), = item.items()
                    entries.append((name, default, True, item.loc(name), item.loc(name, True)))
                else:
                    self.error(f"expected a parameter name or {{name: default}}, got {describe(item)}", at, key="params")
        elif value is None:
            entries = []
        else:
            self.error(f"expected the parameters of {context} as a list or a mapping, got {describe(value)}", where,
                       key="params")
            return result
        seen: set[str] = set()
        for name, default, has_default, at, default_at in entries:
            if self.identifier(name, at, "params") is None:
                continue
            if name in seen:
                self.error(f"parameter '{name}' is given twice in {context}", at, key="params")
                continue
            seen.add(name)
            param = Param(name, None, not has_default, at, default_where=default_at)
            if has_default and not self._declaration(default, param):
                param.default = default
            if not param.required:
                if references(param.default):
                    self.error(f"the default of parameter '{name}' cannot use variables", param.default_where,
                               key="params")
                param.default = _plain(param.default)
            result.append(param)
        return result

    def _declaration(self, value: Any, param: Param) -> bool:
        """Fill `param` from a declaration `{type: KIND, default: ..., description: ...}`; False for a plain default."""
        if not (isinstance(value, LMap) and value and "type" in value
                and all(isinstance(k, str) and k in PARAM_DECLARATION_KEYS for k in value)):
            return False
        kind = param_kind(value["type"])
        if kind is None:
            typo = did_you_mean(value["type"], param_kind_names()) if isinstance(value["type"], str) else None
            if typo and len(value) > 1:  # `{type: positon, default: [...]}`: a misspelt declaration, not a value
                self.error(f"unknown parameter type '{value['type']}'", value.loc("type", True), key="type",
                           suggestion=typo)
            return False
        param.type = str(value["type"])
        if "description" in value:
            param.description = self.string(value["description"], value.loc("description", True), "description") or ""
        if "default" in value:
            param.default, param.required = value["default"], False
            param.default_where = value.loc("default", True)
        else:
            param.required = True
        return True


def _article(word: str) -> str:
    return "an" if word[:1].lower() in "aeiou" else "a"


def yaml11_on(step: LMap) -> LMap:
    """YAML 1.1 reads an unquoted key `on` as true; in a step it can only mean the key `on`."""
    fixed = LMap()
    fixed.where, fixed.key_where, fixed.value_where = step.where, {}, {}
    for key, value in step.items():
        name = "on" if key is True else key
        fixed[name] = value
        fixed.key_where[name], fixed.value_where[name] = step.loc(key), step.loc(key, True)
    return fixed


def _plain(value: Any) -> Any:
    """LMap/LList to plain dict/list (values handed to the executor)."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain(v) for v in value]
    return value


plain = _plain


def read_plan(path: str | Path, errors: list[InputError] | None = None) -> Plan:
    """Read a plan file into nodes of the registered types; every structural problem is reported together.

    With an `errors` list, problems are added to it instead of raised (so that later
    checks can report theirs in the same go). Use `language.parse_plan`, which has every
    built-in node type registered.
    """
    path = Path(path)
    data = load_yaml(path)
    fname = str(path)
    parser = Parser()
    if not isinstance(data, LMap):
        raise InputError("a plan file must be a mapping with a 'body' (and optionally world, params, plans)",
                         Location(fname, 1, 1))
    check_keys(data, PLAN_KEYS, PLAN_REQUIRED, "the plan", parser.errors)
    plan = Plan(path=path, body=[], where=data.where)
    if "description" in data:
        plan.description = parser.string(data["description"], data.loc("description", True), "description") or ""
    if "world" in data:
        plan.world = parser.string(data["world"], data.loc("world", True), "world")
        plan.world_where = data.loc("world", True)
    if "params" in data:
        plan.params = parser.params(data["params"], data.loc("params", True), "the plan")
    if "plans" in data:
        plans = data["plans"]
        if not isinstance(plans, LMap):
            parser.error(f"expected a mapping of subplan name to subplan, got {describe(plans)}", data.loc("plans", True),
                         key="plans")
        else:
            for name in plans:
                sub = _parse_subplan(name, plans[name], plans.loc(name), plans.loc(name, True), parser)
                if sub is not None:
                    plan.plans[name] = sub
                elif isinstance(name, str):
                    parser.lost_plans.add(name)
    if "body" in data:
        plan.body = parser.steps(data["body"], data.loc("body", True), "body")
    plan.lost_names, plan.lost_plans = parser.lost_names, parser.lost_plans
    if errors is not None:
        errors.extend(parser.errors)
    else:
        raise_if_any(parser.errors)
    return plan


def _parse_subplan(name: Any, value: Any, key_where: Location, where: Location, parser: Parser) -> Subplan | None:
    if parser.identifier(name, key_where, "plans") is None:
        return None
    if node_class(name) is not None:
        parser.error(f"a subplan cannot be named '{name}': that is a node type", key_where, key="plans",
                     suggestion="choose another name")
        return None
    if isinstance(value, LList):  # shorthand: a subplan without parameters is just its body
        return Subplan(name, [], parser.steps(value, where, name), where=key_where)
    if not isinstance(value, LMap):
        parser.error(f"subplan '{name}': expected a mapping with params and body, got {describe(value)}", where,
                     key=str(name))
        return None
    check_keys(value, SUBPLAN_KEYS, SUBPLAN_REQUIRED, f"subplan '{name}'", parser.errors)
    sub = Subplan(name, [], [], where=key_where)
    if "description" in value:
        sub.description = parser.string(value["description"], value.loc("description", True), "description") or ""
    if "params" in value:
        sub.params = parser.params(value["params"], value.loc("params", True), f"subplan '{name}'")
    if "body" in value:
        sub.body = parser.steps(value["body"], value.loc("body", True), "body")
    if "returns" in value:
        sub.returns, sub.has_returns = _plain(value["returns"]), True
        sub.returns_where = value.loc("returns", True)
    return sub
