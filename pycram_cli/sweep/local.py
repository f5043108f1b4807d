"""Local worker processes: each keeps its worlds loaded and runs one scenario at a time.

The parent hands out tasks over a pipe per worker and takes outcomes back as they finish. A
worker that does not answer within the timeout (plus a grace period for it to interrupt the
scenario itself) is killed, the scenario recorded as a timeout, and a new worker started; one
that dies (a crash in the simulator) has its scenario recorded as an error and is replaced
the same way. Workers ignore Ctrl-C: the parent stops them (`run`'s `check` is called at least
every POLL seconds, and whatever it raises stops every worker at once).

A job says what its workers are (`job.worker()`, made in the worker process) and what a task
that gave no answer is recorded as (`timeout_record`, `error_record`): a sweep's `SweepJob`
loads its worlds in each worker (processes started by `spawn`); a `project` step's job
(projection.py) is inherited by workers made by `fork`, world and run as they are.
"""
from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import signal
import time
from collections import deque
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from typing import Any, Protocol

from ..errors import PycramError
from .worker import Task

#: seconds a worker gets past the timeout to interrupt the scenario itself before it is killed
GRACE = 5.0
#: seconds a new worker may take to read the plan and load its world
STARTUP = 120.0
#: seconds between two calls of `run`'s `check`
POLL = 0.05


class TaskRunner(Protocol):
    """What runs in a worker process: one task's outcome after another."""

    retire: bool  # set when a task left threads behind: the pool starts a new worker

    def run(self, task: Task) -> dict[str, Any]: ...

    def close(self) -> None: ...


class Job(Protocol):
    """What a pool's workers run (see the module docstring)."""

    @property
    def timeout(self) -> float | None: ...

    def worker(self) -> TaskRunner: ...

    def timeout_record(self, task: Task, how: str) -> dict[str, Any]: ...

    def error_record(self, task: Task, message: str) -> dict[str, Any]: ...


class SweepError(PycramError):
    """The sweep cannot go on (a worker cannot even start)."""


def _worker_main(conn: Connection, job: Job) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # a forked worker inherits the command's handler: not its own
    try:
        worker = job.worker()
    except BaseException as exc:  # told to the parent, which stops the sweep
        conn.send(("fatal", f"{type(exc).__name__}: {exc}"))
        return
    conn.send(("ready", os.getpid()))
    while True:
        try:
            task = conn.recv()
        except (EOFError, KeyboardInterrupt):
            break
        if task is None:
            break
        outcome = worker.run(task)
        conn.send(("done", (outcome, worker.retire)))
        if worker.retire:  # a step still runs in a thread of its own: the parent starts a new worker
            break
    worker.close()


@dataclass
class _Slot:
    process: Any
    conn: Connection
    started_at: float
    ready: bool = False
    task: Task | None = None
    sent_at: float = 0.0


class LocalPool:
    """`workers` processes running the job's scenarios; `run(tasks, on_outcome)` returns when all are done.
    `start`: how worker processes are made, `spawn` (fresh) or `fork` (copies of this one)."""

    def __init__(self, job: Job, workers: int, grace: float | None = None, start: str = "spawn") -> None:
        self.job = job
        self.workers = max(1, workers)
        self.grace = GRACE if grace is None else grace
        self.context: Any = mp.get_context(start)  # (typeshed's BaseContext lacks Process; each start method has it)
        self.slots: list[_Slot] = []
        self.started = 0  # processes started, replacements included

    def _spawn(self) -> _Slot:
        parent, child = self.context.Pipe()
        process = self.context.Process(target=_worker_main, args=(child, self.job), daemon=True,
                                       name="pycram sweep worker")
        process.start()
        child.close()
        self.started += 1
        return _Slot(process, parent, time.monotonic())

    def _replace(self, slot: _Slot) -> None:
        _stop(slot, kill=True)
        self.slots[self.slots.index(slot)] = self._spawn()

    def run(self, tasks: Iterable[Task], on_outcome: Callable[[dict[str, Any]], None],
            check: Callable[[], None] | None = None) -> None:
        """Every task's outcome to `on_outcome` as it comes; `check()` raising stops the workers at once."""
        pending = deque(tasks)
        if not pending:
            return
        self.slots = [self._spawn() for _ in range(min(self.workers, len(pending)))]
        stopped = True
        try:
            while pending or any(s.task is not None for s in self.slots):
                for slot in self.slots:
                    if slot.ready and slot.task is None and pending:
                        slot.task, slot.sent_at = pending.popleft(), time.monotonic()
                        slot.conn.send(slot.task)
                now = time.monotonic()
                deadlines = [self._deadline(s) for s in self.slots]
                soonest = min(deadlines, default=float("inf"))
                timeout = None if soonest == float("inf") else max(0.0, soonest - now)
                if check is not None:
                    check()
                    timeout = POLL if timeout is None else min(timeout, POLL)
                ready = wait([s.conn for s in self.slots] + [s.process.sentinel for s in self.slots], timeout)
                for slot in list(self.slots):
                    if slot.conn in ready:
                        self._receive(slot, on_outcome)
                    elif slot.process.sentinel in ready:
                        self._died(slot, on_outcome)
                now = time.monotonic()
                for slot in list(self.slots):
                    if now >= self._deadline(slot):
                        if slot.task is None:
                            raise SweepError(f"a sweep worker did not start within {STARTUP:g} s")
                        on_outcome(self.job.timeout_record(slot.task, " (the worker was stopped)"))
                        self._replace(slot)
            stopped = False
        finally:
            self.close(now=stopped)

    def _deadline(self, slot: _Slot) -> float:
        if not slot.ready:
            return slot.started_at + STARTUP
        if slot.task is None or not self.job.timeout:
            return float("inf")
        return slot.sent_at + self.job.timeout + self.grace

    def _receive(self, slot: _Slot, on_outcome: Callable[[dict[str, Any]], None]) -> None:
        try:
            kind, payload = slot.conn.recv()
        except (EOFError, OSError):
            self._died(slot, on_outcome)
            return
        if kind == "fatal":
            raise SweepError(f"a sweep worker could not start: {payload}")
        if kind == "ready":
            slot.ready = True
            return
        slot.task = None
        outcome, retire = payload
        on_outcome(outcome)
        if retire:  # it exits: a step of its last scenario still runs in a thread
            self._replace(slot)

    def _died(self, slot: _Slot, on_outcome: Callable[[dict[str, Any]], None]) -> None:
        slot.process.join(1.0)
        code = slot.process.exitcode
        if not slot.ready:
            raise SweepError(f"a sweep worker exited before it was ready (exit code {code})")
        if slot.task is not None:  # it died running a scenario (an idle one has none to record)
            on_outcome(self.job.error_record(slot.task, f"the worker process died (exit code {code})"))
        self._replace(slot)

    def close(self, now: bool = False) -> None:
        """Stop the workers: idle ones are asked to exit (`now`: every one is killed at once)."""
        for slot in self.slots:
            if slot.process.is_alive() and slot.task is None and not now:
                with contextlib.suppress(OSError, BrokenPipeError):
                    slot.conn.send(None)
        deadline = time.monotonic() + 5.0
        for slot in self.slots:
            slot.process.join(max(0.0, deadline - time.monotonic()) if slot.task is None and not now else 0.0)
            _stop(slot, kill=True)
        self.slots = []


def _stop(slot: _Slot, kill: bool) -> None:
    if slot.process.is_alive():
        slot.process.kill() if kill else slot.process.terminate()
        slot.process.join(5.0)
    slot.conn.close()
