"""contact(a, b): are two objects touching? Read from the collision shapes, without stepping the simulation.

The world's closest points see teleports and joint changes at once; objects resting on each other
sit about 1e-5 m apart (often slightly negative), so "touching" means closer than a small
tolerance (default 5 mm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ._common import same_world

if TYPE_CHECKING:
    from ..world import Object

#: how far apart two objects may be for `distance` to still be measured (beyond: inf)
SEARCH_DISTANCE = 0.5


@dataclass(frozen=True)
class ContactAnswer:
    """Truthy when the objects touch. `distance` is the closest distance between them
    (negative when they interpenetrate; inf when more than 0.5 m apart); `links` names the
    touching link pairs (a's link, b's link) when asked for."""

    in_contact: bool
    distance: float
    links: list[tuple[str, str]] = field(default_factory=list)

    def __bool__(self) -> bool:
        return self.in_contact


def contact(a: "Object", b: "Object", tolerance: float = 0.005, links: bool = False) -> ContactAnswer:
    """Whether `a` and `b` are within `tolerance` metres of each other (touching)."""
    if a is b:
        raise ValueError(f"contact needs two different objects, got '{a.name}' twice")
    if not (tolerance >= 0 and math.isfinite(tolerance)):
        raise ValueError(f"tolerance must be a non-negative distance in metres, got {tolerance!r}")
    world = same_world(a, b)
    with world.lock:
        if links:
            points = world.closest_points(a, b, tolerance)
            if points:
                distance = min(pt.distance for pt in points)
                pairs = sorted({(a.get_link_name(pt.link_a), b.get_link_name(pt.link_b)) for pt in points})
                return ContactAnswer(True, float(distance), pairs)
        else:
            distance = world.distance(a, b, tolerance)
            if distance < math.inf:
                return ContactAnswer(True, float(distance), [])
        distance = world.distance(a, b, max(SEARCH_DISTANCE, tolerance))
        return ContactAnswer(False, float(distance), [])
