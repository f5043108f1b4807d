#!/usr/bin/env python3
"""Issue 28's target for robots nobody tuned for: `locate reachable-for milk` (the first pose) on each robot of
the zoo within 3x the PR2's time, both measured in this run.

    python bench/zoo_locate.py                 # seeds 0..47, 3 repetitions each; keeps its table in bench/results.json
    python bench/zoo_locate.py --only 1 7 --repeat 5   # nothing kept

Each figure is the median of `--repeat` cold first poses (the floor map built again each time, as
bench/locations.py does), in the robot's zoo kitchen (`pycram_cli.robots.zoo.write_world`: the
bundled kitchen with the zoo robot in the PR2's place); the PR2's is measured the same way in the
bundled kitchen, first and again at the end (the baseline is the lower median, so that load
during the run counts against the zoo, not for it). A robot that finds no pose counts with the
time it took to say so.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from pycram_cli.failures import LocationFailure  # noqa: E402
from pycram_cli.locations import locate  # noqa: E402
from pycram_cli.locations import floor as floor_maps  # noqa: E402
from pycram_cli.reasoning.ik import ANSWERS  # noqa: E402
from pycram_cli.world.cache import forget_everywhere  # noqa: E402
from pycram_cli.robots.zoo import generate, write_world  # noqa: E402
from pycram_cli.worldfile.loader import load_world  # noqa: E402

import results_file  # noqa: E402  (bench/results_file.py, beside this script)

TARGET = 3.0  # at most this many times the PR2's time
LOCATION = {"reachable-for": "milk"}


def first_pose_seconds(world_file: Any, repeat: int) -> tuple[float, bool]:
    """The median time of a cold first pose, and whether one was found."""
    world = load_world(world_file)
    try:
        times, found = [], True
        for _ in range(repeat):
            floor_maps.forget(world)
            forget_everywhere(ANSWERS)  # IK answers are kept per robot state (reasoning/ik.py): each run asks afresh
            with world.snapshot():
                start = time.perf_counter()
                try:
                    locate(world, LOCATION).next()
                except LocationFailure:
                    found = False
                times.append(time.perf_counter() - start)
        return statistics.median(times), found
    finally:
        world.exit()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=48, help="seeds 0..N-1 (default 48)")
    parser.add_argument("--only", type=int, nargs="*", help="just these seeds")
    parser.add_argument("--repeat", type=int, default=3, help="cold first poses per robot (default 3)")
    args = parser.parse_args()
    seeds = args.only if args.only else list(range(args.seeds))
    load_before = os.getloadavg()[0]
    pr2_before, _ = first_pose_seconds("kitchen", args.repeat)
    print(f"PR2 (bundled kitchen): {1000 * pr2_before:.0f} ms", flush=True)
    rows = []
    with tempfile.TemporaryDirectory(prefix="zoo-locate-") as folder:
        for seed in seeds:
            robot = generate(seed)
            seconds, found = first_pose_seconds(write_world(robot, Path(folder) / str(seed)), args.repeat)
            rows.append((seed, robot.name, seconds, found))
            print(f"seed {seed:3d} {robot.name:10s} {1000 * seconds:8.0f} ms  {'found' if found else 'no pose'}",
                  flush=True)
    pr2_after, _ = first_pose_seconds("kitchen", args.repeat)
    pr2 = min(pr2_before, pr2_after)
    print(f"PR2 again: {1000 * pr2_after:.0f} ms; baseline {1000 * pr2:.0f} ms")
    ratios = [(seconds / pr2, seed, name) for seed, name, seconds, _ in rows]
    worst = max(ratios)
    within = sum(r <= TARGET for r, _, _ in ratios)
    print(f"\nmedian ratio to the PR2 {statistics.median(r for r, _, _ in ratios):.2f}x; worst {worst[0]:.2f}x "
          f"(seed {worst[1]}, {worst[2]}); {within} of {len(ratios)} within {TARGET:g}x "
          f"(target: all: {'met' if within == len(ratios) else 'missed'})")
    if not args.only:
        table = summary(rows, pr2, args.repeat)
        print(f"wrote {results_file.record_table('zoo_locate', table, load_before)}", file=sys.stderr)


def summary(rows: list[tuple[int, str, float, bool]], pr2: float, repeat: int) -> str:
    """The README's table: the PR2's time, the zoo's (median, slowest) and how many robots are within the target."""
    ratios = sorted((seconds / pr2, seed, name) for seed, name, seconds, _ in rows)
    times = [seconds for _, _, seconds, _ in rows]
    worst = ratios[-1]
    within = sum(r <= TARGET for r, _, _ in ratios)
    found = sum(ok for _, _, _, ok in rows)
    return "\n".join([
        "| first pose of `reachable-for milk` | PR2, bundled kitchen | zoo robots, median | slowest zoo robot | "
        "robots within 3× the PR2 | beyond 3× | a pose found |",
        "|---|---|---|---|---|---|---|",
        f"| medians of {repeat} cold runs each | {1000 * pr2:.0f} ms | {1000 * statistics.median(times):.0f} ms "
        f"({statistics.median(r for r, _, _ in ratios):.2f}×) | {1000 * worst[0] * pr2:.0f} ms ({worst[0]:.2f}×, "
        f"seed {worst[1]}) | {within} of {len(rows)} (target: all: {'met' if within == len(rows) else '**missed**'}) "
        f"| {', '.join(f'seed {seed} ({r:.1f}×)' for r, seed, _ in ratios if r > TARGET) or 'none'} "
        f"| {found} of {len(rows)} |"])


if __name__ == "__main__":
    main()
