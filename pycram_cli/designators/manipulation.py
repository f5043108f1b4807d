"""`pick-up`, `place` and `accessing`: the designators that take, put down and pull with an arm."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..errors import InputError, Location, did_you_mean
from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..kinds import arm_phrase, gripper_words
from ..locations import take_from_here
from ..planning.drawers import DISTANCE, handle_pose
from ..robots import Robot
from ..signature import Param, Signature
from ..world import Object
from .declaration import Designator, declare_designator, drives_arm
from .inference import choose_arm_and_grasp, free_arms, the_object


def _pick_up(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    obj = the_object(robot, slots["object"], "object")
    arm, grasp = slots.get("arm"), slots.get("grasp")
    if arm is None or grasp is None:
        arm, grasp = take_with(robot, obj, arm, grasp)
    return {"object": obj, "arm": arm, "grasp": grasp}


def take_with(robot: Robot, obj: Object, arm: str | None, grasp: Any) -> tuple[str, Any]:
    """The arm and grasp left open, chosen as the design's next solution: every free arm (nearest first) and grasp
    (the description's order) is tried with pick-up's own planning from where the robot stands, and the first that
    takes the object wins; when none does, the failure says what each ran into."""
    if not free_arms(robot, arm) or (arm is not None and robot.held_objects(arm)):
        held = ", ".join(o.name for o in robot.held_objects(arm))
        raise GripperFailure(f"the {gripper_words(arm)} already holds {held}" if arm is not None else
                             f"no free gripper to take {obj.name}: every gripper holds something", arm=arm, object=obj.name)
    answer = take_from_here(robot.body, obj, arm, grasp)  # a full hand takes nothing: only free arms are tried
    tried = answer.tried
    if answer.takes:
        assert answer.arm is not None
        return answer.arm, answer.grasp
    ways = "; ".join(f"{arm_phrase(a)} with {_grasp_words(g)}: {why}" for a, g, why in tried)
    text = f"nothing takes {obj.name} from here" + (f" ({ways})" if ways else f": {answer.reason}")
    kind = {"blocked": ManipulationFailure, "cannot hold": GripperFailure}.get(answer.reason, ReachabilityFailure)
    raise kind(text, object=obj.name, tried=[[a, g if isinstance(g, str) else list(g), why] for a, g, why in tried])


def _grasp_words(grasp: Any) -> str:
    return f"a {grasp} grasp" if isinstance(grasp, str) else "that grasp"


declare_designator(Designator(
    "pick-up", "Grasp an object with an arm and attach it to the gripper's tool frame.",
    Signature((
        Param("object", "object", True, "the object to pick up"),
        Param("arm", "arm", False, "the arm to use",
              default_doc="an arm that can reach the object (in the description's order)"),
        Param("grasp", "grasp", False, "the side to grasp from",
              default_doc="the first of the robot's grasps that works"),
    )),
    resolve=_pick_up, module="pick-up", uses=drives_arm("arm"), needs=("arms",), resource="arm"))


def _place(robot: Robot, slots: Mapping[str, Any]) -> dict[str, Any]:
    obj = the_object(robot, slots["object"], "object")
    arm = slots.get("arm") or robot.arm_holding(obj)
    if arm is None:
        raise ManipulationFailure(f"cannot place {obj.name}: the robot is not holding it", object=obj.name)
    return {"object": obj, "target": [float(v) for v in slots["target"]], "arm": arm}


declare_designator(Designator(
    "place", "Stand a held object on the surface under a target position, let go, and let it settle.",
    Signature((
        Param("object", "object", True, "the held object"),
        Param("target", "place-position", True, "where it stands: x, y (and z, optionally: the height of the surface)"),
        Param("arm", "arm", False, "the arm holding the object", default_doc="the arm that holds it"),
    )),
    resolve=_place, module="place", uses=drives_arm("arm"), needs=("arms",), resource="arm"))


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
    distance = float(slots["distance"])  # bound: the declared default when not given
    if joint.limited:  # the drawer stops at its joint's upper limit: the distance it really opens
        distance = min(distance, joint.upper - joint.lower)
    arm = slots.get("arm")
    if arm is None:
        pull = next(iter(robot.description.grasps), None)
        arm, _ = choose_arm_and_grasp(robot, lambda a, g: handle_pose(robot, a, part, handle), None, pull,
                                      f"the handle {handle}")
    return {"drawer-handle": handle, "drawer-joint": joint_name, "part-of": part, "distance": float(distance), "arm": arm}


declare_designator(Designator(
    "accessing", "Open a drawer: grasp its handle and pull it open by a distance.",
    Signature((
        Param("drawer-handle", "link", True, "the handle link, as named in the URDF", of="part-of"),
        Param("drawer-joint", "joint", True, "the drawer's prismatic joint", of="part-of"),
        Param("part-of", "object", True, "the object the drawer belongs to (e.g. kitchen)"),
        DISTANCE,
        Param("arm", "arm", False, "the arm that pulls",
              default_doc="an arm that can reach the handle (in the description's order)"),
    )),
    resolve=_accessing, module="accessing", uses=drives_arm("arm"), needs=("arms",), resource="arm"))
