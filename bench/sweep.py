#!/usr/bin/env python3
"""Benchmark of `pycram sweep` on the set-table demo (plans/set_table.vary.yaml), all in one run.

    python bench/sweep.py                    # 40 scenarios per configuration, memory over 200; keeps its table
    python bench/sweep.py -n 60 --memory 1000 --baseline 8   # in bench/results.json (`tables.sweep`) unless --no-keep

Prints, for the same scenarios (seed 0):
- throughput (scenarios/s, worker start-up included) with 1 and 2 local workers, and their ratio
  (target: 2 workers >= 1.8x one worker on a 2-core machine);
- the per-scenario overhead on one worker: world reset and variation (measured in the worker) plus
  the bookkeeping between two scenarios (sending the task, the outcome back, the line written),
  against the median plan time (target: <= 5 %);
- the baseline: a fresh `pycram run set_table --scenario SEED` process per scenario, run one
  after another (the straightforward way), and its ratio to the sweep;
- with Ray installed: the Ray backend on a local Ray instance, its throughput, and whether its
  results are those of the local backend (same seeds, same outcomes, same trace digests);
- a worker's memory (RSS) every 100 scenarios over --memory scenarios run in one process (target: flat);
- the action demo (plans/set_table_actions.yaml, the same variations) swept with 2 workers, --actions scenarios:
  issue 28's target is >= 2 scenarios/s.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from pycram_cli.scenario.variations import scenario_seed  # noqa: E402
from pycram_cli.sweep import SweepSettings, prepare_sweep, run_sweep  # noqa: E402
from pycram_cli.sweep.worker import SweepJob, Task, Worker  # noqa: E402

import results_file  # noqa: E402  (bench/results_file.py, beside this script)

PLAN = REPO / "plans" / "set_table.yaml"
ACTIONS = REPO / "plans" / "set_table_actions.yaml"
VARY = REPO / "plans" / "set_table.vary.yaml"
#: issue 28: the action demo swept at this many scenarios per second or more with 2 workers
ACTIONS_TARGET = 2.0


def sweep(n: int, workers: int, backend: str = "local", plan: Path = PLAN) -> tuple[float, list[float], list[dict]]:
    """Wall time, arrival times of the outcomes, and the outcomes (in scenario order)."""
    with tempfile.TemporaryDirectory() as folder:
        prepared = prepare_sweep(SweepSettings(str(plan), str(VARY), n=n, workers=workers, backend=backend,
                                               out=Path(folder)))
        arrivals: list[float] = []
        started = time.perf_counter()
        run_sweep(prepared, lambda outcome: arrivals.append(time.perf_counter() - started))
        wall = time.perf_counter() - started
        records = [json.loads(line) for line in (Path(folder) / "results.jsonl").read_text().splitlines()]
    return wall, arrivals, records


def untimed(records: list[dict]) -> list[dict]:
    return [{k: v for k, v in r.items() if k != "timing"} for r in records]


def rss_mb() -> float:
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 1e6


def memory(count: int) -> list[tuple[int, float]]:
    worker = Worker(SweepJob(str(PLAN), str(VARY)))
    samples = []
    for index in range(count):
        worker.run(Task(index, scenario_seed(0, index)))
        if (index + 1) % 100 == 0 or index == 0:
            samples.append((index + 1, rss_mb()))
    worker.close()
    return samples


def baseline(count: int) -> list[float]:
    times = []
    for index in range(count):
        command = [sys.executable, "-m", "pycram_cli.cli.main", "run", str(PLAN), "--scenario",
                   str(scenario_seed(0, index)), "--json"]
        started = time.perf_counter()
        done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        times.append(time.perf_counter() - started)
        if done.returncode not in (0, 1):
            raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-n", type=int, default=40, help="scenarios per sweep")
    parser.add_argument("--baseline", type=int, default=6, help="scenarios run as fresh processes")
    parser.add_argument("--memory", type=int, default=200, help="scenarios for the memory check (0: skip)")
    parser.add_argument("--actions", type=int, default=20, help="scenarios of the action demo's sweep (0: skip)")
    parser.add_argument("--no-ray", action="store_true")
    parser.add_argument("--no-keep", action="store_true", help="print only: keep no table in bench/results.json")
    args = parser.parse_args()
    n = args.n
    load_before = os.getloadavg()[0]
    rows: list[str] = []  # the README's table, a row per figure
    print(f"set-table sweep, {n} scenarios of {VARY.relative_to(REPO)}, seed 0, on {os.cpu_count()} cores")

    wall1, arrivals1, one = sweep(n, 1)
    wall2, _, two = sweep(n, 2)
    durations = [r["timing"]["duration"] for r in one]
    setups = [r["timing"]["setup"] for r in one]
    plan = statistics.median(durations)
    # between two outcomes of one worker: its setup and plan time, plus everything else (the bookkeeping)
    gaps = [b - a for a, b in zip(arrivals1, arrivals1[1:])]
    busy = [r["timing"]["duration"] + r["timing"]["setup"] for r in one[1:]]
    bookkeeping = statistics.median(g - b for g, b in zip(gaps, busy))  # one worker: outcomes in scenario order
    tp1, tp2 = n / wall1, n / wall2
    print(f"  1 worker : {tp1:5.2f} scenarios/s ({wall1:.1f} s, start-up included)")
    print(f"  2 workers: {tp2:5.2f} scenarios/s ({wall2:.1f} s)   ratio {tp2 / tp1:.2f}x   target >= 1.8x: "
          f"{'met' if tp2 / tp1 >= 1.8 else 'MISSED'}")
    print(f"  same results with 1 and 2 workers: {untimed(one) == untimed(two)}")
    succeeded = sum(r["status"] == "succeeded" for r in one)
    print(f"  succeeded {succeeded} of {n}; plan time per scenario: median {plan * 1000:.0f} ms")
    rows.append(f"| `set_table`, {n} scenarios, 1 worker | {tp1:.2f} scenarios/s ({succeeded} of {n} succeeded; plan "
                f"time median {plan * 1000:.0f} ms) | | |")
    rows.append(f"| the same, 2 workers | {tp2:.2f} scenarios/s, {tp2 / tp1:.2f}× one worker; the same results: "
                f"{'yes' if untimed(one) == untimed(two) else '**no**'} | | ≥ 1.8×: "
                f"{'met' if tp2 / tp1 >= 1.8 else '**missed**'} |")
    overhead = statistics.median(setups) + max(0.0, bookkeeping)
    print(f"  overhead per scenario: reset+variation median {statistics.median(setups) * 1000:.2f} ms, "
          f"bookkeeping median {bookkeeping * 1000:.2f} ms = {100 * overhead / plan:.1f} % of the plan's time "
          f"(target <= 5 %: {'met' if overhead / plan <= 0.05 else 'MISSED'})")
    rows.append(f"| a scenario's reset, variation and bookkeeping (1 worker) | {overhead * 1000:.1f} ms, "
                f"{100 * overhead / plan:.1f} % of its plan time | | ≤ 5 %: "
                f"{'met' if overhead / plan <= 0.05 else '**missed**'} |")

    if args.baseline:
        base = baseline(args.baseline)
        mb = statistics.median(base)
        print(f"  baseline, a fresh `pycram run --scenario` process per scenario: median {mb:.2f} s "
              f"= {1 / mb:.2f} scenarios/s; the sweep is {tp1 * mb:.1f}x faster on 1 worker, "
              f"{tp2 * mb:.1f}x on 2")
        rows.append(f"| baseline: a fresh `pycram run --scenario` process per scenario | {1 / mb:.2f} scenarios/s | "
                    f"the sweep {tp1 * mb:.1f}× faster on 1 worker, {tp2 * mb:.1f}× on 2 | |")

    if not args.no_ray:
        try:
            import ray  # noqa: F401
        except ImportError:
            print("  ray: not installed (pip install '.[ray]'), skipped")
        else:
            wall_ray, _, on_ray = sweep(n, 2, "ray")
            print(f"  ray, 2 actors on a local Ray: {n / wall_ray:5.2f} scenarios/s ({wall_ray:.1f} s, Ray's start "
                  f"included); same results as the local backend: {untimed(on_ray) == untimed(two)}")
            rows.append(f"| the same on Ray, 2 actors (local Ray, its start-up included) | {n / wall_ray:.2f} "
                        f"scenarios/s; the local backend's results: "
                        f"{'yes' if untimed(on_ray) == untimed(two) else '**no**'} | | |")

    if args.actions:
        wall, _, done = sweep(args.actions, 2, plan=ACTIONS)
        rate = args.actions / wall
        plans = statistics.median(r["timing"]["duration"] for r in done)
        ok = sum(r["status"] == "succeeded" for r in done)
        print(f"  {ACTIONS.name}, 2 workers: {rate:5.2f} scenarios/s ({wall:.1f} s for {args.actions}, succeeded "
              f"{ok}; plan time median {plans:.2f} s) target >= {ACTIONS_TARGET:g}/s: "
              f"{'met' if rate >= ACTIONS_TARGET else 'MISSED'}")
        rows.append(f"| `set_table_actions`, {args.actions} scenarios, 2 workers | {rate:.2f} scenarios/s ({ok} of "
                    f"{args.actions} succeeded; plan time median {plans:.2f} s) | | ≥ {ACTIONS_TARGET:g}/s: "
                    f"{'met' if rate >= ACTIONS_TARGET else '**missed**'} |")

    if args.memory:
        samples = memory(args.memory)
        text = ", ".join(f"{i}: {mb:.0f} MB" for i, mb in samples)
        growth = samples[-1][1] - samples[min(1, len(samples) - 1)][1]
        print(f"  worker memory (RSS) over {args.memory} scenarios: {text} (growth after the first 100: "
              f"{growth:+.1f} MB)")
        rows.append(f"| a worker's memory (RSS) over {args.memory} scenarios | {text} | | flat: "
                    f"{growth:+.1f} MB after the first 100 |")
    if not args.no_keep:
        table = "\n".join([f"| sweep (`{VARY.relative_to(REPO)}`, seed 0, {os.cpu_count()} cores) | measured | "
                            "baseline | target |", "|---|---|---|---|", *rows])
        print(f"wrote {results_file.record_table('sweep', table, load_before)}", file=sys.stderr)


if __name__ == "__main__":
    main()
