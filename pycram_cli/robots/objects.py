"""Object knowledge: how objects of a type are grasped (`resources/objects/grasps.yaml`).

Like robot descriptions, this is data rather than code: a new object type that needs a
special grasp (a bowl by its rim) gets an entry in the file, not a branch in a module.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import yaml

from ..paths import resources_dir


@dataclass(frozen=True)
class GraspPoint:
    offset: tuple[float, float, float]  # tool-frame position in the object's frame (origin: bottom centre)
    width: float  # object width between the fingers there


@functools.lru_cache(maxsize=None)
def _grasp_table() -> dict[str, dict[str, tuple[GraspPoint, ...]]]:
    path = resources_dir() / "objects" / "grasps.yaml"
    if not path.is_file():
        return {}
    data = yaml.safe_load(path.read_text()) or {}
    return {
        object_type: {grasp: tuple(GraspPoint(tuple(float(v) for v in point["offset"]), float(point["width"]))  # type: ignore[arg-type]
                                   for point in points)
                      for grasp, points in grasps.items()}
        for object_type, grasps in data.items()
    }


def grasp_points(object_type: str, grasp: str) -> tuple[GraspPoint, ...]:
    """The special grasp points known for this type and grasp (empty: use the generic rule)."""
    return _grasp_table().get(object_type, {}).get(grasp, ())


def special_grasps(object_type: str) -> tuple[str, ...]:
    """Grasps that have special grasp points for this type (these are the only ones that work for it)."""
    return tuple(_grasp_table().get(object_type, {}))
