"""Resolving a location: a ranked, deterministic sequence of poses, the cheapest tests first.

A base-pose location (reachable-for, visible-for, both, accessing) starts from candidate base
poses on a fixed 5 cm lattice of the floor around its target, each turned to face it (and
20° either way). An arm with fewer than six rotating joints keeps its tool in the plane its pan
turns, so it reaches with the tool pointing sideways only on its own reach line: for it, opening a
drawer and placing a thing held from the side also get poses that put that line through the
handle (facing into the drawer, opening or closing it) or the tool's place (for each heading
place may stand the thing in), tried first; any other arm gets the drawer's poses only once the lattice has failed. Every candidate gets a score from cheap geometry (how far its arm's shoulder
is from the target compared with a comfortable reach, how far its camera is from what it
should see, how much it turns away, how far the robot would drive), and the candidates are
tried best first. Each one goes through the tests, cheapest first, and the first to pass them
all is the answer; the resolution is lazy, so asking again continues where it stopped:

1. geometry: the target within the arm's length of the shoulder, the camera's distance
   in range (vectorised over every candidate) — `out of reach`, `out of view`;
2. the floor map (`floor.py`): the robot's footprint on occupied cells — `collide`;
3. the robot's collision shapes at the pose, as navigation tests them — `collide`;
4. reachable-for: inverse kinematics for each arm and grasp (the object's grasp points,
   `cannot hold` when the gripper cannot) and the arm's final configuration touching nothing
   but the target and what it stands on — `out of reach`, `blocked`;
   accessing: accessing's own plan: the handle's grasp and pre-grasp pose reached, the pull followed step
   by step holding it so (the drawer inside nothing of the robot but the hand), the way to the handle
   free, the robot clear of the opened drawer;
5. visible-for: the head turned to the object and the `visible` query — `not visible`.

Only `EXPENSIVE_LIMIT` candidates get tests 4 and 5; the rest count as `not tried`. A location where
an arm reaches (taking, placing, opening or closing) whose candidates all fail with nothing in the way tries them again with
the torso at other heights of its range (`_next_torso`); the pose found says the height. When no
candidate passes, `LocationFailure` says what ruled them out: "412 candidates: 380 collide,
32 out of reach". Everything is computed from the world and the robot's description: no
randomness, no clock; the same world gives the same answer.
"""
from __future__ import annotations

import contextlib
import math
import threading
import weakref
from collections import Counter
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Iterable, Iterator, Mapping, Sequence

import numpy as np

from ..failures import GripperFailure, LocationFailure, ManipulationFailure, ReachabilityFailure
from ..kinds import arm_phrase, arm_words
from ..planning.drawers import DISTANCE, follows_handle, plan_handle_grasp
from ..planning.head import Mount, camera_mount, camera_pitch, camera_yaw, look_at
from ..planning.paths import move_over
from ..planning.pick_place import PLACE_TURNS, grasp_orientation, level, plan_grasp, plan_place, resting_on
from ..planning.reach import reach, rest_configuration, rest_pose
from ..robots import Robot
from ..reasoning import stable, visible
from ..reasoning.supporting import support_points
from ..reasoning.reachability import TakeAnswer, register_take_check
from ..world import Object
from ..world.pose import compose, invert, quat_multiply, quat_to_matrix, yaw_quaternion
from . import floor
from .spec import LocationSpec

if TYPE_CHECKING:
    from ..world import BulletWorld

#: spots on a surface are looked for within this distance (m, along x and y) of `near` or of the robot
SPOT_REACH = 3.0
#: candidate base positions: a lattice of the floor with this spacing (m)
STEP = 0.05
#: turns tried at every position, besides facing the target (rad)
TURNS = (0.0, math.radians(20), -math.radians(20))
#: the comfortable distance from the shoulder to the target, as a fraction of the arm's length
REACH_FRACTION = 0.6
#: visible-for: horizontal distances from the camera to the object (m): comfortable, least, most
VIEW_DISTANCE = (1.0, 0.45, 2.5)
#: a camera fixed on the body: how much of half its vertical view the target may be off its axis
VIEW_FILL = 0.8
#: score weights: per radian turned away, per metre driven, per metre off the comfortable view distance
TURN_WEIGHT = 0.15
TRAVEL_WEIGHT = 0.02
VIEW_WEIGHT = 0.3
#: candidates that get the expensive tests (inverse kinematics, rendering) before the resolution gives up
EXPENSIVE_LIMIT = 40
#: ... times this many while none of them was blocked by something (see BasePoseResolution._patience)
REACH_PATIENCE = 3
#: how hard the ways of an arm and grasp are tried (`move_over`'s options), cheapest first: every arm and grasp is
#: tried straight before any goes around what is in the way, and that before any joint-space search
STRAIGHT = {"around": False, "search": False}
AROUND = {"around": True, "search": False}
SEARCH = {"around": True, "search": True}
#: a reachable-for location that finds no pose with the torso where it is tries at most this many other heights, first
#: those that put the shoulder nearest this fraction of the arm's length above the target (an arm reaches down onto a
#: counter best), none nearer than TORSO_MIN_CHANGE (m) to where the torso is
TORSO_PASSES = 2
TORSO_SHOULDER = 0.25
TORSO_MIN_CHANGE = 0.02
#: the map test runs on this many candidates at a time
CHUNK = 48
#: the robot touches an object when their shapes are closer than this (m)
TOUCH = 0.001
#: spots on a surface: lattice spacing (m) and the free margin kept around the object (m)
SPOT_STEP = 0.025
SPOT_MARGIN = 0.06

#: why a candidate was ruled out, in the order the tests run, and how the reasons read
REASONS = {
    "out of reach": "out of reach",
    "out of view": "out of view",
    "collides": "collide",
    "occupied": "occupied",
    "cannot hold": "cannot hold it",
    "blocked": "blocked",
    "not visible": "not visible",
    "unstable": "unstable",
    "not tried": "not tried",
}


#: outcome codes of candidates (`Candidates.outcome`): 0 not tested yet, 1 passed, then the reasons in order
OUTCOMES = ("", "ok", *REASONS)
CODE = {name: code for code, name in enumerate(OUTCOMES)}


class Candidates:
    """Every candidate of a resolution as arrays (positions, turns, scores, outcomes), and the order they are tried in."""

    def __init__(self, xs: np.ndarray, ys: np.ndarray, yaws: np.ndarray, scores: np.ndarray,
                 outcome: np.ndarray, first: np.ndarray | None = None) -> None:
        self.xs, self.ys, self.yaws, self.scores = xs, ys, yaws, scores
        self.outcome = outcome.astype(np.int8)
        self.first = np.zeros(len(xs), dtype=bool) if first is None else first.astype(bool)
        self.detail: dict[int, str] = {}
        # best first (those marked `first` before the rest); ties by position and turn, so that the order never
        # depends on arithmetic noise
        index = np.arange(len(xs))
        self.order = np.lexsort((index, np.round(ys, 6), np.round(xs, 6), np.round(scores, 9), ~self.first,
                                 outcome != 0))

    def extended(self, more: "Candidates") -> "Candidates":
        """These candidates (their outcomes and details kept) and `more` after them, ordered anew."""
        joined = Candidates(*(np.concatenate([a, b]) for a, b in
                              ((self.xs, more.xs), (self.ys, more.ys), (self.yaws, more.yaws),
                               (self.scores, more.scores), (self.outcome, more.outcome), (self.first, more.first))))
        joined.detail = dict(self.detail)
        return joined

    def __len__(self) -> int:
        return len(self.xs)

    def mark(self, i: int, reason: str, detail: str = "") -> None:
        self.outcome[i] = CODE[reason]
        if detail:
            self.detail[i] = detail

    def counts(self) -> Counter[str]:
        values, numbers = np.unique(self.outcome, return_counts=True)
        return Counter({OUTCOMES[v]: int(n) for v, n in zip(values, numbers) if v >= 2})

    def untested(self) -> int:
        return int((self.outcome == 0).sum())

    def details(self, reason: str) -> list[str]:
        code = CODE[reason]
        return [text for i, text in sorted(self.detail.items()) if self.outcome[i] == code]


@dataclass(frozen=True)
class BasePose:
    """Where the robot's base stands (and, for visible-for, where it looks; for reachable-for, which arm and grasp)."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    yaw: float
    score: float
    arm: str | None = None
    grasp: Any = None
    look_at: tuple[float, float, float] | None = None
    index: int = 0  # the how-manieth pose of its location (0: the first)
    torso: float | None = None  # the torso height the arm reaches from (None: the torso stays where it is)

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {"position": list(self.position), "orientation": list(self.orientation),
                                "yaw": self.yaw, "score": self.score}
        if self.arm is not None:
            data["arm"] = self.arm
        if self.grasp is not None:
            data["grasp"] = self.grasp if isinstance(self.grasp, str) else list(self.grasp)
        if self.look_at is not None:
            data["look-at"] = list(self.look_at)
        if self.torso is not None:
            data["torso"] = self.torso
        return data


@dataclass(frozen=True)
class Spot:
    """Where an object's origin (its bottom centre) goes on a surface, and how it is turned."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    score: float
    surface: str = ""
    index: int = 0

    def to_json(self) -> dict[str, Any]:
        return {"position": list(self.position), "orientation": list(self.orientation), "score": self.score,
                "surface": self.surface}


def summary(counts: Counter[str], total: int) -> str:
    """`412 candidates: 380 collide, 32 out of reach`."""
    parts = [f"{counts[key]} {REASONS[key]}" for key in REASONS if counts.get(key)]
    return f"{total} candidate{'s' if total != 1 else ''}" + (": " + ", ".join(parts) if parts else "")


# -- the robot, as geometry -----------------------------------------------------------------------------


@dataclass(frozen=True)
class ArmGeometry:
    name: str
    shoulder: np.ndarray  # (x, y, z) in the base frame, z above the floor
    length: float  # shoulder to tool frame, stretched out


def arm_geometry(robot: Robot) -> dict[str, ArmGeometry]:
    """Each arm's shoulder (its first joint) in the base frame and its length (the sum of its links)."""
    body = robot.body
    base_pos, base_orn = body.get_pose()
    to_base = invert((base_pos, base_orn))
    found = {}
    for arm in robot.description.arms.values():
        links = [body.joint(j).child_link for j in arm.joints] + [arm.tool_frame]
        points = [np.asarray(compose(to_base, (body.get_link_position(link), (0, 0, 0, 1)))[0]) for link in links]
        length = float(sum(np.linalg.norm(b - a) for a, b in zip(points, points[1:])))
        found[arm.name] = ArmGeometry(arm.name, points[0], length)
    return found


#: an arm with fewer rotating joints than this cannot turn its tool about every axis wherever it reaches
FREE_ORIENTATION_JOINTS = 6


def straight_reach_line(robot: Robot, arm: str) -> float:
    """The lateral offset (m, the base frame's y) of the arm's tool frame with every arm joint at zero: the line
    straight ahead of the robot on which the arm reaches with its tool pointing along the base's x."""
    body = robot.body
    names = list(robot.description.arm(arm).joints)
    tool = robot.description.arm(arm).tool_frame
    with body.joints_kept(names):
        body.reset_joints({n: 0.0 for n in names})
        offset = compose(invert(body.get_pose()), (body.get_link_position(tool), (0, 0, 0, 1)))[0]
    return float(offset[1])


def aligned_reach_line(robot: Robot, arm: str) -> float | None:
    """`straight_reach_line` for an arm that cannot orient its tool freely (fewer than FREE_ORIENTATION_JOINTS
    rotating joints: a pan, pitches and a wrist roll keep the tool in the vertical plane the pan turns, so a front
    grasp, pointing along the base's x, is reachable only on that line); None for an arm that can."""
    body = robot.body
    rotating = sum(1 for n in robot.description.arm(arm).joints if body.joint(n).type in ("revolute", "continuous"))
    return straight_reach_line(robot, arm) if rotating < FREE_ORIENTATION_JOINTS else None


def line_poses(point: Sequence[float], heading: float, arm: ArmGeometry,
               line: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Base poses (xs, ys, yaws) turned to `heading` (rad) with the arm's reach line (`straight_reach_line`) through
    `point`, the shoulder STEP, 2 STEP, ... up to the arm's length short of it: from these an arm that keeps its
    tool in its pan's plane reaches `point` with its tool pointing along `heading`. The lattice's candidates face
    the target from the base's centre and miss that line by the arm's mount offset."""
    into = np.array([math.cos(heading), math.sin(heading)])
    left = np.array([-into[1], into[0]])
    ahead = arm.shoulder[0] + np.arange(1, int(arm.length / STEP) + 1) * STEP  # the point's x in the base frame
    xs = point[0] - ahead * into[0] - line * left[0]
    ys = point[1] - ahead * into[1] - line * left[1]
    return xs, ys, np.full(len(xs), heading)


def pull_aligned_poses(closed: Sequence[float], opened: Sequence[float], arm: ArmGeometry,
                       line: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """`line_poses` for a handle: facing along its pull (from `opened` towards `closed`), the line through the closed
    handle; from these the arm follows the handle all the way open with one front grasp."""
    into = np.asarray(closed[:2], dtype=float) - np.asarray(opened[:2], dtype=float)
    if float(np.hypot(*into)) < 1e-6:
        return np.zeros(0), np.zeros(0), np.zeros(0)
    return line_poses(closed, math.atan2(into[1], into[0]), arm, line)


def place_headings(robot: Robot, obj: Object, target: Sequence[float]) -> list[tuple[np.ndarray, float]]:
    """(tool position, tool heading) for each way place may stand the held `obj` at `target` (`PLACE_TURNS`), where
    the tool points sideways (a tool pointing down turns about the vertical with the wrist: none)."""
    held = invert(robot.body.attachments[obj].transform)
    upright = level(obj.get_orientation(), obj.upright)
    found = []
    for turn in PLACE_TURNS:
        position, orientation = compose((tuple(target), quat_multiply(yaw_quaternion(turn), upright)), held)
        x = quat_to_matrix(orientation)[:, 0]
        if abs(float(x[2])) < 0.7:
            found.append((np.asarray(position, dtype=float), math.atan2(float(x[1]), float(x[0]))))
    return found


def camera_offset(robot: Robot) -> np.ndarray | None:
    """The camera frame in the base frame (None without a camera)."""
    camera = robot.description.camera
    if camera is None:
        return None
    body = robot.body
    to_base = invert(body.get_pose())
    return np.asarray(compose(to_base, (body.get_link_position(camera.frame), (0, 0, 0, 1)))[0])


def _centre(obj: Object) -> np.ndarray:
    lo, hi = obj.get_aabb()
    return (np.asarray(lo) + np.asarray(hi)) / 2.0


# -- the floor map, kept while the world stands still ----------------------------------------------------------

_MAPS: "weakref.WeakKeyDictionary[BulletWorld, tuple[tuple, floor.FloorMap]]" = weakref.WeakKeyDictionary()
_MAPS_LOCK = threading.Lock()  # worlds may resolve locations in threads of their own


def _signature(robot: Robot, held: Sequence[Object]) -> tuple:
    """What the floor map depends on, exactly (a map is reused only for the very same state): every object's
    pose and joints but the robot's base pose (the map is in world coordinates, the robot's footprint in its
    own frame), and what the robot holds, with how it holds it."""
    parts: list[Any] = [tuple((o.id, tuple(robot.body.attachments[o].transform)) for o in held
                              if o in robot.body.attachments)]
    for obj in robot.world.objects:
        joints = tuple(obj.get_joint_positions().values())
        if obj is robot.body or obj in held:
            parts.append((obj.id, joints))
            continue
        pose = obj.get_com_pose()
        parts.append((obj.id, tuple(pose[0]), tuple(pose[1]), joints))
    return tuple(parts)


def floor_map(robot: Robot, held: Sequence[Object], saved: bool = False) -> floor.FloorMap:
    """The floor map for the world as it is (built again whenever anything has moved). `saved`: the caller
    restores the world afterwards (building turns the robot in place)."""
    world = robot.world
    key = _signature(robot, held)
    with _MAPS_LOCK:
        cached = _MAPS.get(world)
    if cached is not None and cached[0] == key:
        return cached[1]
    if saved:
        built = floor.build(robot.body, held)
    else:
        with world.snapshot():
            built = floor.build(robot.body, held)
    with _MAPS_LOCK:
        _MAPS[world] = (key, built)
    return built


# -- touching -----------------------------------------------------------------------------------------------


#: links of what an object rests on that touch the supporting link's box (grown by this much, m) hold it up too
SUPPORT_NEIGHBOURS = 0.005


def supports_of(world: "BulletWorld", obj: Object) -> set[tuple[int, str]]:
    """(object id, link) of everything `obj` rests on: the supporting links, and the links of the same object
    right against them (a counter top's carcass, under it), which fingers closing around a flat object graze."""
    found = set()
    for other in world.objects:
        if other is obj or other.type == "robot":
            continue
        if world.distance(other, obj, 0.005) == math.inf:
            continue
        for link, _ in support_points(other, obj):
            found.add((other.id, link))
            lo, hi = (np.asarray(v) for v in other.get_aabb(link))
            for index in [-1, *range(len(other.joints))]:
                blo, bhi = (np.asarray(v) for v in other.get_aabb(index))
                if np.all(blo <= hi + SUPPORT_NEIGHBOURS) and np.all(bhi >= lo - SUPPORT_NEIGHBOURS):
                    found.add((other.id, other.get_link_name(index)))
    return found


def touching(robot: Robot, held: Sequence[Object], allowed_objects: set[int], allowed_links: set[tuple[int, str]],
             joints: Iterable[str]) -> list[str]:
    """What the part of the robot that `joints` move (and what it holds) touches now, but the allowed objects and
    links (names, sorted). The base, the torso and the wheels on the floor do not move with an arm: not tested."""
    world = robot.world
    body = robot.body
    moving = body.links_below(joints)
    skip = {body.id, *(o.id for o in held)}
    found = set()
    for other in world.objects:
        if other.id in skip or other.id in allowed_objects:
            continue
        for mover in (body, *held):
            points = world.closest_points(mover, other, TOUCH)
            if any((mover is not body or p.link_a in moving)
                   and (other.id, other.get_link_name(p.link_b)) not in allowed_links for p in points):
                found.add(other.name)
                break
    return sorted(found)


def _yaw_of(orientation: Sequence[float]) -> float:
    x, y, z, w = orientation
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def _below(obj: Object, index: int, ancestor: int) -> bool:
    while index != -1:
        if index == ancestor:
            return True
        index = obj.joints[index].parent_index
    return False



class _Resolution:
    """What both kinds of resolution share: candidates tried in order, lazily, and the report when none is left."""

    candidates: Candidates
    spec: LocationSpec

    def __init__(self, robot: Robot, spec: LocationSpec, limit: int) -> None:
        self.robot = robot
        self.spec = spec
        self.limit = limit
        self.cursor = 0
        self.expensive = 0
        self._prepared = False
        self.found: list[Any] = []

    def _prepare(self) -> None:
        raise NotImplementedError

    @property
    def prepared(self) -> bool:
        return self._prepared

    def prepare(self) -> None:
        """The candidates, ranked (resolving does this first; the world is left as it was)."""
        if not self._prepared:
            world = self.robot.world
            with world.lock, world.snapshot():
                self._prepared_inside()

    def _prepared_inside(self) -> None:
        """Inside the caller's snapshot: the candidates, once."""
        if not self._prepared:
            self._prepare()
            self._prepared = True

    def __iter__(self) -> Iterator[Any]:
        while True:
            try:
                yield self.next()
            except LocationFailure:
                return

    def next(self) -> Any:
        raise NotImplementedError

    def counts(self) -> Counter[str]:
        """Why candidates were ruled out so far (those never tested count as `not tried`; none before there are any)."""
        if not self._prepared:
            return Counter()
        counts = self.candidates.counts()
        untested = self.candidates.untested()
        if untested:
            counts["not tried"] += untested
        return counts

    def summary(self) -> str:
        return summary(self.counts(), len(self.candidates) if self._prepared else 0)

    def _fail(self, text: str) -> LocationFailure:
        return LocationFailure(text, location=self.spec.describe(), counts=dict(self.counts()))


# -- base poses -------------------------------------------------------------------------------------------------


class BasePoseResolution(_Resolution):
    """The base poses of one location, best first, found lazily (`next()`; iterate for all)."""

    def __init__(self, robot: Robot, spec: LocationSpec, limit: int = EXPENSIVE_LIMIT) -> None:
        super().__init__(robot, spec, limit)
        self.map: floor.FloorMap | None = None
        self.open_map: floor.FloorMap | None = None
        self.target: np.ndarray | None = None  # the point the candidates face
        self.view_target: np.ndarray | None = None
        self.arm_names: list[str] = []
        self.arm_order = np.zeros((0, 0), dtype=np.int8)
        self._allowed: tuple[set[int], set[tuple[int, str]]] = (set(), set())
        self._handle_path: list[np.ndarray] = []
        #: candidates tried only once all the others failed (with their arm orders): see `_prepare`
        self._deferred: tuple[Candidates, np.ndarray] | None = None
        #: whether the tests may search the arm's joint space for a way (`move_over`'s last resort, about 0.4 s when
        #: no way exists): not at first, so that a pose from which the ways need no search is found without paying
        #: for the searches at the poses before it; the candidates whose test failed only for want of a search
        #: (`_search_wanted`, marked by `_no_search`) are tried again with it once no other is left (`_search`)
        self.searching = False
        self._wanting: list[int] = []
        self._search_wanted = False
        #: whether the robot's current pose is the first candidate (an action asks: no need to drive when it will do)
        self.here = False
        self.here_index: int | None = None
        #: what each arm and grasp ran into at the last pose tested (arm, grasp, why), for take_here's failure
        self.attempts: list[tuple[str, Any, str]] = []
        self.taken: Any = None  # the grasp's IK solution of the last arm and grasp that take the object
        self.shortfall = math.inf  # how far the tool stayed from the nearest grasp out of reach (m)
        #: the torso height the candidates are tried with (None: where it is), the heights still to try, and what the
        #: passes with earlier heights found
        self.torso: float | None = None
        self._torso_todo: list[float] | None = None
        self._passes: list[str] = []

    def take_here(self) -> TakeAnswer:
        """Only the pose the robot stands at, for an object to take: the arm and grasp pick-up itself would take it
        with (its own planning, `_grasp`), or why none does. The base's own contacts where it stands do not count."""
        world = self.robot.world
        self.here = True
        with world.lock, world.snapshot():
            self._prepared_inside()
            i = self.here_index
            assert i is not None
            self.searching = True  # the only pose there is
            found = self._reach(i)
        if found is not None:
            solution = self.taken
            return TakeAnswer(True, found[0], found[1], joint_positions=dict(solution.joint_positions),
                              position_error=solution.position_error, orientation_error=solution.orientation_error)
        arm = self.arm_names[int(self.arm_order[i][0])] if len(self.arm_order) and self.arm_names else None
        return TakeAnswer(False, arm, reason=OUTCOMES[self.candidates.outcome[i]],
                          detail=self.candidates.detail.get(i, ""), tried=tuple(self.attempts),
                          position_error=self.shortfall)

    # -- the candidates ---------------------------------------------------------------------------------------
    def _prepare(self) -> None:
        robot, spec = self.robot, self.spec
        self.held = robot.held_objects()
        self.map = floor_map(robot, self.held, saved=True)
        self.floor_z = self.map.floor_z
        arms = arm_geometry(robot)
        if spec.arm is not None:
            arms = {spec.arm: arms[spec.arm]}
        if spec.placing is not None:
            holding = robot.arm_holding(spec.placing)
            arms = {name: geo for name, geo in arms.items() if name == holding}
        elif spec.reachable_for is not None or spec.accessing is not None:  # a full hand takes nothing, opens nothing
            arms = {name: geo for name, geo in arms.items() if not robot.held_objects(name)}
        if not arms and (spec.reachable_for is not None or spec.accessing is not None):
            if spec.placing is not None:
                why = f"the robot does not hold {spec.placing.name}" + (f" in {arm_phrase(spec.arm)}" if spec.arm else "")
            elif spec.arm is not None:
                why = f"{arm_phrase(spec.arm)} holds {', '.join(o.name for o in robot.held_objects(spec.arm))}"
            else:
                why = "every gripper holds something"
            raise LocationFailure(f"no pose for {spec.describe()}: {why}", location=spec.describe())
        self.arm_names = list(arms)
        camera = camera_offset(robot)
        reach_target = None
        if spec.reachable_for is not None:
            reach_target = (_centre(spec.reachable_for) if isinstance(spec.reachable_for, Object)
                            else np.asarray(spec.reachable_for, dtype=float))
        if spec.accessing is not None:
            handle = spec.accessing
            reach_target = np.asarray(handle.obj.get_link_position(handle.link))
            self._handle_path = self._handle_positions()
            self.open_map = self._opened_map()
        view_target = _centre(spec.visible_for) if spec.visible_for is not None else None
        self.view_target = view_target
        primary = reach_target if reach_target is not None else view_target
        assert primary is not None
        self.target = primary
        if reach_target is not None:
            radius = max(float(np.hypot(*a.shoulder[:2])) + a.length for a in arms.values()) + STEP
        else:
            radius = VIEW_DISTANCE[2] + (float(np.hypot(*camera[:2])) if camera is not None else 0.0)
        # the lattice of the floor around the target, each position facing it (and turned a little either way)
        lo = np.floor((primary[:2] - radius) / STEP).astype(int)
        hi = np.ceil((primary[:2] + radius) / STEP).astype(int)
        gx, gy = np.meshgrid(np.arange(lo[0], hi[0] + 1) * STEP, np.arange(lo[1], hi[1] + 1) * STEP, indexing="ij")
        px, py = gx.ravel(), gy.ravel()
        keep = np.hypot(px - primary[0], py - primary[1]) <= radius
        px, py = px[keep], py[keep]
        facing = np.arctan2(primary[1] - py, primary[0] - px)
        fixed_camera = view_target is not None and camera_mount(robot).kind is Mount.BODY
        if fixed_camera and reach_target is None:  # the camera, not the base's front, faces the object
            facing = facing - camera_yaw(robot)
        # a head or an arm turns the camera to look: facing is enough; a camera fixed on the body needs the turns too
        tried = TURNS if reach_target is not None or fixed_camera else TURNS[:1]
        xs = np.concatenate([px] * len(tried))
        ys = np.concatenate([py] * len(tried))
        turns = np.concatenate([np.full(len(px), t) for t in tried])
        yaws = np.concatenate([facing] * len(tried)) + turns
        lattice = len(xs)
        # an accessing location also stands in line with the pull (`pull_aligned_poses`): first for an arm that cannot
        # turn its tool freely (the lattice misses the line it reaches on), after the lattice for any other arm
        kind = np.zeros(0, dtype=np.int8)  # of the aligned poses: 1 for a constrained arm, 2 deferred
        parts = []
        if spec.accessing is not None and robot.description.mobile:
            # facing into the drawer, opening it or closing it: the handle's closed end is the path's end nearer the
            # joint's lower limit (where `_goal` counts the distance from)
            closed, opened = self._handle_path[0], self._handle_path[-1]
            if self._closing():
                closed, opened = opened, closed
            for name, geo in arms.items():
                line = aligned_reach_line(robot, name)
                ax, ay, ayaw = pull_aligned_poses(closed, opened,
                                                  geo, line if line is not None else straight_reach_line(robot, name))
                parts.append((ax, ay, ayaw, np.full(len(ax), 1 if line is not None else 2, dtype=np.int8)))
        elif spec.placing is not None and reach_target is not None and robot.description.mobile:
            # an arm that cannot turn its tool freely puts a thing held from the side down only on its reach line
            for name, geo in arms.items():
                line = aligned_reach_line(robot, name)
                if line is None:
                    continue
                for point, heading in place_headings(robot, spec.placing, reach_target):
                    ax, ay, ayaw = line_poses(point, heading, geo, line)
                    parts.append((ax, ay, ayaw, np.ones(len(ax), dtype=np.int8)))
        if parts:
            ax, ay, ayaw, kind = (np.concatenate([part[k] for part in parts]) for k in range(4))
            near = np.hypot(ax - primary[0], ay - primary[1]) <= radius
            ax, ay, ayaw, kind = ax[near], ay[near], ayaw[near], kind[near]
            aturn = np.angle(np.exp(1j * (ayaw - np.arctan2(primary[1] - ay, primary[0] - ax))))
            xs, ys, yaws = np.concatenate([xs, ax]), np.concatenate([ys, ay]), np.concatenate([yaws, ayaw])
            turns = np.concatenate([turns, aturn])
        here = np.asarray(robot.body.get_position()[:2])
        scores = TURN_WEIGHT * np.abs(turns) + TRAVEL_WEIGHT * np.hypot(xs - here[0], ys - here[1])
        outcome = np.zeros(len(xs), dtype=np.int8)
        c, s = np.cos(yaws), np.sin(yaws)
        self.arm_order = np.zeros((len(xs), len(arms)), dtype=np.int8)
        if reach_target is not None:
            costs = []
            for geo in arms.values():
                sx = xs + c * geo.shoulder[0] - s * geo.shoulder[1]
                sy = ys + s * geo.shoulder[0] + c * geo.shoulder[1]
                sz = self.floor_z + geo.shoulder[2]
                distance = np.sqrt((reach_target[0] - sx) ** 2 + (reach_target[1] - sy) ** 2 + (reach_target[2] - sz) ** 2)
                cost = np.abs(distance - REACH_FRACTION * geo.length)
                costs.append(np.where(distance > geo.length + 0.02, np.inf, cost))
            stacked = np.stack(costs, axis=1)  # candidates x arms
            best = stacked.min(axis=1)
            order = np.argsort(stacked, axis=1, kind="stable")
            self.arm_order = np.where(np.isfinite(np.take_along_axis(stacked, order, axis=1)), order, -1).astype(np.int8)
            outcome[~np.isfinite(best)] = CODE["out of reach"]
            scores = scores + np.where(np.isfinite(best), best, 0.0)
        if view_target is not None:
            cx = xs + c * camera[0] - s * camera[1] if camera is not None else xs
            cy = ys + s * camera[0] + c * camera[1] if camera is not None else ys
            distance = np.hypot(view_target[0] - cx, view_target[1] - cy)
            out = (distance < VIEW_DISTANCE[1]) | (distance > VIEW_DISTANCE[2])
            if fixed_camera and camera is not None and robot.description.camera is not None:
                # a camera that cannot tilt sees the target only from the distances that put it in its view's height
                off = np.abs(np.arctan2(view_target[2] - (self.floor_z + camera[2]), distance) - camera_pitch(robot))
                out |= off > VIEW_FILL * robot.description.camera.vertical_fov / 2
                scores = scores + VIEW_WEIGHT * off
            outcome[(outcome == 0) & out] = CODE["out of view"]
            scores = scores + VIEW_WEIGHT * np.abs(distance - VIEW_DISTANCE[0])
        todo = outcome == 0
        core = self.map.core_collides(xs[todo], ys[todo], yaws[todo])
        outcome[np.flatnonzero(todo)[core]] = CODE["collides"]
        if not robot.description.mobile:  # a base that cannot drive: only where it stands
            xs, ys, yaws, scores = (np.zeros(0) for _ in range(4))
            outcome, self.arm_order = np.zeros(0, dtype=np.int8), np.zeros((0, len(arms)), dtype=np.int8)
            self.here = True
        first = np.zeros(len(xs), dtype=bool)
        if len(kind):  # the aligned poses of arms that need them go first; the others wait until the lattice fails
            first[lattice:] = kind == 1
            kept = np.ones(len(xs), dtype=bool)
            kept[lattice:] = kind != 2
            later = ~kept
            self._deferred = (Candidates(xs[later], ys[later], yaws[later], scores[later], outcome[later],
                                         np.ones(int(later.sum()), dtype=bool)), self.arm_order[later])
            xs, ys, yaws, scores, outcome, first = xs[kept], ys[kept], yaws[kept], scores[kept], outcome[kept], first[kept]
            self.arm_order = self.arm_order[kept]
        if self.here:  # the pose the robot stands at, tried first (its map test is skipped: it stands there)
            rx, ry = robot.body.get_position()[:2]
            ryaw = _yaw_of(robot.body.get_orientation())
            xs, ys, yaws = np.append(xs, rx), np.append(ys, ry), np.append(yaws, ryaw)
            scores, outcome, first = np.append(scores, -1.0), np.append(outcome, 0), np.append(first, False)
            self.arm_order = np.concatenate([self.arm_order, self._here_arms(arms, reach_target, rx, ry, ryaw)])
            self.here_index = len(xs) - 1
        self.candidates = Candidates(xs, ys, yaws, scores, outcome, first)
        self._allowed = self._allowed_contacts()

    def _here_arms(self, arms: dict[str, ArmGeometry], target: np.ndarray | None, x: float, y: float,
                   yaw: float) -> np.ndarray:
        """The arms to try from the robot's own pose: nearest shoulder first."""
        if target is None or not arms:
            return np.zeros((1, len(arms)), dtype=np.int8)
        c, s = math.cos(yaw), math.sin(yaw)
        distance = [math.dist(target, (x + c * g.shoulder[0] - s * g.shoulder[1], y + s * g.shoulder[0] + c * g.shoulder[1],
                                       self.floor_z + g.shoulder[2])) for g in arms.values()]
        return np.array([sorted(range(len(arms)), key=lambda k: (distance[k], k))], dtype=np.int8)

    def _handle_positions(self) -> list[np.ndarray]:
        """Where the handle is now and where accessing takes it (the location's distance; the drawer put back)."""
        handle = self.spec.accessing
        assert handle is not None
        obj = handle.obj
        start = obj.get_joint_position(handle.joint)
        goal = self._goal(start)
        positions = []
        with obj.joints_kept([handle.joint]):
            for value in (start, goal):
                obj.reset_joints({handle.joint: value})
                positions.append(np.asarray(obj.get_link_position(handle.link)))
        return positions

    def _goal(self, start: float) -> float:
        """Where the accessing process module takes the joint: `distance` above its lower limit (at most to its upper
        limit); the designator's default distance when the location names none."""
        handle = self.spec.accessing
        assert handle is not None
        joint = handle.obj.joint(handle.joint)
        distance = DISTANCE.default if self.spec.distance is None else self.spec.distance
        return min(joint.upper, joint.lower + distance) if joint.limited else start + distance

    def _closing(self) -> bool:
        """Whether accessing pushes the handle towards the joint's lower limit (closes the drawer or door)."""
        handle = self.spec.accessing
        assert handle is not None
        start = handle.obj.get_joint_position(handle.joint)
        return self._goal(start) < start

    def _opened_map(self) -> floor.FloorMap:
        handle = self.spec.accessing
        assert handle is not None
        obj = handle.obj
        with obj.joints_kept([handle.joint]):
            obj.reset_joints({handle.joint: self._goal(obj.get_joint_position(handle.joint))})
            return floor.build(self.robot.body, self.held)

    def _allowed_contacts(self) -> tuple[set[int], set[tuple[int, str]]]:
        """What the arm may touch at its final configuration: the target and what the target rests on."""
        world = self.robot.world
        target = self.spec.reachable_for
        if self.spec.accessing is not None:  # the hand holds the handle: the drawer (or door) may be touched
            handle = self.spec.accessing
            obj = handle.obj
            moving = obj.joint(handle.joint).index
            parts = {obj.get_link_name(moving)} | {j.child_link for j in obj.joints if _below(obj, j.index, moving)}
            return set(), {(obj.id, link) for link in parts}
        if self.spec.placing is not None and self.spec.onto is not None:
            surface = self.spec.onto
            if surface.link is None:
                return {surface.obj.id}, set()
            return set(), {(surface.obj.id, surface.link)}
        if isinstance(target, Object):
            return {target.id}, supports_of(world, target)
        return set(), set()

    # -- the tests ----------------------------------------------------------------------------------------------
    def next(self) -> BasePose:
        """The next base pose (best first); LocationFailure when none is left. A reachable-for location that finds
        none with the torso where it is tries other torso heights (`_next_torso`)."""
        world = self.robot.world
        with world.lock, world.snapshot():
            self._prepared_inside()
            self._set_torso()
            while True:
                pose = self._search()
                if pose is not None:
                    return pose
                if not self._next_torso():
                    break
        raise self._fail(self.failure_message())

    def _search(self) -> BasePose | None:
        """The next candidate that passes every test, or None when none is left (or patience has run out)."""
        order = self.candidates.order
        while self.cursor < len(order) and self.expensive < self._patience():
            chunk = order[self.cursor:self.cursor + CHUNK]
            self._map_test(chunk)
            for i in chunk:
                self.cursor += 1
                if self.candidates.outcome[i] != 0:
                    continue
                pose = self._test(int(i))
                if pose is not None:
                    self.candidates.outcome[i] = CODE["ok"]
                    self.found.append(pose)
                    return pose
                if self.expensive >= self._patience():
                    break
            if self.cursor >= len(order) or self.expensive >= self._patience():
                pose = self._search_again()
                if pose is not None:
                    return pose
                if not self._take_deferred():
                    break
                order = self.candidates.order
        return None

    # -- the torso ----------------------------------------------------------------------------------------------
    def _set_torso(self) -> None:
        """The torso at the height this pass tries (nothing while it stays where it is); what the robot holds follows."""
        joint = self.robot.description.torso_joint
        if self.torso is not None and joint is not None:
            self.robot.body.reset_joints({joint: self.torso})
            self.robot.body.move_attached()

    def _torso_heights(self) -> list[float]:
        """The torso heights to try besides where it is: the bottom, middle and top of its range, those putting some
        arm's shoulder nearest TORSO_SHOULDER (of the arm's length) above the target first, at most TORSO_PASSES."""
        robot, body = self.robot, self.robot.body
        joint = robot.description.torso_joint
        if joint is None or self.target is None or not body.joint(joint).limited:
            return []
        torso = body.joint(joint)
        current = body.get_joint_positions([joint])[joint]
        heights = [h for h in (torso.lower, (torso.lower + torso.upper) / 2.0, torso.upper)
                   if abs(h - current) > TORSO_MIN_CHANGE]
        target_z = float(self.target[2])

        def off(height: float) -> float:
            with body.joints_kept([joint]):
                body.reset_joints({joint: height})
                arms = arm_geometry(robot)
            return min(abs(self.floor_z + arms[name].shoulder[2] - target_z - TORSO_SHOULDER * arms[name].length)
                       for name in self.arm_names)

        return sorted(heights, key=lambda h: (off(h), h))[:TORSO_PASSES]

    def _next_torso(self) -> bool:
        """When no pose reached the target with the torso where it is (and nothing was in the way: that is the plan's
        to move), the candidates anew with the torso at the next height (`_torso_heights`): whether there is one. Only
        locations where an arm reaches (taking, placing, opening or closing) do this; the pose found says the height
        (`torso`)."""
        robot, spec = self.robot, self.spec
        if (robot.description.torso_joint is None or (spec.reachable_for is None and spec.accessing is None)
                or CODE["blocked"] in self.candidates.outcome):
            return False
        if self._torso_todo is None:
            self._torso_todo = self._torso_heights()
        if not self._torso_todo:
            return False
        self._passes.append(self._pass_text())
        self.torso = self._torso_todo.pop(0)
        self._set_torso()
        self._deferred = None
        self._prepare()
        self.cursor, self.expensive = 0, 0
        return True

    def _search_again(self) -> BasePose | None:
        """The next of the candidates whose test failed only for want of a search (in the order they were tried) that
        passes with one, or None when none does. The pose found is the one the tests would have found with searches
        from the start, unless a later candidate passed without one (then that one was found first)."""
        while self._wanting:
            i = self._wanting.pop(0)
            self.searching = True
            try:
                pose = self._test(i)
            finally:
                self.searching = False
            if pose is not None:
                self.candidates.outcome[i] = CODE["ok"]
                self.found.append(pose)
                return pose
        return None

    def _take_deferred(self) -> bool:
        """Add the deferred candidates when all the others failed (tried anew, with patience anew): whether there were."""
        if self._deferred is None or not len(self._deferred[0]):
            return False
        more, arm_order = self._deferred
        self._deferred = None
        self.candidates = self.candidates.extended(more)
        self.arm_order = np.concatenate([self.arm_order, arm_order])
        self.cursor, self.expensive = 0, 0
        return True

    def _map_test(self, chunk: np.ndarray) -> None:
        todo = chunk[(self.candidates.outcome[chunk] == 0) & (chunk != (self.here_index if self.here_index is not None else -1))]
        if not len(todo):
            return
        cand = self.candidates
        assert self.map is not None
        hit = self.map.collides(cand.xs[todo], cand.ys[todo], cand.yaws[todo])
        if self.open_map is not None:
            hit |= self.open_map.collides(cand.xs[todo], cand.ys[todo], cand.yaws[todo])
        cand.outcome[todo[hit]] = CODE["collides"]

    def _test(self, i: int) -> BasePose | None:
        robot, spec, cand = self.robot, self.spec, self.candidates
        x, y, yaw = float(cand.xs[i]), float(cand.ys[i]), float(cand.yaws[i])
        hits = floor.exact_collisions(robot.body, self.held, x, y, yaw)
        if hits:
            cand.mark(i, "collides", ", ".join(hits))
            return None
        if spec.accessing is not None and self._opened_collides(i):
            return None
        self.expensive += 1
        arm, grasp = None, None
        if spec.reachable_for is not None or spec.accessing is not None:
            self._search_wanted = False
            found = self._reach(i)
            if found is None:
                if self._search_wanted and not self.searching:
                    self._wanting.append(i)
                return None
            arm, grasp = found
        look = None
        if spec.visible_for is not None:
            look = self._view(i)
            if look is None:
                return None
        return BasePose((x, y, self.floor_z), yaw_quaternion(yaw), yaw, float(cand.scores[i]), arm, grasp, look,
                        len(self.found), self.torso)

    def _patience(self) -> int:
        """How many candidates get the expensive tests: the limit, or REACH_PATIENCE times it while nothing was found
        blocked (an arm that is merely short of the geometric estimate, as a user's weaker arm is, finds its pose
        farther down the list; something in the way is the plan's to move, and waits for no more tries)."""
        if CODE["blocked"] in self.candidates.outcome:
            return self.limit
        return self.limit * REACH_PATIENCE

    def _opened_collides(self, i: int) -> bool:
        handle = self.spec.accessing
        assert handle is not None
        obj, cand = handle.obj, self.candidates
        with obj.joints_kept([handle.joint]):
            obj.reset_joints({handle.joint: self._goal(obj.get_joint_position(handle.joint))})
            hits = floor.exact_collisions(self.robot.body, self.held, float(cand.xs[i]), float(cand.ys[i]),
                                          float(cand.yaws[i]))
        if hits:
            cand.mark(i, "collides", f"{', '.join(hits)} (opened)")
        return bool(hits)

    def _reach(self, i: int) -> tuple[str, Any] | None:
        """The first arm and grasp (arms nearest first, grasps in the description's order) that reach untouched."""
        robot, spec, cand = self.robot, self.spec, self.candidates
        blocked: list[str] = []
        holdable = False
        arms = [self.arm_names[k] for k in self.arm_order[i] if k >= 0] if len(self.arm_order) else self.arm_names
        target = spec.reachable_for
        if isinstance(target, Object) and spec.placing is None and spec.accessing is None:
            return self._grasp(i, arms, target)
        if spec.placing is not None:
            return self._place(i, arms, spec.placing, target)
        for arm in arms:
            for grasp, position, orientation in self._reach_targets(arm):
                if position is None:
                    continue
                holdable = True
                solution = reach(robot, arm, position, orientation)
                if not solution.success:
                    continue
                if spec.accessing is not None and not self._takes_handle(arm):
                    continue
                if self._touches_at(solution.joint_positions, blocked):
                    continue
                return arm, grasp
        if blocked:
            cand.mark(i, "blocked", ", ".join(blocked))
        elif not holdable and isinstance(spec.reachable_for, Object):
            cand.mark(i, "cannot hold", spec.reachable_for.name)
        else:
            cand.mark(i, "out of reach")
        return None

    def _grasp(self, i: int, arms: list[str], obj: Object) -> tuple[str, Any] | None:
        """The first arm and grasp with which pick-up itself would take `obj` from here: the test is the pick-up
        process module's own planning (pre-grasp and grasp reached, the open gripper inside nothing), so a pose found
        here is one from which the pick-up succeeds; the arm at the grasp then touches nothing but the object and
        what it stands on. An arm and grasp whose ways are straight come before one whose ways must go around
        something (finding that a way round does not exist costs a search: about 0.4 s)."""
        robot, spec, cand = self.robot, self.spec, self.candidates
        blocked: list[str] = []
        holdable = False
        viable: list[tuple[str, Any, Any, Any, dict[str, Any]]] = []
        grasps = [spec.grasp] if spec.grasp is not None else list(robot.description.grasps)
        attempts: dict[tuple[str, Any], str] = {}  # what each arm and grasp ran into (for take_here's failure)
        for arm in arms:
            for grasp in grasps:
                try:
                    _, pre, solution = plan_grasp(robot, arm, obj, grasp)
                except GripperFailure as failure:
                    attempts[arm, grasp] = str(failure)
                    continue
                except ManipulationFailure as failure:
                    holdable = True
                    blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                    attempts[arm, grasp] = str(failure)
                    continue
                except ReachabilityFailure as failure:
                    holdable = True
                    attempts[arm, grasp] = str(failure)
                    self.shortfall = min(self.shortfall, float(failure.details.get("position_error", math.inf)))
                    continue
                holdable = True
                touched: list[str] = []
                if self._touches_at(solution.joint_positions, touched):
                    blocked.extend(n for n in touched if n not in blocked)
                    attempts[arm, grasp] = f"{arm_phrase(arm)} at the grasp would touch {', '.join(touched)}"
                    continue
                legs: dict[str, Any] = {}
                if self._ways_free(obj, arm, pre, solution, STRAIGHT, blocked, legs):
                    self.taken = solution
                    return arm, grasp
                viable.append((arm, grasp, pre, solution, legs))  # its ways may go around what is in the way
        for tier in ((AROUND, SEARCH) if self.searching else (AROUND,)):
            for arm, grasp, pre, solution, legs in viable:
                if self._ways_free(obj, arm, pre, solution, tier, blocked, legs):
                    self.taken = solution
                    return arm, grasp
        self._search_wanted |= bool(viable) and not self.searching
        for arm, grasp, _, _, legs in viable:
            failure = legs.get("pre") if legs.get("pre") is not True else legs.get("rest")
            attempts[arm, grasp] = str(failure) if failure is not None else "its ways are blocked"
        self.attempts = [(arm, grasp, attempts[arm, grasp]) for arm in arms for grasp in grasps
                         if (arm, grasp) in attempts]
        if blocked:
            cand.mark(i, "blocked", ", ".join(blocked))
        elif not holdable:
            cand.mark(i, "cannot hold", obj.name)
        else:
            cand.mark(i, "out of reach")
        return None

    def _touches_at(self, joints: Mapping[str, float], blocked: list[str]) -> bool:
        """Whether the arm at these joint values touches anything but what it may (the target, its support), what
        it touches added to `blocked`; the joints are put back."""
        body = self.robot.body
        saved = body.get_joint_positions(list(joints))
        body.set_joint_positions(joints)
        try:
            touched = touching(self.robot, self.held, *self._allowed, joints)
        finally:
            body.set_joint_positions(saved)
        blocked.extend(t for t in touched if t not in blocked)
        return bool(touched)

    def _ways_free(self, obj: Object, arm: str, pre: Any, solution: Any, tier: dict[str, bool],
                   blocked: list[str], legs: dict[str, Any]) -> bool:
        """Whether the arm's ways are free as pick-up will move it: from where it is to the pre-grasp pose, and from
        the grasp to the pose it will rest in holding the object (the object itself not counted), tried as `tier`
        says (`STRAIGHT`, `AROUND`, `SEARCH`: see `move_over`). What they would hit is added to `blocked`. `legs`
        remembers, across the tiers of one arm and grasp, which way was found free and which way's straight path
        is not (a dearer tier need not walk them again)."""
        robot = self.robot
        body = robot.body
        rest = rest_pose(robot, arm, holding=True)
        with body.joints_kept(list(pre.joint_positions)):
            try:
                if legs.get("pre") is not True:
                    move_over(robot, arm, pre.joint_positions, f"the {arm_words(arm)}'s motion to the pre-grasp pose",
                              straight=legs.get("pre"), **tier)
                    legs["pre"] = True
                if rest is not None and legs.get("rest") is not True:
                    body.reset_joints(solution.joint_positions)  # holding it as grasped: the way to rest holding it so
                    move_over(robot, arm, rest_configuration(robot, arm, holding=True) or {},
                              f"the {arm_words(arm)}'s motion to its {rest} pose", down_onto_goal=False, ignore=[obj],
                              straight=legs.get("rest"), **tier)
                    legs["rest"] = True
            except ManipulationFailure as failure:  # move_over raises its straight path's failure
                legs["pre" if legs.get("pre") is not True else "rest"] = failure
                blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                return False
        return True

    def _place(self, i: int, arms: list[str], obj: Object, target: Any) -> tuple[str, Any] | None:
        """The arm with which place itself would put `obj` down at `target` from here (the place process module's own
        planning), the arm there touching nothing but the surface."""
        robot, cand = self.robot, self.candidates
        body = robot.body
        if robot.arm_holding(obj) is None:  # let go since the resolution began (a step after the place failed)
            raise self._fail(f"no pose for {self.spec.describe()}: the robot no longer holds {obj.name}")
        blocked: list[str] = []
        for arm in arms:
            try:
                _, _, solution, above, _ = plan_place(robot, arm, obj, tuple(float(v) for v in target))
            except (ManipulationFailure, ReachabilityFailure):
                continue
            saved = body.get_joint_positions(list(solution.joint_positions))
            body.set_joint_positions(solution.joint_positions)
            body.move_attached()
            try:
                touched = touching(robot, self.held, *self._allowed, solution.joint_positions)
            finally:
                body.set_joint_positions(saved)
                body.move_attached()
            if touched:
                blocked.extend(t for t in touched if t not in blocked)
                continue
            # and the arm's way, with what it holds, from where it is to above the place, as place will move it
            free = True
            with body.joints_kept(list(above.joint_positions)):
                try:
                    move_over(robot, arm, above.joint_positions, f"the {arm_words(arm)}'s motion above the place",
                              search=self.searching)
                except ManipulationFailure as failure:
                    self._search_wanted = True
                    blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                    free = False
            body.move_attached()  # what it holds back with the arm (joints_kept puts only the joints back)
            if free and self._way_back_free(arm, obj, solution.joint_positions, blocked):
                return arm, None
        if blocked:
            cand.mark(i, "blocked", ", ".join(blocked))
        else:
            cand.mark(i, "out of reach")
        return None

    def _way_back_free(self, arm: str, obj: Object, placed: Mapping[str, float], blocked: list[str]) -> bool:
        """Whether the arm, having let `obj` go at the place (`placed`: its joint values there), finds a way back to the
        pose it rests in empty (an arm that cannot get away from what stands around the place would be stuck there);
        the object itself is not in the way (the arm backs off it first). What is in the way is added to `blocked`."""
        robot = self.robot
        body = robot.body
        rest = rest_configuration(robot, arm, holding=False)
        if rest is None:
            return True
        with _let_go_for_now(obj), body.joints_kept(list(placed)):
            body.reset_joints(placed)
            try:
                move_over(robot, arm, rest, f"the {arm_words(arm)}'s way back from the place", down_onto_goal=False,
                          ignore=[obj], search=self.searching)
            except ManipulationFailure as failure:
                self._search_wanted = True
                blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                return False
        return True

    def _reach_targets(self, arm: str) -> Iterator[tuple[Any, Any, Any]]:
        """(grasp, tool position or None when the gripper cannot hold it so, tool orientation) to try, in order."""
        robot, spec = self.robot, self.spec
        target = spec.reachable_for
        if spec.accessing is not None:
            pull = next(iter(robot.description.grasps), None)
            yield pull, tuple(self._handle_path[0]), grasp_orientation(robot, pull) if pull is not None else None
            return
        grasps = [spec.grasp] if spec.grasp is not None else list(robot.description.grasps)
        for grasp in grasps:  # a position (an object is tested by `_grasp`)
            orientation = grasp_orientation(robot, grasp) if grasp is not None else None
            yield grasp, tuple(target), orientation  # type: ignore[arg-type]
            if spec.grasp is None:
                return  # a position in any orientation: one IK call answers for every grasp

    def _takes_handle(self, arm: str) -> bool:
        """Accessing's own planning takes the handle from here and pulls it to the goal: its grasp (aligned with the handle's
        box, not turned with the base as `_reach`'s first test) and its pre-grasp pose are reached, the arm holding
        the handle so follows it all the way, step by step (`follows_handle`: the drawer then inside no part of
        the robot but the hand, as a robot standing too close would open it into its own arm), and the arm, its
        gripper open as accessing opens it, has a free way from where it is to the pre-grasp pose (`move_over`)."""
        handle = self.spec.accessing
        assert handle is not None
        robot, obj = self.robot, handle.obj
        gripper = robot.description.arm(arm).gripper
        names = list(robot.description.arm(arm).joints) + list(gripper.joints)
        with robot.body.joints_kept(names):
            try:
                robot.body.reset_joints({joint: gripper.open for joint in gripper.joints})
                _, pre, at = plan_handle_grasp(robot, arm, obj, handle.link)
                goal = self._goal(obj.get_joint_position(handle.joint))
                robot.body.reset_joints({joint: gripper.closed for joint in gripper.joints})  # holding the handle
                if not follows_handle(robot, arm, obj, handle.link, handle.joint, goal, at):
                    return False
                robot.body.reset_joints({joint: gripper.open for joint in gripper.joints})
            except (GripperFailure, ReachabilityFailure, ManipulationFailure):
                return False
            try:
                move_over(robot, arm, pre.joint_positions, f"the {arm_words(arm)}'s motion to the handle",
                          search=self.searching)
            except ManipulationFailure:
                self._search_wanted = True
                return False
        return True

    def _view(self, i: int) -> tuple[float, float, float] | None:
        obj = self.spec.visible_for
        assert obj is not None
        target = tuple(float(v) for v in _centre(obj))
        try:
            look_at(self.robot, target, turn_base=False)
        except ReachabilityFailure:  # the camera cannot be pointed there: not from this pose
            self.candidates.mark(i, "out of view", "the camera cannot point at it")
            return None
        answer = visible(obj, world=self.robot.world)
        if not answer.visible:
            self.candidates.mark(i, "not visible", f"{answer.fraction:.0%} seen")
            return None
        return target  # type: ignore[return-value]

    # -- reporting --------------------------------------------------------------------------------------------
    def _pass_text(self) -> str:
        """What this pass's candidates ran into: `412 candidates: 380 collide, 32 out of reach (blocked by cereal)`."""
        text = self.summary()
        blockers = Counter(name for detail in self.candidates.details("blocked") for name in detail.split(", "))
        if blockers:
            text += " (blocked by " + ", ".join(name for name, _ in blockers.most_common()) + ")"
        if self.torso is not None:
            text = f"with the torso at {self.torso:.3f} m, {text}"
        return text

    def failure_message(self) -> str:
        return f"no pose for {self.spec.describe()}: " + "; ".join([*self._passes, self._pass_text()])


# -- spots on a surface ------------------------------------------------------------------------------------


class SpotResolution(_Resolution):
    """Free spots on a surface where an object fits, touches nothing and stands stably, best first."""

    def __init__(self, robot: Robot, spec: LocationSpec, limit: int = 8) -> None:
        assert spec.on is not None and spec.for_object is not None
        super().__init__(robot, spec, limit)
        self.radius = 0.0

    def _prepare(self) -> None:
        spec = self.spec
        surface, obj = spec.on, spec.for_object
        assert surface is not None and obj is not None
        lo, hi = surface.box()
        self.top = float(hi[2])
        self.surface_link = surface.obj.get_link_id(surface.link) if surface.link is not None else None
        self.upright = level(obj.get_orientation(), obj.upright)
        position = obj.get_position()  # inside the caller's snapshot: the object stood upright where it is
        _quiet_let_go(obj)
        obj.set_position_and_orientation(position, self.upright)
        olo, ohi = obj.get_aabb()
        corners = np.array([[olo[0], olo[1]], [olo[0], ohi[1]], [ohi[0], olo[1]], [ohi[0], ohi[1]]]) - np.asarray(position[:2])
        self.radius = float(np.max(np.hypot(corners[:, 0], corners[:, 1])))
        self.height = float(ohi[2] - olo[2])
        inset = self.radius + SPOT_MARGIN
        reference = np.asarray(spec.near[:2]) if spec.near is not None else np.asarray(self.robot.body.get_position()[:2])
        # a surface as large as a floor: only the part within SPOT_REACH of its point nearest the reference (millions
        # of spots else); a table across the room is searched whole
        nearest = np.clip(reference, np.asarray(lo[:2]), np.asarray(hi[:2]))
        lo = (max(lo[0], nearest[0] - SPOT_REACH), max(lo[1], nearest[1] - SPOT_REACH), lo[2])
        hi = (min(hi[0], nearest[0] + SPOT_REACH), min(hi[1], nearest[1] + SPOT_REACH), hi[2])
        ix = np.arange(math.ceil((lo[0] + inset) / SPOT_STEP - 1e-9), math.floor((hi[0] - inset) / SPOT_STEP + 1e-9) + 1)
        iy = np.arange(math.ceil((lo[1] + inset) / SPOT_STEP - 1e-9), math.floor((hi[1] - inset) / SPOT_STEP + 1e-9) + 1)
        gx, gy = np.meshgrid(ix * SPOT_STEP, iy * SPOT_STEP, indexing="ij")
        xs, ys = gx.ravel(), gy.ravel()
        scores = np.hypot(xs - reference[0], ys - reference[1])
        outcome = np.zeros(len(xs), dtype=np.int8)
        detail: dict[int, str] = {}
        for name, (blo, bhi) in self._obstacles():
            near = ((xs > blo[0] - inset) & (xs < bhi[0] + inset) & (ys > blo[1] - inset) & (ys < bhi[1] + inset)
                    & (outcome == 0))
            for k in np.flatnonzero(near):
                detail[int(k)] = name
            outcome[near] = CODE["occupied"]
        self.candidates = Candidates(xs, ys, np.zeros(len(xs)), scores, outcome)
        self.candidates.detail = detail

    def _obstacles(self) -> list[tuple[str, tuple[np.ndarray, np.ndarray]]]:
        """Boxes of whatever stands (or hangs) where the object would be: other objects, other links of the surface's object."""
        spec = self.spec
        surface, obj = spec.on, spec.for_object
        assert surface is not None and obj is not None
        robot = self.robot
        skip = {robot.body.id, obj.id, *(o.id for o in robot.held_objects())}
        low, high = self.top + 0.002, self.top + self.height
        found = []
        for other in robot.world.objects:
            if other.id in skip or (other is surface.obj and surface.link is None):
                continue
            if other is surface.obj:
                links: list[int | None] = [i for i in [-1, *range(len(other.joints))] if other.get_link_name(i) != surface.link]
            else:
                links = [None]
            for link in links:
                blo, bhi = other.get_aabb(link) if link is not None else other.get_aabb()
                if bhi[2] > low and blo[2] < high and bhi[0] - blo[0] > floor.THIN and bhi[1] - blo[1] > floor.THIN:
                    name = other.name if link is None else f"{other.name}/{other.get_link_name(link)}"
                    found.append((name, (np.asarray(blo), np.asarray(bhi))))
        return found

    def next(self) -> Spot:
        world = self.robot.world
        obj, surface = self.spec.for_object, self.spec.on
        assert obj is not None and surface is not None
        with world.lock, world.snapshot() as saved:
            self._prepared_inside()
            cand = self.candidates
            while self.cursor < len(cand) and self.expensive < self.limit:
                i = int(cand.order[self.cursor])
                self.cursor += 1
                if cand.outcome[i] != 0:
                    continue
                self.expensive += 1
                position = (float(cand.xs[i]), float(cand.ys[i]), self.top)
                world.restore_state(saved)
                _quiet_let_go(obj)
                # as place will stand it: its lowest point on the surface, wherever the model's origin is
                obj.set_position_and_orientation(resting_on(obj, self.upright, position, self.top, surface.obj,
                                                            self.surface_link), self.upright)
                hits = self._touching(obj, surface)
                if hits:
                    cand.mark(i, "collides", ", ".join(hits))
                    continue
                answer = stable(obj, observe=0.0)  # the verdict only: how it moves on is not asked
                if not answer.stable:
                    cand.mark(i, "unstable", f"moved {answer.displacement * 1000:.1f} mm")
                    continue
                cand.outcome[i] = CODE["ok"]
                spot = Spot(position, self.upright, float(cand.scores[i]), surface.name, len(self.found))
                self.found.append(spot)
                return spot
        raise self._fail(self.failure_message())

    def _touching(self, obj: Object, surface: Any) -> list[str]:
        world = obj.world
        held = self.robot.held_objects()
        found = []
        for other in world.objects:
            if other is obj or other is self.robot.body or other in held:
                continue
            points = world.closest_points(obj, other, 0.0)
            if any(p.distance < -floor.PENETRATION
                   and not (other is surface.obj and (surface.link is None or other.get_link_name(p.link_b) == surface.link))
                   for p in points):
                found.append(other.name)
        return sorted(found)

    def failure_message(self) -> str:
        assert self.spec.on is not None and self.spec.for_object is not None
        what = f"no spot on {self.spec.on.name} for {self.spec.for_object.name}"
        if not len(self.candidates):
            return f"{what}: the surface is smaller than the object with its margins ({self.radius * 200:.0f} cm across)"
        return f"{what}: {self.summary()}"


@contextlib.contextmanager
def _let_go_for_now(obj: Object) -> Iterator[None]:
    """`with _let_go_for_now(obj):` the object stops following what holds it (no events), and follows it again after,
    at exactly the same offset; where the object stands is put back too."""
    pose = obj.get_pose()
    held = {other: att for other, att in obj.attachments.items() if att.child is obj}
    for other in held:
        del obj.attachments[other]
        other.attachments.pop(obj, None)
    try:
        yield
    finally:
        obj.set_position_and_orientation(*pose)
        for other, att in held.items():
            obj.attachments[other] = att
            other.attachments[obj] = att


def _quiet_let_go(obj: Object) -> None:
    """Inside a snapshot only: the object stops following what holds it, without a detachment event
    (the snapshot's restore brings the attachment back), so that physics can tell whether it stands."""
    for other in list(obj.attachments):
        if obj.attachments[other].child is obj:
            del obj.attachments[other]
            other.attachments.pop(obj, None)


def take_from_here(body: Object, obj: Object, arm: str | None = None, grasp: Any = None) -> TakeAnswer:
    """Whether pick-up would take `obj` from where the robot stands (see `BasePoseResolution.take_here`)."""
    robot = Robot.of(body.world)
    return BasePoseResolution(robot, LocationSpec(reachable_for=obj, arm=arm, grasp=grasp)).take_here()


register_take_check(take_from_here)


def resolution(robot: Robot, spec: LocationSpec) -> BasePoseResolution | SpotResolution:
    """The lazy resolution of a location: `.next()` gives the next pose or spot, best first."""
    return SpotResolution(robot, spec) if spec.on is not None else BasePoseResolution(robot, spec)
