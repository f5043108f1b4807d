"""Running a validated plan on a world: steps, threads, cancellation and the trace.

`run_plan(plan, world, params)` runs the plan body and returns a `RunResult` with the
status, the failure (if any) and the trace. Each node class knows how to execute itself
(`Node.execute(ex, tn)`); `Exec` is the `ex` it gets (it implements `runtime.Runtime`):
the run, the current variable frame, the cancellation token and scheduler key of its
thread, and helpers to run child steps in sequence (`seq`) or concurrently
(`concurrent`, where the composite decides the outcome). `tn` is a `trace.TraceNode`.
"""
from __future__ import annotations

import contextlib
import copy
import threading
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, cast

from .. import interrupts
from ..failures import Failure, FailureRecord, InternalError
from ..limits import MAX_RUNNING_BRANCHES, MAX_THREADS, MAX_WAIT
from ..robots import description_for
from ..status import Status
from ..world import BulletWorld
from .context import Frame, evaluate, jsonable, size_problem
from .observer import Observer
from .params import bind_params
from .replay import Recorder
from .resources import ResourceAnalysis
from .runtime import Cancelled, Decider, LimitExceeded, Projector, Record, Token, close_pending
from .scheduler import CancelToken, Key, Scheduler
from .syntax import Node, Plan
from .trace import FORMAT, VERSION, TraceNode, final_state


@dataclass
class RunResult:
    status: Status                    # succeeded, failed, interrupted (by a signal) or cancelled
    failure: FailureRecord | None  # reads as the trace's `failure` mapping too
    trace: dict[str, Any]
    duration: float
    value: Any = None
    steps: int = 0
    error: BaseException | None = field(default=None, repr=False)

    @property
    def succeeded(self) -> bool:
        return self.status == Status.SUCCEEDED


class Run:
    """One execution of a plan on a world."""

    def __init__(self, plan: Plan, world: BulletWorld, params: Mapping[str, Any],
                 observer: Observer | None = None, world_name: str | None = None,
                 projector: Projector | None = None) -> None:
        self.plan = plan
        self.projector = projector
        self.world = world
        self.params = dict(params)
        self.observer = observer
        self.world_name = world_name
        self.scheduler = Scheduler()
        self.token = CancelToken(notify=self.scheduler.wake)
        self.resources = ResourceAnalysis(plan, description_for(world.robot) if world.robot is not None else None)
        self.globals = Frame(self.params)
        self.root = TraceNode("body", "seq", plan.where)
        self.t0 = time.perf_counter()
        self._observer_lock = threading.Lock()
        self.threads = 0  # branch threads alive (at most MAX_THREADS)
        self.limit_error: LimitExceeded | None = None
        self.interrupted: str | None = None  # the signal that stopped the run, if one did
        self._threads_lock = threading.Lock()

    def thread_started(self, path: str) -> None:
        with self._threads_lock:
            if self.threads >= MAX_THREADS:
                raise LimitExceeded(f"more than {MAX_THREADS} branches running at once (the limit)", path)
            self.threads += 1

    def thread_ended(self) -> None:
        with self._threads_lock:
            self.threads -= 1

    def stop_for(self, error: LimitExceeded) -> None:
        """A limit was exceeded: the run stops at once (every thread is cancelled) and fails with the first such error."""
        with self._threads_lock:
            if self.limit_error is None:
                self.limit_error = error
        self.token.cancel(f"stopped: {error.message}")

    def now(self) -> float:
        return time.perf_counter() - self.t0

    def notify(self, event: str, node: TraceNode, *args: Any) -> None:
        if self.observer is None:
            return
        method = getattr(self.observer, event)
        with self._observer_lock, contextlib.suppress(Exception):
            method(node, *args)

    def cancel(self, reason: str = "interrupted") -> None:
        self.token.cancel(reason)

    def interrupt(self, signal_name: str = "SIGINT") -> None:
        """Stop the run because of a signal (Ctrl-C): every branch is cancelled; the run ends `interrupted`."""
        self.interrupted = signal_name
        self.token.cancel(f"interrupted by {signal_name}")

    def execute(self) -> RunResult:
        ex = Exec(self, Frame(parent=self.globals), self.token, ())
        status, failure, value = Status.SUCCEEDED, None, None
        error: BaseException | None = None
        try:
            with interrupts.on_signal(self.interrupt):  # Ctrl-C stops the run; its trace is still complete
                value = ex.run_body(self.plan.body, self.root, self.plan.where)
        except Failure as exc:
            status, failure = Status.FAILED, FailureRecord.of(exc, self.root.path)
        except Cancelled as exc:
            status, failure = Status.CANCELLED, FailureRecord("Cancelled", str(exc) or "cancelled", "body")
            error = exc
        except LimitExceeded as exc:
            self.stop_for(exc)
        except InternalError as exc:  # a bug: the run stops; its trace says where, and the error goes on up
            status, failure, error = Status.ERROR, exc.record or _internal_record(exc.__cause__ or exc, "body"), exc
        if self.limit_error is not None:  # the run was stopped by a limit (whatever it then unwound with)
            status, failure, error = Status.FAILED, FailureRecord.of(self.limit_error, self.limit_error.path), None
            self.root.status = Status.FAILED
            _mark(self.root, Status.CANCELLED)
        elif self.interrupted is not None and status != Status.SUCCEEDED:
            status = Status.INTERRUPTED
            if isinstance(error, InternalError):  # what a step raised as the signal came: the signal's doing
                error = None
            failure = FailureRecord("Interrupted", f"interrupted by {self.interrupted}", "body")
            _mark(self.root, Status.CANCELLED)
        duration = self.now()
        trace = {
            "format": FORMAT, "version": VERSION,
            "plan": self.plan.path.name, "world": self.world_name,
            "params": jsonable(self.params),
            "status": str(status), "failure": failure.to_json() if failure is not None else None,
            "root": self.root.to_dict(timing=True),
            "final_state": final_state(self.world),
            "timing": {"duration": duration},
        }
        if status == Status.INTERRUPTED:
            trace["interrupted"] = {"signal": self.interrupted}
        steps = sum(1 for n in self.root.walk() if not n.children and n.status in (Status.SUCCEEDED, Status.FAILED))
        result = RunResult(status, failure, trace, duration, value, steps, error)
        if isinstance(error, InternalError):
            error.result = result
            raise error
        return result


class Exec:
    """The execution context of one thread inside one plan invocation."""

    def __init__(self, run: Run, frame: Frame, token: CancelToken, key: Key, depth: int = 0) -> None:
        self.run = run
        self.frame = frame
        self.token = token
        self.key = key
        self.depth = depth

    @property
    def world(self) -> BulletWorld:
        return self.run.world

    @property
    def plan(self) -> Plan:
        return self.run.plan

    @property
    def globals(self) -> Frame:
        return self.run.globals

    def derive(self, *, frame: Frame | None = None, token: CancelToken | None = None, key: Key | None = None,
               depth: int | None = None) -> Exec:
        return Exec(self.run, frame if frame is not None else self.frame, token if token is not None else self.token,
                    key if key is not None else self.key, depth if depth is not None else self.depth)

    @property
    def projector(self) -> Projector | None:
        return self.run.projector

    def projected(self, token: Token, record: bool = False) -> Exec:
        """A runtime for one projected run (see runtime.Runtime.projected): a quiet copy of the run — no
        observers, a scheduler of its own (nothing else takes turns in a projection; the `project` step holds
        the world), a limit stops only the projection — with a frame of its own below this thread's."""
        run = copy.copy(self.run)
        run.observer = Recorder(self.run.world) if record else None
        run.scheduler = Scheduler()
        run.token = cast(CancelToken, token)
        run.threads, run.limit_error = 0, None
        run._threads_lock, run._observer_lock = threading.Lock(), threading.Lock()
        return Exec(run, Frame(parent=self.frame), cast(CancelToken, token), (), self.depth)

    def replay_record(self) -> dict[str, Any] | None:
        recorder = self.run.observer
        if not isinstance(recorder, Recorder):
            return None
        recorder.close()
        return recorder.record()

    def keep_replay(self, tn: Record, name: str, run: int, replay: dict[str, Any]) -> None:
        self.run.notify("projected", _own(tn), name, run, replay)

    def evaluate(self, value: Any) -> Any:
        """The value with its references looked up; LimitExceeded (at the step evaluating it) when it is too large."""
        result = evaluate(value, self.frame)
        problem = size_problem(result)
        if problem is not None:
            raise LimitExceeded(problem, "")
        return result

    # -- leaves -------------------------------------------------------------------------------
    @contextlib.contextmanager
    def world_action(self) -> Iterator[None]:
        """Around anything that touches the world (designators, queries): cancellation check, world lock."""
        self.token.check()
        with self.run.world.lock:
            yield


    def sleep(self, seconds: float) -> None:
        self.token.check()
        self.run.scheduler.sleep(self.key, self.token, min(max(0.0, seconds), MAX_WAIT))

    def log(self, tn: Record, message: str) -> None:
        self.run.notify("log", _own(tn), message)

    def fold(self, tn: Record, child: Record, label: str) -> None:
        summary = _own(tn).summarise(_own(child), label)
        if summary is not None:
            self.run.notify("folded", summary, _own(child))

    # -- one step ------------------------------------------------------------------------------
    def step(self, node: Node, record: Record) -> Any:
        """Run one node, recording its status, bound value and failure in `record`."""
        tn = _own(record)
        self.token.check()
        if node.LEAF:  # the turn passes between leaves (see scheduler.py)
            self.run.scheduler.before_leaf(self.key, self.token)
        tn.status, tn.started = Status.RUNNING, self.run.now()
        self.run.notify("started", tn)
        try:
            value = node.execute(self, tn)
            if node.bind:
                self.frame.binder(node.scope).bind(node.bind, value)
                tn.info["bound"] = {node.bind: jsonable(value)}
            tn.status = Status.SUCCEEDED
            if node.LEAF:
                self.run.scheduler.leaf_done(self.key)
            return value
        except Failure as exc:
            if getattr(exc, "plan_path", None) is None:
                exc.plan_path = tn.path
            tn.status, tn.failure = Status.FAILED, FailureRecord.of(exc, tn.path)
            raise
        except Cancelled:
            tn.status = Status.CANCELLED
            _mark(tn, Status.CANCELLED)
            raise
        except LimitExceeded as exc:
            tn.status = Status.FAILED
            exc.path = exc.path or tn.path  # a value too large is found where it is evaluated, not knowing the step
            if tn.failure is None:
                tn.failure = FailureRecord.of(exc, exc.path)
            self.run.stop_for(exc)
            raise
        except InternalError:
            tn.status = Status.FAILED
            raise
        except Exception as exc:  # a bug in a node: never leave the trace half written
            tn.status = Status.FAILED
            tn.failure = _internal_record(exc, tn.path)
            raise InternalError(f"{tn.path}: {type(exc).__name__}: {exc}", tn.failure) from exc
        finally:
            tn.duration = self.run.now() - (tn.started or 0.0)
            self.run.notify("finished", tn)

    def prepare(self, nodes: list[Node], tn: Record) -> list[TraceNode]:
        """Trace nodes (pending) for a list of steps, labelled `index:label`."""
        return [_own(tn).child(f"{i}:{node.label()}", node.head, node.where) for i, node in enumerate(nodes)]

    def seq(self, nodes: list[Node], tn: Record) -> Any:
        """Run steps one after another; a failure skips the rest. The value is the last step's."""
        children = self.prepare(nodes, tn)
        value = None
        try:
            for node, child in zip(nodes, children):
                value = self.step(node, child)
        except Cancelled:
            close_pending(children, Status.CANCELLED)
            raise
        finally:
            close_pending(children, Status.SKIPPED)
        return value

    def run_group(self, nodes: list[Node], record: Record) -> Any:
        """Steps run in sequence under one trace node of their own (the body, an attempt, a handler)."""
        tn = _own(record)
        self.token.check()
        tn.status, tn.started = Status.RUNNING, self.run.now()
        self.run.notify("started", tn)
        try:
            value = self.seq(nodes, tn)
            tn.status = Status.SUCCEEDED
            return value
        except Failure as exc:
            tn.status, tn.failure = Status.FAILED, FailureRecord.of(exc, tn.path)
            raise
        except Cancelled:
            tn.status = Status.CANCELLED
            close_pending(tn.children, Status.CANCELLED)
            raise
        except BaseException:
            tn.status = Status.FAILED
            raise
        finally:
            tn.duration = self.run.now() - (tn.started or 0.0)
            self.run.notify("finished", tn)

    def run_body(self, nodes: list[Node], tn: TraceNode, where: Any = None) -> Any:
        """The plan body: a group whose trace node is the root."""
        return self.run_group(nodes, tn)

    # -- concurrency ---------------------------------------------------------------------------
    # long: starting, scheduling and deciding the branches share their state (see the docstring)
    def concurrent(self, nodes: list[Node], tn: Record, composite: Decider) -> Any:
        """Run steps in threads of their own; `composite` (par, pursue, try_all) decides the outcome.

        At most MAX_RUNNING_BRANCHES of them run at once: the others start, in order, as running
        ones end (the scheduler lets them in at the same moment, so traces stay deterministic).
        """
        children = self.prepare(nodes, tn)
        scheduler = self.run.scheduler
        tokens = [self.token.child() for _ in nodes]
        outcome = Outcome(composite, tokens)
        keys = scheduler.spawn(self.key, len(nodes), self.run.resources.waits_for(nodes), MAX_RUNNING_BRANCHES)
        ended = threading.Semaphore(0)  # one release per branch thread that has ended
        waiting = list(range(len(nodes)))  # branches not started yet, in order
        started: list[threading.Thread] = []
        running = 0

        def launch() -> bool:
            """Start the next branch (True), or close it at once when it was cancelled before it started."""
            i = waiting[0]
            if tokens[i].cancelled:
                waiting.pop(0)
                outcome.report(i, (Status.CANCELLED, None))
                scheduler.finish(keys[i])
                return False
            self.run.thread_started(children[i].path)
            waiting.pop(0)
            branch = self.derive(frame=Frame(parent=self.frame, branch=True), token=tokens[i], key=keys[i])  # own bindings
            thread = threading.Thread(target=branch._branch, args=(i, nodes[i], children[i], outcome, ended),
                                      name=f"pycram {children[i].path}", daemon=True)
            try:
                thread.start()
            except BaseException:
                self.run.thread_ended()
                waiting.insert(0, i)
                raise
            started.append(thread)
            return True

        try:
            while True:
                while waiting and running < MAX_RUNNING_BRANCHES:
                    running += launch()
                if not running:
                    break
                ended.acquire()
                running -= 1
            for thread in started:
                thread.join()
        except BaseException:  # interrupted, a thread could not start, a limit: stop every branch
            for token in tokens:
                token.cancel("interrupted")
            for i in waiting:
                outcome.report(i, (Status.CANCELLED, None))
                scheduler.finish(keys[i])
            for thread in started:
                thread.join()
            raise
        for child in children:
            if child.status in (Status.PENDING, Status.RUNNING):
                child.status = Status.CANCELLED
        scheduler.acquire(self.key, self.token)  # may raise Cancelled when this branch was cancelled meanwhile
        return outcome.result(self, children)

    def _branch(self, index: int, node: Node, tn: TraceNode, outcome: Outcome,
                ended: threading.Semaphore | None = None) -> None:
        result: tuple[Status, Any] = (Status.CANCELLED, None)
        error: BaseException | None = None
        try:
            self.run.scheduler.acquire(self.key, self.token)
            result = (Status.SUCCEEDED, self.step(node, tn))
        except Failure as exc:
            result = (Status.FAILED, exc)
        except Cancelled:
            if tn.status == Status.PENDING:
                tn.status = Status.CANCELLED
            result = (Status.CANCELLED, None)
        except BaseException as exc:  # carried to the parent thread
            error = exc
        finally:
            if error is not None:
                outcome.report_error(index, error)
            else:
                outcome.report(index, result)
            self.run.scheduler.finish(self.key)
            self.run.thread_ended()
            if ended is not None:
                ended.release()


def _own(tn: Record) -> TraceNode:
    """The runtime only ever gets back the trace nodes it made: a TraceNode (for the type checker)."""
    return cast(TraceNode, tn)


def _internal_record(exc: BaseException, path: str) -> FailureRecord:
    """The failure record of an internal error raised at `path`."""
    return FailureRecord("InternalError", f"{type(exc).__name__}: {exc}", path)


def _mark(tn: TraceNode, status: Status) -> None:
    """Children still pending or running when their parent was cancelled are cancelled too."""
    for child in tn.children:
        if child.status in (Status.PENDING, Status.RUNNING):
            child.status = status
            _mark(child, status)


# -- outcomes of concurrent nodes ------------------------------------------------------------------
class Outcome:
    """Collects what each branch ended with; the deciding branch cancels its siblings at once."""

    def __init__(self, composite: Decider, tokens: list[CancelToken]) -> None:
        self.composite = composite
        self.tokens = tokens
        self.results: dict[int, tuple[Status, Any]] = {}
        self.errors: dict[int, BaseException] = {}  # branches that raised what is no plan failure (a bug, a limit)
        self.decided: int | None = None
        self._lock = threading.Lock()

    def report(self, index: int, result: tuple[Status, Any]) -> None:
        with self._lock:
            self.results[index] = result
            cancel = self._decides(index, self.composite.decides(result[0]))
        if cancel:
            self._cancel_others(index)

    def report_error(self, index: int, error: BaseException) -> None:
        """A branch that raised what is no plan failure: it decides, and the node re-raises it."""
        with self._lock:
            self.errors[index] = error
            cancel = self._decides(index, True)
        if cancel:
            self._cancel_others(index)

    def _decides(self, index: int, decides: bool) -> bool:
        """Whether branch `index` is the first to decide (under the lock)."""
        if self.decided is None and decides:
            self.decided = index
            return True
        return False

    def _cancel_others(self, index: int) -> None:
        for i, token in enumerate(self.tokens):
            if i != index:
                token.cancel(f"{self.composite.head} decided by branch {index}")

    def result(self, ex: Exec, children: list[TraceNode]) -> Any:
        if self.errors:
            error = self.errors[min(self.errors)]
            if isinstance(error, (InternalError, LimitExceeded)):
                raise error
            raise InternalError(f"{type(error).__name__}: {error}")
        ordered = [self.results.get(i, (Status.CANCELLED, None)) for i in range(len(self.tokens))]
        return self.composite.outcome(ordered, self.decided, children)


def run_plan(plan: Plan, world: BulletWorld, params: Mapping[str, Any] | None = None,
             observer: Observer | None = None, world_name: str | None = None, bound: bool = False,
             projector: Projector | None = None) -> RunResult:
    """Run `plan` on `world` with the given parameters (defaults filled in by `bind_params`, unless `bound`:
    the values were bound already, as a `Scenario` does once). `projector`: who runs `project` steps'
    projected runs (default: the step itself, in this process)."""
    values = dict(params or {}) if bound else bind_params(plan, params or {})
    run = Run(plan, world, values, observer, world_name, projector)
    try:
        return run.execute()
    except KeyboardInterrupt:
        run.cancel("interrupted")
        raise
