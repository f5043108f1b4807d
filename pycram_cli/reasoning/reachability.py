"""reachable(target, robot, gripper_link, grasp) and blocking(...): can the arm get there, and what would it touch?

Both solve inverse kinematics for the arm that owns `gripper_link` (see `ik.py`): only
that arm's joints move; torso and base stay. The target is an object (its position), a
position, or a pose (whose orientation then counts as the grasp). A grasp is `front`,
`top`, `left` or `right` — the robot description's tool orientations relative to the robot
base, turned with the base's current orientation — or a world quaternion; with a grasp the
tool must also come within `angle_threshold` of that orientation (the design's future work).

`blocking` puts the arm at the solution (the best one found when the target is out of
reach) on the world's prospection copy and lists every object the robot then touches —
never the target, the robot itself or what it holds. Objects the robot holds move with the
copy's hand while checking (and collide too). The world itself is only read.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..errors import BadValue
from ..kinds import arm_phrase
from ..robots import description_for
from ..signature import Param
from ..world import Object
from ..world.pose import check_position, check_quaternion, quat_multiply
from ._common import attached_descendants
from .ik import Settings, solve_link
from .query import Call, QueryAnswer, QuerySpec, declare_query, degrees, finite, mm, parameters, place

if TYPE_CHECKING:
    from ..world import Object

#: the robot touches an object when their collision shapes are closer than this (m)
TOUCH = 0.001
#: how close (m) the tool frame must come to reach: the functions' default and the queries' declared one
REACH = 0.01


@dataclass(frozen=True)
class ReachableAnswer:
    """Truthy when reachable. `joint_positions`: the IK solution (the best found when unreachable);
    `position_error` (m) and `orientation_error` (rad, None without a grasp): what remains."""

    reachable: bool
    joint_positions: dict[str, float] = field(default_factory=dict)
    position_error: float = math.inf
    orientation_error: float | None = None

    def __bool__(self) -> bool:
        return self.reachable


@dataclass(frozen=True)
class TakeAnswer:
    """Whether the robot can take an object from where it stands, as pick-up would: with which arm and grasp, or why
    not (`reason`: out of reach, blocked, cannot hold; `detail`: what blocks, which object)."""

    takes: bool
    arm: str | None = None
    grasp: Any = None
    reason: str = ""
    detail: str = ""
    tried: tuple[tuple[str, Any, str], ...] = ()  # (arm, grasp, what it ran into) for every way tried
    joint_positions: dict[str, float] = field(default_factory=dict)  # the arm at the grasp
    position_error: float = math.inf  # at the grasp; when out of reach, how far the nearest grasp stays (m)
    orientation_error: float | None = None

    def __bool__(self) -> bool:
        return self.takes


#: how to tell whether the robot can take an object from where it stands: pick-up's own planning, registered by the
#: layer that has it (locations) — a query asked of an object answers for the poses pick-up will use
TakeCheck = Callable[["Object", "Object", "str | None", Any], TakeAnswer]
_TAKE_CHECKS: list[TakeCheck] = []


def register_take_check(check: TakeCheck) -> None:
    """Let `reachable` and `blocking` ask pick-up's planning about objects (done once, by pycram_cli.locations)."""
    _TAKE_CHECKS[:] = [check]


def can_take(robot: Object, obj: Object, arm: str | None = None, grasp: Any = None) -> TakeAnswer | None:
    """Pick-up's own answer for `obj` from where the robot stands, or None when no planner is loaded."""
    return _TAKE_CHECKS[0](robot, obj, arm, grasp) if _TAKE_CHECKS else None


def target_pose(target: Any) -> tuple[tuple[float, float, float], tuple[float, float, float, float] | None]:
    """(position, orientation or None) of an object, a position or a (position, orientation) pose."""
    if hasattr(target, "get_position") and hasattr(target, "world"):
        return target.get_position(), None
    items = list(target)
    if len(items) == 2 and all(hasattr(v, "__len__") for v in items):
        return check_position(items[0], "target position"), check_quaternion(items[1], "target orientation")
    return check_position(items, "target position"), None


def grasp_orientation(robot: Object, grasp: Any) -> tuple[float, float, float, float] | None:
    """World orientation of the tool for a grasp name (robot description, relative to the base) or a quaternion."""
    if grasp is None:
        return None
    if isinstance(grasp, str):
        desc = description_for(robot)
        grasps = desc.grasps if desc is not None else {}
        if grasp not in grasps:
            known = ", ".join(grasps) or "none: the robot has no description"
            raise BadValue(f"unknown grasp '{grasp}' for robot '{robot.name}' (grasps: {known})")
        return quat_multiply(robot.get_orientation(), grasps[grasp])
    return check_quaternion(grasp, "grasp orientation")


def _solve(target: Any, robot: Object, gripper_link: str, grasp: Any, threshold: float, angle_threshold: float):
    position, orientation = target_pose(target)
    wanted = grasp_orientation(robot, grasp)
    if wanted is None:
        wanted = orientation
    return solve_link(robot, gripper_link, position, wanted,
                      settings=Settings(threshold=threshold, angle_threshold=angle_threshold))


def reachable(target: Any, robot: Object, gripper_link: str, grasp: Any = None, threshold: float = REACH,
              angle_threshold: float = 0.1) -> ReachableAnswer:
    """Whether IK brings `gripper_link` within `threshold` m (and `angle_threshold` rad of the grasp) of `target`."""
    if not (threshold > 0 and math.isfinite(threshold)):
        raise BadValue(f"threshold must be a positive distance in metres, got {threshold!r}")
    with robot.world.lock:
        sol = _solve(target, robot, gripper_link, grasp, threshold, angle_threshold)
    return ReachableAnswer(sol.success, sol.joint_positions, sol.position_error, sol.orientation_error)


def blocking(target: Any, robot: Object, gripper_link: str, grasp: Any = None,
             exclude_types: Iterable[str] = (), threshold: float = REACH, angle_threshold: float = 0.1,
             tolerance: float = TOUCH) -> list[Object]:
    """The objects the robot touches at the IK solution for `target` (sorted by name).

    Never the target itself, the robot, or what the robot holds; objects whose type is in
    `exclude_types` are left out. For an unreachable target the best solution found is used.
    """
    with robot.world.lock:
        sol = _solve(target, robot, gripper_link, grasp, threshold, angle_threshold)
        return touching_at(robot, sol.joint_positions, target, exclude_types, tolerance)


def touching_at(robot: Object, joint_positions: dict[str, float], target: Any = None,
                exclude_types: Iterable[str] = (), tolerance: float = TOUCH) -> list[Object]:
    """The objects the robot touches with `joint_positions` applied (then put back exactly)."""
    world = robot.world
    excluded_types = {exclude_types} if isinstance(exclude_types, str) else set(exclude_types)
    with world.lock:
        held = attached_descendants(robot)
        skip = {robot.id, *(o.id for o in held)}
        if hasattr(target, "world") and hasattr(target, "id"):
            skip.add(target.id)
        candidates = [o for o in world.objects if o.id not in skip and o.type not in excluded_types]
        # tried on the world's prospection copy (held objects follow the copy's hand): the world is only read
        twin = world.prospection(velocities=False)
        copy = twin.copy_of(robot)
        if held:
            copy.set_joint_positions(joint_positions)
        else:
            copy.reset_joints(joint_positions)
        # what moves is what may not touch: the links the joints carry and what the robot holds (the base, the
        # torso and the wheels on the floor stay where they are)
        moving = copy.links_below(name for name in joint_positions if copy.joint(name).movable)
        found = [other for other in (twin.copy_of(o) for o in candidates)
                 if _touches(copy, moving, other, tolerance)
                 or any(other.world.distance(twin.copy_of(o), other, tolerance) < math.inf for o in held)]
        return sorted((twin.original_of(o) for o in found), key=lambda o: (o.name, o.id))


def _touches(body: Object, links: frozenset[int], other: Object, tolerance: float) -> bool:
    """Whether any of the body's `links` comes within `tolerance` of `other`."""
    return any(point.link_a in links for point in body.world.closest_points(body, other, tolerance))


# -- the query, by name (plans, `pycram query`, docs) --------------------------------------------------


_TARGET = "an object name or a position [x, y, z]"
_ARM = Param("arm", "arm", doc="the arm to reach with",
             default_doc="every arm in the description's order: the first that reaches")
_GRASP = Param("grasp", "grasp", doc="tool orientation: a grasp of the robot (front, top, ...) or a quaternion [x, y, z, w]",
               default_doc="any orientation")
_REACH = Param("threshold", "distance", doc="how close (m) the tool frame must come", default=REACH)


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
        target = place(a["target"])
        if answer.result:
            return f"{target} is reachable: pick-up takes it with {arm_phrase(d['arm'])} and a {place(d['grasp'])} grasp"
        why = {"blocked": f"blocked by {d['detail']}", "cannot hold": "no gripper can hold it"}.get(d["reason"],
                                                                                                  d["reason"])
        if d["reason"] == "out of reach" and d.get("position_error") is not None:
            why += f": the nearest grasp stays {mm(d['position_error'])} away"
        arms = ", ".join(arm_phrase(arm) for arm in d["arms_tried"])
        return f"{target} is NOT reachable from here: pick-up with {arms} finds no grasp ({why})"
    grasp = f", {place(a['grasp'])} grasp" if a.get("grasp") is not None else ""
    errors = f"{mm(d['position_error'])} from the target" + (f", {degrees(d['orientation_error'])} off" if grasp else "")
    if not answer.result:
        errors = f"{mm(d['position_error'])} short of the target" + (f", {degrees(d['orientation_error'])} off" if grasp else "")
    target = place(a["target"])
    if answer.result:
        return f"{target} is reachable with {arm_phrase(d['arm'])}{grasp} ({errors})"
    return f"{target} is NOT reachable (best: {arm_phrase(d['arm'])}{grasp}, {errors})"


declare_query(QuerySpec(
    "reachable", "Can the robot bring its tool frame to the target (within 1 cm, and the grasp orientation)? For an object: "
    "can pick-up take it from where the robot stands (its grasps, the ways there and back)?",
    parameters(Param("target", "target", True, _TARGET, positional=True), _ARM, _GRASP, _REACH), _reachable,
    _say_reachable))


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
    target = place(a["target"])
    reach = "" if d["reachable"] else f" (out of reach: the best solution stops {mm(d['position_error'])} short of the target)"
    if answer.result:
        return f"reaching {target} with {arm_phrase(d['arm'])} touches: {', '.join(answer.result)}{reach}"
    return f"nothing blocks {arm_phrase(d['arm'])} reaching {target}{reach}"


declare_query(QuerySpec(
    "blocking", "Which objects would the robot touch when reaching for the target?",
    parameters(Param("target", "target", True, _TARGET, positional=True), _ARM, _GRASP,
               Param("exclude-type", "types", doc="object types to leave out (e.g. environment)", default=[],
                     multiple=True), _REACH), _blocking, _say_blocking))
