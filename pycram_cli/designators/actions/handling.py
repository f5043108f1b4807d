"""`pick-up`, `place`, `open`, `close` and `transport`: actions that take, put down, pull and carry.

Where to stand, which arm and which grasp are found by location designators when the slots
leave them open; each choice that fails (the robot cannot stand there, the grasp slips) is
followed by the next candidate before the action fails.
"""
from __future__ import annotations

import contextlib
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from ...errors import InputError, Location, did_you_mean
from ...failures import Failure, LocationFailure, ManipulationFailure, ReasoningFailure
from ...locations import Handle, LocationSpec, find_handle, handle_of
from ...locations.base_poses import EXPENSIVE_LIMIT
from ...locations.spec import find_object
from ...planning.drawers import DISTANCE
from ...reasoning import QUERIES
from ...signature import Param, Signature
from ..declaration import ANY_ARM, drives
from .actor import Actor, Finder, as_failure
from .common import PARK, go, location_slot, object_of, rest_of, rest_pose, resting, try_choices
from .declaration import Action, declare_action
from .perceiving import container_of, is_closed

EVERYTHING = drives("base", "head", "torso", ANY_ARM)


def _rest_first(actor: Actor) -> None:
    """Arms parked (or carrying) before the base moves, unless they are already."""
    if resting(actor.robot):
        actor.action("park-arms", {})


# -- pick-up -----------------------------------------------------------------------------------------------------


def _pick_up(actor: Actor, slots: Mapping[str, Any]) -> Any:
    obj = object_of(actor, slots["object"], "object")
    _rest_first(actor)
    location = {"reachable-for": obj, "arm": slots.get("arm"), "grasp": slots.get("grasp")}

    def take(a: Actor, pose: Any) -> Any:
        go(a, pose)
        was = list(obj.get_position())
        a.motion("pick-up", {"object": obj, "arm": pose.arm, "grasp": pose.grasp})
        lift = rest_of(a.robot, pose.arm)
        if lift is not None:
            try:
                a.motion("move-arm-joints", {"arms": {pose.arm: lift}})
            except ManipulationFailure:
                # the arm cannot draw it in from here: put it back where it was, so that the next place to stand
                # starts as this one did
                a.motion("place", {"object": obj, "target": was, "arm": pose.arm})
                raise
        return obj

    return try_choices(actor, Finder(location, here=True), take, f"pick up {obj.name}")


declare_action(Action(
    "pick-up", "Pick an object up: stand where an arm reaches it untouched, grasp it, lift it into the carry pose.",
    Signature((
        Param("object", "object", True, "the object to pick up"),
        Param("arm", "arm", False, "the arm to use", default_doc="found with where to stand: the arm that reaches"),
        Param("grasp", "grasp", False, "the grasp",
              default_doc="found with where to stand: the first grasp that works"),
    )),
    run=_pick_up, uses=EVERYTHING, needs=("arms",), returns="the object"))


# -- place -------------------------------------------------------------------------------------------------------


def _place(actor: Actor, slots: Mapping[str, Any]) -> Any:
    obj = object_of(actor, slots["object"], "object")
    robot = actor.robot
    arm = slots.get("arm") or robot.arm_holding(obj)
    if arm is None or robot.arm_holding(obj) != arm:
        raise ManipulationFailure(f"cannot place {obj.name}: the robot is not holding it"
                                  + (f" in {arm}" if arm else ""), object=obj.name)
    spots = Finder(slots["target"], for_object=obj)

    def put(a: Actor, spot: Any) -> Any:
        surface = spots.resolution.spec.on if spots.resolution is not None else None
        stand = Finder(LocationSpec(reachable_for=spot.position, placing=obj, onto=surface, arm=arm), here=True)

        def release(b: Actor, pose: Any) -> Any:
            go(b, pose)
            b.motion("place", {"object": obj, "target": list(spot.position), "arm": arm})
            if rest_pose(b.robot, arm) == PARK:
                b.motion("move-arm-joints", {"arms": {arm: PARK}})
            return obj

        return try_choices(a, stand, release, f"place {obj.name}")

    _rest_first(actor)
    return try_choices(actor, spots, put, f"place {obj.name}", past_locations=True)


declare_action(Action(
    "place", "Put a held object down on a free spot of a surface: stand where the arm reaches the spot, place it, "
             "park the arm.",
    Signature((
        Param("object", "object", True, "the held object"),
        Param("target", "location", True, "where: {on: SURFACE, near: [x, y, z]?} (for: the object, inferred)"),
        Param("arm", "arm", False, "the arm holding it", default_doc="the arm that holds it"),
    ), across=location_slot("target", ("on",), "place puts an object on a surface: {on: SURFACE}")),
    run=_place, uses=EVERYTHING, needs=("arms",), returns="the object"))


# -- open and close ----------------------------------------------------------------------------------------------


def handle_from(actor: Actor, slots: Mapping[str, Any]) -> Handle:
    """The handle (and its joint) from the `handle` slot, or from `joint` (and `part-of`)."""
    try:
        if slots.get("handle") is not None:
            handle = find_handle(actor.world, slots["handle"], "handle")
        else:
            handle = _handle_of_joint(actor, slots["joint"], slots.get("part-of"))
    except InputError as exc:
        raise as_failure(exc, "handle" if slots.get("handle") is not None else "joint") from exc
    if slots.get("joint") is not None and slots["joint"] != handle.joint:
        raise ManipulationFailure(f"{handle.link} is on {handle.joint}, not on {slots['joint']}")
    return handle


def _handle_of_joint(actor: Actor, joint: str, part_of: Any) -> Handle:
    world = actor.world
    owners = ([find_object(world, part_of, "part-of")] if part_of is not None
              else [o for o in world.objects if o is not world.robot and joint in o.joint_names])
    if not owners or joint not in owners[0].joint_names:
        known = [j.name for o in (owners or [o for o in world.objects if o is not world.robot]) for j in o.movable_joints]
        raise InputError(f"no joint '{joint}'" + (f" in {owners[0].name}" if owners else " in the world"),
                         Location("joint"), key="joint", suggestion=did_you_mean(joint, known))
    name = handle_of(owners[0], joint)
    if name is None:
        raise ManipulationFailure(f"{joint} carries no link named like a handle: name the handle with 'handle:'")
    return Handle(owners[0], name, joint)


def _access(actor: Actor, slots: Mapping[str, Any], distance: float, verb: str, patience: int | None = None) -> None:
    handle = handle_from(actor, slots)
    _rest_first(actor)
    spec = LocationSpec(accessing=handle, distance=distance, arm=slots.get("arm"), patience=patience)

    def pull(a: Actor, pose: Any) -> None:
        go(a, pose)
        a.motion("accessing", {"drawer-handle": handle.link, "drawer-joint": handle.joint, "part-of": handle.obj,
                               "distance": distance, "arm": pose.arm})
        lift = rest_of(a.robot, pose.arm)
        if lift is not None:
            a.motion("move-arm-joints", {"arms": {pose.arm: lift}})

    try_choices(actor, Finder(spec, here=True), pull, f"{verb} {handle.joint}")


def _open(actor: Actor, slots: Mapping[str, Any]) -> None:
    _in_strokes(actor, slots, slots["distance"], "open")  # bound: the declared default when not given


#: a drawer or door no pose pulls open or pushes shut in one stroke is moved in up to this many equal strokes, each
#: from a pose of its own: an arm whose hand must stay level (a 5-joint arm) follows a long pull only part of the way,
#: and an arm that cannot fold close enough to take the handle of the open drawer from where it also reaches it shut
#: (the pre-grasp pose is nearer the robot than the handle) stands back for the first stroke
STROKES = 3


def _close(actor: Actor, slots: Mapping[str, Any]) -> None:
    _in_strokes(actor, slots, 0.0, "close")


def _in_strokes(actor: Actor, slots: Mapping[str, Any], distance: float, verb: str) -> None:
    """Open (or close) the handle's joint to `distance` above its lower limit: in one stroke when a pose reaches it so,
    else in 2, then 3 equal strokes from where it is (a joint without limits: in one)."""
    handle = handle_from(actor, slots)
    info = handle.obj.joint(handle.joint)
    for strokes in range(1, STROKES + 1 if info.limited else 2):
        start = handle.obj.get_joint_position(handle.joint) - info.lower
        # while shorter strokes are left to try, each pose search is as patient as one that meets something in the
        # way (EXPENSIVE_LIMIT), not three times that: an arm whose pull is too long fails at every pose
        patience = EXPENSIVE_LIMIT if strokes < STROKES and info.limited else None
        try:
            for k in range(1, strokes + 1):
                _access(actor, slots, start + (distance - start) * k / strokes, verb, patience)
            return
        except LocationFailure:  # no pose for this stroke: shorter strokes, while there are
            if strokes == STROKES or not info.limited:
                raise


_HANDLE = (Param("handle", "link", False, "the handle link (e.g. sink_area_left_upper_drawer_handle)", of="part-of"),
           Param("joint", "joint", False, "the drawer's or door's joint (its handle is the link named *handle* on it)",
                 of="part-of"),
           Param("part-of", "object", False, "the object the joint belongs to",
                 default_doc="the object that has the joint"))
_ARM = Param("arm", "arm", False, "the arm that pulls",
             default_doc="found with where to stand: a free arm that reaches")

declare_action(Action(
    "open", "Open a drawer or door by its handle (or joint): stand where a free arm reaches the handle all the way "
            "open, pull it open, park the arm; when no pose reaches it so, pull it open in up to three strokes, each "
            "from a pose of its own.",
    Signature((
        *_HANDLE,
        replace(DISTANCE, kind="distance", default_doc="0.3, or the joint's range if smaller"),
        _ARM,
    ), one_of=("handle", "joint")),
    run=_open, uses=EVERYTHING, needs=("arms",)))

declare_action(Action(
    "close", "Close a drawer or door by its handle (or joint): stand where a free arm reaches the handle all the way "
             "closed, push it shut, park the arm; when no pose reaches it so, push it shut in up to three strokes, "
             "each from a pose of its own.",
    Signature((
        *_HANDLE,
        _ARM,
    ), one_of=("handle", "joint")),
    run=_close, uses=EVERYTHING, needs=("arms",)))


# -- transport ---------------------------------------------------------------------------------------------------


def _transport(actor: Actor, slots: Mapping[str, Any]) -> Any:
    wanted = {"object": slots["object"]} if slots.get("object") is not None else {"object-type": slots["object-type"]}
    torso = _torso(actor)
    found = actor.action("search", wanted)
    was = list(found.get_position())
    taken_out_of = container_of(found, closed=False)
    if actor.robot.arm_holding(found) is None:  # already in hand when a place failed earlier and nothing took it back
        actor.action("pick-up", {"object": found, "arm": slots.get("arm"), "grasp": slots.get("grasp")})
    taken_from = actor.robot.body.get_pose()
    try:
        actor.action("place", {"object": found, "target": slots["target"]})
    except Failure:
        _put_back(actor, found, was, taken_from)
        raise
    actor.action("park-arms", {})
    now = _torso(actor)
    if torso is not None and now is not None and abs(now - torso) > 1e-6:  # raised or lowered to reach: back as it was
        actor.motion("moving-torso", {"position": torso})
    answer = actor.query("stable", {"object": found})
    if not answer:  # with what it does: tips over and lies still, keeps moving, or rocks
        how = QUERIES["stable"].describe(answer).split(": ", 1)[-1]
        raise ReasoningFailure(f"{found.name} is not stable where it was placed: {how}", object=found.name,
                               motion=answer.details.get("motion"))
    if taken_out_of is not None:
        _seal(actor, *taken_out_of)
    return found


def _torso(actor: Actor) -> float | None:
    """Where the torso is (None without one): transport puts it back there once the object is delivered, when taking or
    placing it moved the torso (`go`), so that what comes next starts from the height it started from."""
    joint = actor.robot.description.torso_joint
    return None if joint is None else actor.robot.body.get_joint_positions([joint])[joint]


def _seal(actor: Actor, container: Any, joint: str, handle: str) -> None:
    """Close the drawer or door the object was taken out of, once it is delivered (CRAM's transport seals what it
    accessed): an open drawer left behind stands where the robot must stand for the next things it fetches. The object
    is delivered either way: when the robot cannot close it, the failed `close` shows in the trace and the transport
    still succeeds."""
    if is_closed(container, joint):
        return
    with contextlib.suppress(Failure):
        actor.action("close", {"handle": handle, "part-of": container})


def _put_back(actor: Actor, obj: Any, was: list[float], taken_from: Any) -> None:
    """When the object cannot be placed where it should go, the robot puts it back where it took it from (driving
    back to where it stood then), so that a plan that tries again later finds the world as it was and its gripper
    free; when even that fails, it keeps holding the object (the place's failure is what the plan sees)."""
    arm = actor.robot.arm_holding(obj)
    if arm is None:
        return
    try:
        actor.motion("moving", {"target": list(taken_from[0]), "orientation": list(taken_from[1])})
        actor.motion("place", {"object": obj, "target": was, "arm": arm})
        actor.action("park-arms", {})
    except Failure:
        pass


declare_action(Action(
    "transport", "Bring an object (or one of a type) to a location: find it, stand, pick it up, carry it, stand, "
                 "place it, park, check that it stands stably (ReasoningFailure if not), and close the drawer or "
                 "door it was taken out of.",
    Signature((
        Param("object", "object", False, "the object to bring"),
        Param("object-type", "object-type", False, "or the type of object to bring (found by search)"),
        Param("target", "location", True, "where: {on: SURFACE, near: [x, y, z]?}"),
        Param("arm", "arm", False, "the arm to carry it with", default_doc="found when picking it up"),
        Param("grasp", "grasp", False, "the grasp", default_doc="found when picking it up"),
    ), one_of=("object", "object-type"),
       across=location_slot("target", ("on",), "transport brings an object onto a surface: {on: SURFACE}")),
    run=_transport, uses=EVERYTHING, needs=("arms", "camera"), returns="the object"))
