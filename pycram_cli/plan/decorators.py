"""Nodes that wrap steps: retry, try/catch, if, unless, for_each.

    - retry: 2                       run `body`; on a failure of a type in `on` (default: any), run
      on: [PerceptionFailure]        `recover` and run `body` again, at most 2 more times (CRAM's
      recover: [steps]               retry count: 3 attempts in all); other failures, and the last
      body: [steps]                  one, propagate
    - try: [steps]                   run the steps; a failure is handled by the first `catch` entry
      catch:                         whose type it is (in order; `Failure` catches all). The handler
        PerceptionFailure: [steps]   sees `$failure` (.type, .message, .path); `fail: $failure`
        Failure: [steps]             re-raises it
    - if: condition                  `then` when the condition holds, else `else` (optional)
      then: [steps]
      else: [steps]
    - unless: condition              `then` when the condition does not hold, else `else`
      then: [steps]
    - for_each: [milk, cereal]       run `do` for each item (a list or a $variable), bound to `as`
      as: item
      do: [steps]
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..errors import Location
from ..failures import Failure, failure_class
from ..limits import MAX_RETRIES, RETRY_KEPT
from ..schema import describe
from ..yamlsource import LList, LMap
from .context import REFERENCE, FailureInfo, jsonable
from .leaves import Condition
from .runtime import Record, Runtime
from .syntax import Node, Parser, node_type, plain

if TYPE_CHECKING:  # for annotations only: validate imports syntax, which the node classes extend
    from .validate import Validator


def _matches(error: Failure, types: list[str]) -> bool:
    return any((cls := failure_class(name)) is not None and isinstance(error, cls) for name in types)


@node_type("retry")
class Retry(Node):
    KEYS = ("on", "recover", "body")
    REQUIRED = ("body",)
    BINDS = True
    DOC = "run the body again after a failure of the given types, up to N more times, recovering in between"

    def __init__(self, head: str, where: Location, count: Any, on: list[tuple[str, Location]],
                 recover: list[Node], body: list[Node], count_where: Location) -> None:
        super().__init__(head, where)
        self.count, self.on, self.recover, self.body, self.count_where = count, on, recover, body, count_where

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        count = step[head]
        if isinstance(count, bool) or not isinstance(count, int) or count < 0:
            parser.error(f"expected how many times to retry (a whole number, 0 or more), got {describe(count)}",
                         step.loc(head, True), key=head)
            count = 0
        elif count > MAX_RETRIES:
            parser.error(f"at most {MAX_RETRIES} retries, got {count}", step.loc(head, True), key=head)
            count = 0
        on = parser.names(step["on"], step.loc("on", True), "on") if "on" in step else []
        recover = parser.steps(step["recover"], step.loc("recover", True), "recover") if "recover" in step else []
        body = parser.steps(step["body"], step.loc("body", True), "body") if "body" in step else []
        return cls(head, step.loc(head), count, on, recover, body, step.loc(head, True))

    def parts(self) -> list[tuple[str, list[Node]]]:
        return [("body", self.body), ("recover", self.recover)]

    def check(self, v: Validator) -> None:
        for name, where in self.on:
            v.failure_type(name, where, "on")
        v.check_steps(self.body)
        v.check_steps(self.recover)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        types = [name for name, _ in self.on] or ["Failure"]
        tn.info["retries"] = 0
        attempt = 1
        groups: dict[int, list[Record]] = {}  # the trace nodes of each attempt (and its recovery)
        while True:
            child = tn.child(f"attempt {attempt}", "attempt", self.where)
            groups[attempt] = [child]
            try:
                return _run_part(ex, self.body, child)
            except Failure as exc:
                if attempt > self.count or not _matches(exc, types):
                    raise
            ex.token.check()
            if self.recover:
                groups[attempt].append(tn.child(f"recover {attempt}", "recover", self.where))
                _run_part(ex, self.recover, groups[attempt][-1])
            # the trace keeps the first and the last RETRY_KEPT attempts; those between are counted in a summary
            old = attempt - RETRY_KEPT
            if old > RETRY_KEPT:
                for record in groups.pop(old):
                    ex.fold(tn, record, "folded attempts")
            attempt += 1
            tn.info["retries"] = attempt - 1


def _run_part(ex: Runtime, steps: list[Node], tn: Record) -> Any:
    """A named group of steps (an attempt, a branch, a handler) recorded as one trace node."""
    return ex.run_group(steps, tn)


@node_type("try")
class Try(Node):
    KEYS = ("catch",)
    REQUIRED = ("catch",)
    BINDS = True
    DOC = "run steps; handle failures by type with the first matching `catch` entry"

    def __init__(self, head: str, where: Location, body: list[Node],
                 handlers: list[tuple[str, Location, list[Node]]]) -> None:
        super().__init__(head, where)
        self.body, self.handlers = body, handlers

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        body = parser.steps(step[head], step.loc(head, True), head)
        handlers = (parser.named_steps(step, "catch", "failure type to steps",
                                       "e.g. catch: {PerceptionFailure: [{log: not seen}]}") if "catch" in step else [])
        return cls(head, step.loc(head), body, handlers)

    def parts(self) -> list[tuple[str, list[Node]]]:
        return [("try", self.body), *((f"catch {name}", steps) for name, _, steps in self.handlers)]

    def bindings(self) -> list[tuple[str, Location]]:
        found = super().bindings()
        if self.handlers:
            found.append(("failure", self.handlers[0][1]))
        return found

    def check(self, v: Validator) -> None:
        v.check_steps(self.body)
        for name, where, steps in self.handlers:
            v.failure_type(name, where, "catch")
            v.define("failure", where)
            v.check_steps(steps)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        try:
            return _run_part(ex, self.body, tn.child("try", "try", self.where))
        except Failure as exc:
            for name, where, steps in self.handlers:
                if _matches(exc, [name]):
                    info = FailureInfo(exc.type_name, exc.message, getattr(exc, "plan_path", None) or tn.path, exc)
                    ex.frame.bind("failure", info)
                    child = tn.child(f"catch {name}", "catch", where)
                    child.info["caught"] = jsonable(info)
                    return _run_part(ex, steps, child)
            raise


class Conditional(Node):
    KEYS = ("then", "else")
    REQUIRED = ("then",)
    BINDS = True
    NEGATE = False

    def __init__(self, head: str, where: Location, condition: Condition, then: list[Node],
                 otherwise: list[Node]) -> None:
        super().__init__(head, where)
        self.condition, self.then, self.otherwise = condition, then, otherwise

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        condition = Condition.parse(step[head], step.loc(head, True), head, parser)
        then = parser.steps(step["then"], step.loc("then", True), "then") if "then" in step else []
        otherwise = parser.steps(step["else"], step.loc("else", True), "else") if "else" in step else []
        return None if condition is None else cls(head, step.loc(head), condition, then, otherwise)

    def parts(self) -> list[tuple[str, list[Node]]]:
        return [("then", self.then), ("else", self.otherwise)]

    def check(self, v: Validator) -> None:
        self.condition.check(v)
        v.check_steps(self.then)
        v.check_steps(self.otherwise)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        holds = self.condition.evaluate(ex, tn)
        branch = "then" if holds != self.NEGATE else "else"
        steps = self.then if branch == "then" else self.otherwise
        if not steps:
            return None
        return _run_part(ex, steps, tn.child(branch, branch, self.where))


@node_type("if")
class If(Conditional):
    DOC = "run `then` when the condition holds, otherwise `else`"


@node_type("unless")
class Unless(Conditional):
    DOC = "run `then` when the condition does not hold, otherwise `else`"
    NEGATE = True


@node_type("for_each")
class ForEach(Node):
    KEYS = ("as", "do")
    REQUIRED = ("as", "do")
    DOC = "run `do` once for each item of a list, the item bound to the `as` name"

    def __init__(self, head: str, where: Location, items: Any, items_where: Location, var: str | None,
                 var_where: Location, body: list[Node]) -> None:
        super().__init__(head, where)
        self.items, self.items_where, self.var, self.var_where, self.body = items, items_where, var, var_where, body

    @classmethod
    def allowed_keys(cls, head: str) -> tuple[str, ...]:
        return cls.KEYS

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        items = step[head]
        if not isinstance(items, LList) and not (isinstance(items, str) and REFERENCE.match(items)):
            parser.error(f"expected a list or a $variable holding one, got {describe(items)}", step.loc(head, True),
                         key=head)
            items = []
        var = parser.identifier(step["as"], step.loc("as", True), "as") if "as" in step else None
        body = parser.steps(step["do"], step.loc("do", True), "do") if "do" in step else []
        return cls(head, step.loc(head), plain(items), step.loc(head, True), var, step.loc("as", True), body)

    def parts(self) -> list[tuple[str, list[Node]]]:
        return [("do", self.body)]

    def bindings(self) -> list[tuple[str, Location]]:
        found = super().bindings()
        if self.var:
            found.append((self.var, self.var_where))
        return found

    def check(self, v: Validator) -> None:
        v.refs(self.items, self.items_where)
        if self.var:  # over a literal list, the variable's values are known before the run
            v.define(self.var, self.var_where, self.items if isinstance(self.items, list) else None)
        v.check_steps(self.body)

    def execute(self, ex: Runtime, tn: Record) -> Any:
        items = ex.evaluate(self.items)
        if isinstance(items, (str, dict)) or not hasattr(items, "__iter__"):
            raise Failure(f"for_each: expected a list, got {describe(jsonable(items))}")
        items = list(items)
        tn.info["items"] = jsonable(items)
        for index, item in enumerate(items):
            if self.var:
                ex.frame.bind(self.var, item)
            child = tn.child(f"item {index}", "item", self.where)
            child.info["item"] = jsonable(item)
            _run_part(ex, self.body, child)
        return None
