"""Possible starts: objects that start inside another body, or over nothing, cannot be a real scene.

`start_problems(world, objects)` says why some objects of a loaded world could not stand where
they are: more than START_DEPTH inside another body (what holds them, and what they hold, may
touch them), or, for free objects, a centre of mass not over something within SUPPORT_GAP below
their bottom (straight down: past a counter's edge, or in the air). Sweeps draw such scenarios
again (scenario/starts.py), and the plan's `project` node its varied runs.
"""
from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from .loader import START_DEPTH

if TYPE_CHECKING:
    from ..world import BulletWorld, Object

#: how far below an object's bottom what it stands on may be (m): resting contact is about 0.01 mm; more is in the air
SUPPORT_GAP = 0.01
#: how far straight down from the centre of mass the support is looked for (m)
LOOK_DOWN = 3.0


def start_problems(world: BulletWorld, objects: Iterable[Object]) -> list[str]:
    """Why `objects` (of `world`) cannot start where they are, one line each (empty: they can)."""
    problems: list[str] = []
    reported: set[frozenset[str]] = set()
    for obj in objects:
        inside = _inside(world, obj, reported)
        if inside:
            problems.append(inside)
        elif obj is not world.robot and not obj.fixed:
            floating = unsupported(world, obj)
            if floating:
                problems.append(floating)
    return problems


def _inside(world: BulletWorld, obj: Object, reported: set[frozenset[str]]) -> str | None:
    for other in world.objects:
        pair = frozenset((obj.name, other.name))
        if other is obj or pair in reported or other in obj.attachments or obj in other.attachments:
            continue
        depth = -world.distance(obj, other, 0.0)
        if depth > START_DEPTH:
            reported.add(pair)
            return f"{obj.name} starts {depth * 1000:.0f} mm inside {other.name}"
    return None


def unsupported(world: BulletWorld, obj: Object) -> str | None:
    """Why `obj` is not supported (nothing within SUPPORT_GAP under its centre of mass), or None when it is."""
    (x, y, z), _ = obj.get_com_pose()
    bottom = obj.get_aabb()[0][2]
    hit = world.cast_rays([(x, y, z)], [(x, y, z - LOOK_DOWN)], ignore=[obj])[0]
    if hit is None:
        return f"{obj.name} has nothing under its centre of mass"
    gap = bottom - hit.position[2]
    if gap <= SUPPORT_GAP:
        return None
    under = hit.object.name if hit.object is not None else "something"
    return f"{obj.name} is not supported: its centre of mass is {gap * 1000:.0f} mm above {under}"
