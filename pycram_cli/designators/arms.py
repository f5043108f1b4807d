"""`move-tcp`, `move-arm-joints`, `opening-gripper` and `closing-gripper`: arms and grippers."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..failures import ReachabilityFailure
from ..kinds import KINDS, Robots
from ..planning.pick_place import grasp_orientation
from ..planning.reach import arm_configs, reach
from ..robots import Robot
from ..signature import Param, Problem, Signature
from .declaration import ANY_ARM, Designator, declare_designator, drives_arm


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


declare_designator(Designator(
    "move-tcp", "Move an arm's tool centre point (tool frame) to a position.",
    Signature((
        Param("target", "position", True, "where the tool frame goes"),
        Param("orientation", "grasp", False, "tool orientation: a grasp of the robot or a quaternion",
              default_doc="any orientation"),
        Param("arm", "arm", False, "the arm to move",
              default_doc="an arm that can reach the target (in the description's order)"),
    )),
    resolve=_move_tcp, module="tcp", uses=drives_arm("arm"), needs=("arms",), resource="arm"))


def _move_arm_joints(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in slots.items() if v is not None}


def _arms_moved(slots: Mapping[str, Any]) -> frozenset[str]:
    """The arms whose configuration is given (every arm when the `arms` mapping is only known at run time)."""
    if "arms" in slots and not isinstance(slots["arms"], Mapping):
        return frozenset({ANY_ARM})
    return frozenset(f"arm:{arm}" for arm in arm_configs(slots))


def _check_design_slots(slots: Mapping[str, Any], robots: Robots) -> list[Problem]:
    """`left-arm` and `right-arm` name arms too: the robot must have them, with as many joints as values given."""
    problems = []
    for key in ("left-arm", "right-arm"):
        if key not in slots:
            continue
        arm = key[: -len("-arm")]
        problem = KINDS["arm"].check(arm, robots)
        if problem:
            problems.append(Problem(f"slot '{key}': {problem}", key, "use arms: {ARM: CONFIGURATION} for the "
                                        "robot's own arm names" if "has no arm" in problem else None))
            continue
        if isinstance(slots[key], str):
            continue  # a pose's name: the slot's own kind checks it against the robot's poses
        problem = KINDS["arm-configs"].check({arm: slots[key]}, robots)  # joint values counted against the arm
        if problem:
            problems.append(Problem(f"slot '{key}': {problem.split(': ', 1)[1]}", key))
    return problems


declare_designator(Designator(
    "move-arm-joints", "Set the joints of arms to a named pose (park) or to joint values, along a collision-free "
    "path: straight in joint space, else around what is in the way.",
    Signature((
        Param("arms", "arm-configs", False, "configuration by arm name, e.g. {left: park, right: [0, 0, ...]}"),
        Param("left-arm", "arm-config", False, "configuration of the left arm (the design's slot name)"),
        Param("right-arm", "arm-config", False, "configuration of the right arm (the design's slot name)"),
    ), one_of=("arms", "left-arm", "right-arm"), across=_check_design_slots),
    resolve=_move_arm_joints, module="arm-joints", uses=_arms_moved, needs=("arms",), resource="arms"))


def _gripper(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    return {"gripper": slots["gripper"]}


for _name, _verb, _module in (("opening-gripper", "Open", "open-gripper"), ("closing-gripper", "Close", "close-gripper")):
    declare_designator(Designator(
        _name, f"{_verb} a gripper.",
        Signature((
            Param("gripper", "arm", True, "which gripper: the arm it belongs to"),
        )),
        resolve=_gripper, module=_module, uses=drives_arm("gripper"), needs=("arms",), resource="gripper"))
