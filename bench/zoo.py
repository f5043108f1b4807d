#!/usr/bin/env python3
"""The robot zoo's target (issue 23): `set_table_actions` on zoo robots that can reach the counter and the island.

    python bench/zoo.py                 # seeds 0..19, 2 workers
    python bench/zoo.py --seeds 20 --workers 1
    python bench/zoo.py --only 1 3 12   # just these seeds

For each seed, `pycram_cli.robots.zoo` writes the robot and its kitchen; then

(a) an independent reachability check, with plain PyBullet only (no pycram planning, location or
    IK code: the zoo robot's URDF, its description YAML for the arm's joints, tool frame and torso,
    and the kitchen's URDF are loaded in a DIRECT client of their own). A robot **can reach** the
    counter and the island when its arm, with its torso anywhere in its range, brings its tool
    frame within REACH_TOLERANCE of

    - every counter target: the bowl, the milk and the cereal as the world places them, at
      GRASP_HEIGHT above the counter top, and
    - at least one island target: a point ISLAND_INSET inside each of the island top's four edges
      (at the edge's middle), GRASP_HEIGHT above it,

    with one of the grasps its description names (front, top, left, right: tool orientations
    relative to the base) held within ANGLE_TOLERANCE, each from some base pose near it: base
    positions on a STEP lattice from 0.2 m to the arm's stretched length (plus 0.3 m) from the
    target, turned to face it and up to ±45° away, where the robot standing in its world file's
    configuration touches no part of the kitchen. The reach is kinematic (PyBullet's
    `calculateInverseKinematics` from a few starting configurations, joints clamped to their
    limits, checked by forward kinematics): whether the arm's way there is free is the planner's
    business, not this check's.

(b) `pycram run plans/set_table_actions.yaml --world W --json` in a fresh process, and

(c) one line per seed: reachable yes/no, the outcome, the failure's type and message.

The summary: how many reachable robots set the table (the target: at least TARGET of them), and
whether every other run failed honestly: exit 1 with a plan failure (a `pycram_cli.failures`
type), never an internal error, an input error or a timeout.
"""
from __future__ import annotations

import argparse
import json
import math
import multiprocessing
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

PLAN = REPO / "plans" / "set_table_actions.yaml"
TARGET = 0.9
REACH_TOLERANCE = 0.02  # m
ANGLE_TOLERANCE = math.radians(5.0)
GRASP_HEIGHT = 0.08  # m above the surface: about the middle of a carton's lower half
ISLAND_INSET = 0.15  # m inside the island top's edge
STEP = 0.1  # m, the base-position lattice
TURNS_DEG = (0, 15, -15, 30, -30, 45, -45)
RESTARTS = 4
TIMEOUT = 900.0  # s for one run
COUNTER_OBJECTS = ("bowl", "milk", "cereal")
COUNTER_LINK = "sink_area_surface"
ISLAND_LINK = "kitchen_island_surface"
PLAN_FAILURES = ("Failure", "GripperFailure", "LocationFailure", "ManipulationFailure", "NavigationFailure",
                 "PerceptionFailure", "ReachabilityFailure", "ReasoningFailure")


# -- (a) the independent reachability check --------------------------------------------------------------------


class _Scene:
    """The zoo robot and the kitchen in a PyBullet client of their own (nothing of pycram's world)."""

    def __init__(self, world_file: Path) -> None:
        import pybullet as p
        import yaml

        from pycram_cli.paths import resources_dir  # where the bundled kitchen's URDF is: a path, no planning

        self.p = p
        self.cid = p.connect(p.DIRECT)
        world = yaml.safe_load(world_file.read_text())
        entries = {o["name"]: o for o in world["objects"]}
        robot = next(o for o in world["objects"] if o.get("type") == "robot")
        description = yaml.safe_load(Path(robot["description"]).read_text())
        arm = next(iter(description["arms"].values()))
        self.robot = p.loadURDF(robot["file"], useFixedBase=True, physicsClientId=self.cid)
        self.kitchen = p.loadURDF(str(resources_dir() / entries["kitchen"]["file"]), useFixedBase=True,
                                  physicsClientId=self.cid)
        self.joints = {p.getJointInfo(self.robot, j, physicsClientId=self.cid)[1].decode(): j
                       for j in range(p.getNumJoints(self.robot, physicsClientId=self.cid))}
        links = {p.getJointInfo(self.robot, j, physicsClientId=self.cid)[12].decode(): j
                 for j in range(p.getNumJoints(self.robot, physicsClientId=self.cid))}
        self.tool = links[arm["tool_frame"]]
        self.grasps = [tuple(q) for q in (description.get("grasps") or {"front": (0, 0, 0, 1)}).values()]
        torso = description.get("torso")
        self.free = list(arm["joints"]) + ([torso["joint"]] if torso else [])
        self.start = {name: float(value) for name, value in (robot.get("joints") or {}).items()}
        if torso:
            self.start.setdefault(torso["joint"], float(torso.get("default", 0.0)))
        self.movable = [j for j in range(p.getNumJoints(self.robot, physicsClientId=self.cid))
                        if p.getJointInfo(self.robot, j, physicsClientId=self.cid)[2] != p.JOINT_FIXED]
        self.limits = {j: p.getJointInfo(self.robot, j, physicsClientId=self.cid)[8:10] for j in self.movable}
        self.kitchen_links = {p.getJointInfo(self.kitchen, j, physicsClientId=self.cid)[12].decode(): j
                              for j in range(p.getNumJoints(self.kitchen, physicsClientId=self.cid))}
        self.objects = {name: entries[name]["position"] for name in COUNTER_OBJECTS}
        self.length = self._arm_length(arm["joints"])

    def close(self) -> None:
        self.p.disconnect(self.cid)

    def _rest(self) -> None:
        for name, j in self.joints.items():
            self.p.resetJointState(self.robot, j, self.start.get(name, 0.0), physicsClientId=self.cid)

    def _arm_length(self, joints: list[str]) -> float:
        self._rest()
        points = [self.p.getLinkState(self.robot, self.joints[n], physicsClientId=self.cid)[4] for n in joints]
        points.append(self.p.getLinkState(self.robot, self.tool, physicsClientId=self.cid)[4])
        return sum(math.dist(a, b) for a, b in zip(points, points[1:]))

    def top(self, link: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return self.p.getAABB(self.kitchen, self.kitchen_links[link], physicsClientId=self.cid)

    def _place(self, x: float, y: float, yaw: float) -> None:
        self.p.resetBasePositionAndOrientation(self.robot, (x, y, 0.0), self.p.getQuaternionFromEuler((0, 0, yaw)),
                                               physicsClientId=self.cid)

    def _clear(self) -> bool:
        self._rest()
        return not self.p.getClosestPoints(self.robot, self.kitchen, 0.0, physicsClientId=self.cid)

    def _ik(self, target: tuple[float, float, float], orientation: tuple[float, ...]) -> bool:
        p, cid = self.p, self.cid
        free = {self.joints[n] for n in self.free}
        for attempt in range(RESTARTS):
            self._rest()
            for j in sorted(free):
                lo, hi = self.limits[j]
                if attempt and hi > lo:
                    p.resetJointState(self.robot, j, lo + (hi - lo) * ((attempt * 0.618 + j * 0.3) % 1.0),
                                      physicsClientId=cid)
            for _ in range(3):
                solution = p.calculateInverseKinematics(self.robot, self.tool, target, orientation,
                                                        maxNumIterations=200, residualThreshold=1e-5,
                                                        physicsClientId=cid)
                for j, value in zip(self.movable, solution):
                    if j in free:
                        lo, hi = self.limits[j]
                        p.resetJointState(self.robot, j, min(max(value, lo), hi) if hi > lo else value,
                                          physicsClientId=cid)
            state = p.getLinkState(self.robot, self.tool, computeForwardKinematics=True, physicsClientId=cid)
            dot = abs(sum(a * b for a, b in zip(state[5], orientation)))
            if math.dist(state[4], target) <= REACH_TOLERANCE and 2 * math.acos(min(1.0, dot)) <= ANGLE_TOLERANCE:
                return True
        return False

    def reaches(self, target: tuple[float, float, float]) -> bool:
        """Whether the tool reaches `target` from some clear base pose near it (see the module's docstring)."""
        radius = self.length + 0.3
        steps = int(radius / STEP)
        poses = []
        for i in range(-steps, steps + 1):
            for k in range(-steps, steps + 1):
                x, y = target[0] + i * STEP, target[1] + k * STEP
                d = math.hypot(x - target[0], y - target[1])
                if 0.2 <= d <= radius:
                    poses.append((d, x, y))
        for _, x, y in sorted(poses):
            facing = math.atan2(target[1] - y, target[0] - x)
            for turn in TURNS_DEG:
                yaw = facing + math.radians(turn)
                self._place(x, y, yaw)
                if not self._clear():
                    continue
                base = self.p.getQuaternionFromEuler((0, 0, yaw))
                for grasp in self.grasps:
                    if self._ik(target, self.p.multiplyTransforms((0, 0, 0), base, (0, 0, 0), grasp)[1]):
                        return True
        return False


def can_reach(world_file: Path) -> tuple[bool, str]:
    """(whether the robot can reach the counter and the island, what it could not reach)."""
    scene = _Scene(world_file)
    try:
        counter_top = scene.top(COUNTER_LINK)[1][2]
        missed = [name for name, (x, y, _) in scene.objects.items()
                  if not scene.reaches((x, y, counter_top + GRASP_HEIGHT))]
        lo, hi = scene.top(ISLAND_LINK)
        z = hi[2] + GRASP_HEIGHT
        cx, cy = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2
        sides = [(lo[0] + ISLAND_INSET, cy, z), (hi[0] - ISLAND_INSET, cy, z),
                 (cx, lo[1] + ISLAND_INSET, z), (cx, hi[1] - ISLAND_INSET, z)]
        if not any(scene.reaches(point) for point in sides):
            missed.append("the island")
        return not missed, ", ".join(missed)
    finally:
        scene.close()


# -- (b) the run ---------------------------------------------------------------------------------------------


@dataclass
class Row:
    seed: int
    robot: str
    reachable: bool
    missed: str
    outcome: str  # succeeded, plan failure, internal error, input error, timeout
    failure: str  # the failure's type
    message: str
    seconds: float

    @property
    def honest(self) -> bool:
        return self.outcome in ("succeeded", "plan failure")


def run_seed(seed: int) -> Row:
    from pycram_cli.robots.zoo import generate, write_world

    with tempfile.TemporaryDirectory(prefix=f"zoo{seed}-") as folder:
        robot = generate(seed)
        world = write_world(robot, Path(folder))
        reachable, missed = can_reach(world)
        start = time.perf_counter()
        command = [sys.executable, "-m", "pycram_cli.cli.main", "run", str(PLAN), "--world", str(world), "--json"]
        try:
            done = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT, cwd=REPO)
        except subprocess.TimeoutExpired:
            return Row(seed, robot.name, reachable, missed, "timeout", "", f"over {TIMEOUT:.0f} s", TIMEOUT)
        seconds = time.perf_counter() - start
    failure, message = "", ""
    try:
        answer = json.loads(done.stdout)
        status, found = answer.get("status"), answer.get("failure") or {}
        failure, message = str(found.get("type", "")), str(found.get("message", ""))
    except (json.JSONDecodeError, AttributeError):
        status = None
        message = (done.stderr.strip().splitlines() or [""])[-1]
    if done.returncode == 0 and status == "succeeded":
        outcome = "succeeded"
    elif done.returncode == 1 and failure in PLAN_FAILURES and "Traceback" not in done.stderr:
        outcome = "plan failure"
    elif done.returncode == 2:
        outcome = "input error"
    else:
        outcome = "internal error"
        message = message or (done.stderr.strip().splitlines() or [""])[-1]
    return Row(seed, robot.name, reachable, missed, outcome, failure, " ".join(message.split()), seconds)


# -- (c) the report ------------------------------------------------------------------------------------------


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=20, help="seeds 0..N-1 (default 20)")
    parser.add_argument("--only", type=int, nargs="*", help="just these seeds")
    parser.add_argument("--workers", type=int, default=2, help="processes (at most 2)")
    args = parser.parse_args()
    seeds = args.only if args.only else list(range(args.seeds))
    workers = max(1, min(2, args.workers))
    rows: list[Row] = []
    with multiprocessing.get_context("spawn").Pool(workers) as pool:
        for row in pool.imap(run_seed, seeds):
            rows.append(row)
            print(f"seed {row.seed:3d} {row.robot:10s} reachable {'yes' if row.reachable else 'no ':3s} "
                  f"{row.outcome:14s} {row.seconds:6.1f} s  {row.failure}"
                  f"{': ' + row.message[:160] if row.message else ''}"
                  f"{'  (cannot reach: ' + row.missed + ')' if row.missed else ''}", flush=True)
    reachable = [r for r in rows if r.reachable]
    succeeded = [r for r in reachable if r.outcome == "succeeded"]
    others = [r for r in rows if r.outcome != "succeeded"]
    ratio = len(succeeded) / len(reachable) if reachable else 0.0
    print(f"\n{len(succeeded)} of {len(reachable)} reachable robots set the table ({ratio:.0%}; target {TARGET:.0%}: "
          f"{'met' if ratio >= TARGET else 'missed'}); {sum(r.outcome == 'succeeded' for r in rows)} of {len(rows)} in all")
    dishonest = [r for r in others if not r.honest]
    print(f"every other run failed with a plan failure (exit 1): {'yes' if not dishonest else 'no'}"
          + (f" ({', '.join(f'seed {r.seed}: {r.outcome}' for r in dishonest)})" if dishonest else "")
          + f"; {len(others)} failed")


if __name__ == "__main__":
    main()
