"""Object knowledge: how objects of a type are grasped (`resources/objects/grasps.yaml`).

Like robot descriptions, this is data rather than code: a new object type that needs a
special grasp (a bowl by its rim) or is round (a bottle) gets an entry in the file, not a
branch in a module. Everything is given in the object's own frame and relative to its box
in that frame (the box of its collision shapes), so it holds whatever the mesh's origin.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any

import yaml

from ..paths import resources_dir

#: how an object looks the same turned about its own z axis: by quarter turns of its box, or by any angle
SYMMETRIES = ("box", "revolution")


@dataclass(frozen=True)
class GraspPoint:
    """Where the tool frame goes for a special grasp, in the grasp's object frame (see `planning/grasps.py`):
    `at` a point of the object's box in half-extents from its centre (-1 .. 1 per axis: [0, -1, 1] is the
    middle of the box's top edge on its -y side), plus `offset` metres; `width`: how much of the object is then
    between the fingers."""

    at: tuple[float, float, float]
    offset: tuple[float, float, float]
    width: float


@dataclass(frozen=True)
class ObjectKnowledge:
    symmetry: str = "box"
    grasps: dict[str, tuple[GraspPoint, ...]] = field(default_factory=dict)


def _triple(value: Any, default: tuple[float, float, float]) -> tuple[float, float, float]:
    if value is None:
        return default
    x, y, z = (float(v) for v in value)
    return (x, y, z)


def _knowledge(entry: dict) -> ObjectKnowledge:
    symmetry = str(entry.get("symmetry", "box"))
    if symmetry not in SYMMETRIES:
        raise ValueError(f"grasps.yaml: symmetry must be one of {', '.join(SYMMETRIES)}, got {symmetry!r}")
    grasps = {
        str(grasp): tuple(GraspPoint(_triple(point.get("at"), (0.0, 0.0, -1.0)), _triple(point.get("offset"), (0.0, 0.0, 0.0)),
                                     float(point["width"])) for point in points)
        for grasp, points in (entry.get("grasps") or {}).items()
    }
    return ObjectKnowledge(symmetry, grasps)


@functools.cache
def _table() -> dict[str, ObjectKnowledge]:
    path = resources_dir() / "objects" / "grasps.yaml"
    if not path.is_file():
        return {}
    data = yaml.safe_load(path.read_text()) or {}
    return {str(object_type): _knowledge(entry or {}) for object_type, entry in data.items()}


def object_knowledge(object_type: str) -> ObjectKnowledge:
    """What is known of objects of this type (a box-like object with no special grasps when nothing is)."""
    return _table().get(object_type, ObjectKnowledge())

