"""Which objects a robot body — and what it holds — penetrates right now (no simulation step needed)."""
from __future__ import annotations

from ..world import Object

PENETRATION = 0.001  # metres; resting contact sits at about -1e-5


def supports_from_below(robot: Object, other: Object) -> bool:
    """True for the surface the robot stands on (its top is at the robot's base height)."""
    base_z = robot.get_position()[2]
    return other.get_aabb()[1][2] <= base_z + 0.01


def collisions(robot: Object, ignore: set[Object] | None = None, links: set[int] | None = None,
               held: list[Object] | tuple[Object, ...] = ()) -> dict[Object, list[tuple[str, str]]]:
    """Objects penetrated by the robot (or by `links` of it) and by the objects it holds (`held`, which move with it),
    with the touching pairs (the robot's link or the held object's name, the other's link)."""
    ignore = set(ignore or set()) | set(held)
    found: dict[Object, set[tuple[str, str]]] = {}
    for other in robot.world.objects:
        if other is robot or other in ignore:
            continue
        if not supports_from_below(robot, other):
            points = robot.world.closest_points(robot, other, 0.0)
            found.setdefault(other, set()).update(
                (robot.get_link_name(pt.link_a), other.get_link_name(pt.link_b)) for pt in points
                if pt.distance < -PENETRATION and (links is None or pt.link_a in links))
        for obj in held:  # what the robot carries must not go through anything either (the floor included)
            points = robot.world.closest_points(obj, other, 0.0)
            found.setdefault(other, set()).update(
                (f"the held {obj.name}", other.get_link_name(pt.link_b)) for pt in points if pt.distance < -PENETRATION)
    return {other: sorted(pairs) for other, pairs in sorted(found.items(), key=lambda kv: kv[0].name) if pairs}
