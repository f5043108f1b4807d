"""Projection before acting: the plan run N times in prospection, on scenarios a variation file draws.

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
"""
from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..errors import setting
from ..scenario import prepare
from ..scenario.variations import read_variations, scenario_seed, variation_file
from .local import LocalPool
from .summary import summarise
from .worker import SweepJob, Task, Worker

#: below this many runs per worker, starting worker processes costs more than it saves
RUNS_PER_PROCESS = 4


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
