"""Validation and arithmetic of positions and quaternions (x, y, z, w).

Poses are checked at the boundary: a wrong shape or a non-unit quaternion raises
a BadValue (a ValueError) that names the expected and the actual shape or norm.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any, cast

import numpy as np

from ..errors import BadValue

Vec3 = tuple[float, float, float]
Quat = tuple[float, float, float, float]

QUAT_TOLERANCE = 1e-3


def _numbers(value: object, what: str, size: int) -> list[float]:
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise BadValue(f"{what}: expected {size} numbers, got {type(value).__name__} {value!r}")
    items = list(cast(Iterable[Any], value))  # it has a length and is no string: a sequence
    if len(items) != size:
        raise BadValue(f"{what}: expected {size} numbers, got {len(items)}: {items!r}")
    out = []
    for item in items:
        if isinstance(item, bool) or not isinstance(item, (int, float, np.floating, np.integer)):
            raise BadValue(f"{what}: expected {size} numbers, got {item!r} ({type(item).__name__})")
        if not math.isfinite(float(item)):
            raise BadValue(f"{what}: expected finite numbers, got {item!r}")
        out.append(float(item))
    return out


def vec3(values: Iterable[Any]) -> Vec3:
    """Three numbers as a float triple (a numpy row, a list): the `Vec3` the rest of the code passes around."""
    x, y, z = (float(v) for v in values)
    return (x, y, z)


def check_position(value: object, what: str = "position") -> Vec3:
    x, y, z = _numbers(value, what, 3)
    return (x, y, z)


def check_quaternion(value: object, what: str = "orientation") -> Quat:
    q = _numbers(value, what + " (quaternion x, y, z, w)", 4)
    norm = math.sqrt(sum(c * c for c in q))
    if abs(norm - 1.0) > QUAT_TOLERANCE:
        raise BadValue(f"{what}: quaternion must have unit length, got norm {norm:.6g} for {q!r}")
    return (q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm) if norm != 1.0 else (q[0], q[1], q[2], q[3])


def quat_to_matrix(q: Sequence[float]) -> np.ndarray:
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def quats_to_matrices(quats: np.ndarray) -> np.ndarray:
    """`quat_to_matrix` for an (n, 4) array of quaternions at once, (n, 3, 3): the same arithmetic, element by
    element, so the same numbers, bitwise."""
    x, y, z, w = quats[:, 0], quats[:, 1], quats[:, 2], quats[:, 3]
    m = np.empty((len(quats), 3, 3))
    m[:, 0, 0], m[:, 0, 1], m[:, 0, 2] = 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)
    m[:, 1, 0], m[:, 1, 1], m[:, 1, 2] = 2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)
    m[:, 2, 0], m[:, 2, 1], m[:, 2, 2] = 2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)
    return m


def matrix_to_quat(m: np.ndarray) -> Quat:
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0:
        s = 0.5 / math.sqrt(trace + 1.0)
        w, x, y, z = 0.25 / s, (m[2, 1] - m[1, 2]) * s, (m[0, 2] - m[2, 0]) * s, (m[1, 0] - m[0, 1]) * s
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        w, x, y, z = (m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        w, x, y, z = (m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        w, x, y, z = (m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s
    n = math.sqrt(x * x + y * y + z * z + w * w)
    return (x / n, y / n, z / n, w / n)


def quat_multiply(a: Sequence[float], b: Sequence[float]) -> Quat:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def quat_inverse(q: Sequence[float]) -> Quat:
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Sequence[float], v: Sequence[float]) -> Vec3:
    """`v` turned by the quaternion `q`: `quat_to_matrix(q) @ v`, in plain floats (a hot path: every held object
    follows its hand at every step of a checked motion, and numpy's overhead on three numbers is most of the cost)."""
    x, y, z, w = (float(c) for c in q)
    vx, vy, vz = (float(c) for c in v)
    return ((1 - 2 * (y * y + z * z)) * vx + 2 * (x * y - z * w) * vy + 2 * (x * z + y * w) * vz,
            2 * (x * y + z * w) * vx + (1 - 2 * (x * x + z * z)) * vy + 2 * (y * z - x * w) * vz,
            2 * (x * z - y * w) * vx + 2 * (y * z + x * w) * vy + (1 - 2 * (x * x + y * y)) * vz)


def compose(a: tuple[Sequence[float], Sequence[float]], b: tuple[Sequence[float], Sequence[float]]) -> tuple[Vec3, Quat]:
    """a ∘ b: the pose b expressed in a's frame, brought into the frame a is in."""
    (pa, qa), (pb, qb) = a, b
    rp = rotate(qa, pb)
    return (pa[0] + rp[0], pa[1] + rp[1], pa[2] + rp[2]), quat_multiply(qa, qb)


def invert(a: tuple[Sequence[float], Sequence[float]]) -> tuple[Vec3, Quat]:
    p, q = a
    qi = quat_inverse(q)
    rp = rotate(qi, p)
    return (-rp[0], -rp[1], -rp[2]), qi


def angle_between(a: Sequence[float], b: Sequence[float]) -> float:
    """The rotation angle (radians, 0..π) between two orientations."""
    d = abs(sum(x * y for x, y in zip(a, b)))
    return 2.0 * math.acos(min(1.0, d))


def yaw_quaternion(yaw: float) -> Quat:
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


_H = math.sqrt(0.5)
#: the model axis that points up -> the turn (about x or y) that stands a model with that axis up upright
UP_TURNS: dict[str, Quat] = {"z": (0.0, 0.0, 0.0, 1.0), "y": (_H, 0.0, 0.0, _H), "x": (0.0, -_H, 0.0, _H),
                             "-z": (1.0, 0.0, 0.0, 0.0), "-y": (-_H, 0.0, 0.0, _H), "-x": (0.0, _H, 0.0, _H)}


def up_axis(orientation: Sequence[float]) -> str:
    """The model axis (z, y, x, -z, -y, -x) that points most nearly up in this orientation."""
    column = quat_to_matrix(orientation)[2]  # the world z component of each model axis
    scores = {"z": column[2], "y": column[1], "x": column[0], "-z": -column[2], "-y": -column[1], "-x": -column[0]}
    return max(scores, key=lambda axis: (scores[axis], -list(scores).index(axis)))
