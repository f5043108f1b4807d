#!/usr/bin/env python3
"""The robot zoo's target (issue 23): `set_table_actions` on zoo robots that can reach the counter and the island.

    python bench/zoo.py                 # seeds 0..19, 2 workers
    python bench/zoo.py --seeds 20 --workers 1
    python bench/zoo.py --only 1 3 12   # just these seeds

For each seed, `pycram_cli.robots.zoo` writes the robot and its kitchen; then

(a) an independent reachability check, with plain PyBullet only (no pycram planning, location,
    grasping or IK code: the zoo robot's URDF, its description YAML for the arm's joints, tool
    frame, torso, gripper width and `front` grasp, the kitchen's URDF, the objects' meshes and the
    object knowledge's data file `resources/objects/grasps.yaml` are read and loaded in a DIRECT
    client of their own). A robot **can reach** the counter and the island when it can take

    - every counter object (the bowl, the milk and the cereal, where the world puts them), and
    - the milk standing on the island top at one of four points ISLAND_INSET inside the middle of
      each of its edges (placing it there is taking it in reverse), and
    - the drawer the spoon lies in, pulled open by OPEN_FRACTION of its travel (the least `search`
      opens a drawer by) by its handle: from one base pose and torso height, the tool holds the
      middle of the handle's box, pointing into the drawer (the fingers closing vertically or
      horizontally), at the closed end (after a pre-grasp APPROACH back) and at the opened end,
      the arm inside no part of the kitchen but the handle and the drawer's front, and the rest of
      the robot clear of the opened drawer (the pull in between is the planner's business),

    where **taking an object** means: some base pose, with the robot in its world file's
    configuration (arm parked) there touching no part of the kitchen, and a torso height (one of
    TORSO_LEVELS evenly over its range), from which the arm (joints within their limits) brings its
    tool frame within REACH_TOLERANCE and ANGLE_TOLERANCE of the grasp pose of one way to hold the
    object and of its pre-grasp pose APPROACH back along the approach, the arm inside no part of the
    kitchen (deeper than PENETRATION) at either. The ways to hold an object, from its box (its
    mesh's bounding box where it stands, square to the world's axes) and the object knowledge: its
    special grasp points when it has them (the bowl by its rim, from above: the tool at RIM_POINTS
    points around it, the fingers closing across the wall), else the tool pointing into the middle
    of a side face (through each of the four sides, the fingers closing horizontally or vertically)
    or straight down onto the middle of the top face (the fingers closing along either horizontal
    axis; a round object: RIM_POINTS sides), wherever the object between the fingers is no wider
    than the gripper opens. The tool's approach and closing axes are those of the description's
    `front` grasp (the base's x and y with the tool in it).

    The base pose is solved together with the arm: the robot's URDF is loaded under three virtual
    joints (x, y, yaw), which the IK moves (after trying the arm alone from the start) within
    BASE_SLACK and TURN_SLACK of each start on a STEP lattice from the target out to the arm's
    stretched length (plus 0.3 m), facing it (starts deeper in the kitchen than BASE_SLACK, and
    grasps through the object's far side from the start, are skipped). The reach is kinematic:
    PyBullet's damped least squares `calculateInverseKinematics` (the joints that must stay, damped
    still) from RESTARTS starting configurations spread over the arm's joint ranges at each torso
    height, clamped to the limits (and the base's box) after each of up to ROUNDS calls, judged by forward kinematics;
    whether the arm's way there is free of the robot itself and of the objects is the planner's
    business, not this check's. So a robot the check calls reachable can do it (up to those
    tolerances); one it calls unreachable might still, from a pose the lattice and the restarts
    missed.

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
from typing import Sequence

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

PLAN = REPO / "plans" / "set_table_actions.yaml"
TARGET = 0.9
REACH_TOLERANCE = 0.01  # m
ANGLE_TOLERANCE = math.radians(3.0)
APPROACH = 0.10  # m: the pre-grasp pose, back along the approach
PENETRATION = 0.003  # m the arm may graze the kitchen by
ISLAND_INSET = 0.15  # m inside the island top's edge
RIM_POINTS = 8  # points around a round object's rim (or directions around it)
STEP = 0.2  # m, the lattice of base positions the IK starts from
BASE_SLACK = 0.1  # m the IK may move the base from its start (half the lattice's step: every position is covered)
TURN_SLACK = math.radians(60.0)  # rad the IK may turn the base from facing the target
RESTARTS = 8  # per torso height
TORSO_LEVELS = 3  # torso heights tried, evenly over its range (bottom, middle, top)
ROUNDS = 8  # IK calls per restart at most, the joints clamped to their limits after each (until one stalls)
ITERATIONS = 100  # of each IK call
STALL_ANGLE = math.radians(0.2)  # a round that brings the tool no nearer by 1 mm nor this angle: the restart ends
FREE_DAMPING, BASE_DAMPING, LOCKED_DAMPING = 0.01, 0.3, 1e4  # the IK's damping: arm and torso, base, joints kept
TIMEOUT = 900.0  # s for one run
COUNTER_OBJECTS = ("bowl", "milk", "cereal")
ISLAND_OBJECT = "milk"
COUNTER_LINK = "sink_area_surface"
ISLAND_LINK = "kitchen_island_surface"
DRAWER_HANDLE, DRAWER_JOINT = "sink_area_left_upper_drawer_handle", "sink_area_left_upper_drawer_main_joint"
OPEN_FRACTION = 0.75  # of the drawer's travel: the least `search` pulls a drawer open by (its PARTLY)
PLAN_FAILURES = ("Failure", "GripperFailure", "LocationFailure", "ManipulationFailure", "NavigationFailure",
                 "PerceptionFailure", "ReachabilityFailure", "ReasoningFailure")
VIRTUAL = ("reach_check_x", "reach_check_y", "reach_check_yaw")  # the virtual joints carrying the robot


# -- (a) the independent reachability check --------------------------------------------------------------------


def _unit(v: Sequence[float]) -> tuple[float, float, float]:
    n = math.sqrt(sum(c * c for c in v))
    return (v[0] / n, v[1] / n, v[2] / n)


def _cross(a: Sequence[float], b: Sequence[float]) -> tuple[float, float, float]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _rotate(q: Sequence[float], v: Sequence[float]) -> tuple[float, float, float]:
    """The vector v turned by the quaternion q (x, y, z, w)."""
    x, y, z, w = q
    u = (x, y, z)
    t = tuple(2.0 * c for c in _cross(u, v))
    c = _cross(u, t)
    return (v[0] + w * t[0] + c[0], v[1] + w * t[1] + c[1], v[2] + w * t[2] + c[2])


def _matrix_quaternion(m: list[list[float]]) -> tuple[float, float, float, float]:
    """The quaternion (x, y, z, w) of a rotation matrix (rows)."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = math.sqrt(trace + 1.0) * 2
        return ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s)
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1.0 + m[i][i] - m[j][j] - m[k][k]) * 2
    q = [0.0, 0.0, 0.0, 0.0]
    q[i] = 0.25 * s
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return (q[0], q[1], q[2], q[3])


PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23)


def _halton(index: int, base: int) -> float:
    """The index-th number (from 1) of the van der Corput sequence in `base`: points spread evenly over [0, 1)."""
    found, fraction = 0.0, 1.0 / base
    while index:
        index, digit = divmod(index, base)
        found += digit * fraction
        fraction /= base
    return found


@dataclass(frozen=True)
class Grasp:
    """One way to hold an object: the tool frame's position and orientation, and the direction it approaches in."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    approach: tuple[float, float, float]

    @property
    def pre(self) -> tuple[float, float, float]:
        return tuple(p - APPROACH * a for p, a in zip(self.position, self.approach))  # type: ignore[return-value]


def _virtual_urdf(urdf: Path, root: str) -> Path:
    """The robot's URDF with its root link carried by three virtual joints (x, y, yaw about z), written beside it."""
    import xml.etree.ElementTree as ET

    tree = ET.parse(urdf)
    robot = tree.getroot()
    inertial = ('<inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.01"/>'
                '<inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial>')
    chain = ["reach_check_origin", "reach_check_x_link", "reach_check_y_link", root]
    parts = [ET.fromstring(f'<link name="{name}">{inertial}</link>') for name in chain[:3]]
    for (name, kind, axis), parent, child in zip(
            ((VIRTUAL[0], "prismatic", "1 0 0"), (VIRTUAL[1], "prismatic", "0 1 0"),
             (VIRTUAL[2], "continuous", "0 0 1")),
            chain, chain[1:]):
        limit = '<limit lower="-20" upper="20" effort="1" velocity="1"/>' if kind == "prismatic" else \
            '<limit effort="1" velocity="1"/>'
        parts.append(ET.fromstring(f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
                                   f'<child link="{child}"/><origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="{axis}"/>'
                                   f'{limit}</joint>'))
    for k, part in enumerate(parts):
        robot.insert(k, part)
    out = urdf.with_name(urdf.stem + ".reach_check.urdf")
    tree.write(out)
    return out


class _Scene:
    """The zoo robot (on virtual base joints), the kitchen and the objects in a PyBullet client of their own."""

    def __init__(self, world_file: Path) -> None:
        import pybullet as p
        import yaml

        from pycram_cli.paths import resources_dir  # where the bundled files are: paths, no planning

        self.p = p
        self.cid = p.connect(p.DIRECT)
        cid = self.cid
        world = yaml.safe_load(world_file.read_text())
        entries = {o["name"]: o for o in world["objects"]}
        robot = next(o for o in world["objects"] if o.get("type") == "robot")
        description = yaml.safe_load(Path(robot["description"]).read_text())
        arm = next(iter(description["arms"].values()))
        self.robot = p.loadURDF(str(_virtual_urdf(Path(robot["file"]), description["base_link"])), useFixedBase=True,
                                physicsClientId=cid)
        self.kitchen = p.loadURDF(str(resources_dir() / entries["kitchen"]["file"]), useFixedBase=True,
                                  physicsClientId=cid)
        info = [p.getJointInfo(self.robot, j, physicsClientId=cid)
                for j in range(p.getNumJoints(self.robot, physicsClientId=cid))]
        self.joints = {i[1].decode(): i[0] for i in info}
        links = {i[12].decode(): i[0] for i in info}
        self.tool = links[arm["tool_frame"]]
        self.movable = [i[0] for i in info if i[2] != p.JOINT_FIXED]
        self.limits = {i[0]: (i[8], i[9]) if i[9] > i[8] else (-math.pi, math.pi)
                       for i in info if i[2] != p.JOINT_FIXED}
        self.continuous = {i[0] for i in info if i[2] == p.JOINT_REVOLUTE and i[9] <= i[8]}
        torso = description.get("torso")
        self.arm = [self.joints[n] for n in arm["joints"]]
        self.torso = self.joints[torso["joint"]] if torso else None
        self.base = [self.joints[n] for n in VIRTUAL]
        self.start = {self.joints[name]: float(value) for name, value in (robot.get("joints") or {}).items()}
        if torso:
            self.start.setdefault(self.torso, float(torso.get("default", 0.0)))
        first = self.arm[0]
        self.arm_links = {j for j in range(len(info)) if self._below(j, first, info)}
        front = (description.get("grasps") or {}).get("front", (0, 0, 0, 1))
        inverse = (-front[0], -front[1], -front[2], front[3])
        self.tool_approach, self.tool_closing = _rotate(inverse, (1, 0, 0)), _rotate(inverse, (0, 1, 0))
        self.max_width = float(arm["gripper"]["max_width"])
        self.knowledge = yaml.safe_load((resources_dir() / "objects" / "grasps.yaml").read_text()) or {}
        self.boxes = {}
        for name, entry in entries.items():
            if name in COUNTER_OBJECTS or name == ISLAND_OBJECT:
                shape = p.createCollisionShape(p.GEOM_MESH, fileName=str(resources_dir() / entry["file"]),
                                               physicsClientId=cid)
                body = p.createMultiBody(0, shape, basePosition=entry["position"], physicsClientId=cid)
                self.boxes[name] = (p.getAABB(body, -1, physicsClientId=cid), entry["type"])
                p.removeBody(body, physicsClientId=cid)
        self._rest()
        tool = p.getLinkState(self.robot, self.tool, physicsClientId=cid)[4]
        points = [p.getLinkState(self.robot, j, physicsClientId=cid)[4] for j in self.arm] + [tool]
        self.length = sum(math.dist(a, b) for a, b in zip(points, points[1:]))

    @staticmethod
    def _below(index: int, ancestor: int, info: list) -> bool:
        while index != -1:
            if index == ancestor:
                return True
            index = info[index][16]
        return False

    def close(self) -> None:
        self.p.disconnect(self.cid)

    def top(self, link: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
        links = {self.p.getJointInfo(self.kitchen, j, physicsClientId=self.cid)[12].decode(): j
                 for j in range(self.p.getNumJoints(self.kitchen, physicsClientId=self.cid))}
        return self.p.getAABB(self.kitchen, links[link], physicsClientId=self.cid)

    # -- the ways to hold an object --------------------------------------------------------------------------
    def _tool_orientation(self, approach: Sequence[float], closing: Sequence[float]) -> tuple[float, ...]:
        """The tool orientation whose approach and closing axes point along these world directions."""
        a, c = _unit(approach), _unit(closing)
        world = (a, c, _cross(a, c))
        ta, tc = self.tool_approach, self.tool_closing
        tool = (ta, tc, _cross(ta, tc))
        m = [[sum(world[k][r] * tool[k][col] for k in range(3)) for col in range(3)] for r in range(3)]
        return _matrix_quaternion(m)

    def grasps(self, name: str, at: Sequence[float] | None = None) -> list[Grasp]:
        """The ways to hold object `name` (standing at `at`: its box's bottom centre, else where it stands)."""
        (lo, hi), kind = self.boxes[name]
        centre = [(a + b) / 2 for a, b in zip(lo, hi)]
        half = [(b - a) / 2 for a, b in zip(lo, hi)]
        if at is not None:
            centre = [at[0], at[1], at[2] + half[2]]
        known = self.knowledge.get(kind) or {}
        round_ = known.get("symmetry") == "revolution"
        found: list[Grasp] = []
        down = (0.0, 0.0, -1.0)
        if known.get("grasps"):
            for point in (known["grasps"].get("top") or [])[:1]:  # special points, from above (the bowl's rim): the
                # first of them, at every point around (the others are the same points of a round object)
                if float(point["width"]) > self.max_width:
                    continue
                for k in range(RIM_POINTS):
                    phi = 2 * math.pi * k / RIM_POINTS
                    x_dir, y_dir = (math.cos(phi), math.sin(phi), 0.0), (-math.sin(phi), math.cos(phi), 0.0)
                    local = [point["at"][i] * max(half[0], half[1]) + point["offset"][i] for i in range(2)]
                    z = centre[2] + point["at"][2] * half[2] + point["offset"][2]
                    position = tuple(centre[i] + local[0] * x_dir[i] + local[1] * y_dir[i] for i in range(2)) + (z,)
                    for sign in (1, -1):
                        found.append(Grasp(position, self._tool_orientation(down, [sign * v for v in y_dir]), down))
            return found
        sides = [(math.cos(2 * math.pi * k / RIM_POINTS), math.sin(2 * math.pi * k / RIM_POINTS), 0.0)
                 for k in range(RIM_POINTS)] if round_ else [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0)]
        for a in sides:  # into the middle of a side face
            across = (-a[1], a[0], 0.0)
            depth = max(half[0], half[1]) if round_ else abs(a[0]) * half[0] + abs(a[1]) * half[1]
            position = (centre[0] - a[0] * depth, centre[1] - a[1] * depth, centre[2])
            width_across = 2 * max(half[0], half[1]) if round_ else \
                2 * (abs(across[0]) * half[0] + abs(across[1]) * half[1])
            for closing, width in ((across, width_across), ((0.0, 0.0, 1.0), 2 * half[2])):
                if width <= self.max_width:
                    for sign in (1, -1):
                        found.append(Grasp(position, self._tool_orientation(a, [sign * v for v in closing]), a))
        top = (centre[0], centre[1], centre[2] + half[2])
        for closing, width in (((1.0, 0.0, 0.0), 2 * half[0]), ((0.0, 1.0, 0.0), 2 * half[1])):
            if width <= self.max_width or (round_ and 2 * max(half[0], half[1]) <= self.max_width):
                for sign in (1, -1):
                    found.append(Grasp(top, self._tool_orientation(down, [sign * v for v in closing]), down))
        return found

    # -- the search ------------------------------------------------------------------------------------------
    def _rest(self, base: Sequence[float] = (0.0, 0.0, 0.0)) -> None:
        for j in self.movable:
            self.p.resetJointState(self.robot, j, self.start.get(j, 0.0), physicsClientId=self.cid)
        for j, value in zip(self.base, base):
            self.p.resetJointState(self.robot, j, value, physicsClientId=self.cid)

    def _state(self) -> dict[int, float]:
        return {j: self.p.getJointState(self.robot, j, physicsClientId=self.cid)[0] for j in self.movable}

    def _set(self, values: dict[int, float]) -> None:
        for j, value in values.items():
            self.p.resetJointState(self.robot, j, value, physicsClientId=self.cid)

    def _touches(self, links: set[int] | None, depth: float, ignore: frozenset[int] = frozenset()) -> bool:
        """Whether the robot (only `links`, when given) is inside the kitchen (but its links `ignore`) deeper than
        `depth` (or touches it, 0)."""
        points = self.p.getClosestPoints(self.robot, self.kitchen, 0.0, physicsClientId=self.cid)
        return any((links is None or pt[3] in links) and pt[4] not in ignore and pt[8] < -depth for pt in points)

    def _solve(self, target: Sequence[float], orientation: Sequence[float], free: list[int],
               box: dict[int, tuple[float, float]]) -> bool:
        """IK for the tool from the current state, only `free` joints moving, each clamped to `box` (or its limits)."""
        p, cid = self.p, self.cid
        last = None
        for _ in range(ROUNDS):
            # the joints that must not move damped still; the base's joints damped some (the arm reaches first)
            limits = {"jointDamping": [(BASE_DAMPING if j in box else FREE_DAMPING) if j in free else LOCKED_DAMPING
                                       for j in self.movable]}
            solution = p.calculateInverseKinematics(self.robot, self.tool, target, orientation,
                                                    maxNumIterations=ITERATIONS, residualThreshold=1e-6,
                                                    physicsClientId=cid, **limits)
            for j, value in zip(self.movable, solution):
                if j not in free:
                    continue
                lo, hi = box.get(j, self.limits[j])
                if j in self.continuous and j not in box:
                    value = math.atan2(math.sin(value), math.cos(value))
                p.resetJointState(self.robot, j, min(max(value, lo), hi), physicsClientId=cid)
            error = self._error(target, orientation)
            if error[0] <= REACH_TOLERANCE and error[1] <= ANGLE_TOLERANCE:
                return True
            if last is not None and error[0] > last[0] - 0.001 and error[1] > last[1] - STALL_ANGLE:  # stalled
                return False
            last = error
        return False

    def _error(self, target: Sequence[float], orientation: Sequence[float]) -> tuple[float, float]:
        """Forward kinematics: how far (m) and how much turned (rad) the tool is from the pose."""
        state = self.p.getLinkState(self.robot, self.tool, computeForwardKinematics=True, physicsClientId=self.cid)
        dot = abs(sum(a * b for a, b in zip(state[5], orientation)))
        return math.dist(state[4], target), 2 * math.acos(min(1.0, dot))

    def _at(self, target: Sequence[float], orientation: Sequence[float]) -> bool:
        """Forward kinematics: the tool within the tolerances of the pose."""
        state = self.p.getLinkState(self.robot, self.tool, computeForwardKinematics=True, physicsClientId=self.cid)
        dot = abs(sum(a * b for a, b in zip(state[5], orientation)))
        return math.dist(state[4], target) <= REACH_TOLERANCE and 2 * math.acos(min(1.0, dot)) <= ANGLE_TOLERANCE

    def _base_box(self, x: float, y: float, yaw: float) -> dict[int, tuple[float, float]]:
        """How far the IK may move the base's virtual joints from a start at (x, y, yaw)."""
        return {self.base[0]: (x - BASE_SLACK, x + BASE_SLACK), self.base[1]: (y - BASE_SLACK, y + BASE_SLACK),
                self.base[2]: (yaw - TURN_SLACK, yaw + TURN_SLACK)}

    def _torso_levels(self) -> list[float | None]:
        """The torso heights tried: TORSO_LEVELS evenly over its range (None: no torso)."""
        if self.torso is None:
            return [None]
        lo, hi = self.limits[self.torso]
        return [lo + (hi - lo) * k / (TORSO_LEVELS - 1) for k in range(TORSO_LEVELS)]

    def _start(self, base: Sequence[float], height: float | None, attempt: int) -> None:
        """The robot at rest with its base at `base`, the torso at `height` (None: where it rests), the arm at restart
        `attempt`."""
        self._rest(base)
        if height is not None:
            self.p.resetJointState(self.robot, self.torso, height, physicsClientId=self.cid)
        self._restart(attempt)

    def _parks_clear(self, solved: dict[int, float]) -> bool:
        """Whether the robot, parked (its arm as at the start) at the base pose and torso height of `solved`, touches
        no part of the kitchen."""
        self._set({j: self.start.get(j, 0.0) for j in self.arm})
        self._set({j: solved[j] for j in self.base})
        return not self._touches(None, 0.0)

    def _restart(self, attempt: int) -> None:
        """Restart `attempt` (0: the arm where it is) spreads the arm's joints over their ranges: a Halton sequence,
        no randomness."""
        if not attempt:
            return
        for k, j in enumerate(self.arm):
            lo, hi = self.limits[j]
            self.p.resetJointState(self.robot, j, lo + (hi - lo) * _halton(attempt, PRIMES[k % len(PRIMES)]),
                                   physicsClientId=self.cid)

    def _takes_from(self, x: float, y: float, yaw: float, grasp: Grasp) -> bool:
        """Whether the robot, its base starting at (x, y, yaw), takes the grasp (see the module's docstring)."""
        box = self._base_box(x, y, yaw)
        free = [*self.base, *self.arm]
        # at each torso height and start, the arm alone from the base's start, then the base moving too
        starts = ((h, a, m) for h in self._torso_levels() for a in range(RESTARTS) for m in (False, True))
        for height, attempt, moving in starts:
            self._start((x, y, yaw), height, attempt)
            if not self._solve(grasp.position, grasp.orientation, free if moving else self.arm,
                               box if moving else {}):
                continue
            solved = self._state()
            if self._touches(self.arm_links, PENETRATION):
                continue
            # the pre-grasp pose from the same base pose and torso height
            if not self._solve(grasp.pre, grasp.orientation, self.arm, {}) or \
                    self._touches(self.arm_links, PENETRATION):
                continue
            # the robot parked at that base pose and torso height, clear of the kitchen
            if self._parks_clear(solved):
                return True
        return False

    def _stands_around(self, centre: Sequence[float]) -> list[tuple[float, float]]:
        """Where the base may stand to work at `centre`: a grid of STEP from 0.2 m to the arm's length + 0.3 m away,
        nearest first."""
        radius = self.length + 0.3
        steps = int(radius / STEP)
        offsets = sorted((math.hypot(i * STEP, k * STEP), i, k) for i in range(-steps, steps + 1)
                         for k in range(-steps, steps + 1) if 0.2 <= math.hypot(i * STEP, k * STEP) <= radius)
        return [(centre[0] + i * STEP, centre[1] + k * STEP) for _, i, k in offsets]

    def takes(self, name: str, at: Sequence[float] | None = None) -> bool:
        """Whether the robot can take object `name` (standing at `at`, else where it stands): see the docstring."""
        grasps = self.grasps(name, at)
        if not grasps:
            return False
        target = grasps[0].position
        for x, y in self._stands_around(target):
            yaw = math.atan2(target[1] - y, target[0] - x)
            self._rest((x, y, yaw))
            if self._touches(None, BASE_SLACK):  # deeper in the kitchen than the base may move: no start
                continue
            for grasp in grasps:
                # not through the object's far side (the arm would reach around it)
                if grasp.approach[0] * (target[0] - x) + grasp.approach[1] * (target[1] - y) < 0.0:
                    continue
                if self._takes_from(x, y, yaw, grasp):
                    return True
        return False


    # -- the drawer ------------------------------------------------------------------------------------------
    def _kitchen_links(self) -> dict[str, int]:
        return {self.p.getJointInfo(self.kitchen, j, physicsClientId=self.cid)[12].decode(): j
                for j in range(self.p.getNumJoints(self.kitchen, physicsClientId=self.cid))}

    def _handle_at(self, handle: int, drawer: int, value: float) -> tuple[float, float, float]:
        """The middle of the handle's box with the drawer's joint at `value`."""
        self.p.resetJointState(self.kitchen, drawer, value, physicsClientId=self.cid)
        lo, hi = self.p.getAABB(self.kitchen, handle, physicsClientId=self.cid)
        return ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2)

    def opens(self, handle_link: str, joint: str, fraction: float) -> bool:
        """Whether the robot can pull the drawer `joint` open by `fraction` of its range by `handle_link`: see the
        module's docstring."""
        p, cid = self.p, self.cid
        links = self._kitchen_links()
        handle = links[handle_link]
        drawer = next(j for j in range(p.getNumJoints(self.kitchen, physicsClientId=cid))
                      if p.getJointInfo(self.kitchen, j, physicsClientId=cid)[1].decode() == joint)
        info = p.getJointInfo(self.kitchen, drawer, physicsClientId=cid)
        lower, upper = info[8], info[9]
        values = (lower, lower + fraction * (upper - lower))
        closed, opened = (self._handle_at(handle, drawer, v) for v in values)
        pull = _unit((opened[0] - closed[0], opened[1] - closed[1], 0.0))
        into = (-pull[0], -pull[1], 0.0)
        across = (-pull[1], pull[0], 0.0)
        ways = [self._tool_orientation(into, [sign * c for c in closing])
                for closing in ((0.0, 0.0, 1.0), across) for sign in (1, -1)]
        ignore = frozenset({handle, drawer})  # the gripper holds the handle, on the drawer's front
        try:
            for x, y in self._stands_around(closed):
                if (x - closed[0]) * pull[0] + (y - closed[1]) * pull[1] <= 0.0:  # behind the drawer's front
                    continue
                yaw = math.atan2(closed[1] - y, closed[0] - x)
                p.resetJointState(self.kitchen, drawer, values[1], physicsClientId=cid)
                self._rest((x, y, yaw))
                if self._touches(None, BASE_SLACK):  # deeper in the kitchen (the drawer open) than the base may move
                    continue
                for orientation in ways:
                    if self._pulls_from(x, y, yaw, (closed, opened), orientation, into, drawer, values, ignore):
                        return True
            return False
        finally:
            p.resetJointState(self.kitchen, drawer, lower, physicsClientId=cid)

    def _reaches_too(self, target: Sequence[float], orientation: Sequence[float], drawer: int, value: float,
                     ignore: frozenset[int], body: set[int]) -> bool:
        """Whether the arm alone, from where it is or from one of the restarts, brings the tool to `target` with the
        drawer's joint at `value`, the arm inside nothing (but `ignore`) and the rest of the robot (`body`) touching
        nothing."""
        p, cid = self.p, self.cid
        p.resetJointState(self.kitchen, drawer, value, physicsClientId=cid)
        here = {j: p.getJointState(self.robot, j, physicsClientId=cid)[0] for j in self.arm}
        for attempt in range(RESTARTS):
            self._set(here)
            self._restart(attempt)
            if self._solve(target, orientation, self.arm, {}) and \
                    not self._touches(self.arm_links, PENETRATION, ignore) and not self._touches(body, 0.0):
                return True
        return False

    def _pulls_from(self, x: float, y: float, yaw: float, ends: tuple[Sequence[float], Sequence[float]],
                    orientation: Sequence[float], into: Sequence[float], drawer: int, values: tuple[float, float],
                    ignore: frozenset[int]) -> bool:
        """Whether the robot, its base starting at (x, y, yaw), holds the handle at both ends of the pull from one
        base pose and torso height: the arm inside nothing (but the handle and the drawer's front) at either, the
        rest of the robot touching nothing with the drawer open, and the pre-grasp before the closed end reached."""
        p, cid = self.p, self.cid
        box = self._base_box(x, y, yaw)
        free = [*self.base, *self.arm]
        body = {j for j in range(p.getNumJoints(self.robot, physicsClientId=cid))} - self.arm_links
        starts = ((h, a, f) for h in self._torso_levels() for a in range(RESTARTS) for f in (0, 1))
        for height, attempt, first in starts:
            self._start((x, y, yaw), height, attempt)
            # one end with the base moving, then the other from the same base pose with the arm alone (from where
            # the first left it, else from the restarts)
            p.resetJointState(self.kitchen, drawer, values[first], physicsClientId=cid)
            if not self._solve(ends[first], orientation, free, box) or \
                    self._touches(self.arm_links, PENETRATION, ignore) or (first == 1 and self._touches(body, 0.0)):
                continue
            if not self._reaches_too(ends[1 - first], orientation, drawer, values[1 - first], ignore, body):
                continue
            solved = self._state()
            pre = [c - APPROACH * a for c, a in zip(ends[0], into)]  # the pre-grasp, touching not even the handle
            if not self._reaches_too(pre, orientation, drawer, values[0], frozenset(), set()):
                continue
            if self._parks_clear(solved):
                return True
        return False


def can_reach(world_file: Path) -> tuple[bool, str]:
    """(whether the robot can reach the counter and the island, what it could not reach)."""
    scene = _Scene(world_file)
    try:
        missed = [name for name in COUNTER_OBJECTS if not scene.takes(name)]
        lo, hi = scene.top(ISLAND_LINK)
        cx, cy, z = (lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2]
        sides = [(lo[0] + ISLAND_INSET, cy, z), (hi[0] - ISLAND_INSET, cy, z),
                 (cx, lo[1] + ISLAND_INSET, z), (cx, hi[1] - ISLAND_INSET, z)]
        if not any(scene.takes(ISLAND_OBJECT, point) for point in sides):
            missed.append(f"the {ISLAND_OBJECT} on the island")
        if not scene.opens(DRAWER_HANDLE, DRAWER_JOINT, OPEN_FRACTION):
            missed.append(f"the drawer, pulled {OPEN_FRACTION:.0%} open")
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
