"""Composite nodes with CPL's semantics: seq, par, pursue, try_all, try_in_order.

    - seq: [steps]            one after another; the first failure fails it (the rest are skipped)
    - par: [steps]            all at once; succeeds when all succeed; the first failure cancels the others
    - pursue: [steps]         all at once; the first to end (succeeded or failed) decides, the rest are cancelled
    - try_all: [steps]        all at once; the first success decides and cancels the rest; fails with every
                              failure when all failed
    - try_in_order: [steps]   one after another until one succeeds; fails with every failure when none does

Each takes `as: name` to bind its value: seq and try_in_order the value of the last step run,
par the list of its steps' values, pursue and try_all the value of the deciding step.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..failures import Failure
from ..yamlsource import LMap
from .executor import PAR, PURSUE, TRY_ALL, Policy, close_pending, combined_failure
from .runtime import Cancelled
from .syntax import Node, Parser, node_type

if TYPE_CHECKING:
    from .executor import Exec
    from .trace import TraceNode


class Composite(Node):
    BINDS = True

    def __init__(self, head: str, where: Any, steps: list[Node]) -> None:
        super().__init__(head, where)
        self.steps = steps

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node:
        return cls(head, step.loc(head), parser.steps(step[head], step.loc(head, True), head))

    def parts(self) -> list[tuple[str, list[Node]]]:
        return [(self.head, self.steps)]


@node_type("seq")
class Seq(Composite):
    DOC = "run the steps one after another; the first failure fails the sequence"

    def execute(self, ex: "Exec", tn: "TraceNode") -> Any:
        return ex.seq(self.steps, tn)


class Concurrent(Composite):
    POLICY: Policy = PAR

    def execute(self, ex: "Exec", tn: "TraceNode") -> Any:
        return ex.concurrent(self.steps, tn, self.POLICY)


@node_type("par")
class Par(Concurrent):
    DOC = "run the steps at once; all must succeed; the first failure cancels the others"
    POLICY = PAR


@node_type("pursue")
class Pursue(Concurrent):
    DOC = "run the steps at once; the first to end decides (success or failure), the others are cancelled"
    POLICY = PURSUE


@node_type("try_all")
class TryAll(Concurrent):
    DOC = "run the steps at once; the first success wins and cancels the others; fails only when all failed"
    POLICY = TRY_ALL


@node_type("try_in_order")
class TryInOrder(Composite):
    DOC = "try the steps one after another until one succeeds; fails only when all failed"

    def execute(self, ex: "Exec", tn: "TraceNode") -> Any:
        children = ex.prepare(self.steps, tn)
        failures: list[Failure] = []
        try:
            for node, child in zip(self.steps, children):
                try:
                    return ex.step(node, child)
                except Failure as exc:
                    failures.append(exc)
            raise combined_failure(failures, "try_in_order", children)
        except Cancelled:
            close_pending(children, "cancelled")
            raise
        finally:
            close_pending(children, "skipped")
