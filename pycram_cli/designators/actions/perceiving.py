"""`detect` and `search`: finding objects with the camera."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ...failures import Failure, LocationFailure, NavigationFailure, PerceptionFailure, ReachabilityFailure
from ...locations import handle_of, opening_joint
from ...reasoning.supporting import support_points
from ...signature import Param, Signature
from ...world import Object
from ..declaration import ANY_ARM, drives
from .actor import Actor, Finder
from .common import go, object_of, try_choices
from .declaration import Action, declare_action

#: a drawer or door opened less than this fraction of its range counts as closed: what is inside cannot be seen
CLOSED = 0.2
#: search opens a container all the way; a robot that cannot pull it that far from any pose opens it this far
#: (fractions of its range) instead, while what lies inside may still come out from under what covers it
PARTLY = (0.75,)


def _detect(actor: Actor, slots: Mapping[str, Any]) -> Object:
    if slots.get("object") is None:
        return actor.motion("detecting", {"object-type": slots["object-type"]})
    obj = object_of(actor, slots["object"], "object")
    actor.motion("looking", {"object": obj})
    found = actor.motion("detecting", {"object-type": obj.type})
    if found is not obj and not actor.query("visible", {"object": obj}):
        raise PerceptionFailure(f"{obj.name} is not in sight (the camera sees {found.name}, of its type)", object=obj.name)
    return obj


declare_action(Action(
    "detect", "Detect an object (looking at it first) or any object of a type in sight; PerceptionFailure if not seen.",
    Signature((
        Param("object-type", "object-type", False, "the type to find in sight"),
        Param("object", "object", False, "the object to look at and detect"),
    ), one_of=("object-type", "object")),
    run=_detect, uses=drives("head"), needs=("camera",), returns="the object seen"))


def is_closed(obj: Object, joint: str) -> bool:
    """Whether a drawer or door is (nearly) closed: opened less than CLOSED of its range."""
    info = obj.joint(joint)
    span = (info.upper - info.lower) if info.limited else 1.0
    return obj.get_joint_position(joint) - (info.lower if info.limited else 0.0) < CLOSED * span


def container_of(obj: Object, closed: bool = True) -> tuple[Object, str, str] | None:
    """(object, joint, handle) of the closed drawer or door `obj` is in (rests on a link its joint carries), or None;
    `closed=False`: of the drawer or door it is in, however far open."""
    world = obj.world
    for other in world.objects:
        if other is obj or other.type == "robot" or not other.movable_joints:
            continue
        for link, _ in support_points(other, obj):
            joint = opening_joint(other, link)
            if joint is None:
                continue
            if not closed or is_closed(other, joint):
                handle = handle_of(other, joint)
                if handle is not None:
                    return other, joint, handle
    return None


def _search(actor: Actor, slots: Mapping[str, Any]) -> Object:
    if slots.get("object") is not None:
        obj = object_of(actor, slots["object"], "object")
    else:  # where the robot's belief (the world state) puts an object of the type
        obj = actor.motion("world-state-detecting", {"object-type": slots["object-type"]})
    if actor.robot.arm_holding(obj) is not None:  # in the robot's own hand (a place failed earlier): found
        return obj
    inside = container_of(obj)
    if inside is not None:  # all the way: what lies inside is seen, and taken, best from above the open drawer
        container, joint, handle = inside
        info = container.joint(joint)
        if not info.limited:
            actor.action("open", {"handle": handle, "distance": None})
        else:
            ways = [1.0, *PARTLY]
            for k, fraction in enumerate(ways):
                try:
                    actor.action("open", {"handle": handle, "distance": fraction * (info.upper - info.lower)})
                    break
                except LocationFailure:  # no pose to pull it that far from (a short arm): less far, while there is
                    if k == len(ways) - 1:
                        raise
    robot = actor.robot
    places: list[dict[str, Any]] = [{"visible-for": obj}]
    if any(not robot.held_objects(arm) for arm in robot.description.arms):  # stand where it could be picked up too
        places.insert(0, {"visible-for": obj, "reachable-for": obj})

    def look(a: Actor, pose: Any) -> Object:
        go(a, pose)
        a.motion("looking", {"object": obj})
        return a.motion("detecting", {"object-type": obj.type})

    failures: list[Failure] = []
    for place in places:
        try:
            return try_choices(actor, Finder(place, here=True), look, f"search for {obj.type}",
                               (NavigationFailure, PerceptionFailure, ReachabilityFailure))
        except Failure as exc:
            failures.append(exc)
    raise PerceptionFailure(f"searched for {obj.type} where {obj.name} should be and did not see it: "
                            + "; ".join(f.message for f in failures), object_type=obj.type)


declare_action(Action(
    "search", "Look for an object (or one of a type) where the robot believes it is — opening the drawer or door "
              "it is in — until it is detected; stands where it could pick it up too, when there is such a place.",
    Signature((
        Param("object-type", "object-type", False, "the type to look for"),
        Param("object", "object", False, "the object to look for"),
    ), one_of=("object-type", "object")),
    run=_search, uses=drives("base", "head", ANY_ARM), needs=("camera",), returns="the object detected"))
