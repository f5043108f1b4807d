"""`pycram sweep PLAN --vary VARY.yaml`: run a plan over many varied scenarios, in parallel, and summarise."""
from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any

import click
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

from ..errors import InputError, Location
from ..sweep import BACKENDS, PreparedSweep, SweepSettings, prepare_sweep, run_sweep, summary_of
from ..sweep.plot import plot_outcomes
from . import console
from .complete import plan_names, world_names
from .files import check_plot
from .options import json_option
from .sweep_report import DEFAULT_REPLAYS, MAX_REPLAYS, check_sweep_report, write_sweep_report

EXIT_INTERRUPTED = 130


class _Progress:
    """A progress bar with the running success rate on a terminal; nothing otherwise."""

    def __init__(self, total: int, done: int, succeeded: int, enabled: bool) -> None:
        self.runs, self.succeeded = done, succeeded
        self.bar: Progress | None = None
        if enabled:
            self.bar = Progress(TextColumn("[bold]sweep[/]"), BarColumn(), MofNCompleteColumn(),
                                TextColumn("{task.fields[rate]}"), TimeRemainingColumn(), console=console.err,
                                transient=True)
            self.task = self.bar.add_task("sweep", total=total, completed=done, rate=self._rate())

    def _rate(self) -> str:
        return f"succeeded {100.0 * self.succeeded / self.runs:.1f} %" if self.runs else ""

    def __call__(self, outcome: dict[str, Any]) -> None:
        self.runs += 1
        self.succeeded += outcome["status"] == "succeeded"
        if self.bar is not None:
            self.bar.update(self.task, advance=1, rate=self._rate())

    def __enter__(self) -> _Progress:
        if self.bar is not None:
            self.bar.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        if self.bar is not None:
            self.bar.__exit__(*exc)


@click.command("sweep")
@click.argument("plan_file", metavar="PLAN", shell_complete=plan_names)
@click.option("--world", "world_file", metavar="WORLD", shell_complete=world_names,
              help="World file or bundled world name (default: the plan's `world:`, else the kitchen).")
@click.option("--vary", "vary_file", metavar="VARY.yaml",
              help="The variation file (default: PLAN.vary.yaml beside the plan).")
@click.option("-n", "count", type=click.IntRange(min=1), default=100, show_default=True, help="Number of scenarios.")
@click.option("--seed", type=int, default=0, show_default=True, help="Seed of the sweep; scenario i's own seed derives from it.")
@click.option("--workers", type=click.IntRange(min=1), default=None, help="Worker processes (default: the number of cores).")
@click.option("--backend", type=click.Choice(BACKENDS), default="local", show_default=True,
              help="Local worker processes, or Ray actors (pip install '.[ray]').")
@click.option("--address", metavar="ADDR", help="Ray: the cluster to join ('auto': the running one); default: a local Ray.")
@click.option("--out", "out_dir", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Folder for results.jsonl and sweep.json (default: sweep-PLAN).")
@click.option("--plot", "plot_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write a PNG map of the outcomes over the varied start positions.")
@click.option("--report", "report_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write a page (HTML) of the sweep: the map of the outcomes and the scenarios by outcome, each "
                   "linking to its replay (recorded for --replays of them, written to REPORT-replays/ beside it).")
@click.option("--replays", type=click.IntRange(0, MAX_REPLAYS), default=None, metavar="N",
              help=f"With --report: run at most N scenarios again to record their replays, the failed ones first "
                   f"(0-{MAX_REPLAYS}; default: {DEFAULT_REPLAYS}).")
@click.option("--compare", metavar="PARAM=A,B,...", help="Run every scenario once per value of a plan parameter.")
@click.option("--timeout", type=click.FloatRange(min=0.0, min_open=True), default=None, metavar="SECONDS",
              help="Record a scenario that runs longer as a timeout and go on.")
@click.option("--resume", is_flag=True, help="Go on with the sweep in --out: skip the scenarios already in it.")
@click.option("--force", is_flag=True, help="Run the sweep again from the start in --out, replacing the results there.")
@json_option
@click.pass_context
def sweep(ctx: click.Context, plan_file: str, world_file: str | None, vary_file: str | None, count: int, seed: int,
          workers: int | None, backend: str, address: str | None, out_dir: Path | None, plot_file: Path | None,
          report_file: Path | None, replays: int | None, compare: str | None, timeout: float | None, resume: bool, force: bool,
          as_json: bool) -> None:
    """Run PLAN over many scenarios varied as VARY.yaml says, in parallel; summarise where it fails.

    Each scenario's outcome is a line of OUT/results.jsonl, written as it finishes (Ctrl-C keeps
    them; --resume goes on). Scenario i is drawn from its own seed, so results are the same
    whatever the number of workers; `pycram run PLAN --vary VARY.yaml --scenario SEED` replays one.
    Exit code 0 when the sweep ran (whatever its success rate), 2 for invalid input.
    """
    check_plot(plot_file)
    check_sweep_report(report_file)
    if report_file is None and replays is not None:
        raise InputError("sets how many replays the sweep's report links to, but no --report FILE is given",
                         Location("--replays"), suggestion="add --report sweep.html, or leave --replays out")
    out = out_dir if out_dir is not None else Path(f"sweep-{Path(plan_file).stem}")
    settings = SweepSettings(plan_file, vary_file, world_file, count, seed, workers, backend, address, out, compare,
                             timeout, resume, force)
    prepared = prepare_sweep(settings)
    done = len(prepared.results.done)
    succeeded = sum(1 for r in prepared.results.done.values() if r["status"] == "succeeded")
    used = min(workers or os.cpu_count() or 1, max(1, len(prepared.tasks)))
    if not as_json:
        console.info(f"sweeping {prepared.scenario.plan.path} on {prepared.scenario.world_path} with "
                     f"{prepared.job.vary}: {count} scenarios"
                     + (f" x {len(prepared.alternatives)} alternatives" if prepared.alternatives else "")
                     + (f", {done} done already" if done else "")
                     + f", {used} {'Ray ' if backend == 'ray' else ''}worker{'s' if used != 1 else ''}")
    started = time.perf_counter()
    interrupted = False
    with _Progress(prepared.total, done, succeeded, console.err.is_terminal and not as_json) as progress:
        try:
            summary = run_sweep(prepared, progress)
        except KeyboardInterrupt:
            interrupted = True
            summary = summary_of(prepared)
    elapsed = time.perf_counter() - started
    ran = progress.runs - done
    summary["throughput"] = {"runs": ran, "seconds": round(elapsed, 3),
                             "per_second": round(ran / elapsed, 3) if elapsed > 0 else None}
    summary["complete"] = not interrupted
    if plot_file is not None:
        plot_outcomes(prepared, summary_records(prepared), plot_file)
    if report_file is not None and not interrupted:
        write_sweep_report(prepared, summary, summary_records(prepared), report_file,
                           DEFAULT_REPLAYS if replays is None else replays)
    if as_json:
        console.emit_json(summary)
    else:
        _print(summary, prepared, plot_file)
    if interrupted:
        console.error(f"interrupted: {summary['runs']} of {prepared.total} runs are in {summary['results']} "
                      "(--resume goes on)" + (f"; {report_file} was not written" if report_file is not None else ""))
        ctx.exit(EXIT_INTERRUPTED)


def summary_records(prepared: PreparedSweep) -> list[dict[str, Any]]:
    return prepared.results.records()


def _percent(value: float | None) -> str:
    return "-" if value is None else f"{100.0 * value:.1f} %"


def _print(summary: dict[str, Any], prepared: PreparedSweep, plot_file: Path | None) -> None:
    runs, ok = summary["runs"], summary["succeeded"]
    lo, hi = summary["interval"]
    console.plain(f"sweep of {Path(summary['plan']).name} on {Path(summary['world']).name}: {summary['scenarios']} "
                  f"scenarios (seed {summary['seed']}), results in {summary['results']}")
    console.plain(f"succeeded {ok} of {runs}: {_percent(summary['rate'])} "
                  f"(95 % interval {100 * lo:.1f}-{100 * hi:.1f} %)")
    starts = summary["starts"]
    if starts["redrawn"]:
        console.plain(f"{starts['redrawn']} scenarios drawn again: their first draw could not start "
                      f"(e.g. {starts['example']})")
    if starts["invalid"]:
        console.plain(f"{starts['invalid']} scenarios not run, no draw could start (not counted): "
                      f"{starts['invalid_example']}")
    if summary["failures"]:
        console.plain("failures by type and node:")
        for failure in summary["failures"]:
            example = failure["example"]
            console.plain(f"  {failure['count']:>5}  {failure['type']} at {failure['path'] or '-'}")
            console.plain(f"         e.g. scenario {example['index']}: {example['message']}")
            console.plain(f"         replay: {example['replay']}")
    time_ = summary["time"]
    throughput = summary["throughput"]
    if time_["median"] is not None:
        console.plain(f"time per scenario: median {time_['median']:.3f} s, mean {time_['mean']:.3f} s "
                      f"(world reset and variation: median {1000 * time_['setup_median']:.2f} ms); "
                      f"{throughput['runs']} runs in {throughput['seconds']:.1f} s = "
                      f"{throughput['per_second'] or 0:.2f} runs/s")
    compare = summary.get("compare")
    if compare:
        console.plain(f"compare {compare['param']}:")
        for row in compare["alternatives"]:
            lo, hi = row["interval"]
            console.plain(f"  {compare['param']}={row['value']}: succeeded {row['succeeded']} of {row['runs']}, "
                          f"{_percent(row['rate'])} (95 % interval {100 * lo:.1f}-{100 * hi:.1f} %)")
        if compare["best"] is not None:
            console.plain(f"  best: {compare['param']}={compare['best']}")
        else:
            console.plain(f"  no single best: {', '.join(str(v) for v in compare['tied'])} succeed equally often")
        differ = compare["differ"]
        console.plain(f"  the alternatives' outcomes differ on {len(differ)} scenario(s)"
                      + (":" if differ else ""))
        for row in differ[:10]:
            outcomes = ", ".join(f"{k}: {v}" for k, v in row["outcomes"].items())
            console.plain(f"    scenario {row['index']} (seed {row['seed']}): {outcomes}")
        if len(differ) > 10:
            console.plain(f"    ... {len(differ) - 10} more in the JSON summary (--json)")
    if plot_file is not None:
        console.info(f"map of the outcomes written to {plot_file}")



