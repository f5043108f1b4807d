"""contact(a, b): are two objects touching? Read from the collision shapes, without stepping the simulation.

The world's closest points see teleports and joint changes at once; objects resting on each other
sit about 1e-5 m apart (often slightly negative), so "touching" means closer than a small
tolerance (default 5 mm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..errors import BadValue
from ..signature import Param
from ._common import same_world
from .query import AN_OBJECT, Call, QueryAnswer, QuerySpec, declare_query, finite, mm, parameters

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


def contact(a: Object, b: Object, tolerance: float = 0.005, links: bool = False) -> ContactAnswer:
    """Whether `a` and `b` are within `tolerance` metres of each other (touching)."""
    if a is b:
        raise BadValue(f"contact needs two different objects, got '{a.name}' twice")
    if not (tolerance >= 0 and math.isfinite(tolerance)):
        raise BadValue(f"tolerance must be a non-negative distance in metres, got {tolerance!r}")
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


# -- the query, by name (plans, `pycram query`, docs) --------------------------------------------------


def _contact(call: Call) -> QueryAnswer:
    a, b = call.object("a"), call.object("b")
    if a is b:
        raise call.error("b", f"contact needs two different objects, got '{a.name}' twice")
    answer = contact(a, b, links=True)
    return QueryAnswer("contact", call.resolved, answer.in_contact,
                       {"distance": finite(answer.distance), "links": [list(pair) for pair in answer.links]},
                       answer.in_contact)


def _say_contact(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    if answer.result:
        links = ", ".join(f"{x}–{y}" for x, y in d["links"])
        return f"{a['a']} and {a['b']} are in contact (distance {mm(d['distance'])}; touching: {links})"
    far = "more than 0.5 m" if d["distance"] is None else mm(d["distance"])
    return f"{a['a']} and {a['b']} are not in contact (distance {far})"


declare_query(QuerySpec(
    "contact", "Are the two objects touching (within 5 mm)?",
    parameters(Param("a", "object", True, AN_OBJECT, positional=True), Param("b", "object", True, AN_OBJECT, positional=True)),
    _contact, _say_contact))
