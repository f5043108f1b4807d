"""Where base-pose candidates come from: a lattice of the floor around the target, and poses in line with a reach line.

The lattice (every STEP metres within the arms' or the camera's range of the target) faces each position to the
target and turns it a little either way. An arm with fewer than six rotating joints keeps its tool in the plane
its pan turns, so it reaches with the tool pointing sideways only on its own reach line, which the lattice misses
by the arm's mount offset: for it, opening a drawer, placing a thing held from the side and taking one from the side
also get the poses that put that line (turned by the pan, for taking) through the handle, the place or the grasp
(tried first); any other arm gets the drawer's in-line poses only once the lattice has failed (deferred).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..planning.head import camera_yaw
from ..robots import Robot
from ..world import Object
from .geometry import (
    STEP,
    ArmGeometry,
    aligned_reach_line,
    hand_length,
    line_poses,
    pick_lines,
    place_headings,
    pull_aligned_poses,
    straight_reach_line,
)
from .scoring import VIEW_DISTANCE
from .spec import LocationSpec

#: turns tried at every position, besides facing the target (rad)
TURNS = (0.0, math.radians(20), -math.radians(20))
#: `Poses.kind`: a lattice pose, an in-line pose tried first, an in-line pose deferred until the others failed
LATTICE, FIRST, DEFERRED = 0, 1, 2


@dataclass(frozen=True)
class InLine:
    """The poses along one arm's reach line (`line_poses`), and for a line a thing is taken along from the side, the
    arm (its index in the location's arms), where its wrist is at the grasp (the same from every pose on the line:
    the reach score measures it instead of the tool, `scoring.add_reach`) and how far the hand sticks out of it."""

    xs: np.ndarray
    ys: np.ndarray
    yaws: np.ndarray
    kind: int  # FIRST or DEFERRED
    arm: int = -1
    wrist: tuple[float, float, float] = (math.nan, math.nan, math.nan)
    hand: float = math.nan


@dataclass(frozen=True)
class Poses:
    """Candidate base poses as arrays: position, heading, how far each is turned from facing the target, and kind;
    `arm`, `wrist` and `hand` as `InLine` gives them (-1 and NaN for the others)."""

    xs: np.ndarray
    ys: np.ndarray
    yaws: np.ndarray
    turns: np.ndarray
    kind: np.ndarray  # LATTICE, FIRST or DEFERRED (int8)
    arm: np.ndarray | None = None  # int8
    wrist: np.ndarray | None = None  # (poses, 3)
    hand: np.ndarray | None = None

    def level(self) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
        """`scoring.add_reach`'s `level`: each pose's arm, wrist and hand, or None when no pose takes a thing level."""
        if self.arm is None or self.wrist is None or self.hand is None or not (self.arm >= 0).any():
            return None
        return self.arm, self.wrist, self.hand


def search_radius(arms: dict[str, ArmGeometry], reaching: bool, camera: np.ndarray | None) -> float:
    """How far from the target candidates stand: an arm's reach from the base's centre, or the camera's range."""
    if reaching:
        return max(float(np.hypot(*a.shoulder[:2])) + a.length for a in arms.values()) + STEP
    return VIEW_DISTANCE[2] + (float(np.hypot(*camera[:2])) if camera is not None else 0.0)


def floor_lattice(target: np.ndarray, radius: float, turned: float, tried: Sequence[float]) -> Poses:
    """The lattice of the floor within `radius` of `target`, each position facing it (less `turned`: a camera fixed
    at an angle to the base's front) and turned by each of `tried`."""
    lo = np.floor((target[:2] - radius) / STEP).astype(int)
    hi = np.ceil((target[:2] + radius) / STEP).astype(int)
    gx, gy = np.meshgrid(np.arange(lo[0], hi[0] + 1) * STEP, np.arange(lo[1], hi[1] + 1) * STEP, indexing="ij")
    px, py = gx.ravel(), gy.ravel()
    keep = np.hypot(px - target[0], py - target[1]) <= radius
    px, py = px[keep], py[keep]
    facing = np.arctan2(target[1] - py, target[0] - px)
    if turned:
        facing = facing - turned
    xs = np.concatenate([px] * len(tried))
    ys = np.concatenate([py] * len(tried))
    turns = np.concatenate([np.full(len(px), t) for t in tried])
    yaws = np.concatenate([facing] * len(tried)) + turns
    return Poses(xs, ys, yaws, turns, np.zeros(len(xs), dtype=np.int8))


def in_line_poses(robot: Robot, spec: LocationSpec, arms: dict[str, ArmGeometry], reach_target: np.ndarray | None,
                  handle_ends: tuple[np.ndarray, np.ndarray] | None) -> list[InLine]:
    """The poses in line with each arm's reach line: facing along a handle's pull (`handle_ends`: closed, opened), for
    each way a held thing may be placed at `reach_target`, or for each way the thing to take may be taken from the
    side (arms that keep their tool in their pan's plane only)."""
    parts: list[InLine] = []
    if handle_ends is not None:
        closed, opened = handle_ends
        for name, geo in arms.items():
            line = aligned_reach_line(robot, name)
            ax, ay, ayaw = pull_aligned_poses(closed, opened,
                                              geo, line if line is not None else straight_reach_line(robot, name))
            parts.append(InLine(ax, ay, ayaw, FIRST if line is not None else DEFERRED))
    elif spec.placing is None and isinstance(spec.reachable_for, Object):
        # an arm that cannot turn its tool freely takes a thing from the side only with its reach line through it
        names = [spec.grasp] if isinstance(spec.grasp, str) else list(robot.description.grasps) if spec.grasp is None else []
        for k, (name, geo) in enumerate(arms.items()):
            line = aligned_reach_line(robot, name)
            if line is None:
                continue
            hand = hand_length(robot, name)
            for point, heading, pan in pick_lines(robot, name, spec.reachable_for, names):
                wrist = point - hand * np.array([math.cos(heading), math.sin(heading), 0.0])
                parts.append(InLine(*line_poses(point, heading, geo, line, pan), FIRST, k,
                                    (float(wrist[0]), float(wrist[1]), float(wrist[2])), hand))
    elif spec.placing is not None and reach_target is not None:
        # an arm that cannot turn its tool freely puts a thing held from the side down only on its reach line
        for name, geo in arms.items():
            line = aligned_reach_line(robot, name)
            if line is None:
                continue
            for point, heading in place_headings(robot, spec.placing, reach_target):
                parts.append(InLine(*line_poses(point, heading, geo, line), FIRST))
    return parts


def candidate_poses(robot: Robot, spec: LocationSpec, arms: dict[str, ArmGeometry], target: np.ndarray,
                    reach_target: np.ndarray | None, fixed_camera: bool, camera: np.ndarray | None,
                    handle_ends: tuple[np.ndarray, np.ndarray] | None) -> Poses:
    """Every base-pose candidate of a location: the lattice around `target`, then the in-line poses within its
    radius (a base that cannot drive gets them all the same: the resolution keeps only where it stands)."""
    reaching = reach_target is not None
    radius = search_radius(arms, reaching, camera)
    turned = camera_yaw(robot) if fixed_camera and not reaching else 0.0  # the camera, not the front, faces it
    # a head or an arm turns the camera to look: facing is enough; a camera fixed on the body needs the turns too
    poses = floor_lattice(target, radius, turned, TURNS if reaching or fixed_camera else TURNS[:1])
    parts = in_line_poses(robot, spec, arms, reach_target, handle_ends) if robot.description.mobile else []
    if not parts:
        return poses
    ax, ay, ayaw = (np.concatenate([getattr(part, k) for part in parts]) for k in ("xs", "ys", "yaws"))
    counts = [len(part.xs) for part in parts]  # each line's values, one per pose on it
    kind = np.repeat([part.kind for part in parts], counts).astype(np.int8)
    arm = np.repeat([part.arm for part in parts], counts).astype(np.int8)
    wrist = np.repeat(np.array([part.wrist for part in parts], dtype=float).reshape(-1, 3), counts, axis=0)
    hand = np.repeat(np.array([part.hand for part in parts], dtype=float), counts)
    near = np.hypot(ax - target[0], ay - target[1]) <= radius
    ax, ay, ayaw, kind, arm, wrist, hand = (a[near] for a in (ax, ay, ayaw, kind, arm, wrist, hand))
    aturn = np.angle(np.exp(1j * (ayaw - np.arctan2(target[1] - ay, target[0] - ax))))
    lattice = len(poses.xs)
    return Poses(np.concatenate([poses.xs, ax]), np.concatenate([poses.ys, ay]), np.concatenate([poses.yaws, ayaw]),
                 np.concatenate([poses.turns, aturn]), np.concatenate([poses.kind, kind]),
                 np.concatenate([np.full(lattice, -1, dtype=np.int8), arm]),
                 np.concatenate([np.full((lattice, 3), np.nan), wrist]), np.concatenate([np.full(lattice, np.nan), hand]))
