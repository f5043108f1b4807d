#!/usr/bin/env python3
"""Benchmark of one collision-checked arm motion against checking the same path at a fixed resolution.

    python bench/motion.py            # 41 runs of each case; keeps its table in bench/results.json (`tables.motion`)
    python bench/motion.py --quick    # 11 runs, nothing kept

Cases, on the bundled kitchen with the PR2 (the same start and goal for both methods):

- *open floor*: the robot at its start pose, away from the counters; its left arm from `park` to the hand held
  forward (`FORWARD`: all seven joints turn, the shoulder pan by 1.7 rad; nothing in the way);
- *at the counter*: the robot at the demo's counter pose (0.65, 0.7); the same motion, the hand passing within
  centimetres of the counter and the wall cabinet (nothing in the way either).

Ours is `planning.motion.move` as plans call it (the situation memo off: every run checks the path afresh). The
baseline is what a straightforward checker does: the straight joint-space path sampled so that no joint turns more
than 0.01 rad between two samples, and at each sample the arm's links and what they hold measured against every other
body with PyBullet's closest points (`getClosestPoints` per body, 0 m). Both must say the path is free; the ratio is
the baseline's median over ours. Issue 28's target: ≤ 5 ms median when nothing is in the way.
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

from pycram_cli import load_world  # noqa: E402  (imports pybullet quietly)
import pybullet as p  # noqa: E402
from pycram_cli.planning import motion  # noqa: E402
from pycram_cli.planning.reach import arm_configuration  # noqa: E402
from pycram_cli.robots import Robot  # noqa: E402

import results_file  # noqa: E402  (bench/results_file.py, beside this script)

WORLD = REPO / "worlds" / "kitchen.yaml"
COUNTER_POSE = ((0.65, 0.7, 0.0), (0.0, 0.0, 0.0, 1.0))
ARM, START = "left", "park"
#: the left arm's goal: the hand forward at about the counter's height, in front of the robot
FORWARD = (0.0, 0.3, 0.0, -1.0, 0.0, -0.5, 0.0)
TARGET_MS = 5.0
BASELINE_STEP = 0.01  # rad: the largest joint change between two samples of the baseline


def baseline_free(robot: Robot, goal: dict[str, float]) -> bool:
    """The straight joint path from the current values to `goal`, sampled every BASELINE_STEP of the largest joint
    change, each sample's arm links measured against every other body (nothing deeper than motion.PENETRATION)."""
    body, world = robot.body, robot.world
    names = list(goal)
    start = np.array([body.get_joint_positions(names)[n] for n in names])
    end = np.array([goal[n] for n in names])
    links = sorted(body.links_below(names))
    others = [obj for obj in world.objects if obj is not body]
    steps = max(1, math.ceil(float(np.max(np.abs(end - start))) / BASELINE_STEP))
    cid = world.client_id
    try:
        for k in range(steps + 1):
            body.reset_joints(dict(zip(names, start + (end - start) * (k / steps))))
            for obj in others:
                for link in links:
                    for row in p.getClosestPoints(body.id, obj.id, 0.0, linkIndexA=link, physicsClientId=cid):
                        if row[8] < -motion.PENETRATION:
                            return False
        return True
    finally:
        body.reset_joints(dict(zip(names, start)))


def ours_free(robot: Robot, goal: dict[str, float]) -> bool:
    """`motion.move`'s check of the same path (then put back)."""
    hits = motion.hits_on_way(robot, goal)
    return not hits


def timed(run: Callable[[], bool], runs: int) -> tuple[float, bool]:
    times, verdicts = [], set()
    for _ in range(runs):
        start = time.perf_counter()
        verdicts.add(run())
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1000.0, verdicts == {True}


def case(world: Any, name: str, pose: tuple | None, runs: int) -> dict[str, Any]:
    robot = Robot.of(world)
    if pose is not None:
        world.robot.set_position_and_orientation(*pose)
    world.robot.reset_joints(arm_configuration(robot, ARM, START))
    goal = dict(zip(robot.description.arm(ARM).joints, FORWARD))
    ours, ours_ok = timed(lambda: ours_free(robot, goal), runs)
    base, base_ok = timed(lambda: baseline_free(robot, goal), max(3, runs // 4))
    return {"case": name, "ours_ms": ours, "baseline_ms": base, "free": ours_ok and base_ok}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="11 runs of each case, nothing kept")
    args = parser.parse_args(argv)
    runs = 11 if args.quick else 41
    load_before = os.getloadavg()[0]
    world = load_world(WORLD)
    # every run checks the path afresh (the memo would answer a repeated question from memory)
    type(world).tracks_changes = property(lambda self: False)  # type: ignore[method-assign,assignment]
    rows = [case(world, "open floor", None, runs), case(world, "at the counter", COUNTER_POSE, runs)]
    lines = ["| arm motion (PR2, left arm park → forward) | ours (median) | fixed 0.01 rad samples (median) | ratio | "
             "target | met? |",
             "|---|---|---|---|---|---|"]
    for row in rows:
        met = row["ours_ms"] <= TARGET_MS
        lines.append(f"| {row['case']}{'' if row['free'] else ' (a method found it blocked!)'} | "
                     f"{row['ours_ms']:.1f} ms | {row['baseline_ms']:.1f} ms | "
                     f"{row['baseline_ms'] / row['ours_ms']:.0f}× | ≤ {TARGET_MS:.0f} ms | {'yes' if met else 'no'} |")
    print("\n".join(lines))
    print(f"(load average {load_before:.2f} before, {os.getloadavg()[0]:.2f} after)", file=sys.stderr)
    if not args.quick:
        print(f"wrote {results_file.record_table('motion', chr(10).join(lines), load_before)}", file=sys.stderr)
    return 0 if all(row["free"] for row in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
