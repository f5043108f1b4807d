"""What a node may ask of the run that executes it: the contract between the two floors.

Node classes (syntax, composites, decorators, leaves) belong to the language floor and
never import the running floor (executor, scheduler, trace). `Node.execute(ex, tn)` gets
the runtime through its two arguments only, and this module says what they offer:

- `ex` is a `Runtime` (implemented by `executor.Exec`): the variables, the cancellation
  token, the world, and running child steps in sequence, as a group, or concurrently;
- `tn` is a `Record` (implemented by `trace.TraceNode`): the node's entry in the trace.

A concurrent composite hands itself to `Runtime.concurrent` as a `Decider`: the runtime
runs the branches, the composite decides (see composites.py). `Cancelled` and
`close_pending` are shared by both floors and live here, below both.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import AbstractContextManager
from typing import TYPE_CHECKING, Any, Protocol

from ..errors import Location
from ..status import Status
from ..world import BulletWorld
from .context import Frame

if TYPE_CHECKING:  # for annotations only: syntax imports this module
    from .syntax import Node, Plan


class Cancelled(BaseException):
    """A branch was cancelled. Not a Failure: no handler or retry catches it."""


class LimitExceeded(Exception):
    """A run went beyond one of pycram's limits (nested calls or steps, recorded steps, threads; see limits.py).

    Not a Failure: no handler or retry catches it (it would only hit the limit again); the run
    stops and fails with it, naming the step where it happened (`path`).
    """

    def __init__(self, message: str, path: str) -> None:
        super().__init__(message)
        self.message = message
        self.path = path

    @property
    def type_name(self) -> str:
        return "LimitExceeded"


class Record(Protocol):
    """`tn`: a node's entry in the trace of the run."""

    path: str    # `body/1:for_each/item 0/0:call fetch`
    status: Status  # pending, running, succeeded, failed, cancelled, skipped
    info: dict[str, Any]  # what the node records (its designator, query answer, bound values...)
    failure: Any  # the failure the node ended with (a FailureRecord), or None

    def child(self, label: str, type: str, source: Location | None = None) -> Record:
        """A new (pending) entry below this one (raises LimitExceeded beyond the run's limits)."""
        ...

    def detached(self, label: str, type: str, source: Location | None = None) -> Record:
        """A new entry named like a child of this one but in no tree (with a step budget of its own): a projected
        run's, which the `project` step folds into the tree afterwards."""
        ...

    def to_dict(self, timing: bool = True) -> dict[str, Any]:
        """The entry and everything below it as the trace's JSON has them."""
        ...

    def walk(self) -> Iterator[Record]:
        """This entry and every entry below it."""
        ...

    def summarise(self, child: Record, label: str) -> Record | None:
        """Fold `child` (a failed attempt, with its subtree) into the summary entry `label`, made at its place;
        the summary entry (None when `child` was not below this one).

        Keeps the trace bounded when a step repeats without end (see `retry`)."""
        ...


class Token(Protocol):
    """A thread's cancellation token."""

    def check(self) -> None:
        """Raise Cancelled when the thread's branch has been cancelled."""
        ...

    @property
    def cancelled(self) -> bool: ...

    @property
    def reason(self) -> str:
        """Why it was cancelled ("" while it is not)."""
        ...

    def cancel(self, reason: str = "") -> None:
        """Cancel it and every token made from it."""
        ...

    def child(self) -> Token:
        """A token cancelled with this one, and also on its own."""
        ...


class Decider(Protocol):
    """A concurrent composite (par, pursue, try_all): when it is decided and what it then yields."""

    head: str

    def decides(self, status: Status) -> bool: ...

    def outcome(self, results: list[tuple[Status, Any]], decided: int | None, children: Sequence[Record]) -> Any: ...


Row = dict[str, Any]


class Projector(Protocol):
    """Runs the projected runs of a `project` step: here, one after another, or on worker processes.

    The step hands over `count` runs as functions of their index; whoever runs them (the default,
    in this process; sweep/projection.py's `LocalProjector`, on the sweep's local workers) gives
    back each run's row in index order, whatever order they finished in.
    """

    def runs(self, count: int, one: Callable[[int], Row], lost: Callable[[int, str, str], Row],
             check: Callable[[], None], timeout: float | None) -> list[Row]:
        """`[one(i) for i in range(count)]`, each `one(i)` starting from the same saved state. `lost(i, status,
        message)`: the row of a run that gave no answer (its worker died, or it ran `timeout` s and a grace period
        past it). `check()` raises (Cancelled) when the run is stopped: called at least every 0.1 s."""
        ...


class Runtime(Protocol):
    """`ex`: one thread's view of the run executing a node."""

    @property
    def frame(self) -> Frame:
        """The variables of the current plan invocation, or of the branch of a concurrent step this thread runs
        (`as`, `set` and `for_each` bind here; `frame.binder("plan")` is the invocation's own)."""
        ...

    @property
    def globals(self) -> Frame:
        """The plan's parameters (the parent of every invocation's frame)."""
        ...

    @property
    def plan(self) -> Plan: ...

    @property
    def world(self) -> BulletWorld: ...

    @property
    def token(self) -> Token: ...

    @property
    def depth(self) -> int:
        """How many subplan calls deep this invocation is."""
        ...

    def evaluate(self, value: Any) -> Any:
        """A plan value with its `$references` looked up in the current frame."""
        ...

    def derive(self, *, frame: Frame | None = None, depth: int | None = None) -> Runtime:
        """The same thread with another frame or call depth (a subplan call)."""
        ...

    @property
    def projector(self) -> Projector | None:
        """Who runs a `project` step's projected runs (None: the step runs them here, one after another)."""
        ...

    def projected(self, token: Token, record: bool = False) -> Runtime:
        """A runtime for one projected run: a frame of its own below this one, cancelled by `token` (a child of
        this thread's), and nothing of it seen by the run's observers (live views, the replay) or its scheduler;
        with `record`, its own replay is recorded (see `replay_record`)."""
        ...

    def replay_record(self) -> dict[str, Any] | None:
        """What a projected runtime made with `record` recorded (plan/replay.py's record), or None."""
        ...

    def keep_replay(self, tn: Record, name: str, run: int, replay: dict[str, Any]) -> None:
        """Hand a projected run's replay to the run's observers (the replay record keeps it, bounded)."""
        ...

    def world_action(self) -> AbstractContextManager[None]:
        """Around anything that touches the world: cancellation check, world lock."""
        ...

    def sleep(self, seconds: float) -> None:
        """Sleep, giving the turn to other branches; cancellable at once."""
        ...

    def log(self, tn: Record, message: str) -> None:
        """Show a message (the trace has it in `tn.info` already)."""
        ...

    def fold(self, tn: Record, child: Record, label: str) -> None:
        """`tn.summarise(child, label)`, and tell the run's observers (the replay record folds the same steps)."""
        ...

    def step(self, node: Node, tn: Record) -> Any:
        """Run one child step, recording its status, bound value and failure in `tn`."""
        ...

    def prepare(self, nodes: list[Node], tn: Record) -> Sequence[Record]:
        """Pending trace entries for child steps, labelled `index:label`."""
        ...

    def seq(self, nodes: list[Node], tn: Record) -> Any:
        """Child steps one after another (entries under `tn`); the value is the last one's."""
        ...

    def run_group(self, nodes: list[Node], tn: Record) -> Any:
        """Child steps in sequence under `tn` as a running entry of its own (an attempt, a branch, a handler)."""
        ...

    def concurrent(self, nodes: list[Node], tn: Record, composite: Decider) -> Any:
        """Child steps at once, each in a thread of its own; `composite` decides the outcome."""
        ...


def close_pending(children: Iterable[Record], status: Status) -> None:
    """Steps that never started: `skipped` after a failure or success, `cancelled` after a cancellation."""
    for child in children:
        if child.status == Status.PENDING:
            child.status = status
