"""Which objects a robot body penetrates right now (no simulation step needed)."""
from __future__ import annotations

from ..world import Object

PENETRATION = 0.001  # metres; resting contact sits at about -1e-5


def supports_from_below(robot: Object, other: Object) -> bool:
    """True for the surface the robot stands on (its top is at the robot's base height)."""
    base_z = robot.get_position()[2]
    return other.get_aabb()[1][2] <= base_z + 0.01


def collisions(robot: Object, ignore: set[Object] | None = None, links: set[int] | None = None) -> dict[Object, list[tuple[str, str]]]:
    """Objects penetrated by the robot (or by `links` of it), with the touching link pairs."""
    ignore = ignore or set()
    found: dict[Object, list[tuple[str, str]]] = {}
    for other in robot.world.objects:
        if other is robot or other in ignore or supports_from_below(robot, other):
            continue
        points = robot.world.closest_points(robot, other, 0.0)
        pairs = sorted({(robot.get_link_name(pt.link_a), other.get_link_name(pt.link_b)) for pt in points
                        if pt.distance < -PENETRATION and (links is None or pt.link_a in links)})
        if pairs:
            found[other] = pairs
    return dict(sorted(found.items(), key=lambda kv: kv[0].name))
