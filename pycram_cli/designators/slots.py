"""Slot value kinds: how a slot's value is written in a plan and checked before anything runs."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

ARMS = ("left", "right")
GRASPS = ("front", "top", "left", "right")


def _numbers(value: Any, sizes: tuple[int, ...]) -> bool:
    return (isinstance(value, (list, tuple)) and len(value) in sizes
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in value))


def _check_position(value: Any) -> str | None:
    return None if _numbers(value, (3,)) else "expected a position [x, y, z]"


def _check_quaternion(value: Any) -> str | None:
    if not _numbers(value, (4,)):
        return "expected a quaternion [x, y, z, w]" + (" (got 3 numbers)" if _numbers(value, (3,)) else "")
    norm = math.sqrt(sum(v * v for v in value))
    return None if abs(norm - 1) <= 1e-3 else f"quaternion must have unit length, got norm {norm:.4g}"


def _check_object(value: Any) -> str | None:
    return None if isinstance(value, str) and value else "expected an object name"


def _check_arm(value: Any) -> str | None:
    return None if value in ARMS else f"expected one of {', '.join(ARMS)}"


def _check_number(value: Any) -> str | None:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    return None if ok else "expected a number"


def _check_name(value: Any) -> str | None:
    return None if isinstance(value, str) and value else "expected a name"


def _check_grasp(value: Any) -> str | None:
    if value in GRASPS:
        return None
    if _numbers(value, (4,)):
        return _check_quaternion(value)
    return f"expected one of {', '.join(GRASPS)} or a quaternion [x, y, z, w]"


def _check_arm_config(value: Any) -> str | None:
    if isinstance(value, str) and value:
        return None  # a named pose; checked against the robot description when resolved
    if _numbers(value, tuple(range(1, 16))):
        return None
    if isinstance(value, dict) and value and all(isinstance(k, str) and _check_number(v) is None for k, v in value.items()):
        return None
    return "expected a named pose (e.g. park), a list of joint values, or a mapping joint: value"


@dataclass(frozen=True)
class SlotKind:
    name: str
    description: str
    check: Callable[[Any], str | None]


KINDS: dict[str, SlotKind] = {k.name: k for k in (
    SlotKind("position", "[x, y, z] in metres, world frame", _check_position),
    SlotKind("quaternion", "[x, y, z, w], unit length", _check_quaternion),
    SlotKind("object", "an object name (or a $variable bound to an object)", _check_object),
    SlotKind("arm", "left or right", _check_arm),
    SlotKind("number", "a number", _check_number),
    SlotKind("joint", "a joint name of the part-of object", _check_name),
    SlotKind("link", "a link name of the part-of object", _check_name),
    SlotKind("object-type", "an object type, e.g. milk", _check_name),
    SlotKind("grasp", "front, top, left, right or a quaternion", _check_grasp),
    SlotKind("arm-config", "a named pose (park), joint values in order, or {joint: value}", _check_arm_config),
    SlotKind("position-or-object", "[x, y, z] or an object name", lambda v: None if isinstance(v, str) and v else _check_position(v)),
)}
