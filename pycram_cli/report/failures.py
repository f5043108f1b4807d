"""Where a run failed, read from its trace: the failed steps, the objects each names, and the place it meant.

A failed step names what it worked on in its slots or query arguments (`assert: stable(object: milk)`), but
often not where the object was meant to go: that is in an earlier step that moved the same object
(`place: {object: milk, target: [...]}`). `focus(...)` looks back for it, so that a report can show the
object and its target together, and `pycram run --render` of a failed run can frame both.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..plan.replay import PLACES
from ..world.camera import boxes_camera, movable_objects
from ..world.pose import vec3

if TYPE_CHECKING:
    from ..world import BulletWorld
    from ..world.camera import Camera

#: m: a failure is framed at least this far, with what is around it
FAILURE_DISTANCE = 1.4
#: degrees: and from high above, over a robot that may stand between the camera and what failed
FAILURE_PITCH = -65.0

Point = tuple[float, float, float]


@dataclass(frozen=True)
class Focus:
    """What a failed step is about: the objects it names, the place meant for them (if any is known) and the
    step that named that place (the failed one, or an earlier step that moved one of the objects)."""

    objects: tuple[str, ...]
    target: Point | None
    target_step: str | None


def leaves(node: dict[str, Any]) -> Iterator[dict[str, Any]]:
    """The trace's leaf steps, in the order of its tree."""
    children = node.get("children") or []
    if not children:
        yield node
    for child in children:
        yield from leaves(child)


def failed_leaves(root: dict[str, Any]) -> list[dict[str, Any]]:
    """Every leaf step that failed (those recovered from too), in the order of the tree."""
    return [node for node in leaves(root) if node.get("status") == "failed"]


def named_values(info: dict[str, Any]) -> dict[str, Any]:
    """The values a step names: its designator's resolved (else given) slots, its query's arguments, and those
    of the query in its condition (`assert`, `if`)."""
    values: dict[str, Any] = {}
    if isinstance(info.get("designator"), dict):
        values.update(info["designator"].get("resolved") or info["designator"].get("slots") or {})
    if isinstance(info.get("query"), dict):
        values.update(info["query"].get("args") or {})
    condition = info.get("condition")
    while isinstance(condition, dict):
        if isinstance(condition.get("query"), dict):
            values.update(condition["query"].get("args") or {})
        condition = condition.get("not")
    return values


def _names(value: Any, objects: set[str]) -> Iterable[str]:
    if isinstance(value, str) and value in objects:
        yield value
    elif isinstance(value, (list, tuple)):
        for item in value:
            if isinstance(item, str) and item in objects:
                yield item


def _place(values: dict[str, Any]) -> Point | None:
    for key in PLACES:
        value = values.get(key)
        if (isinstance(value, (list, tuple)) and len(value) == 3
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
            return (float(value[0]), float(value[1]), float(value[2]))
    return None


def focus(root: dict[str, Any], failed: dict[str, Any], objects: set[str],
          order: list[str] | None = None) -> Focus:
    """The focus of the failed step `failed` of the tree `root`. `objects`: the names of the things a plan works
    on (not robots, not environments); `order`: the steps' paths in the order they ran (a replay record's),
    default the tree's."""
    values = named_values(failed)
    named = tuple(dict.fromkeys(name for value in values.values() for name in _names(value, objects)))
    target = _place(values)
    if target is not None or not named:
        return Focus(named, target, failed.get("path") if target is not None else None)
    by_path = {node.get("path"): node for node in leaves(root)}
    paths = order if order is not None else list(by_path)
    path = failed.get("path")
    before = paths[:paths.index(path)] if isinstance(path, str) and path in paths else paths
    for earlier in reversed(before):  # the latest step that named one of the objects and a place
        node = by_path.get(earlier)
        if node is None:
            continue
        values = named_values(node)
        if set(named) & {name for value in values.values() for name in _names(value, objects)}:
            place = _place(values)
            if place is not None:
                return Focus(named, place, earlier)
    return Focus(named, None, None)


def failure_camera(world: BulletWorld, trace: dict[str, Any], aspect: float = 4 / 3) -> Camera | None:
    """A camera on a failed run's failure in `world` as the run left it: the objects the failed step names and the
    place meant for them (the box the first of them would have there, its bottom's centre at the target); None
    when the run did not fail or its failure names neither."""
    failure = trace.get("failure") or {}
    root = trace.get("root") or {}
    node = next((n for n in leaves(root) if n.get("path") == failure.get("path")), None)
    if trace.get("status") != "failed" or node is None:
        return None
    names = {o.name for o in movable_objects(world)}
    found = focus(root, node, names, [step.get("path") for step in (trace.get("replay") or {}).get("steps") or []] or None)
    objects = [world.get_object_by_name(name) for name in found.objects]
    boxes = [obj.get_aabb() for obj in objects if obj is not None]
    if found.target is not None:
        if boxes:  # the first object's box, moved so that its bottom's centre is at the target
            lo, hi = boxes[0]
            shift = [t - c for t, c in zip(found.target, ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]))]
            boxes.append((vec3(a + d for a, d in zip(lo, shift)), vec3(b + d for b, d in zip(hi, shift))))
        else:
            boxes.append((vec3(v - 0.05 for v in found.target), vec3(v + 0.05 for v in found.target)))
    if not boxes:
        return None
    return framing(world, boxes, aspect)


def framing(world: BulletWorld, boxes: list[Any], aspect: float, fov_deg: float = 50.0) -> Camera:
    """A camera on a failure's boxes, from above and at least FAILURE_DISTANCE away: past what stands in the way
    where it can, else from outside whatever hides them (not from inside a closed drawer that holds the object)."""
    heading = None
    if len(boxes) > 1:  # the object and its target side by side: looking across the line between them
        a, b = (np.add(*boxes[0]) / 2, np.add(*boxes[-1]) / 2)
        across = (-(b[1] - a[1]), b[0] - a[0])
        if math.hypot(*across) > 0.1:
            robot = world.robot
            middle = (a + b) / 2
            away = (middle[0] - robot.get_position()[0], middle[1] - robot.get_position()[1]) if robot else across
            heading = across if across[0] * away[0] + across[1] * away[1] >= 0 else (-across[0], -across[1])
    camera = boxes_camera(world, boxes, fov_deg, aspect, min_distance=FAILURE_DISTANCE, pitch_deg=FAILURE_PITCH,
                          heading=heading)
    if math.dist(camera.eye, camera.target) < 0.9 * FAILURE_DISTANCE:  # moved in to see past what hides them
        camera = boxes_camera(world, boxes, fov_deg, aspect, min_distance=FAILURE_DISTANCE, pitch_deg=FAILURE_PITCH,
                              clear=False, heading=heading)
    return camera
