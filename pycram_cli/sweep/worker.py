"""One worker of a sweep: a scenario prepared once, its worlds kept loaded, one variant after another.

`Worker(job).run(task)` returns the outcome record of one scenario (a JSON-ready dict, one line
of results.jsonl). Plan failures are outcomes like successes; an exception inside the run is
recorded as an `error`, a run past the job's timeout as a `timeout` (the worker interrupts it
itself when it runs on its process's main thread; the pool kills it otherwise), and in both
cases the world it ran on is dropped, so the next scenario starts from a freshly loaded one.
The same worker runs in a local process (`local.py`) and in a Ray actor (`ray_backend.py`).
"""
from __future__ import annotations

import hashlib
import importlib
import importlib.util
import json
import signal
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..jsonable import jsonable
from ..plan.trace import comparable, normalised
from ..scenario import Scenario, prepare
from ..scenario.starts import ImpossibleStart
from ..scenario.variation_files import read_variations
from ..scenario.variations import Variations
from ..scenario.worlds import LoadedWorlds
from .summary import INVALID


@dataclass(frozen=True)
class SweepJob:
    """What every worker needs to run scenarios of a sweep (small and picklable)."""

    plan: str
    vary: str
    world: str | None = None
    timeout: float | None = None
    #: extensions (module names or .py files) to import before the plan is read: they declare designators or queries
    imports: tuple[str, ...] = ()

    def worker(self) -> Worker:
        """What runs in one worker process (local.py): the scenario prepared, its worlds loaded."""
        return Worker(self)

    def timeout_record(self, task: Task, how: str) -> dict[str, Any]:
        return timeout_record(task, self.timeout, how=how)

    def error_record(self, task: Task, message: str) -> dict[str, Any]:
        return error_record(task, message)


@dataclass(frozen=True)
class Task:
    """One run: scenario `index` (drawn from `seed`), with one alternative of `--compare` (or none)."""

    index: int
    seed: int
    alternative: dict[str, Any] | None = None
    alt: int = 0

    @property
    def key(self) -> tuple[int, int]:
        return (self.index, self.alt)


class ScenarioTimeout(BaseException):
    """Raised in the worker's main thread when a scenario runs past the job's timeout (not an Exception:
    nothing inside the plan catches it)."""


def import_extensions(imports: tuple[str, ...]) -> None:
    for name in imports:
        if name.endswith(".py"):
            path = Path(name)
            module_name = f"pycram_extension_{path.stem}"
            if module_name in sys.modules:
                continue
            spec = importlib.util.spec_from_file_location(module_name, path)
            assert spec is not None and spec.loader is not None
            module = importlib.util.module_from_spec(spec)
            sys.modules[module_name] = module
            spec.loader.exec_module(module)
        else:
            importlib.import_module(name)


def trace_digest(trace: dict[str, Any]) -> str:
    """A short fingerprint of a trace without its timings: equal runs have equal digests."""
    text = json.dumps(normalised(comparable(trace)), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def timeout_record(task: Task, timeout: float | None, varied: dict[str, Any] | None = None,
                   how: str = "") -> dict[str, Any]:
    message = f"ran past the {timeout:g} s timeout" if timeout else "ran past the timeout"
    return outcome(task, "timeout", {"type": "Timeout", "message": message + how, "path": None}, varied or {})


def error_record(task: Task, message: str, varied: dict[str, Any] | None = None,
                 path: str | None = None) -> dict[str, Any]:
    return outcome(task, "error", {"type": "InternalError", "message": message, "path": path}, varied or {})


def invalid_record(task: Task, exc: ImpossibleStart, varied: dict[str, Any]) -> dict[str, Any]:
    """A scenario no draw of which could start (see scenario/starts.py): not a run, not counted in the rate."""
    return outcome(task, INVALID, {"type": "ImpossibleStart", "message": str(exc), "path": None},
                   {**varied, "redrawn": exc.reasons})


def outcome(task: Task, status: str, failure: dict[str, Any] | None, varied: dict[str, Any], steps: int = 0,
            digest: str | None = None, duration: float = 0.0, setup: float = 0.0) -> dict[str, Any]:
    record: dict[str, Any] = {"index": task.index, "seed": task.seed}
    if task.alternative is not None:
        record["alternative"] = jsonable(task.alternative)
    record.update({"status": status, "failure": failure, "steps": steps, "trace": digest, "varied": varied,
                   "timing": {"duration": round(duration, 4), "setup": round(setup, 5)}})
    return record


@dataclass
class Worker:
    job: SweepJob
    scenario: Scenario = field(init=False)
    variations: Variations = field(init=False)
    worlds: LoadedWorlds = field(init=False)

    #: set when a run left threads behind (a step that ignored cancellation): the worker should be replaced
    retire: bool = field(init=False, default=False)

    def __post_init__(self) -> None:
        self._threads = threading.active_count()
        import_extensions(self.job.imports)
        self.scenario = prepare(self.job.plan, self.job.world)
        self.variations = read_variations(self.job.vary, self.scenario.world, self.scenario.plan)
        self.worlds = LoadedWorlds(self.scenario)

    def run(self, task: Task) -> dict[str, Any]:
        started = time.perf_counter()
        alarm = bool(self.job.timeout) and threading.current_thread() is threading.main_thread()
        previous = signal.signal(signal.SIGALRM, _alarm) if alarm else None
        variant = None
        try:
            if alarm and self.job.timeout:
                signal.setitimer(signal.ITIMER_REAL, float(self.job.timeout))
            try:
                variant, world = self.worlds.possible(self.variations, task.seed, task.index)
                setup = time.perf_counter() - started
                scenario = self.scenario.varied(variant)
                if task.alternative is not None:  # --compare's value, or a projection's -p values: they win
                    scenario = scenario.with_params(task.alternative)
                result = scenario.run(world)
            finally:
                if alarm:
                    signal.setitimer(signal.ITIMER_REAL, 0)
        except ImpossibleStart as exc:
            return invalid_record(task, exc, self.variations.sample(task.seed, task.index).varied)
        except ScenarioTimeout:
            varied = (variant or self.variations.sample(task.seed, task.index)).varied
            if variant is not None:
                self.worlds.discard(variant)
            self.retire = threading.active_count() > self._threads
            return timeout_record(task, self.job.timeout, varied)
        except Exception as exc:  # recorded, and the sweep goes on
            varied = (variant or self.variations.sample(task.seed, task.index)).varied
            if variant is not None:
                self.worlds.discard(variant)
            else:
                self.worlds.discard()
            self.retire = threading.active_count() > self._threads
            text = f"{type(exc).__name__}: {exc}"
            path = text.split(": ")[1] if type(exc).__name__ == "InternalError" and text.count(": ") >= 2 else None
            return error_record(task, text, varied, path)
        finally:
            if alarm:
                signal.signal(signal.SIGALRM, previous)
        duration = time.perf_counter() - started - setup
        failure = None
        if result.failure is not None:
            failure = {"type": result.failure.type, "path": result.failure.path, "message": result.failure.message}
        return outcome(task, result.status, failure, variant.varied, result.steps, trace_digest(result.trace),
                       duration, setup)

    def close(self) -> None:
        self.worlds.close()


def _alarm(signum: int, frame: Any) -> None:
    raise ScenarioTimeout()
