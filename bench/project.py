#!/usr/bin/env python3
"""What the `project` step costs: 2 alternatives x RUNS projected runs of one pick-up (issue 27's target: <= 2 s).

    python bench/project.py              # 3 repetitions, 20 runs per alternative
    python bench/project.py --runs 5 --repeat 1
    python bench/project.py --modes 1,2,4,8   # in this process against forked workers, by projected runs

Measured in one process on the bundled kitchen, PR2 at the counter:

- `project`: a plan whose one step projects `pick-up milk` with the left and with the right arm,
  RUNS runs each, the milk moved by up to 2 cm and turned by up to 0.3 rad, then runs the chosen
  one (timed: the whole plan minus the chosen pick-up);
- baseline: what a person would otherwise do by hand — the same 2 x RUNS pick-ups, each run as a
  plan of its own on the world put back with `reset_to` and the milk moved by the same kind of draw.

Both print medians over the repetitions, and their ratio. Then what a projected run costs
beyond its own steps (saving, resetting, drawing, checking starts, the quiet runtime, folding
the trace): the same step whose alternatives only log, in this process, per run. The figures
go to bench/results.json (`project`), from which the README's are written
(bench/readme_figures.py).
The step runs as `pycram run` runs it (sweep/projection.py's LocalProjector: the first run here,
timed, the rest on forked workers when that is faster).

`--modes R1,R2,...`: the step with 2 x R projected runs, in this process and on forked workers
(one per core; the first run always here), medians of each; and the same with runs that do
nothing (a log step): what forking the workers and collecting their rows costs (STARTUP_COST).
"""
from __future__ import annotations

import argparse
import os
import random
import statistics
import sys
import tempfile
import textwrap
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import results_file  # noqa: E402
from pycram_cli.plan import load_plan, run_plan  # noqa: E402
from pycram_cli.sweep.projection import LocalProjector, cores  # noqa: E402
from pycram_cli.world.pose import quat_multiply, yaw_quaternion  # noqa: E402
from pycram_cli.worldfile.loader import load_world  # noqa: E402

COUNTER = "{target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}"


def project_plan(folder: Path, runs: int, action: str = "pick-up") -> Path:
    """The plan: drive to the counter, project the left and the right arm's pick-up (or a log step), run the best."""
    path = folder / "project.yaml"
    left, right = (("{pick-up: {object: milk, arm: left}}", "{pick-up: {object: milk, arm: right}}")
                   if action == "pick-up" else ("{log: left}", "{log: right}"))
    path.write_text(textwrap.dedent(f"""\
        world: kitchen
        body:
          - moving: {COUNTER}
          - project:
              alternatives:
                left: [{left}]
                right: [{right}]
              runs: {runs}
              vary: {{milk: {{noise: [0.02, 0.02, 0], yaw: 0.3}}}}
        """))
    return path


def one_plan(folder: Path, arm: str) -> Path:
    path = folder / f"pick_{arm}.yaml"
    path.write_text(f"world: kitchen\nbody:\n  - pick-up: {{object: milk, arm: {arm}}}\n")
    return path


def chosen_seconds(trace: dict) -> float:
    project = trace["root"]["children"][1]
    chosen = next(c for c in project["children"] if c["path"].endswith(("chosen left", "chosen right")))
    return float(chosen["timing"]["duration"])


def cpu() -> float:
    """CPU seconds of this process and of its ended children (forked workers): what the work cost, whatever the
    load (wall-clock seconds on a loaded machine also count the waits for a core)."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def step_seconds(world, plan, start, projector) -> float:
    """The project step's own time: the plan's, minus the chosen pick-up's."""
    world.reset_to(start)
    began = time.perf_counter()
    result = run_plan(plan, world, projector=projector)
    assert result.succeeded, result.failure
    return time.perf_counter() - began - chosen_seconds(result.trace)


def modes(world, folder: Path, counts: list[int], repeat: int) -> None:
    start = world.save_state()
    print(f"2 x R projected runs, medians over {repeat}: in this process | on {cores()} forked workers")
    for action in ("pick-up", "log"):
        for runs in counts:
            plan = load_plan(project_plan(folder, runs, action), world)
            here, forked = [], []
            for _ in range(repeat):
                here.append(step_seconds(world, plan, start, LocalProjector(startup=float("inf"))))
                forked.append(step_seconds(world, plan, start, LocalProjector(startup=0.0)))
            a, b = statistics.median(here), statistics.median(forked)
            print(f"{action:8s} R={runs:3d} ({2 * runs:3d} runs): {a:6.3f} s | {b:6.3f} s   "
                  f"({'workers' if b < a else 'in process'} faster by {abs(a - b):.3f} s)")
    print(f"(load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20, help="projected runs per alternative (default 20)")
    parser.add_argument("--repeat", type=int, default=3, help="repetitions (default 3)")
    parser.add_argument("--modes", help="R1,R2,...: in this process against forked workers for 2 x R runs")
    args = parser.parse_args()
    world = load_world("kitchen")
    if args.modes:
        with tempfile.TemporaryDirectory() as tmp:
            modes(world, Path(tmp), [int(r) for r in args.modes.split(",")], args.repeat)
        world.exit()
        return
    load_before = os.getloadavg()[0]
    used: list[int] = []
    overhead: list[float] = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        logging = load_plan(project_plan(folder, args.runs, "log"), world)
        project = load_plan(project_plan(folder, args.runs), world)
        singles = {arm: load_plan(one_plan(folder, arm), world) for arm in ("left", "right")}
        (folder / "move.yaml").write_text(f"world: kitchen\nbody:\n  - moving: {COUNTER}\n")
        mover = load_plan(folder / "move.yaml", world)
        start = world.save_state()
        milk = world.get_object_by_name("milk")
        assert milk is not None
        timed: list[float] = []
        baseline: list[float] = []
        timed_cpu: list[float] = []
        baseline_cpu: list[float] = []
        for _ in range(args.repeat):
            overhead.append(step_seconds(world, logging, start, LocalProjector(startup=float("inf"))) / (2 * args.runs))
            world.reset_to(start)
            projector = LocalProjector()  # as `pycram run` runs the step
            began, began_cpu = time.perf_counter(), cpu()
            result = run_plan(project, world, projector=projector)
            chosen = chosen_seconds(result.trace)
            timed.append(time.perf_counter() - began - chosen)
            timed_cpu.append(cpu() - began_cpu - chosen)  # the chosen pick-up (wall time: about its CPU time)
            used.append(projector.used)
            assert result.succeeded, result.failure
            world.reset_to(start)
            run_plan(mover, world)
            at_counter = world.save_state()
            (x, y, z), orientation = milk.get_pose()
            rng = random.Random(0)
            began, began_cpu = time.perf_counter(), cpu()
            for arm in ("left", "right"):
                for _ in range(args.runs):
                    world.reset_to(at_counter)
                    turned = quat_multiply(yaw_quaternion(rng.uniform(-0.3, 0.3)), orientation)
                    milk.set_position_and_orientation((x + rng.uniform(-0.02, 0.02), y + rng.uniform(-0.02, 0.02), z),
                                                      turned)
                    run_plan(singles[arm], world)
            baseline.append(time.perf_counter() - began)
            baseline_cpu.append(cpu() - began_cpu)
        world.exit()
    step, plain, extra = statistics.median(timed), statistics.median(baseline), statistics.median(overhead)
    load = os.getloadavg()[0]
    print(f"project step, 2 x {args.runs} projected pick-ups: median {step:.2f} s over {args.repeat} "
          f"(target <= 2 s), {1000 * step / (2 * args.runs):.0f} ms a run; workers {used}")
    print(f"baseline, the same pick-ups as plans of their own: median {plain:.2f} s")
    print(f"ratio step / baseline: {step / plain:.2f}   (load average {load:.2f} on {os.cpu_count()} cores)")
    step_cpu, plain_cpu = statistics.median(timed_cpu), statistics.median(baseline_cpu)
    print(f"CPU seconds: step {step_cpu:.2f}, baseline {plain_cpu:.2f}, ratio {step_cpu / plain_cpu:.2f}")
    print(f"a projected run's cost beyond its own steps: {1000 * extra:.1f} ms (median)")
    figures = {"runs": args.runs, "repeat": args.repeat, "step_s": round(step, 3), "baseline_s": round(plain, 3),
               "run_ms": round(1000 * step / (2 * args.runs), 1), "overhead_ms": round(1000 * extra, 2),
               "step_cpu_s": round(step_cpu, 3), "baseline_cpu_s": round(plain_cpu, 3),
               "run_cpu_ms": round(1000 * step_cpu / (2 * args.runs), 1),
               "workers": max(used), "cores": os.cpu_count(), **results_file.provenance(),
               "load_before": round(load_before, 2)}
    print(f"wrote {results_file.update('project', figures)}")


if __name__ == "__main__":
    main()
