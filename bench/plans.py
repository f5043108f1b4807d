#!/usr/bin/env python3
"""Benchmark of every shipped plan: plan time, process start to exit, and machine units (writes bench/results.json).

    python bench/plans.py                  # 3 runs of each plan; writes bench/results.json and prints a table
    python bench/plans.py --runs 5 --only set_table,fetch_milk
    python bench/plans.py --write-readme   # also rewrites the README's figures from the results (bench/readme_figures.py)

Every plan in plans/ runs on its own world, `set_table_actions` also on `kitchen_fetch`, and the README's
failing example (the milk placed over the island's edge) as it is shown there. For each case:

- *plan time*: the `duration` that `pycram run PLAN --json` reports, median over the runs;
- *process*: a fresh `pycram run PLAN` process from its start to its exit (the same runs), median;
- *units*: plan time divided by one second of simulated physics of the bundled kitchen (240 steps of
  `world.simulate(1.0)`), both measured in one process (`--child`: the physics second, then the plan through
  the same command-line code), so that the machine's load weighs on both alike; median over the runs.

The load average (1 min) is read before every run and kept with each case, with the commit measured (and
whether the work tree had changes). Timings on a shared machine are noisy: compare units, or figures measured
in the same run.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
RESULTS = Path(__file__).resolve().parent / "results.json"
PHYSICS_REPEATS = 3
# The README's failing example: the milk placed over the island's edge tips over (`stable` says no).
EDGE_JOBS = "jobs=[{type: milk, target: [-0.65, 1.0, 0.862], arm: left, look: [1.3, 0.8, 0.95]}]"


@dataclass(frozen=True)
class Case:
    """One benchmarked run: a plan, the world it runs on (None: the plan's own) and its parameters."""

    name: str
    plan: str
    world: str | None = None
    params: tuple[str, ...] = field(default_factory=tuple)

    def args(self) -> list[str]:
        """The `pycram run` arguments after `run`."""
        args = [self.plan]
        if self.world is not None:
            args += ["--world", self.world]
        for param in self.params:
            args += ["-p", param]
        return args


def cases() -> list[Case]:
    """Every shipped plan on its world, set_table_actions also on the Fetch, and the README's failing example."""
    found = [Case(p.stem, p.stem) for p in sorted((REPO / "plans").glob("*.yaml")) if not p.name.endswith(".vary.yaml")]
    found.append(Case("set_table_actions@kitchen_fetch", "set_table_actions", "kitchen_fetch"))
    found.append(Case("set_table@edge", "set_table", None, (EDGE_JOBS,)))
    return found


def leaves(trace: dict[str, Any]) -> list[dict[str, Any]]:
    """The trace's leaves (its steps), in order."""
    found, stack = [], [trace["root"]]
    while stack:
        node = stack.pop()
        children = node.get("children") or []
        if not children:
            found.append(node)
        stack.extend(reversed(children))
    return found


def steps_of(trace: dict[str, Any]) -> int:
    """The steps a run reports: leaves of the trace that succeeded or failed (as `pycram run` counts them)."""
    return sum(1 for node in leaves(trace) if node.get("status") in ("succeeded", "failed"))


def step_times(trace: dict[str, Any]) -> dict[str, float]:
    """Each step's duration by its path (the run log's figures)."""
    return {node["path"]: node["timing"]["duration"] for node in leaves(trace) if node.get("timing")}


def load() -> float:
    """The machine's load average over the last minute."""
    return round(os.getloadavg()[0], 2)


def run_command(case: Case) -> dict[str, Any]:
    """One fresh `pycram run CASE --json` process: its plan time, start-to-exit time, status and steps."""
    command = [sys.executable, "-m", "pycram_cli.cli.launch", "run", *case.args(), "--json", "-q"]
    started = time.perf_counter()
    done = subprocess.run(command, cwd=REPO, capture_output=True, text=True)
    elapsed = time.perf_counter() - started
    if done.returncode not in (0, 1):
        raise SystemExit(f"{case.name}: pycram exited {done.returncode}\n{done.stderr}")
    answer = json.loads(done.stdout)
    failure = answer.get("failure") or {}
    return {"plan_s": answer["duration"], "process_s": round(elapsed, 3), "status": answer["status"],
            "steps": steps_of(answer["trace"]), "step_s": step_times(answer["trace"]),
            "failure": failure.get("type"), "failure_path": failure.get("path")}


def physics_second() -> float:
    """Seconds of wall time for one second of simulated physics of the bundled kitchen (median of a few)."""
    from pycram_cli.worldfile.loader import load_world

    world = load_world()
    try:
        times = []
        for _ in range(PHYSICS_REPEATS):
            with world.snapshot():
                started = time.perf_counter()
                world.simulate(1.0)
                times.append(time.perf_counter() - started)
        return statistics.median(times)
    finally:
        world.exit()


def child(name: str) -> None:
    """In this one process: the physics second, then the plan through `pycram run --json`; prints both (JSON)."""
    case = next(c for c in cases() if c.name == name)
    sys.path.insert(0, str(REPO))
    unit = physics_second()
    from pycram_cli.cli.main import cli

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        cli.main(["run", *case.args(), "--json", "-q"], prog_name="pycram", standalone_mode=False)
    plan_s = json.loads(out.getvalue())["duration"]
    print(json.dumps({"unit_s": round(unit, 4), "plan_s": plan_s}))


def run_child(case: Case) -> dict[str, Any]:
    """One `--child` process for the case: its physics second and plan time."""
    done = subprocess.run([sys.executable, __file__, "--child", case.name], cwd=REPO, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{case.name}: the child exited {done.returncode}\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure(case: Case, runs: int) -> dict[str, Any]:
    """Medians over `runs` of the command and of the child, with the load before each run."""
    commands, children, loads = [], [], []
    for _ in range(runs):
        loads.append(load())
        commands.append(run_command(case))
        children.append(run_child(case))
    first = commands[0]
    if any((c["status"], c["steps"], c["failure_path"]) != (first["status"], first["steps"], first["failure_path"])
           for c in commands):
        raise SystemExit(f"{case.name}: runs disagree: {commands}")
    units = [c["plan_s"] / c["unit_s"] for c in children]
    return {
        "plan": case.plan, "world": case.world, "params": list(case.params),
        "status": first["status"], "steps": first["steps"], "failure": first["failure"],
        "failure_path": first["failure_path"],
        "plan_s": round(statistics.median(c["plan_s"] for c in commands), 3),
        "process_s": round(statistics.median(c["process_s"] for c in commands), 3),
        "units": round(statistics.median(units), 2),
        "unit_s": round(statistics.median(c["unit_s"] for c in children), 4),
        "load": round(statistics.median(loads), 2),
        "step_s": {path: round(statistics.median(c["step_s"].get(path, 0.0) for c in commands), 4)
                   for path in first["step_s"]},
        "runs": {"plan_s": [c["plan_s"] for c in commands], "process_s": [c["process_s"] for c in commands],
                 "units": [round(u, 2) for u in units], "load": loads},
    }


def table(results: dict[str, Any]) -> str:
    """The results as a plain-text table."""
    rows = [("case", "status", "steps", "plan (s)", "process (s)", "units", "1 unit (ms)", "load")]
    for name, r in results["plans"].items():
        rows.append((name, r["status"], str(r["steps"]), f"{r['plan_s']:.2f}", f"{r['process_s']:.2f}",
                     f"{r['units']:.1f}", f"{1000 * r['unit_s']:.0f}", f"{r['load']:.2f}"))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)) for row in rows]
    return "\n".join(lines) + (f"\ncommit {results['commit']}{' (with changes)' if results['dirty'] else ''}, "
                               f"{results['runs']} runs each, medians")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="runs of each case (default 3)")
    parser.add_argument("--only", help="comma-separated case names (the others keep their last results)")
    parser.add_argument("--write-readme", action="store_true", help="rewrite the README's figures from the results")
    parser.add_argument("--no-run", action="store_true", help="measure nothing: only print (and --write-readme)")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.child)
        return
    results = json.loads(RESULTS.read_text()) if RESULTS.exists() else {"plans": {}}
    if not args.no_run:
        chosen = cases()
        if args.only:
            names = set(args.only.split(","))
            unknown = names - {c.name for c in chosen}
            if unknown:
                parser.error(f"--only: no case {', '.join(sorted(unknown))}; cases: {', '.join(c.name for c in chosen)}")
            chosen = [c for c in chosen if c.name in names]
        else:
            results["plans"] = {}
        for case in chosen:
            print(f"{case.name} ...", file=sys.stderr, flush=True)
            results["plans"][case.name] = measure(case, args.runs)
        from results_file import provenance  # bench/results_file.py (this script's folder is on sys.path)

        measured = provenance()
        results.update({"commit": measured["commit"], "dirty": measured["dirty"]})
        results.update({"runs": args.runs, "date": time.strftime("%Y-%m-%d", time.gmtime()),
                        "machine": {"cpus": os.cpu_count(), "python": platform.python_version(),
                                    "system": platform.system()}})
        order = [c.name for c in cases()]
        results["plans"] = {k: results["plans"][k] for k in sorted(results["plans"], key=lambda k: (
            order.index(k) if k in order else len(order), k))}
        RESULTS.write_text(json.dumps(results, indent=2) + "\n")
        print(f"wrote {RESULTS}", file=sys.stderr)
    print(table(results))
    if args.write_readme:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from readme_figures import write

        for path in write(results):
            print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
