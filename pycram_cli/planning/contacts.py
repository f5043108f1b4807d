"""Which objects a robot body — and what it holds — penetrates right now (no simulation step needed).

What the robot stands on is support, never a collision: nearly every real robot's wheels or
casters rest on the floor (0 mm), and a floor may be an object of its own or a link of the
environment (an apartment's floor plate). A link of another object is support when its top is
no higher than the robot's *ground* — the lowest point of the robot's own collision shapes (or
its base origin, when that is lower) — plus `SUPPORT_SLACK`.
"""
from __future__ import annotations

from ..world import Object

PENETRATION = 0.001  # metres; resting contact sits at about -1e-5
#: a link whose top is at most this far above the robot's ground holds it up (m)
SUPPORT_SLACK = 0.01


def ground_z(robot: Object) -> float:
    """The height the robot stands at: the bottom of its lowest collision shape, or its base origin if lower."""
    lo, _ = robot.link_aabbs()
    solid = [row for index, row in zip(range(-1, len(robot.joints)), lo) if index in robot.solid_links()]
    base = float(robot.get_position()[2])
    return min([base, *(float(row[2]) for row in solid)])


def supports_from_below(robot: Object, other: Object, ground: float | None = None) -> bool:
    """True for a surface the robot stands on as a whole (its top is at the robot's ground)."""
    ground = ground_z(robot) if ground is None else ground
    return other.get_aabb()[1][2] <= ground + SUPPORT_SLACK


def support_links(robot: Object, other: Object, ground: float | None = None) -> frozenset[int]:
    """The links of `other` the robot stands on (their tops at the robot's ground): a floor inside an environment."""
    ground = ground_z(robot) if ground is None else ground
    _, hi = other.link_aabbs()
    return frozenset(index for index, top in zip(range(-1, len(other.joints)), hi[:, 2])
                     if float(top) <= ground + SUPPORT_SLACK)


def collisions(robot: Object, ignore: set[Object] | None = None, links: set[int] | None = None,
               held: list[Object] | tuple[Object, ...] = ()) -> dict[Object, list[tuple[str, str]]]:
    """Objects penetrated by the robot (or by `links` of it) and by the objects it holds (`held`, which move with it),
    with the touching pairs (the robot's link or the held object's name, the other's link)."""
    ignore = set(ignore or set()) | set(held)
    found: dict[Object, set[tuple[str, str]]] = {}
    ground = ground_z(robot)
    for other in robot.world.objects:
        if other is robot or other in ignore:
            continue
        if not supports_from_below(robot, other, ground):
            points = [pt for pt in robot.world.closest_points(robot, other, 0.0)
                      if pt.distance < -PENETRATION and (links is None or pt.link_a in links)]
            floor = support_links(robot, other, ground) if points else frozenset()  # only asked when it matters
            found.setdefault(other, set()).update(
                (robot.get_link_name(pt.link_a), other.get_link_name(pt.link_b)) for pt in points
                if pt.link_b not in floor)
        for obj in held:  # what the robot carries must not go through anything either (the floor included)
            points = robot.world.closest_points(obj, other, 0.0)
            found.setdefault(other, set()).update(
                (f"the held {obj.name}", other.get_link_name(pt.link_b)) for pt in points if pt.distance < -PENETRATION)
    return {other: sorted(pairs) for other, pairs in sorted(found.items(), key=lambda kv: kv[0].name) if pairs}
