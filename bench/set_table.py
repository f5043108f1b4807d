#!/usr/bin/env python3
"""Benchmark of the whole set-table demo, from process start to exit (target: at most 3 s).

    python bench/set_table.py            # 5 runs of each
    python bench/set_table.py --runs 3

Its medians, with the load average before the runs, go into bench/results.json under `set_table_demo`
(the README's Benchmarks table quotes them: bench/readme_figures.py).

"ours" is exactly what a user runs: `pycram run plans/set_table.yaml` in a fresh process.
The baseline runs the same plan in a fresh process with the design's straightforward
reasoning swapped in where the demo uses it (thesis §4.4, as in bench/reasoning.py):
`stable` simulates the whole scene for 480 steps, `visible`/`occluding` render the full
camera frame at 256×256 twice. Both must succeed; the script prints the medians and the ratio.
"""
from __future__ import annotations

import argparse
import importlib
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import results_file  # bench/results_file.py, beside this script

REPO = Path(__file__).resolve().parents[1]
PLAN = REPO / "plans" / "set_table.yaml"
TARGET = 3.0


def _baseline_run() -> int:
    """Run the demo with the design's straightforward reasoning (called in a subprocess)."""
    sys.path.insert(0, str(REPO))
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import numpy as np
    from reasoning import Baseline  # bench/reasoning.py

    from pycram_cli.process_modules import perception
    from pycram_cli.reasoning import visibility
    from pycram_cli.reasoning.stable import StableAnswer
    from pycram_cli.reasoning.visibility import VisibleAnswer

    def stable(obj, world=None):  # type: ignore[no-untyped-def]
        return StableAnswer(Baseline(obj.world).stable(obj), math.nan, math.nan, 2.0)

    def visible(obj, camera=None, world=None, threshold=0.8):  # type: ignore[no-untyped-def]
        scene, alone = Baseline(obj.world)._two_renders(obj)
        total = int((alone == obj.id).sum())
        seen = int(((scene == obj.id) & (alone == obj.id)).sum())
        fraction = seen / total if total else 0.0
        return VisibleAnswer(total > 0 and fraction >= threshold, fraction, seen, total)

    def occluding(obj, camera=None, world=None):  # type: ignore[no-untyped-def]
        scene, alone = Baseline(obj.world)._two_renders(obj)
        ids = set(np.unique(scene[alone == obj.id]).tolist()) - {obj.id, -1}
        return sorted((obj.world.get_object_by_id(i) for i in ids), key=lambda o: o.name)

    stable_module = importlib.import_module("pycram_cli.reasoning.stable")  # the package's `stable` is the function
    stable_module.stable, visibility.visible, visibility.occluding = stable, visible, occluding  # what the queries call
    perception.visible, perception.occluding = visible, occluding
    from pycram_cli.cli.main import cli

    return cli.main(["run", str(PLAN)], prog_name="pycram", standalone_mode=False) or 0


def _time(command: list[str]) -> float:
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--baseline-run", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.baseline_run:
        raise SystemExit(_baseline_run())
    ours_cmd = [sys.executable, "-m", "pycram_cli.cli.main", "run", str(PLAN)]
    base_cmd = [sys.executable, str(Path(__file__).resolve()), "--baseline-run"]
    ours, base = [], []
    load = os.getloadavg()[0]
    for _ in range(args.runs):  # interleaved, so both see the same machine load
        ours.append(_time(ours_cmd))
        base.append(_time(base_cmd))
    mo, mb = statistics.median(ours), statistics.median(base)
    print(f"set-table demo, process start to exit, {args.runs} runs each (median, min..max)")
    print(f"{'':<10}{'median':>9}{'range':>16}")
    print(f"{'ours':<10}{mo:>8.2f}s{min(ours):>8.2f}..{max(ours):.2f}s")
    print(f"{'baseline':<10}{mb:>8.2f}s{min(base):>8.2f}..{max(base):.2f}s")
    print(f"ratio baseline/ours: {mb / mo:.1f}x   target: ours <= {TARGET:.1f} s: {'met' if mo <= TARGET else 'MISSED'}")
    figures = {"ours_s": round(mo, 3), "baseline_s": round(mb, 3), "runs": args.runs, **results_file.provenance(),
               "load_before": round(load, 2)}
    print(f"wrote {results_file.update('set_table_demo', figures)}")


if __name__ == "__main__":
    main()
