"""Projection before acting: the plan run N times in prospection, on scenarios a variation file draws;
and a `project` step's runs on the sweep's local workers (`LocalProjector`).

    summary = project(Projection(plan="set_table_actions", vary=None, runs=20))
    summary["rate"], summary["interval"], summary["failures"]

The design's purpose for a fast BulletWorld: simulate what would happen before the robot acts.
`pycram run PLAN --project N [--require P]` calls this before it runs PLAN for real, and refuses
to act when the projected success rate is below P. Each projected run is one scenario of a
sweep (drawn from its own seed, redrawn while it cannot start, on its own copy of the world),
so the real world is never touched and the same seed gives the same projection; the runs go to
the sweep's local worker processes when there are several runs and cores, else run in this
process. The summary is the sweep's (summary.py): success rate with its 95 % interval, the
failures by type and node with an example each.

`LocalProjector` runs a `project` step's projected runs (plan/projecting.py) on LocalPool
workers made by forking this process in the middle of the run: each worker starts with the
world, the plan and the bindings exactly as they are at the step (no loading, nothing sent but
the run's index), runs its share from the step's saved state, and sends back rows, which the
step folds in index order: the same rows, choice and trace as the runs in this process, with
any number of workers. Whichever is faster: the first run runs in this process and is timed,
and the others go to the workers only when they would take longer here than forking the
workers costs plus their share there (`STARTUP_COST`, measured with bench/project.py): quick
runs, or few, stay here. So do all runs where a fork is not safe (a PyBullet window; a worker
process of a sweep, which may not have children).
"""
from __future__ import annotations

import multiprocessing as mp
import os
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..errors import setting
from ..scenario import prepare
from ..scenario.variation_files import read_variations, variation_file
from ..scenario.variations import scenario_seed
from .local import LocalPool
from .summary import summarise
from .worker import SweepJob, Task, Worker

#: below this many runs per worker, starting worker processes costs more than it saves
RUNS_PER_PROCESS = 4
#: seconds it costs a `project` step to fork 2 workers and collect their rows (bench/project.py --modes: 0.1 s
#: under load on 2 cores), against which the time its runs would save on them is weighed
STARTUP_COST = 0.15

Row = dict[str, Any]


@dataclass(frozen=True)
class Projection:
    """What to project: the plan (and world, parameters) as `pycram run` has them, how often and how varied."""

    plan: str
    vary: str | None = None            # default: PLAN.vary.yaml beside the plan
    world: str | None = None
    params: dict[str, Any] = field(default_factory=dict)   # values given on the command line (-p)
    runs: int = 20
    seed: int = 0
    workers: int | None = None         # default: the number of cores


def project(projection: Projection, on_outcome: Callable[[dict[str, Any]], None] | None = None) -> dict[str, Any]:
    """Run the projection; the sweep's summary of its outcomes (plus `runs_total` and `workers`)."""
    scenario = prepare(projection.plan, projection.world)
    vary = variation_file(scenario.plan.path, projection.vary, setting("project"), "projecting the plan")
    read_variations(vary, scenario.world, scenario.plan)  # its problems now, as input errors
    job = SweepJob(str(scenario.plan.path), str(vary), str(scenario.world_path))
    given = dict(projection.params) or None
    tasks = [Task(i, scenario_seed(projection.seed, i), given) for i in range(projection.runs)]
    records: list[dict[str, Any]] = []

    def record(outcome: dict[str, Any]) -> None:
        outcome.pop("alternative", None)  # the given parameters: the same for every run
        records.append(outcome)
        if on_outcome is not None:
            on_outcome(outcome)

    workers = min(projection.workers or os.cpu_count() or 1, max(1, projection.runs // RUNS_PER_PROCESS))
    if workers > 1:
        LocalPool(job, workers).run(tasks, record)
    else:
        worker = Worker(job)
        try:
            for task in tasks:
                record(worker.run(task))
        finally:
            worker.close()
    records.sort(key=lambda r: r["index"])
    meta = {"plan": str(scenario.plan.path), "world": str(scenario.world_path), "vary": str(vary),
            "seed": projection.seed}
    summary = summarise(records, meta)
    summary["workers"] = workers
    return summary


def cores() -> int:
    """The cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def idle_cores() -> int:
    """The cores this process may use that other processes leave free (this one counted as busy on one)."""
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = 0.0
    return max(1, min(cores(), int(cores() - max(0.0, load - 1.0) + 0.5)))


class LocalProjector:
    """A `Projector` (plan/runtime.py): the first run in this process, timed; the rest on forked local workers
    when that is faster by the measure of the first (see `parallel`), else here as well."""

    def __init__(self, workers: int | None = None, startup: float = STARTUP_COST, grace: float | None = None) -> None:
        self.workers = workers
        self.startup = startup  # seconds it costs to fork the workers and collect their rows (bench/project.py)
        self.grace = grace  # past a run's timeout, before its worker is killed (default local.GRACE)
        self.used = 1  # the workers the last step's runs after the first went to (1: this process)

    def usable(self, count: int) -> int:
        """How many workers `count` runs could go to (1: only this process): given, else the cores not busy with
        other work (by the load average: on cores others keep busy, workers only take turns with them)."""
        if count < 2 or "fork" not in mp.get_all_start_methods() or mp.current_process().daemon:
            return 1
        return max(1, min(self.workers or idle_cores(), count))

    def parallel(self, count: int, seconds: float) -> int:
        """The workers for `count` runs of `seconds` each: more than 1 only when they save more than they cost
        (`count * seconds` here against `startup + count * seconds / workers` on them)."""
        workers = self.usable(count)
        return workers if workers > 1 and count * seconds * (1 - 1 / workers) > self.startup else 1

    def runs(self, count: int, one: Callable[[int], Row], lost: Callable[[int, str, str], Row],
             check: Callable[[], None], timeout: float | None) -> list[Row]:
        rows: list[Row] = []
        self.used = 1
        if not count:
            return rows
        check()
        began = time.perf_counter()
        rows.append(one(0))
        workers = self.parallel(count - 1, time.perf_counter() - began)
        self.used = workers
        if workers == 1:
            for index in range(1, count):
                check()
                rows.append(one(index))
            return rows
        found: dict[int, Row] = {}

        def record(outcome: dict[str, Any]) -> None:
            found[outcome["index"]] = outcome["row"]

        LocalPool(_ForkedJob(one, lost, timeout), workers, self.grace, start="fork").run(
            [Task(i, i) for i in range(1, count)], record, check)
        return rows + [found[i] for i in range(1, count)]


@dataclass
class _ForkedJob:
    """A `project` step's runs as a LocalPool job: `one(i)` runs in a forked worker (inherited, never pickled)."""

    one: Callable[[int], Row]
    lost: Callable[[int, str, str], Row]
    timeout: float | None

    def worker(self) -> _ForkedWorker:
        return _ForkedWorker(self)

    def timeout_record(self, task: Task, how: str) -> dict[str, Any]:
        limit = f"the {self.timeout:g} s timeout" if self.timeout else "the timeout"
        return {"index": task.index, "row": self.lost(task.index, "timeout", f"ran past {limit}{how}")}

    def error_record(self, task: Task, message: str) -> dict[str, Any]:
        return {"index": task.index, "row": self.lost(task.index, "error", message)}


class _ForkedWorker:
    """One forked worker: the step's runs by index, in the world it was forked with."""

    def __init__(self, job: _ForkedJob) -> None:
        self.job = job
        self.retire = False
        self._threads = threading.active_count()

    def run(self, task: Task) -> dict[str, Any]:
        try:
            outcome = {"index": task.index, "row": self.job.one(task.index)}
        except BaseException as exc:  # noqa: BLE001 - whatever escapes a run is that run's internal error
            outcome = self.job.error_record(task, f"{type(exc).__name__}: {exc}")
        self.retire = threading.active_count() > self._threads
        return outcome

    def close(self) -> None:
        pass
