"""Resolution: fill in defaults and infer what a designator leaves open (design §4.6).

One resolver per designator type, registered in RESOLVERS. Each returns the complete
slot values the process module needs; `jsonable` turns them into what traces record.
"""
from __future__ import annotations

import math
from typing import Any, Callable, Mapping, Sequence

from ..errors import InputError, Location, did_you_mean
from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..process_modules.arms import GRASP_ORDER, reach
from ..process_modules.base import Robot
from ..process_modules.manipulation import grasp_orientation, grasp_target
from ..world import Object

Resolver = Callable[[Robot, Mapping[str, Any]], dict[str, Any]]
RESOLVERS: dict[str, Resolver] = {}


def resolver(name: str) -> Callable[[Resolver], Resolver]:
    def register(func: Resolver) -> Resolver:
        RESOLVERS[name] = func
        return func

    return register


def the_object(robot: Robot, value: Any, slot: str) -> Object:
    if isinstance(value, Object):
        return value
    found = robot.world.get_object_by_name(str(value))
    if found is None:
        names = [o.name for o in robot.world.objects]
        raise InputError(f"no object '{value}'", Location(f"slot {slot}"), key=slot, suggestion=did_you_mean(str(value), names))
    return found


def _free_arms(robot: Robot, preferred: str | None) -> list[str]:
    arms = [preferred] if preferred else list(robot.description.arms)
    return [a for a in arms if preferred or not robot.held_objects(a)]


def choose_arm_and_grasp(robot: Robot, position_of: Callable[[str, Any], Sequence[float] | None], arm: str | None,
                         grasp: Any, what: str) -> tuple[str, Any]:
    """The first arm (in description order) and grasp (front, top, left, right) that can hold it and whose IK succeeds.

    `position_of(arm, grasp)` gives the tool position for a grasp, or None when that arm cannot hold it that way.
    """
    grasps = [grasp] if grasp is not None else list(GRASP_ORDER)
    best: tuple[float, str, Any] | None = None
    holdable = False
    for candidate_arm in _free_arms(robot, arm):
        for candidate in grasps:
            position = position_of(candidate_arm, candidate)
            if position is None:
                continue
            holdable = True
            solution = reach(robot, candidate_arm, position, grasp_orientation(robot, candidate))
            if solution.success:
                return candidate_arm, candidate
            if best is None or solution.position_error < best[0]:
                best = (solution.position_error, candidate_arm, candidate)
    if best is None:
        if not _free_arms(robot, arm):
            raise GripperFailure(f"no free gripper to take {what}: both hold something")
        if not holdable:
            raise GripperFailure(f"no gripper can hold {what} with " + (f"a {grasp} grasp" if isinstance(grasp, str) else "any grasp")
                                 + " (too wide between the fingers)")
        raise ReachabilityFailure(f"no arm can reach {what}")
    grasp_text = f" with a {best[2]} grasp" if isinstance(best[2], str) else ""
    raise ReachabilityFailure(f"no arm can reach {what}: best is the {best[1]} arm{grasp_text}, "
                              f"{best[0] * 100:.1f} cm away", position_error=best[0])


def _grasp_position(robot: Robot, arm: str, obj: Object, grasp: Any) -> Sequence[float] | None:
    target = grasp_target(robot, arm, obj, grasp)
    return None if target is None else target[0]


@resolver("moving")
def _moving(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {"target": [float(v) for v in slots["target"]],
            "orientation": list(slots.get("orientation") or robot.body.get_orientation())}


@resolver("pick-up")
def _pick_up(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    obj = the_object(robot, slots["object"], "object")
    arm, grasp = slots.get("arm"), slots.get("grasp")
    if arm is None or grasp is None:
        arm, grasp = choose_arm_and_grasp(robot, lambda a, g: _grasp_position(robot, a, obj, g), arm, grasp, obj.name)
    return {"object": obj, "arm": arm, "grasp": grasp}


@resolver("place")
def _place(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    obj = the_object(robot, slots["object"], "object")
    arm = slots.get("arm") or robot.arm_holding(obj)
    if arm is None:
        raise ManipulationFailure(f"cannot place {obj.name}: the robot is not holding it", object=obj.name)
    return {"object": obj, "target": [float(v) for v in slots["target"]], "arm": arm}


@resolver("accessing")
def _accessing(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    part = the_object(robot, slots["part-of"], "part-of")
    joint_name, handle = slots["drawer-joint"], slots["drawer-handle"]
    if joint_name not in part.joint_names:
        raise InputError(f"'{part.name}' has no joint '{joint_name}'", Location("slot drawer-joint"), key="drawer-joint",
                         suggestion=did_you_mean(joint_name, [j.name for j in part.movable_joints]))
    if handle not in part.link_names:
        raise InputError(f"'{part.name}' has no link '{handle}'", Location("slot drawer-handle"), key="drawer-handle",
                         suggestion=did_you_mean(handle, part.link_names))
    joint = part.joint(joint_name)
    distance = slots.get("distance")
    if distance is None:
        distance = min(0.3, joint.upper - joint.lower) if joint.limited else 0.3
    arm = slots.get("arm")
    if arm is None:
        arm, _ = choose_arm_and_grasp(robot, lambda a, g: part.get_link_position(handle), None, "front", f"the handle {handle}")
    return {"drawer-handle": handle, "drawer-joint": joint_name, "part-of": part, "distance": float(distance), "arm": arm}


@resolver("looking")
def _looking(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    if slots.get("target") is not None:
        return {"target": [float(v) for v in slots["target"]]}
    obj = the_object(robot, slots["object"], "object")
    lo, hi = obj.get_aabb()
    return {"object": obj, "target": [(a + b) / 2 for a, b in zip(lo, hi)]}


@resolver("opening-gripper")
@resolver("closing-gripper")
def _gripper(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {"gripper": slots["gripper"]}


@resolver("detecting")
@resolver("world-state-detecting")
def _detecting(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {"object-type": slots["object-type"]}


@resolver("move-tcp")
def _move_tcp(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    target = [float(v) for v in slots["target"]]
    grasp = slots.get("orientation")
    orientation = grasp_orientation(robot, grasp) if grasp is not None else None
    arm = slots.get("arm")
    if arm is None:
        for candidate in robot.description.arms:
            if reach(robot, candidate, target, orientation).success:
                arm = candidate
                break
        else:
            raise ReachabilityFailure(f"no arm can reach ({', '.join(f'{v:.3f}' for v in target)})")
    return {"target": target, "orientation": list(orientation) if orientation else None, "arm": arm,
            **({"grasp": grasp} if isinstance(grasp, str) else {})}


@resolver("move-arm-joints")
def _move_arm_joints(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in slots.items() if k in ("left-arm", "right-arm")}


def jsonable(value: Any) -> Any:
    """Objects become names, tuples lists, floats rounded: stable and comparable in traces."""
    if isinstance(value, Object):
        return value.name
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, float):
        rounded = round(value, 6)
        return 0.0 if rounded == 0 or math.isclose(rounded, 0.0, abs_tol=1e-12) else rounded
    return value
