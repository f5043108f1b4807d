"""Location designators: where the robot should stand (or an object should go), resolved from the world.

    from pycram_cli.locations import locate
    poses = locate(world, {"reachable-for": "milk"})      # lazy: poses.next() gives the best pose
    pose = poses.next()                                     # BasePose(position, orientation, arm, grasp, ...)
    spot = locate(world, {"on": "kitchen_island_surface", "for": "milk"}).next()   # Spot(position, ...)

A location is a slot value written as a mapping (the `location` kind of `pycram_cli.kinds`):
`{reachable-for: OBJECT|POSE, arm?, grasp?}`, `{visible-for: OBJECT}`, both at once,
`{on: SURFACE, for: OBJECT, near: POSE?}` and `{accessing: HANDLE_LINK}`. It is resolved
lazily into a ranked, deterministic sequence of poses (`resolve.py`): candidates from a map
of the floor (`floor.py`), tested cheapest first, verified with the reasoning queries; an
unsatisfiable location raises `LocationFailure` saying what ruled the candidates out.
This package sits between motion planning (`planning/`, whose geometry it reuses: grasp points, the
head, collisions) and the designators (whose actions use it).
"""
from __future__ import annotations

from typing import Any

from ..robots import Robot
from ..world import BulletWorld, Object
from .floor import FloorMap
from .resolve import (
    REASONS,
    BasePose,
    BasePoseResolution,
    Candidates,
    Spot,
    SpotResolution,
    floor_map,
    resolution,
    summary,
    take_from_here,
)
from .spec import Handle, LocationSpec, Surface, find_handle, find_surface, handle_of, opening_joint, parse_location


def locate(world: BulletWorld, location: Any, for_object: Object | None = None) -> BasePoseResolution | SpotResolution:
    """The lazy resolution of a location mapping (or a parsed `LocationSpec`) in a world."""
    spec = location if isinstance(location, LocationSpec) else parse_location(world, location, for_object)
    return resolution(Robot.of(world), spec)


__all__ = ["REASONS", "BasePose", "BasePoseResolution", "Candidates", "FloorMap", "Handle", "LocationSpec", "Spot",
           "SpotResolution", "Surface", "find_handle", "find_surface", "floor_map", "handle_of", "locate",
           "opening_joint", "parse_location", "resolution", "summary", "take_from_here"]
