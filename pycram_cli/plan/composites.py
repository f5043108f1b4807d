"""Composite nodes with CPL's semantics: seq, par, pursue, try_all, try_in_order.

    - seq: [steps]            one after another; the first failure fails it (the rest are skipped)
    - par: [steps]            all at once; succeeds when all succeed; the first failure cancels the others
    - pursue: [steps]         all at once; the first to end (succeeded or failed) decides, the rest are cancelled
    - try_all: [steps]        all at once; the first success decides and cancels the rest; fails with every
                              failure when all failed
    - try_in_order: [steps]   one after another until one succeeds; fails with every failure when none does

Each takes `as: name` to bind its value: seq and try_in_order the value of the last step run,
par the list of its steps' values, pursue and try_all the value of the deciding step.

The concurrent composites own their policy (as py_trees' `Parallel` does): `decides(status)`
says whether a branch ending so decides the node (its siblings are then cancelled), and
`outcome(...)` turns the branches' results into the node's value or failure. The executor
only runs the branches and asks.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from ..failures import Failure
from ..limits import MAX_BRANCHES
from ..status import Status
from ..yamlsource import LMap
from .runtime import Cancelled, Record, Runtime, close_pending
from .syntax import Node, Parser, node_type

if TYPE_CHECKING:
    from .validate import Validator


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

    def execute(self, ex: Runtime, tn: Record) -> Any:
        return ex.seq(self.steps, tn)


class Concurrent(Composite):
    """Steps run at once, each in a thread of its own; the first branch whose end `decides` decides.

    Each branch has its own bindings (CPL): it reads what is bound around the step, and what it
    binds stays in the branch, unless bound with `scope: plan`.
    """

    def check(self, validator: Validator) -> None:
        validator.check_branches(self.steps)

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node:
        node = super().parse(head, step, parser)
        if isinstance(node, Concurrent) and len(node.steps) > MAX_BRANCHES:
            parser.error(f"'{head}' has {len(node.steps)} branches, more than {MAX_BRANCHES} (the limit)",
                         step.loc(head, True), key=head, suggestion="use for_each for many similar steps")
        return node

    def execute(self, ex: Runtime, tn: Record) -> Any:
        return ex.concurrent(self.steps, tn, self)

    def decides(self, status: Status) -> bool:
        """Whether a branch that ended with `status` ("succeeded" or "failed") decides the node."""
        raise NotImplementedError

    def outcome(self, results: list[tuple[Status, Any]], decided: int | None, children: Sequence[Record]) -> Any:
        """The node's value (or raise its failure) from every branch's (status, value or failure), in order.

        `decided` is the index of the deciding branch, None when no branch decided.
        """
        raise NotImplementedError


@node_type("par")
class Par(Concurrent):
    DOC = "run the steps at once; all must succeed; the first failure cancels the others"

    def decides(self, status: Status) -> bool:
        return status == Status.FAILED

    def outcome(self, results: list[tuple[Status, Any]], decided: int | None, children: Sequence[Record]) -> Any:
        if decided is not None:
            raise results[decided][1]
        return [value for _, value in results]


@node_type("pursue")
class Pursue(Concurrent):
    DOC = "run the steps at once; the first to end decides (success or failure), the others are cancelled"

    def decides(self, status: Status) -> bool:
        return status in (Status.SUCCEEDED, Status.FAILED)

    def outcome(self, results: list[tuple[Status, Any]], decided: int | None, children: Sequence[Record]) -> Any:
        if decided is None:
            raise Cancelled("pursue: every branch was cancelled")
        status, value = results[decided]
        if status == Status.FAILED:
            raise value
        return value


@node_type("try_all")
class TryAll(Concurrent):
    DOC = "run the steps at once; the first success wins and cancels the others; fails only when all failed"

    def decides(self, status: Status) -> bool:
        return status == Status.SUCCEEDED

    def outcome(self, results: list[tuple[Status, Any]], decided: int | None, children: Sequence[Record]) -> Any:
        if decided is not None:
            return results[decided][1]
        failures = [value for status, value in results if status == Status.FAILED]
        raise combined_failure(failures, "try_all", children)


@node_type("try_in_order")
class TryInOrder(Composite):
    DOC = "try the steps one after another until one succeeds; fails only when all failed"

    def execute(self, ex: Runtime, tn: Record) -> Any:
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
            close_pending(children, Status.CANCELLED)
            raise
        finally:
            close_pending(children, Status.SKIPPED)


def combined_failure(failures: list[Failure], what: str, children: Sequence[Record]) -> Failure:
    """One failure for several alternatives that all failed: of their most specific common type."""
    if not failures:
        return Failure(f"{what}: no alternative could run")
    common = type(failures[0])
    while not all(isinstance(f, common) for f in failures):
        common = common.__mro__[1]
        if not issubclass(common, Failure):
            common = Failure
            break
    parts = "; ".join(f"{f.type_name}: {f.message}" for f in failures)
    error = common(f"all {len(failures)} alternatives of {what} failed: {parts}")
    error.failures = failures
    return error
