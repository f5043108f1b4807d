"""The seven reasoning queries of the design (§4.4), each declared once: parameters, runner, answer sentence.

A new query is one more `declare_query(...)` in a module of its own, imported by
`reasoning/__init__.py`; plans, validation, `pycram query` and its help pick it up.
"""
from __future__ import annotations

import math
from typing import Any

from ..errors import did_you_mean
from ..kinds import arm_phrase
from ..world import Object
from .contact import contact
from .query import Call, QueryAnswer, QueryParam, QuerySpec, declare_query, finite
from .reachability import ReachableAnswer, can_take, reachable, touching_at
from .stable import OBSERVE, stable
from .supporting import support_points
from .visibility import occluding, visible

_OBJECT = "an object name"
_TARGET = "an object name or a position [x, y, z]"
_FROM = QueryParam("from", "camera", doc="camera: a link of the robot or a position [x, y, z] looking at the object",
                   default_doc="the robot's camera frame")
_ARM = QueryParam("arm", "arm", doc="the arm to reach with", default_doc="every arm in the description's order: the first that reaches")
_GRASP = QueryParam("grasp", "grasp", doc="tool orientation: a grasp of the robot (front, top, ...) or a quaternion [x, y, z, w]",
                    default_doc="any orientation")
_REACH = QueryParam("threshold", "distance", doc="how close (m) the tool frame must come", default=0.01)


# -- how answers read ------------------------------------------------------------------------------


def _mm(value: float | None) -> str:
    if value is None:
        return "-"
    mm = value * 1000
    return f"{mm:.2f} mm" if abs(mm) < 10 else f"{mm:.1f} mm"


def _deg(value: float | None) -> str:
    return "-" if value is None else f"{math.degrees(value):.2f}°"


def _place(value: Any) -> str:
    if isinstance(value, list) and value and isinstance(value[0], (int, float)):
        return "(" + ", ".join(f"{v:g}" for v in value) + ")"
    return str(value)


# -- stable -------------------------------------------------------------------------------------------


def _stable(call: Call) -> QueryAnswer:
    answer = stable(call.object("object"))
    details: dict[str, Any] = {"displacement": answer.displacement, "rotation": answer.rotation,
                               "simulated": answer.simulated}
    if not answer.stable:  # what it does once past the limits (a stable answer's is "at rest")
        details.update(motion=answer.motion, observed=answer.observed)
        if answer.amplitude is not None:
            details["amplitude"] = {"displacement": answer.amplitude[0], "rotation": answer.amplitude[1]}
    return QueryAnswer("stable", call.resolved, answer.stable, details, answer.stable)


def _say_stable(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    moved = f"moved {_mm(d['displacement'])} and {_deg(d['rotation'])}"
    if answer.result:
        return f"{a['object']} is stable ({moved} in {d['simulated']:.2f} s simulated)"
    total = f"{d['simulated'] + d.get('observed', 0.0):.2f} s simulated"
    motion = d.get("motion")
    if motion == "rocks":
        swing = d["amplitude"]
        return (f"{a['object']} is NOT stable: it is not at rest, it rocks back and forth by {_deg(swing['rotation'])} "
                f"and {_mm(swing['displacement'])} and is still moving ({total})")
    if motion == "settled":
        return f"{a['object']} is NOT stable: it {moved}, then came to rest ({total})"
    if motion == "moving":
        return f"{a['object']} is NOT stable: it {moved} and is still moving ({total})"
    return f"{a['object']} is NOT stable: it {moved} in {total}"


declare_query(QuerySpec(
    "stable", "Does the object stay put (within 1 mm and 1°) while the world is simulated for 2 s? When not, it is "
              f"watched {OBSERVE:g} s longer: it came to rest elsewhere, is still moving, or rocks (and by how much).",
    (QueryParam("object", "object", True, _OBJECT, positional=True),), _stable, _say_stable))


# -- contact -------------------------------------------------------------------------------------------


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
        return f"{a['a']} and {a['b']} are in contact (distance {_mm(d['distance'])}; touching: {links})"
    far = "more than 0.5 m" if d["distance"] is None else _mm(d["distance"])
    return f"{a['a']} and {a['b']} are not in contact (distance {far})"


declare_query(QuerySpec(
    "contact", "Are the two objects touching (within 5 mm)?",
    (QueryParam("a", "object", True, _OBJECT, positional=True), QueryParam("b", "object", True, _OBJECT, positional=True)),
    _contact, _say_contact))


# -- visible and occluding ------------------------------------------------------------------------------


def _visible(call: Call) -> QueryAnswer:
    obj = call.object("object")
    camera = call.camera()
    threshold = call.number("threshold")
    answer = visible(obj, camera, threshold=threshold)
    return QueryAnswer("visible", call.resolved, answer.visible,
                       {"fraction": answer.fraction, "pixels": answer.pixels, "total": answer.total,
                        "camera": call.resolved["from"]}, answer.visible)


def _say_visible(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    seen = f"{d['fraction']:.0%} of its pixels seen from {_place(d['camera'])} (threshold {a['threshold']:.0%})"
    return f"{a['object']} is visible: {seen}" if answer.result else f"{a['object']} is NOT visible: {seen}"


declare_query(QuerySpec(
    "visible", "Are at least 80 % of the object's pixels seen from the camera?",
    (QueryParam("object", "object", True, _OBJECT, positional=True), _FROM,
     QueryParam("threshold", "fraction", doc="the fraction of pixels that must be seen", default=0.8)),
    _visible, _say_visible))


def _occluding(call: Call) -> QueryAnswer:
    obj = call.object("object")
    camera = call.camera()
    found = occluding(obj, camera)
    return QueryAnswer("occluding", call.resolved, [o.name for o in found],
                       {"count": len(found), "camera": call.resolved["from"]}, found)


def _say_occluding(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    if answer.result:
        return f"{a['object']} is occluded by: {', '.join(answer.result)} (seen from {_place(d['camera'])})"
    return f"nothing occludes {a['object']} (seen from {_place(d['camera'])})"


declare_query(QuerySpec(
    "occluding", "Which objects cover the object's pixels, seen from the camera?",
    (QueryParam("object", "object", True, _OBJECT, positional=True), _FROM), _occluding, _say_occluding))


# -- reachable and blocking -----------------------------------------------------------------------------


def _reach(call: Call, target: Any, grasp: Any, threshold: float) -> tuple[str, str, ReachableAnswer, dict[str, Any]]:
    """Try the arms in order; the first that reaches wins, else the one that came closest."""
    robot = call.robot()
    desc = call.description("arms", "arm")
    tried: dict[str, Any] = {}
    best: tuple[str, str, ReachableAnswer] | None = None
    for arm in call.arms():
        tool = desc.arm(arm).tool_frame
        answer = reachable(target, robot, tool, grasp=grasp, threshold=threshold)
        tried[arm] = finite(answer.position_error)
        if answer.reachable:
            return arm, tool, answer, tried
        if best is None or answer.position_error < best[2].position_error:
            best = (arm, tool, answer)
    assert best is not None  # call.arms() is never empty
    return (*best, tried)


def _reachable(call: Call) -> QueryAnswer:
    target = call.target()
    grasp = call.grasp()
    threshold = call.number("threshold")
    if isinstance(target, Object):  # an object: can pick-up take it from here (its own grasps and ways)?
        arms = call.arms()
        taken = can_take(call.robot(), target, arms[0] if call.args.get("arm") is not None else None, grasp)
        if taken is not None:
            call.resolved["arm"] = taken.arm
            desc = call.description("arms", "arm")
            details = {"arm": taken.arm, "gripper_link": desc.arm(taken.arm).tool_frame if taken.arm else None,
                       "grasp": taken.grasp, "as": "pick-up", "position_error": finite(taken.position_error),
                       "orientation_error": finite(taken.orientation_error), "joint_positions": taken.joint_positions,
                       "reason": taken.reason, "detail": taken.detail, "arms_tried": arms,
                       "tried": [[a, g, why] for a, g, why in taken.tried]}
            return QueryAnswer("reachable", call.resolved, taken.takes, details, taken.takes)
    arm, tool, answer, tried = _reach(call, target, grasp, threshold)
    call.resolved["arm"] = arm
    details = {"arm": arm, "gripper_link": tool, "position_error": finite(answer.position_error),
               "orientation_error": finite(answer.orientation_error), "joint_positions": answer.joint_positions,
               "arms_tried": tried}
    return QueryAnswer("reachable", call.resolved, answer.reachable, details, answer.reachable)


def _say_reachable(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    if d.get("as") == "pick-up":
        target = _place(a["target"])
        if answer.result:
            return f"{target} is reachable: pick-up takes it with {arm_phrase(d['arm'])} and a {_place(d['grasp'])} grasp"
        why = {"blocked": f"blocked by {d['detail']}", "cannot hold": "no gripper can hold it"}.get(d["reason"],
                                                                                                  d["reason"])
        if d["reason"] == "out of reach" and d.get("position_error") is not None:
            why += f": the nearest grasp stays {_mm(d['position_error'])} away"
        arms = ", ".join(arm_phrase(arm) for arm in d["arms_tried"])
        return f"{target} is NOT reachable from here: pick-up with {arms} finds no grasp ({why})"
    grasp = f", {_place(a['grasp'])} grasp" if a.get("grasp") is not None else ""
    errors = f"{_mm(d['position_error'])} from the target" + (f", {_deg(d['orientation_error'])} off" if grasp else "")
    if not answer.result:
        errors = f"{_mm(d['position_error'])} short of the target" + (f", {_deg(d['orientation_error'])} off" if grasp else "")
    target = _place(a["target"])
    if answer.result:
        return f"{target} is reachable with {arm_phrase(d['arm'])}{grasp} ({errors})"
    return f"{target} is NOT reachable (best: {arm_phrase(d['arm'])}{grasp}, {errors})"


declare_query(QuerySpec(
    "reachable", "Can the robot bring its tool frame to the target (within 1 cm, and the grasp orientation)? For an object: "
    "can pick-up take it from where the robot stands (its grasps, the ways there and back)?",
    (QueryParam("target", "target", True, _TARGET, positional=True), _ARM, _GRASP, _REACH), _reachable, _say_reachable))


def _blocking(call: Call) -> QueryAnswer:
    target = call.target()
    grasp = call.grasp()
    threshold = call.number("threshold")
    excluded = call.types("exclude-type")
    arm, tool, answer, _ = _reach(call, target, grasp, threshold)
    call.resolved["arm"] = arm
    found = touching_at(call.robot(), answer.joint_positions, target, excluded)
    details = {"arm": arm, "gripper_link": tool, "reachable": answer.reachable,
               "position_error": finite(answer.position_error), "excluded_types": excluded}
    return QueryAnswer("blocking", call.resolved, [o.name for o in found], details, found)


def _say_blocking(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    target = _place(a["target"])
    reach = "" if d["reachable"] else f" (out of reach: the best solution stops {_mm(d['position_error'])} short of the target)"
    if answer.result:
        return f"reaching {target} with {arm_phrase(d['arm'])} touches: {', '.join(answer.result)}{reach}"
    return f"nothing blocks {arm_phrase(d['arm'])} reaching {target}{reach}"


declare_query(QuerySpec(
    "blocking", "Which objects would the robot touch when reaching for the target?",
    (QueryParam("target", "target", True, _TARGET, positional=True), _ARM, _GRASP,
     QueryParam("exclude-type", "types", doc="object types to leave out (e.g. environment)", default=[], multiple=True),
     _REACH), _blocking, _say_blocking))


# -- supporting -------------------------------------------------------------------------------------------


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
    (QueryParam("a", "object", True, "the supporting object's name", positional=True),
     QueryParam("b", "object", True, "the supported object's name", positional=True),
     QueryParam("link", "link", doc="only count support by this link of a (e.g. kitchen_island_surface)", of="a")),
    _supporting, _say_supporting))
