"""supporting(a, b): does `a` carry `b` — b above a, touching it, through a roughly horizontal contact?

The design compared z coordinates and asked `contact`; comparing origins fails for objects
whose origin is not where they rest (a kitchen's origin is on the floor, a shelf's anywhere),
so here the contact itself decides: at least one contact point between them whose normal
is within ~45° of vertical, with b's centre above that point.

"Contact" here is real contact: the collision shapes are at most 1 mm apart (`TOLERANCE`). An
object at rest sits about 1e-5 m from its support (often slightly inside it), and objects are
spawned and placed within PyBullet's 1 mm collision margin of their support, so 1 mm tells resting
from hovering: a milk carton 2 mm above the counter is not carried by it. (`contact` keeps its
looser 5 mm, the design's "touching".)
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from ..errors import BadValue, did_you_mean
from ..signature import Param
from ._common import same_world
from .query import Call, QueryAnswer, QuerySpec, declare_query, parameters

if TYPE_CHECKING:
    from ..world import Object

#: |n_z| of the contact normal: above this the contact is "roughly horizontal" (about 45°)
MIN_NORMAL_Z = 0.7
#: how far apart b may be from a and still rest on it (m): real contact, not the 5 mm of `contact`
TOLERANCE = 0.001


def support_points(a: Object, b: Object, tolerance: float = TOLERANCE) -> list[tuple[str, tuple[float, float, float]]]:
    """The contact points where `a` holds `b` up: (a's link name, point on a)."""
    if a is b:
        raise BadValue(f"supporting needs two different objects, got '{a.name}' twice")
    world = same_world(a, b)
    with world.lock:
        # b first, a second: the normal on the second points from a towards b (up, when b rests on a)
        points = world.closest_points(b, a, tolerance)
        if not points:
            return []
        lo, hi = b.get_aabb(-1) if not b.joints else b.get_aabb()
        centre_z = (lo[2] + hi[2]) / 2.0
        found = []
        for pt in points:
            normal_z = pt.normal_on_b[2]
            on_a = pt.position_on_b
            if normal_z > MIN_NORMAL_Z and centre_z > on_a[2]:
                found.append((a.get_link_name(pt.link_b), (float(on_a[0]), float(on_a[1]), float(on_a[2]))))
        return found


def supporting(a: Object, b: Object, link: str | None = None) -> bool:
    """True when `b` rests on `a` (on `a`'s link `link`, if given): b above, in contact, the contact roughly horizontal."""
    if link is not None:
        a.get_link_id(link)  # an unknown link is an error, not a "no"
    return any(link is None or on == link for on, _ in support_points(a, b))


# -- the query, by name (plans, `pycram query`, docs) --------------------------------------------------


def _supporting(call: Call) -> QueryAnswer:
    a, b = call.object("a"), call.object("b")
    if a is b:
        raise call.error("b", f"supporting needs two different objects, got '{a.name}' twice")
    link = call.args.get("link")
    if link is not None:
        if link not in a.link_names:
            raise call.error("link", f"'{a.name}' has no link '{link}'", did_you_mean(str(link), a.link_names))
        call.resolved["link"] = link
    points = [(on, point) for on, point in support_points(a, b) if link is None or on == link]
    details = {"contacts": [{"link": on, "point": list(point)} for on, point in points]}
    return QueryAnswer("supporting", call.resolved, bool(points), details, bool(points))


def _say_supporting(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    if answer.result:
        links = sorted({c["link"] for c in d["contacts"]})
        return f"{a['a']} supports {a['b']} (at {', '.join(links)})"
    return f"{a['a']} does NOT support {a['b']}"


declare_query(QuerySpec(
    "supporting", "Does object a carry object b (b on top of a, touching)?",
    parameters(Param("a", "object", True, "the supporting object's name", positional=True),
               Param("b", "object", True, "the supported object's name", positional=True),
               Param("link", "link", doc="only count support by this link of a (e.g. kitchen_island_surface)", of="a")),
    _supporting, _say_supporting))
