"""The park search of a zoo robot's arm: kinematics over a sphere cover of its shapes, in numpy.

What: `find_park(problem)` tries the arm's pan and pitch joints on a grid and keeps the first configuration tucked
over the base, above its top at every torso height, clear of the body and of itself and, where it can be, out of
the body camera's view of the counter in front.
Why: a robot's description needs a park pose; pybullet is not needed to find one, and thousands of candidates are
rated at once.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..urdf_writer import rpy_matrix
from .model import PARK_HEIGHT, X_AXIS, Z_AXIS, Joint, Link, Shape, Vec3

# -- kinematics and a sphere cover, for the park search --------------------------------------------------------


def _axis_rotations(axis: Sequence[float], angles: np.ndarray) -> np.ndarray:
    """Rotation matrices (N, 3, 3) about a unit axis by each angle (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    s, c = np.sin(angles)[:, None, None], np.cos(angles)[:, None, None]
    return np.eye(3) + s * kx + (1 - c) * (kx @ kx)


def _spheres(shape: Shape) -> tuple[np.ndarray, np.ndarray]:
    """Spheres (centres in link coordinates, radii) whose union covers the shape."""
    rot, centre = rpy_matrix(shape.rpy), np.asarray(shape.xyz, dtype=float)
    if shape.kind == "sphere":
        return centre[None, :], np.array([shape.dims[0]])
    if shape.kind == "cylinder":
        radius, length = shape.dims
        count = max(1, math.ceil(length / radius))
        step = length / count
        along = np.linspace(-length / 2 + step / 2, length / 2 - step / 2, count)
        local = np.column_stack([np.zeros(count), np.zeros(count), along])
        return centre + local @ rot.T, np.full(count, math.hypot(radius, step / 2))
    dims = np.asarray(shape.dims, dtype=float)
    cell = max(float(dims.min()) / 2, 0.015)
    counts = [max(1, math.ceil(d / cell)) for d in dims]
    axes = [np.linspace(-d / 2 + d / (2 * n), d / 2 - d / (2 * n), n) for d, n in zip(dims, counts)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    half = np.array([d / (2 * n) for d, n in zip(dims, counts)])
    return centre + grid @ rot.T, np.full(len(grid), float(np.linalg.norm(half)))


@dataclass(frozen=True)
class Obstacle:
    """An axis-aligned box of the body in the floor frame (torso at its default)."""

    lo: tuple[float, float, float]
    hi: tuple[float, float, float]


def _box_distance(points: np.ndarray, obstacle: Obstacle) -> np.ndarray:
    lo, hi = np.asarray(obstacle.lo), np.asarray(obstacle.hi)
    outside = np.maximum(np.maximum(lo - points, points - hi), 0.0)
    return np.linalg.norm(outside, axis=-1)


@dataclass(frozen=True)
class ParkProblem:
    """What the park search needs: the arm's subtree, where it is mounted, and the body to keep clear of."""

    joints: tuple[Joint, ...]  # the arm's subtree, parents first (its first joint is the pan joint)
    links: dict[str, Link]
    arm_joints: tuple[str, ...]
    up_sign: dict[str, float]
    mount: Vec3  # the pan joint in the floor frame, torso at its default
    hand: frozenset[str]  # links rigid with the palm (their pairs are not checked)
    obstacles: tuple[Obstacle, ...]
    base_shape: str
    base_radius: float
    floor_z: float  # every arm sphere stays above this (the base top plus the torso's default plus a margin)
    sight: tuple[float, float] | None  # the camera (x, z) on the body; the parked arm stays below its view of the counter


def _limits(joint: Joint) -> tuple[float, float]:
    """An arm joint's range (the zoo's arm joints are all limited)."""
    assert joint.lower is not None and joint.upper is not None, joint.name
    return joint.lower, joint.upper


def _candidates(problem: ParkProblem, steps: int = 13) -> np.ndarray:
    """Joint values (N, arm joints) to try: the pan at 0, ±45°, ±90° or ±135°, the rolls and slides at 0, the pitches
    on a grid."""
    axes: list[np.ndarray] = []
    for name in problem.arm_joints:
        joint = next(j for j in problem.joints if j.name == name)
        if name == problem.arm_joints[0]:
            pans = (0.0, math.pi / 4, -math.pi / 4, math.pi / 2, -math.pi / 2, 3 * math.pi / 4, -3 * math.pi / 4)
            low, high = _limits(joint)
            axes.append(np.array([v for v in pans if low <= v <= high]))
        elif name in problem.up_sign:
            low, high = _limits(joint)
            axes.append(np.linspace(low, high, steps + 2)[1:-1])
        else:
            axes.append(np.array([0.0]))
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(axes))


def _link_spheres(problem: ParkProblem, values: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each arm link's sphere centres (N, k, 3) in the floor frame and radii (k,), for N joint value rows."""
    count = len(values)
    frames: dict[str, np.ndarray] = {}
    root = np.tile(np.eye(4), (count, 1, 1))
    root[:, :3, 3] = problem.mount
    column = {name: i for i, name in enumerate(problem.arm_joints)}
    out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for joint in problem.joints:
        local = np.eye(4)
        local[:3, :3] = rpy_matrix(joint.rpy)
        parent = frames.get(joint.parent)
        if parent is None:  # the pan joint: at the mount
            base = root @ local
        else:
            local[:3, 3] = joint.xyz
            base = parent @ local
        q = values[:, column[joint.name]] if joint.name in column else np.zeros(count)
        motion = np.tile(np.eye(4), (count, 1, 1))
        if joint.type in ("revolute", "continuous"):
            motion[:, :3, :3] = _axis_rotations(joint.axis or Z_AXIS, q)
        elif joint.type == "prismatic":
            motion[:, :3, 3] = np.outer(q, joint.axis or X_AXIS)
        frames[joint.child] = base @ motion
        link = problem.links[joint.child]
        if link.shapes:
            pieces = [_spheres(shape) for shape in link.shapes]
            centres = np.concatenate([c for c, _ in pieces])
            radii = np.concatenate([r for _, r in pieces])
            # R·c for every row and centre, as one matrix product (einsum's loop is several times slower here)
            world = np.matmul(frames[joint.child][:, :3, :3], centres.T).transpose(0, 2, 1) + frames[joint.child][:, None, :3, 3]
            out[joint.child] = (world, radii)
    return out


@dataclass(frozen=True)
class _Rating:
    """How each row of joint values does: breaks of the body rules, how far past the footprint, how low."""

    body: np.ndarray  # how far it breaks the rules against the body (0: none)
    outside: np.ndarray  # how far the arm reaches past the base's footprint (m)
    lowest: np.ndarray  # the lowest point of the arm past the pan link (m)
    highest: np.ndarray  # its highest point (m)
    in_view: np.ndarray  # how far the arm reaches into the body camera's view of the counter (m)


def _rate(problem: ParkProblem, spheres: dict[str, tuple[np.ndarray, np.ndarray]], count: int) -> _Rating:
    first = problem.joints[0].child  # the pan link: fixed to the body, not checked against it
    bad, outside = np.zeros(count), np.zeros(count)
    lowest, highest = np.full(count, np.inf), np.full(count, -np.inf)
    in_view = np.zeros(count)
    for name, (centres, radii) in spheres.items():
        bottom = centres[..., 2] - radii
        bad += np.maximum(problem.floor_z - bottom, 0.0).max(axis=1)
        if problem.base_shape == "box":
            reach = np.maximum(np.abs(centres[..., 0]), np.abs(centres[..., 1])) + radii
        else:
            reach = np.hypot(centres[..., 0], centres[..., 1]) + radii
        outside = np.maximum(outside, (reach - problem.base_radius).max(axis=1))
        if name == first:
            continue
        lowest = np.minimum(lowest, bottom.min(axis=1))
        highest = np.maximum(highest, (centres[..., 2] + radii).max(axis=1))
        if problem.sight is not None:
            in_view = np.maximum(in_view, _into_view(problem.sight, centres, radii))
        for obstacle in problem.obstacles:
            bad += np.maximum(0.02 - (_box_distance(centres, obstacle) - radii), 0.0).max(axis=1)
    return _Rating(bad, outside, lowest, highest, in_view)


#: what a camera on the body must see past the parked arm: things this high (m) this far in front of the base (m)
VIEW_TARGET = (0.55, 0.85)


def _into_view(sight: tuple[float, float], centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """How far (m) spheres in front of the camera reach above its line of sight down to VIEW_TARGET (x-z plane):
    above it, the parked arm would hide the counter's front from the camera."""
    (cx, cz), (tx, tz) = sight, VIEW_TARGET
    x = centres[..., 0]
    line = cz + (x - cx) * (tz - cz) / (tx - cx)
    above = centres[..., 2] + radii + 0.02 - line
    return np.where(x + radii > cx - 0.05, np.maximum(above, 0.0), 0.0).max(axis=1)


def _self_clear(problem: ParkProblem, spheres: dict[str, tuple[np.ndarray, np.ndarray]], rows: np.ndarray) -> np.ndarray:
    """Whether, in each of the rows, links not joined to each other keep 1.5 cm apart (the hand counts as one)."""
    parents = {j.child: j.parent for j in problem.joints}
    clear = np.ones(len(rows), dtype=bool)
    names = sorted(spheres)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if parents.get(a) == b or parents.get(b) == a or (a in problem.hand and b in problem.hand):
                continue
            (ca, ra), (cb, rb) = spheres[a], spheres[b]
            gap = np.linalg.norm(ca[rows][:, :, None, :] - cb[rows][:, None, :, :], axis=-1) - ra[:, None] - rb[None, :]
            clear &= gap.reshape(len(rows), -1).min(axis=1) >= 0.015
    return clear


def find_park(problem: ParkProblem) -> tuple[float, ...]:
    """A park pose: clear of the body and of itself; out of the body camera's view of the counter and within the
    tightest footprint (up to 0.2 m past the base's edge) that allows one, else in its view, else farther out; its
    lowest point as high as it goes up to PARK_HEIGHT (above the counters and what stands on them), its highest as
    low as can be."""
    values = _candidates(problem)
    spheres = _link_spheres(problem, values)
    rating = _rate(problem, spheres, len(values))
    near = [(view, tolerance) for view in (0.0, math.inf) for tolerance in (0.0, 0.05, 0.1, 0.2)]
    far = [(view, tolerance) for tolerance in (0.4, math.inf) for view in (0.0, math.inf)]
    for view, tolerance in near + far:  # the view kept free, the arm within 0.2 m of the footprint, first
        rows = np.flatnonzero((rating.body <= 0.0) & (rating.outside <= tolerance) & (rating.in_view <= view))
        rows = rows[np.lexsort((rating.highest[rows], -np.minimum(rating.lowest[rows], PARK_HEIGHT)))]
        for start in range(0, len(rows), 256):  # the highest first; self-collision is checked on few rows
            chunk = rows[start:start + 256]
            clear = np.flatnonzero(_self_clear(problem, spheres, chunk))
            if len(clear):
                return tuple(round(float(v), 3) + 0.0 for v in values[chunk[clear[0]]])
    raise ValueError("no park pose clear of the body")

