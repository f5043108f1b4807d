"""The Ray backend: the same workers as Ray actors, on an existing cluster or a local one.

    pycram sweep set_table -n 1000 --backend ray --address auto     # a running cluster (`ray start --head`)
    pycram sweep set_table -n 100 --backend ray                      # a local Ray instance for this sweep

Each actor is a `Worker` (one CPU): it keeps its worlds loaded and runs one scenario at a time,
exactly as a local worker process does, so both backends give the same outcomes for the same
seeds. An actor that does not answer within the timeout (plus a grace period) is killed and
replaced, one that dies has its scenario recorded as an error. Ray is an optional extra
(`pip install 'pycram-cli[ray]'`); every machine of the cluster needs pycram installed.
"""
from __future__ import annotations

import importlib
import os
import socket
import time
from collections import deque
from collections.abc import Callable, Iterable
from typing import Any

from ..errors import InputError, Location, setting
from .local import GRACE, STARTUP, SweepError
from .worker import SweepJob, Task, Worker, error_record, timeout_record

MISSING = ("the ray backend needs Ray, an optional extra: pip install 'pycram-cli[ray]' "
           "(in a checkout: pip install '.[ray]')")


START = (f"start one on this machine with Ray's `ray start --head` and give {setting('address')} auto (or the address it "
         f"prints), or leave {setting('address')} out for a Ray of this sweep's own")
#: seconds to wait for a cluster's address to answer before Ray is asked to join it (Ray itself retries for minutes)
CONNECT_TIMEOUT = 5.0
#: seconds between two checks that the cluster is still there while scenarios run (Ray's own wait has no bound)
HEARTBEAT = 5.0


def cluster_alive(ray: Any) -> bool:
    """Whether the cluster answers and has a node alive (a cluster that dropped after connecting does not)."""
    try:
        return any(node.get("Alive") for node in ray.nodes())
    except Exception:  # whatever Ray raises for a lost cluster, it is lost
        return False


def reachable(address: str) -> None:
    """An input error unless something answers at `address` (`HOST:PORT` or `ray://HOST:PORT`; `auto` is Ray's to
    find). Ray retries an address that does not answer for minutes before it gives up."""
    if address == "auto":
        return
    host, _, port = address.removeprefix("ray://").rpartition(":")
    if not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise InputError(f"expected HOST:PORT (or ray://HOST:PORT, or auto), got '{address}'", Location(setting("address")),
                         suggestion=START)
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=CONNECT_TIMEOUT).close()
    except OSError as exc:
        raise InputError(f"cannot join a Ray cluster at '{address}': nothing answers there ({exc.strerror or exc})",
                         Location(setting("address")), suggestion=START) from None


def load_ray() -> Any:
    """The `ray` module, or an input error saying how to install it."""
    try:
        # why: Ray is optional and takes a second to import; only the ray backend needs it
        return importlib.import_module("ray")
    except ImportError:
        raise InputError(MISSING, Location(setting("backend"))) from None


class RayWorker:
    """A sweep worker inside a Ray actor."""

    def __init__(self, job: SweepJob) -> None:
        self.worker = Worker(job)

    def ready(self) -> int:
        return os.getpid()

    def run(self, task: Task) -> tuple[dict[str, Any], bool]:
        """The outcome, and whether this actor should be replaced (see `Worker.retire`)."""
        return self.worker.run(task), self.worker.retire


# long: the scheduling loop: submitting, waiting, timeouts and cancelling share its state
def run(job: SweepJob, tasks: Iterable[Task], workers: int, on_outcome: Callable[[dict[str, Any]], None],
        address: str | None = None, grace: float | None = None) -> None:
    ray = load_ray()
    grace = GRACE if grace is None else grace
    pending = deque(tasks)
    if not pending:
        return
    started_here = not ray.is_initialized()
    if started_here:
        options: dict[str, Any] = {"include_dashboard": False, "log_to_driver": False, "logging_level": "ERROR"}
        if address is not None:
            reachable(address)
            options["address"] = address
        else:
            options["num_cpus"] = workers
        try:
            ray.init(**options)
        except (ConnectionError, TimeoutError) as exc:  # `auto` with no cluster running, a cluster gone
            raise InputError(f"cannot join a Ray cluster at '{address}': {exc}", Location(setting("address")),
                             suggestion=START) from None
    actor_class = ray.remote(num_cpus=1, max_restarts=0)(RayWorker)
    try:
        actors = [actor_class.remote(job) for _ in range(min(workers, len(pending)))]
        try:
            ray.get([a.ready.remote() for a in actors], timeout=STARTUP)
        except Exception as exc:  # an actor that cannot start stops the sweep
            raise SweepError(f"a Ray worker could not start: {exc}") from None
        running: dict[Any, tuple[Any, Task, float]] = {}

        def submit(actor: Any) -> None:
            task = pending.popleft()
            running[actor.run.remote(task)] = (actor, task, time.monotonic())

        for actor in actors:
            if pending:
                submit(actor)
        while running:
            deadlines = [sent + job.timeout + grace for _, _, sent in running.values()] if job.timeout else []
            wait = min(max(0.0, min(deadlines) - time.monotonic()), HEARTBEAT) if deadlines else HEARTBEAT
            done, _ = ray.wait(list(running), num_returns=1, timeout=wait)
            if not done and not cluster_alive(ray):
                where = f"at '{address}'" if address is not None else "of this sweep"
                raise SweepError(f"lost the Ray cluster {where} while {len(running)} scenario(s) ran: what finished "
                                 f"is kept ({setting('resume')} runs the rest)")
            for ref in done:
                actor, task, _ = running.pop(ref)
                try:
                    outcome, retire = ray.get(ref)
                except Exception as exc:  # the actor died: record, replace, go on
                    outcome, retire = error_record(task, f"the Ray worker died: {type(exc).__name__}"), True
                if retire:
                    ray.kill(actor)
                    actor = actor_class.remote(job)
                on_outcome(outcome)
                if pending:
                    submit(actor)
            now = time.monotonic()
            for ref, (actor, task, sent) in list(running.items()):
                if job.timeout and now >= sent + job.timeout + grace:
                    running.pop(ref)
                    ray.kill(actor)
                    on_outcome(timeout_record(task, job.timeout, how=" (the worker was stopped)"))
                    replacement = actor_class.remote(job)
                    if pending:
                        submit(replacement)
    finally:
        if started_here:
            ray.shutdown()
