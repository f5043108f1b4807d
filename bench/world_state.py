#!/usr/bin/env python3
"""Benchmark of saving and restoring the world state on the demo scene (target: restore under 1 ms).

    python bench/world_state.py            # 2000 repetitions
    python bench/world_state.py --reps 500

Its medians go into bench/results.json under `world_state` (with the commit and the load average), which
the README's Benchmarks table quotes (bench/readme_figures.py).

Ours is `world.save_state()` / `world.restore_state(state)`: PyBullet's saveState/restoreState
plus our attachment records; positions come back bitwise. A world saves once per change: "save"
is a save after a change, "save again" one while nothing changed (the saved state is reused). The baseline is the straightforward
method: read every object's base pose and velocity and every joint's position and velocity,
and write them all back one call at a time (it is not even bitwise exact for bodies whose
centre of mass is off their origin). Both run on the same kitchen world in the same process.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path


REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from pycram_cli import load_world  # noqa: E402  (imports pybullet quietly)
import pybullet as p  # noqa: E402

import results_file  # noqa: E402  (bench/results_file.py, beside this script)

TARGET_MS = 1.0


def baseline_save(world):  # type: ignore[no-untyped-def]
    cid = world.client_id
    saved = []
    for obj in world.objects:
        ids = [j.index for j in obj.joints]
        saved.append((obj.id, p.getBasePositionAndOrientation(obj.id, physicsClientId=cid),
                      p.getBaseVelocity(obj.id, physicsClientId=cid),
                      [(i, s[0], s[1]) for i, s in zip(ids, p.getJointStates(obj.id, ids, physicsClientId=cid) if ids else [])]))
    return saved


def baseline_restore(world, saved) -> None:  # type: ignore[no-untyped-def]
    cid = world.client_id
    for body, (pos, orn), (lin, ang), joints in saved:
        p.resetBasePositionAndOrientation(body, pos, orn, physicsClientId=cid)
        p.resetBaseVelocity(body, lin, ang, physicsClientId=cid)
        for index, position, velocity in joints:
            p.resetJointState(body, index, position, velocity, physicsClientId=cid)


def timed(func, reps: int) -> list[float]:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        func()
        times.append((time.perf_counter() - start) * 1000.0)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reps", type=int, default=2000)
    args = parser.parse_args()
    load_before = os.getloadavg()[0]
    world = load_world(REPO / "worlds" / "kitchen.yaml")
    world.robot.attach(world.get_object_by_name("milk"), "r_gripper_tool_frame")
    world.simulate(0.1)
    state = world.save_state()
    saved = baseline_save(world)
    def save_after_change() -> None:
        world.mark_changed()  # something changed: the world is saved again
        world.release_state(world.save_state())

    rows = [
        ("restore", timed(lambda: world.restore_state(state), args.reps), timed(lambda: baseline_restore(world, saved), args.reps)),
        ("save", timed(save_after_change, max(50, args.reps // 20)), timed(lambda: baseline_save(world), args.reps)),
        ("save again", timed(lambda: world.release_state(world.save_state()), args.reps),
         timed(lambda: baseline_save(world), args.reps)),
    ]
    world.exit()
    print(f"world state on the kitchen demo scene ({len(saved)} objects), medians in ms")
    print(f"{'':<11}{'ours':>9}{'baseline':>10}{'ratio':>8}")
    for name, ours, base in rows:
        mo, mb = statistics.median(ours), statistics.median(base)
        print(f"{name:<11}{mo:>9.3f}{mb:>10.3f}{mb / mo:>7.1f}x")
    restore = statistics.median(rows[0][1])
    print(f"target: restore < {TARGET_MS:.0f} ms: {'met' if restore < TARGET_MS else 'MISSED'} ({restore:.3f} ms)")
    figures = {f"{name.replace(' ', '_')}_ms": round(statistics.median(ours), 4) for name, ours, _ in rows}
    figures.update({f"{name.replace(' ', '_')}_baseline_ms": round(statistics.median(base), 4) for name, _, base in rows})
    figures.update({"reps": args.reps, **results_file.provenance(), "load_before": round(load_before, 2)})
    print(f"wrote {results_file.update('world_state', figures)}")


if __name__ == "__main__":
    main()
