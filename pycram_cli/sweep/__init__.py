"""Sweeps: one plan over many varied scenarios, in parallel, with a summary of where it fails.

    sweep = prepare_sweep(SweepSettings("set_table", vary="plans/set_table.vary.yaml", n=200, out=Path("out")))
    summary = run_sweep(sweep, on_outcome=print)      # results in out/results.jsonl, as they finish

The layer above `scenario`: everything is checked once in `prepare_sweep` (plan, world,
variations, `--compare`, the results folder), then scenario i — drawn from its own seed,
`scenario_seed(seed, i)` — runs once per alternative on a worker: a local process
(`local.py`) or a Ray actor (`ray_backend.py`), each keeping its worlds loaded
(`scenario.worlds`). Outcomes depend on the seed alone, never on the worker or the order.

    worker.py        SweepJob, Task, Worker: one scenario's outcome record
    local.py         LocalPool: worker processes (spawned for sweeps, forked for `project` steps), timeouts, crashes
    projection.py    `pycram run --project N`, and LocalProjector: a `project` step's runs on forked workers
    ray_backend.py   the same on a Ray cluster (optional extra: pip install '.[ray]')
    results.py       results.jsonl and sweep.json: append, resume, sorted at the end
    summary.py       success rate and interval, failures by type and node, --compare
    plot.py          the map of outcomes over the varied start positions
"""
from __future__ import annotations

import math
import os
import shlex
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from ..errors import InputError, Location, PycramError, as_list, raise_if_any, setting
from ..jsonable import jsonable
from ..limits import MAX_SCENARIO_TIMEOUT, MAX_SWEEP_RUNS, MAX_WORKERS
from ..paths import plans_dir, worlds_dir
from ..plan import bind_params
from ..plan.syntax import plain
from ..scenario import Scenario, prepare
from ..scenario.variation_files import beside, read_variations, variation_file
from ..scenario.variations import Variations, scenario_seed
from ..yamlsource import load_yaml_text
from . import ray_backend
from .local import LocalPool, SweepError
from .results import ResultsFile, file_digest
from .summary import summarise
from .worker import SweepJob, Task, import_extensions

BACKENDS = ("local", "ray")

__all__ = ["BACKENDS", "PreparedSweep", "SweepError", "SweepSettings", "prepare_sweep", "replay_command",
           "run_sweep"]


@dataclass
class SweepSettings:
    plan: str
    vary: str | None = None
    world: str | None = None
    n: int = 100
    seed: int = 0
    workers: int | None = None        # default: the number of cores
    backend: str = "local"
    address: str | None = None        # Ray: an existing cluster ("auto") or None for a local one
    out: Path = Path("sweep")
    compare: str | None = None        # PARAM=A,B,...
    timeout: float | None = None
    resume: bool = False
    force: bool = False               # start again in a results folder that holds a sweep, replacing its results
    imports: tuple[str, ...] = ()     # extensions every worker imports first


@dataclass
class PreparedSweep:
    settings: SweepSettings
    scenario: Scenario
    variations: Variations
    job: SweepJob
    meta: dict[str, Any]
    alternatives: list[dict[str, Any]] | None
    results: ResultsFile
    tasks: list[Task] = field(default_factory=list)   # what is left to run

    @property
    def total(self) -> int:
        return self.settings.n * len(self.choices)

    @property
    def choices(self) -> list[dict[str, Any] | None]:
        """The alternatives each scenario runs with: [None] when the sweep compares none."""
        return [*self.alternatives] if self.alternatives else [None]


def parse_compare(text: str, scenario: Scenario, variations: Variations) -> tuple[str, list[dict[str, Any]]]:
    """`PARAM=A,B,...` (values read as YAML, like -p) -> the parameter and one {PARAM: value} per alternative."""
    where = Location(setting("compare"))
    name, sep, values = text.partition("=")
    name = name.strip()
    if not sep or not name or not values.strip():
        raise InputError(f"expected PARAM=A,B,..., got '{text}'", where, suggestion=f"e.g. {setting('compare')} arm=left,right")
    try:  # with the limits of every YAML value (nesting, aliases), as -p reads its values
        parsed = plain(load_yaml_text(f"[{values}]", setting("compare")))
    except InputError as exc:
        raise InputError(f"cannot read the values (YAML, separated by commas): {exc.message}", where) from None
    if len(parsed) < 2:
        raise InputError("give at least two alternatives to compare", where, suggestion=f"e.g. {name}=A,B")
    if any(d.name == name for d in variations.params):
        raise InputError(f"'{name}' is drawn by the variation file: compare a parameter it leaves alone", where)
    alternatives = []
    for value in parsed:
        bind_params(scenario.plan, {**scenario.params, name: value}, where=setting("compare"))
        alternatives.append({name: value})
    return name, alternatives


# long: every setting checked before anything opens, all problems collected at once
def prepare_sweep(settings: SweepSettings) -> PreparedSweep:
    """Check everything (every problem together, as InputErrors) and open the results folder."""
    import_extensions(settings.imports)
    errors: list[InputError] = []
    if settings.backend not in BACKENDS:
        errors.append(InputError(f"unknown backend '{settings.backend}'", Location(setting("backend")),
                                 suggestion=f"one of {', '.join(BACKENDS)}"))
    if settings.address is not None and settings.backend != "ray":
        errors.append(InputError(f"joins a Ray cluster: it needs {setting('backend')} ray", Location(setting("address")),
                                 suggestion=f"set {setting('backend')} ray, or leave {setting('address')} out"))
    elif settings.address is not None:
        try:
            ray_backend.reachable(settings.address)  # before the results folder is made
        except InputError as exc:
            errors.append(exc)
    if settings.force and settings.resume:
        errors.append(InputError(f"{setting('force')} starts the sweep again and {setting('resume')} goes on with it: give "
                                 "one of them", Location(setting("force"))))
    if settings.n < 1:
        errors.append(InputError("the number of scenarios must be at least 1", Location(setting("n"))))
    elif settings.n > MAX_SWEEP_RUNS:
        errors.append(InputError(f"at most {MAX_SWEEP_RUNS} scenarios (the limit), got {settings.n}", Location(setting("n")),
                                 suggestion=f"sweep in parts: another {setting('seed')} gives another set of scenarios"))
    if settings.timeout is not None and not (math.isfinite(settings.timeout)
                                             and 0 < settings.timeout <= MAX_SCENARIO_TIMEOUT):
        errors.append(InputError(f"expected a number of seconds above 0 and at most {MAX_SCENARIO_TIMEOUT:g} (one day), "
                                 f"got {settings.timeout}", Location(setting("timeout"))))
    if settings.workers is not None and not 1 <= settings.workers <= MAX_WORKERS:
        errors.append(InputError(f"expected between 1 and {MAX_WORKERS} workers (the limit), got {settings.workers}",
                                 Location(setting("workers"))))
    scenario = prepare(settings.plan, settings.world)
    vary = variation_file(scenario.plan.path, settings.vary, setting("vary"), "a sweep")
    variations: Variations | None = None
    try:
        variations = read_variations(vary, scenario.world, scenario.plan)
    except PycramError as exc:
        errors.extend(as_list(exc))
    alternatives = None
    param = None
    if settings.compare is not None and variations is not None:
        try:
            param, alternatives = parse_compare(settings.compare, scenario, variations)
        except PycramError as exc:
            errors.extend(as_list(exc))
    if alternatives and settings.n <= MAX_SWEEP_RUNS and settings.n * len(alternatives) > MAX_SWEEP_RUNS:
        errors.append(InputError(f"at most {MAX_SWEEP_RUNS} runs (the limit): {settings.n} scenarios x "
                                 f"{len(alternatives)} alternatives are {settings.n * len(alternatives)}",
                                 Location("-n"), suggestion="fewer scenarios or fewer alternatives"))
    raise_if_any(errors)
    assert variations is not None
    meta = {"plan": str(scenario.plan.path), "world": str(scenario.world_path), "vary": str(vary),
            "digests": {"plan": file_digest(scenario.plan.path), "world": file_digest(scenario.world_path),
                        "vary": file_digest(vary)},
            "seed": settings.seed,
            "compare": {"param": param, "alternatives": jsonable(alternatives)} if alternatives else None,
            "n": settings.n, "timeout": settings.timeout, "workers": settings.workers, "backend": settings.backend}
    job = SweepJob(str(scenario.plan.path), str(vary), str(scenario.world_path), settings.timeout,
                   tuple(str(Path(i).resolve()) if i.endswith(".py") else i for i in settings.imports))
    results = ResultsFile(settings.out, meta, settings.resume, settings.force)
    prepared = PreparedSweep(settings, scenario, variations, job, meta, jsonable(alternatives) if alternatives else None,
                             results)
    for index in range(settings.n):
        seed = scenario_seed(settings.seed, index)
        for alt, alternative in enumerate(prepared.choices):
            task = Task(index, seed, alternative, alt)
            if task.key not in results.done:
                prepared.tasks.append(task)
    return prepared


def run_sweep(sweep: PreparedSweep, on_outcome: Callable[[dict[str, Any]], None] | None = None) -> dict[str, Any]:
    """Run what is left of the sweep; each outcome is written as it comes, then the summary of all of them."""
    settings = sweep.settings

    def record(outcome: dict[str, Any]) -> None:
        if not outcome["varied"]:  # the worker died with the scenario: draw it again here to say what it was
            outcome["varied"] = sweep.variations.sample(outcome["seed"], outcome["index"]).varied
        sweep.results.append(outcome)
        if on_outcome is not None:
            on_outcome(outcome)

    workers = settings.workers or os.cpu_count() or 1
    try:
        if settings.backend == "ray":
            ray_backend.run(sweep.job, sweep.tasks, workers, record, settings.address)
        else:
            LocalPool(sweep.job, workers).run(sweep.tasks, record)
    finally:
        keys = [(i, a) for i in range(settings.n) for a in range(len(sweep.choices))]
        sweep.results.finish(keys)
    return summary_of(sweep)


def summary_of(sweep: PreparedSweep) -> dict[str, Any]:
    """The summary of the outcomes in the results file so far, with a command to replay each example."""
    wanted = {(i, a) for i in range(sweep.settings.n) for a in range(len(sweep.choices))}
    records = [r for k, r in sorted(sweep.results.done.items()) if k in wanted]
    summary = summarise(records, sweep.meta)
    summary["results"] = str(sweep.results.path)
    for failure in summary["failures"]:
        example = failure["example"]
        failure["example"]["replay"] = replay_command(sweep, example["seed"], example.get("alternative"))
    for row in (summary.get("compare") or {}).get("differ", []):
        row["replay"] = replay_command(sweep, row["seed"], None)
    return summary


def replay_command(sweep: PreparedSweep, seed: int, alternative: dict[str, Any] | None) -> str:
    """The `pycram run` command that reproduces one scenario exactly."""
    parts = ["pycram", "run", _short(sweep.meta["plan"]), "--world", _short(sweep.meta["world"])]
    if beside(Path(sweep.meta["plan"])) != Path(sweep.meta["vary"]):
        parts += ["--vary", _short(sweep.meta["vary"])]
    parts += ["--scenario", str(seed)]
    for name, value in (alternative or {}).items():
        parts += ["-p", f"{name}={yaml.safe_dump(value, default_flow_style=True).strip().removesuffix('...').strip()}"]
    return shlex.join(parts)


def _short(path: str) -> str:
    """A bundled plan or world by its name, another file relative to the current folder if inside it."""
    file = Path(path).resolve()
    for folder in (plans_dir(), worlds_dir()):
        if file.parent == folder.resolve() and file.suffix == ".yaml" and not file.name.endswith(".vary.yaml"):
            return file.stem
    try:
        return str(Path(path).resolve().relative_to(Path.cwd()))
    except ValueError:
        return path
