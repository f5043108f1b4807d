#!/usr/bin/env python3
"""Benchmark of location designators: the first pose, ours against uniform random sampling.

    python bench/locations.py            # full run (a few minutes: the baseline is slow)
    python bench/locations.py --quick    # fewer repetitions

A full run keeps its table in bench/results.json (`tables.locations`, with the commit and the load average),
from which the README's table is written (bench/readme_figures.py).

Ours: `locate(world, LOCATION).next()` on the bundled kitchen, from scratch every time (the
floor map is built again: the cache is cleared before each run), so each figure is the whole
cost of a first pose. "warm" repeats it with the floor map kept (the world has not moved).

The baseline, measured in the same run on its own copy of the world: base poses drawn
uniformly at random (position over the kitchen's floor, heading over the full turn; a seeded
generator per run) and checked with the same tests ours uses, in the same order — the robot's
collision shapes, inverse kinematics for each arm and grasp with the object's grasp points,
the arm touching nothing but the target and its support, the head turned and the `visible`
query — until one pose passes (at most `--samples` draws). No map, no ranking: what a
straightforward sampler does.

PyCRAM's own figure, for reference (measured by the issue's author on the thesis kitchen):
`CostmapLocation(reachable_for=...)` found no pose in 5.3 s.
"""
from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any, Callable

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import results_file  # noqa: E402  (bench/results_file.py, beside this script)
from pycram_cli.locations import locate, parse_location  # noqa: E402
from pycram_cli.locations import floor as floor_maps  # noqa: E402
from pycram_cli.locations import BasePoseResolution, Candidates  # noqa: E402
from pycram_cli.reasoning.ik import ANSWERS  # noqa: E402
from pycram_cli.world.cache import forget_everywhere  # noqa: E402
from pycram_cli.robots import Robot  # noqa: E402
from pycram_cli.worldfile.loader import load_world  # noqa: E402

KITCHEN = REPO / "worlds" / "kitchen.yaml"
FETCH = REPO / "worlds" / "kitchen_fetch.yaml"
PYCRAM_FIGURE = "no pose in 5.3 s"


def first_pose(world: Any, location: dict[str, Any], cold: bool = True) -> Any:
    forget_everywhere(ANSWERS)  # IK answers are kept per robot state (reasoning/ik.py): each run asks its questions afresh
    if cold:
        floor_maps.forget(world)
    return locate(world, location).next()


class RandomSampler:
    """Uniform random base poses, checked with the resolution's own tests (no map, no ranking)."""

    def __init__(self, world: Any, location: dict[str, Any], samples: int) -> None:
        self.world, self.samples = world, samples
        self.spec = parse_location(world, location)
        lo = np.full(2, np.inf)
        hi = np.full(2, -np.inf)
        for obj in world.objects:  # the kitchen's floor: the extent of everything but the floor itself
            blo, bhi = obj.get_aabb()
            if bhi[0] - blo[0] > 20:
                continue
            lo, hi = np.minimum(lo, blo[:2]), np.maximum(hi, bhi[:2])
        self.lo, self.hi = lo, hi

    def run(self, seed: int) -> tuple[Any, int]:
        rng = np.random.default_rng(seed)
        resolution = BasePoseResolution(Robot.of(self.world), self.spec, limit=10 ** 9)
        with self.world.lock, self.world.snapshot():
            resolution._prepared_inside()  # arms, targets, allowed contacts (the candidates are replaced below)
            xs = rng.uniform(self.lo[0], self.hi[0], self.samples)
            ys = rng.uniform(self.lo[1], self.hi[1], self.samples)
            yaws = rng.uniform(-math.pi, math.pi, self.samples)
            resolution.candidates = Candidates(xs, ys, yaws, np.zeros(self.samples), np.zeros(self.samples))
            names = resolution.arm_names
            resolution.arm_order = np.tile(np.arange(len(names), dtype=np.int8), (self.samples, 1))
            resolution.here_index = None
            for i in range(self.samples):
                pose = resolution._test(i)
                if pose is not None:
                    return pose, i + 1
        return None, self.samples


def median_ms(func: Callable[[int], Any], repeat: int) -> tuple[float, list[Any]]:
    times, answers = [], []
    for k in range(repeat):
        t0 = time.perf_counter()
        answers.append(func(k))
        times.append((time.perf_counter() - t0) * 1000.0)
    return statistics.median(times), answers


def fmt_ms(ms: float) -> str:
    return f"{ms / 1000:.2f} s" if ms >= 1000 else f"{ms:.0f} ms" if ms >= 10 else f"{ms:.1f} ms"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    parser.add_argument("--samples", type=int, default=3000, help="the baseline's most draws per run (default 3000)")
    opts = parser.parse_args(argv)
    ours_n, base_n = (5, 3) if opts.quick else (21, 9)
    cases = [
        ("reachable-for milk", KITCHEN, {"reachable-for": "milk"}, 100.0),
        ("visible-for milk", KITCHEN, {"visible-for": "milk"}, 100.0),
        ("reachable-for + visible-for milk", KITCHEN, {"reachable-for": "milk", "visible-for": "milk"}, 300.0),
        ("fetch: reachable-for milk", FETCH, {"reachable-for": "milk"}, 100.0),
        ("fetch: visible-for milk", FETCH, {"visible-for": "milk"}, 100.0),
        ("fetch: reachable-for + visible-for milk", FETCH, {"reachable-for": "milk", "visible-for": "milk"}, 300.0),
    ]
    rows = []
    load_before = os.getloadavg()[0]
    for label, path, location, target in cases:
        ours_world, base_world = load_world(path), load_world(path)
        try:
            first_pose(ours_world, location)  # warm-up: first-use caches (meshes, IK chains)
            ours, poses = median_ms(lambda k: first_pose(ours_world, location), ours_n)
            warm, _ = median_ms(lambda k: first_pose(ours_world, location, cold=False), ours_n)
            sampler = RandomSampler(base_world, location, opts.samples)
            base, found = median_ms(lambda k: sampler.run(1000 + k), base_n)
        finally:
            ours_world.exit()
            base_world.exit()
        hits = sum(1 for pose, _ in found if pose is not None)
        draws = statistics.median(n for _, n in found)
        first = poses[0]
        said = f"({first.position[0]:.2f}, {first.position[1]:.2f}) {math.degrees(first.yaw):.0f}°" + (
            f" {first.arm}" if first.arm else "")
        rows.append((label, fmt_ms(ours), fmt_ms(warm), fmt_ms(base), f"{base / ours:.0f}×", f"≤ {fmt_ms(target)}",
                     "yes" if ours <= target else "no", said, f"{hits}/{len(found)} found, median {draws:.0f} draws"))
        print(f"  {label}: ours {fmt_ms(ours)} (warm {fmt_ms(warm)}), random sampling {fmt_ms(base)}",
              file=sys.stderr, flush=True)
    header = ("location (first pose)", "ours (median)", "warm map", "random sampling (median)", "ratio", "target",
              "met?", "ours says", "random sampling")
    widths = [max(len(str(r[k])) for r in [header, *rows]) for k in range(len(header))]
    line = lambda r: "| " + " | ".join(str(c).ljust(w) for c, w in zip(r, widths)) + " |"  # noqa: E731
    lines = [line(header), "|" + "|".join("-" * (w + 2) for w in widths) + "|", *(line(row) for row in rows)]
    print("\n".join(lines))
    if not opts.quick:
        print(f"wrote {results_file.record_table('locations', chr(10).join(lines), load_before)}", file=sys.stderr)
    print(f"\nPyCRAM's CostmapLocation(reachable_for=...) on the thesis kitchen, for reference: {PYCRAM_FIGURE}.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
