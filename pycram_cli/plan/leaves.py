"""Leaf steps: motion designators, reasoning queries, call, fail, assert, log, set, wait.

    - moving: {target: [0.65, 0.7, 0]}            any motion designator with its slots (`as:` binds its
      as: ...                                     result, e.g. the object `detecting` found)
    - stable: {object: $obj}                      any reasoning query; as a step it only records its
      as: ok                                      answer (`as:` binds it: true/false or a list of objects)
    - call: fetch                                 run a subplan; args positional (list) or by name
      args: {object: milk}                        (`as:` binds the subplan's `returns` value)
    - fail: PerceptionFailure                     raise a failure (`fail: $failure` re-raises a caught one)
      message: "no $object here"
    - assert: {stable: {object: $obj}}            a condition that must hold, else the failure is raised
      failure: ReasoningFailure                   (default ReasoningFailure; default message says what failed)
      message: "$obj is not stable"
    - log: "fetching $object"                     a message in the trace and on the console
    - set: {target: [1, 0.5, 0.9]}                bind variables
    - wait: 0.5                                   sleep (seconds); cancellable at once

A condition (for `if`, `unless`, `assert`) is a `$variable`, true/false, a query
mapping (`{blocking: {...}}`: true when it answers true or a non-empty list),
`{equal: [a, b]}` (objects compare by name), or `{not: condition}`.
"""
from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

from ..designators import DESIGNATORS, check_designator, perform
from ..errors import Location, PycramError, did_you_mean
from ..failures import FAILURES, Failure, as_failure, failure_class
from ..limits import MAX_CALL_DEPTH, MAX_WAIT
from ..reasoning import QUERIES, check_query_args, run_query
from ..schema import describe
from ..yamlsource import LList, LMap
from .context import REFERENCE, FailureInfo, Frame, display, is_reference, jsonable, size_problem, truthy
from .resources import ResourceAnalysis
from .runtime import LimitExceeded, Record, Runtime
from .syntax import Node, Parser, node_family, node_type, plain

if TYPE_CHECKING:  # for annotations only: validate imports syntax, which the node classes extend
    from .validate import Validator

def _problems_where(slots: Any, slot: str | None, fallback: Location) -> Location:
    if isinstance(slots, LMap) and slot is not None and slot in slots:
        return slots.loc(slot, True)
    return fallback


def _mapping(value: Any, where: Location, head: str, parser: Parser, what: str) -> LMap | None:
    if value is None:
        empty = LMap()
        empty.where, empty.key_where, empty.value_where = where, {}, {}
        return empty
    if not isinstance(value, LMap):
        parser.error(f"expected the {what} of '{head}' as a mapping, got {describe(value)}", where, key=head,
                     suggestion=f"e.g. {head}: {{name: value}}")
        return None
    return parser.names_only(value)


class _MappingStep(Node):
    """A leaf step whose head names what it runs and whose value is a mapping (a designator's slots, a query's
    arguments): the one way both are parsed and kept; each subclass keeps the mapping under its own attribute name."""

    BINDS = True
    LEAF = True
    WHAT = "mapping"  # what the mapping is, in the error for a value that is not one
    ATTRIBUTE = "mapping"  # the attribute the subclass reads it from (declared there, for the type checker)

    def __init__(self, head: str, where: Location, mapping: LMap) -> None:
        super().__init__(head, where)
        setattr(self, self.ATTRIBUTE, mapping)

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        value = _mapping(step[head], step.loc(head, True), head, parser, cls.WHAT)
        return None if value is None else cls(head, step.loc(head), value)


@contextmanager
def _world_call(ex: Runtime, name: str) -> Iterator[None]:
    """Hold the world while a designator or query runs, and turn an error of a value it cannot use into the
    failure plans handle; a failure passes as it is, anything else is a bug (an internal error)."""
    with ex.world_action():
        try:
            yield
        except Failure:
            raise
        except PycramError as exc:
            raise as_failure(exc, name) from exc


# -- motion designators -------------------------------------------------------------------------------
@node_family("designator", lambda: DESIGNATORS.keys())
class DesignatorStep(_MappingStep):
    WHAT = ATTRIBUTE = "slots"
    DOC = "perform a motion designator through its process module"
    slots: LMap

    def resources(self, analysis: ResourceAnalysis) -> frozenset[str]:
        return analysis.designator(self.head, self.slots)

    def check(self, v: Validator) -> None:
        for problem in check_designator(self.head, plain(self.slots), is_reference, v.robots):
            v.error(problem.message, _problems_where(self.slots, problem.param, self.where),
                    key=problem.param or self.head, suggestion=problem.suggestion)
        v.refs(self.slots, self.slots.where)
        v.objects(self.head, self.slots)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        values = ex.evaluate(self.slots)
        tn.info["designator"] = {"slots": jsonable(values)}
        with _world_call(ex, self.head):  # perform checks the slots' run-time values against the robot
            performed = perform(ex.world, self.head, values)
            tn.info["designator"] = {**tn.info["designator"], "resolved": jsonable(performed.resolved)}
        return performed.result


# -- reasoning queries --------------------------------------------------------------------------------------
def check_query(name: str, args: LMap, v: Validator) -> None:
    """Report a query call's problems, each at the argument it names (its key for an unknown one), else at the call."""
    spec = QUERIES.get(name)
    for problem in check_query_args(name, plain(args), is_reference, v.robots):
        where = args.where
        if problem.param is not None and problem.param in args:
            where = args.loc(problem.param, value=spec is not None and spec.param(problem.param) is not None)
        v.error(problem.message, where, key=name, suggestion=problem.suggestion)


def ask(ex: Runtime, name: str, args: Any) -> tuple[Any, dict[str, Any]]:
    """Run a query with evaluated arguments; its value and the record for the trace."""
    values = ex.evaluate(args)
    with _world_call(ex, name):
        answer = run_query(ex.world, name, values)
    record = {"name": name, "args": jsonable(answer.args), "result": jsonable(answer.result),
              "details": jsonable(answer.details)}
    return answer.value, record


@node_family("query", lambda: QUERIES.keys())
class QueryStep(_MappingStep):
    WHAT, ATTRIBUTE = "arguments", "args"
    DOC = "ask a reasoning query; records the answer (bind it with `as`)"
    args: LMap

    def check(self, v: Validator) -> None:
        check_query(self.head, self.args, v)
        v.refs(self.args, self.args.where)
        v.query_objects(self.head, self.args)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        value, record = ask(ex, self.head, self.args)
        record.pop("name")
        tn.info["query"] = record
        return value


# -- conditions ------------------------------------------------------------------------------------------------
#: the condition forms beside the queries, and what each holds for
CONDITION_FORMS = {"not": "the condition given does not hold",
                   "equal": "the two values [a, b] are equal (objects compare by name)"}


class Condition:
    """`$variable`, true/false, a query mapping, {equal: [a, b]}, or {not: condition}."""

    def __init__(self, kind: str, where: Location, value: Any = None, name: str = "",
                 inner: Condition | None = None) -> None:
        self.kind, self.where, self.value, self.name, self.inner = kind, where, value, name, inner

    @classmethod
    def parse(cls, value: Any, where: Location, key: str, parser: Parser) -> Condition | None:
        if isinstance(value, bool):
            return cls("literal", where, value)
        if isinstance(value, str) and value.startswith("$"):
            if not REFERENCE.match(value):
                parser.error(f"expected a variable like $name or $name.attr, got '{value}'", where, key=key)
                return None
            return cls("variable", where, value)
        if isinstance(value, LMap) and len(value) == 1:
            (head, args), = value.items()
            if head == "not":  # CONDITION_FORMS
                inner = cls.parse(args, value.loc("not", True), key, parser)
                return None if inner is None else cls("not", where, inner=inner)
            if head == "equal":
                if not isinstance(args, LList) or len(args) != 2:
                    parser.error(f"expected two values to compare, e.g. {{equal: [$o, spoon]}}, got {describe(args)}",
                                 value.loc("equal", True), key="equal")
                    return None
                return cls("equal", value.loc("equal", True), plain(args))
            if head in QUERIES:
                mapping = _mapping(args, value.loc(head, True), head, parser, "arguments")
                return None if mapping is None else cls("query", where, mapping, name=head)
            parser.error(f"unknown query '{head}' in a condition", value.loc(head), key=key,
                         suggestion=did_you_mean(str(head), [*QUERIES, *CONDITION_FORMS])
                         or f"queries: {', '.join(QUERIES)}")
            return None
        parser.error(f"expected a condition: a $variable, true/false, a query like {{stable: {{object: $obj}}}}, "
                     f"{{equal: [a, b]}} or {{not: ...}}, got {describe(value)}", where, key=key)
        return None

    def check(self, v: Validator) -> None:
        if self.kind == "variable":
            v.refs(self.value, self.where)
        elif self.kind == "query":
            check_query(self.name, self.value, v)
            v.refs(self.value, self.value.where)
            v.query_objects(self.name, self.value)
        elif self.kind == "not" and self.inner is not None:
            self.inner.check(v)
        elif self.kind == "equal":
            v.refs(self.value, self.where)

    def text(self) -> str:
        if self.kind == "literal":
            return "true" if self.value else "false"
        if self.kind == "variable":
            return self.value
        if self.kind == "not" and self.inner is not None:
            return f"not {self.inner.text()}"
        if self.kind == "equal":
            return f"{display(self.value[0])} = {display(self.value[1])}"
        args = ", ".join(f"{k}={display(v)}" for k, v in self.value.items())
        return f"{self.name}({args})"

    def evaluate(self, ex: Runtime, tn: Record) -> bool:
        holds, record = self._evaluate(ex)
        tn.info["condition"] = record
        return holds

    def _evaluate(self, ex: Runtime) -> tuple[bool, dict[str, Any]]:
        if self.kind == "literal":
            return bool(self.value), {"value": bool(self.value)}
        if self.kind == "variable":
            value = ex.evaluate(self.value)
            return truthy(value), {"variable": self.value, "value": jsonable(value), "holds": truthy(value)}
        if self.kind == "not" and self.inner is not None:
            holds, record = self.inner._evaluate(ex)
            return not holds, {"not": record, "holds": not holds}
        if self.kind == "equal":
            values = [jsonable(ex.evaluate(v)) for v in self.value]
            holds = values[0] == values[1]
            return holds, {"equal": values, "holds": holds}
        value, record = ask(ex, self.name, self.value)
        record["holds"] = truthy(value)
        return truthy(value), {"query": record, "holds": truthy(value)}


# -- call -----------------------------------------------------------------------------------------------------------

@node_type("call")
class CallStep(Node):
    KEYS = ("args",)
    BINDS = True
    DOC = "run a subplan with arguments (positional list or by name)"

    def __init__(self, head: str, where: Location, name: str | None, args: Any, args_where: Location) -> None:
        super().__init__(head, where)
        self.name = name
        self.args = args
        self.args_where = args_where

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        name = parser.string(step[head], step.loc(head, True), head)
        args = step.get("args")
        if args is not None and not isinstance(args, (LList, LMap)):
            parser.error(f"expected the arguments as a list or a mapping, got {describe(args)}", step.loc("args", True),
                         key="args")
            args = None
        if isinstance(args, LMap):
            parser.names_only(args)
        return cls(head, step.loc(head), name, args, step.loc("args", True) if "args" in step else step.loc(head))

    def label(self) -> str:
        return f"call {self.name}"

    def resources(self, analysis: ResourceAnalysis) -> frozenset[str]:
        return analysis.subplan(self.name)

    def check(self, v: Validator) -> None:
        v.check_call(self.name, self.args, self.args_where, self.where)
        if self.args is not None:
            v.refs(self.args, self.args_where)

    def bound_args(self, ex: Runtime) -> dict[str, Any]:
        sub = ex.plan.plans[self.name or ""]
        values: dict[str, Any] = {}
        if isinstance(self.args, list):
            for param, value in zip(sub.params, self.args):
                values[param.name] = ex.evaluate(value)
        elif isinstance(self.args, dict):
            for key, value in self.args.items():
                values[key] = ex.evaluate(value)
        for param in sub.params:
            if param.name not in values:
                values[param.name] = param.default
        return values

    def execute(self, ex: Runtime, tn: Record) -> Any:
        sub = ex.plan.plans[self.name or ""]
        values = self.bound_args(ex)
        tn.info["call"] = {"plan": self.name, "args": jsonable(values)}
        if ex.depth >= MAX_CALL_DEPTH:
            raise LimitExceeded(f"call {self.name}: more than {MAX_CALL_DEPTH} nested calls (the limit; endless "
                                "recursion?)", tn.path)
        inner = ex.derive(frame=Frame(values, parent=ex.globals), depth=ex.depth + 1)
        inner.seq(sub.body, tn)
        return inner.evaluate(sub.returns) if sub.has_returns else None


# -- fail and assert ------------------------------------------------------------------------------------------------
def _failure_type(name: str) -> type[Failure]:
    cls = failure_class(name)
    if cls is None:
        raise Failure(f"fail: unknown failure type '{name}' (known: {', '.join(FAILURES)})")
    return cls


@node_type("fail")
class FailStep(Node):
    LEAF = True
    KEYS = ("message",)
    DOC = "raise a failure of a type, with a message (`fail: $failure` re-raises a caught failure)"

    def __init__(self, head: str, where: Location, kind: Any, message: Any, kind_where: Location,
                 message_where: Location) -> None:
        super().__init__(head, where)
        self.kind, self.message, self.kind_where, self.message_where = kind, message, kind_where, message_where

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        kind = parser.string(step[head], step.loc(head, True), head)
        message = step.get("message")
        if "message" in step:
            parser.string(message, step.loc("message", True), "message")
        return cls(head, step.loc(head), kind, message, step.loc(head, True), step.loc("message", True))

    def check(self, v: Validator) -> None:
        if isinstance(self.kind, str) and not is_reference(self.kind):
            v.failure_type(self.kind, self.kind_where, "fail")
        v.refs(self.kind, self.kind_where)
        if self.message is not None:
            v.refs(self.message, self.message_where)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        kind = ex.evaluate(self.kind)
        if isinstance(kind, FailureInfo):
            tn.info["rethrow"] = kind.path
            raise kind.error
        message = display(ex.evaluate(self.message)) if self.message is not None else f"{kind} raised by the plan"
        raise _failure_type(str(kind))(message)


@node_type("assert")
class AssertStep(Node):
    LEAF = True
    KEYS = ("failure", "message")
    DOC = "check a condition; raise a failure (default ReasoningFailure) when it does not hold"

    def __init__(self, head: str, where: Location, condition: Condition, kind: str, message: Any,
                 kind_where: Location, message_where: Location) -> None:
        super().__init__(head, where)
        self.condition, self.kind, self.message, self.kind_where = condition, kind, message, kind_where
        self.message_where = message_where

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        condition = Condition.parse(step[head], step.loc(head, True), head, parser)
        kind = "ReasoningFailure"
        if "failure" in step:
            kind = parser.string(step["failure"], step.loc("failure", True), "failure") or kind
        if "message" in step:
            parser.string(step["message"], step.loc("message", True), "message")
        if condition is None:
            return None
        return cls(head, step.loc(head), condition, kind, step.get("message"), step.loc("failure", True),
                   step.loc("message", True))

    def check(self, v: Validator) -> None:
        self.condition.check(v)
        v.failure_type(self.kind, self.kind_where, "failure")
        if self.message is not None:
            v.refs(self.message, self.message_where)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        if not self.condition.evaluate(ex, tn):
            message = (display(ex.evaluate(self.message)) if self.message is not None
                       else f"assertion failed: {self.condition.text()} does not hold")
            raise _failure_type(self.kind)(message)
        return True


# -- log, set, wait -------------------------------------------------------------------------------------------------
class _ValueStep(Node):
    """A leaf step whose head holds one value, $references allowed: log's message, wait's seconds."""

    LEAF = True

    def __init__(self, head: str, where: Location, value: Any, value_where: Location) -> None:
        super().__init__(head, where)
        self.value, self.value_where = value, value_where

    def check(self, v: Validator) -> None:
        v.refs(self.value, self.value_where)


@node_type("log")
class LogStep(_ValueStep):
    DOC = "write a message ($variables are filled in) to the trace and the console"

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        return cls(head, step.loc(head), plain(step[head]), step.loc(head, True))

    def execute(self, ex: Runtime, tn: Record) -> Any:
        message = display(ex.evaluate(self.value))
        tn.info["message"] = message
        ex.log(tn, message)
        return None


@node_type("set")
class SetStep(Node):
    LEAF = True
    KEYS = ("scope",)
    DOC = "bind variables to values (`scope: plan` binds them beyond the branch of a concurrent step)"

    def __init__(self, head: str, where: Location, values: LMap) -> None:
        super().__init__(head, where)
        self.values = values

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        values = _mapping(step[head], step.loc(head, True), head, parser, "variables")
        if values is None:
            return None
        for name in values:
            parser.identifier(name, values.loc(name), head)
        return cls(head, step.loc(head), values)

    def bindings(self) -> list[tuple[str, Location]]:
        return [*super().bindings(), *((str(name), self.values.loc(name)) for name in self.values)]

    def check(self, v: Validator) -> None:
        v.refs(self.values, self.values.where)
        for name in self.values:
            v.define(str(name), self.values.loc(name))

    def execute(self, ex: Runtime, tn: Record) -> Any:
        values = {name: ex.evaluate(value) for name, value in self.values.items()}
        problem = size_problem(values)  # the work of one set: its values together, recorded in the trace
        if problem is not None:
            raise LimitExceeded(problem, tn.path)
        frame = ex.frame.binder(self.scope)
        for name, value in values.items():
            frame.bind(name, value)
        tn.info["bound"] = jsonable(values)
        return None


def _seconds_problem(seconds: Any) -> str | None:
    """Why a value cannot be waited for, or None: a finite number of seconds from 0 to MAX_WAIT."""
    if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or not math.isfinite(seconds) \
            or seconds < 0:
        return f"expected a number of seconds (0 or more), got {describe(jsonable(seconds))}"
    if seconds > MAX_WAIT:
        return f"at most {MAX_WAIT:g} seconds (one day) can be waited for, got {seconds:g}"
    return None


@node_type("wait")
class WaitStep(_ValueStep):
    DOC = "sleep for some seconds (other branches go on; cancellation wakes it at once)"

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        seconds = step[head]
        if not is_reference(seconds) and _seconds_problem(seconds):
            parser.error(_seconds_problem(seconds) or "", step.loc(head, True), key=head)
            return None
        return cls(head, step.loc(head), seconds, step.loc(head, True))

    def check(self, v: Validator) -> None:
        super().check(v)
        if is_reference(self.value):  # a plan parameter's value (-p, else its default) is known before the run
            for value in v.possible(self.value) or []:
                problem = _seconds_problem(value)
                if problem:
                    v.error(f"{problem} ({self.value})", self.value_where, key=self.head)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        seconds = ex.evaluate(self.value)
        problem = _seconds_problem(seconds)
        if problem:
            raise Failure(f"wait: {problem}")
        tn.info["seconds"] = jsonable(seconds)
        ex.sleep(float(seconds))
        return None
