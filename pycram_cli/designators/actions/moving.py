"""`navigate`, `park-arms`, `move-torso`, `look-at`: actions that move the robot's body."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ...failures import ManipulationFailure, NavigationFailure
from ...kinds import arm_words
from ...schema import is_vector
from ...signature import Param, Signature
from ..declaration import ANY_ARM, drives
from .actor import Actor, Finder
from .common import go, location_slot, object_of, rest_pose, resting, try_choices
from .declaration import Action, declare_action

BASE_POSE_GOALS = ("reachable-for", "visible-for", "accessing")


def _navigate(actor: Actor, slots: Mapping[str, Any]) -> Any:
    finder = Finder(slots["target"], here=True)

    def drive(a: Actor, pose: Any) -> Any:
        go(a, pose)
        return pose.to_json()

    return try_choices(actor, finder, drive, "navigate", (NavigationFailure,))


declare_action(Action(
    "navigate", "Drive to a base pose of a location (the best one that works; stays put when the robot stands at one).",
    Signature((
        Param("target", "location", True, "where to stand: {reachable-for: ...}, {visible-for: ...} or {accessing: ...}"),
    ), across=location_slot("target", BASE_POSE_GOALS,
                            "navigate goes to a base pose: reachable-for, visible-for or accessing")),
    run=_navigate, uses=drives("base"), needs=("mobile base",), returns="the pose (position, orientation, ...)"))


def _park_arms(actor: Actor, slots: Mapping[str, Any]) -> None:
    robot = actor.robot
    arms = [slots["arm"]] if slots.get("arm") else list(robot.description.arms)
    for arm in arms:
        if rest_pose(robot, arm) is None:
            raise ManipulationFailure(f"the {arm_words(arm)} of {robot.description.name} has no park pose in its description",
                                      arm=arm)
    moves = resting(robot, arms)
    if moves:
        actor.motion("move-arm-joints", {"arms": moves})


def _park_uses(slots: Mapping[str, Any]) -> frozenset[str]:
    arm = slots.get("arm")
    return frozenset({f"arm:{arm}"}) if isinstance(arm, str) and arm else frozenset({ANY_ARM})


declare_action(Action(
    "park-arms", "Put the arms in their park pose (an arm holding something in its carry pose, if it has one).",
    Signature((
        Param("arm", "arm", False, "the arm to park", default_doc="every arm"),
    )),
    run=_park_arms, uses=_park_uses, needs=("arms",)))


def _move_torso(actor: Actor, slots: Mapping[str, Any]) -> None:
    actor.motion("moving-torso", {"position": slots.get("position")})


declare_action(Action(
    "move-torso", "Raise or lower the torso.",
    Signature((
        Param("position", "number", False, "the torso joint's position in metres",
              default_doc="the description's torso default"),
    )),
    run=_move_torso, uses=drives("torso"), needs=("torso",)))


def _look_at(actor: Actor, slots: Mapping[str, Any]) -> None:
    target = slots["target"]
    if is_vector(target, 3):
        actor.motion("looking", {"target": [float(v) for v in target]})
    else:
        actor.motion("looking", {"object": object_of(actor, target, "target")})


declare_action(Action(
    "look-at", "Point the camera at an object or a position (turning the head, the arm or the base that carries it).",
    Signature((
        Param("target", "target", True, "what to look at"),
    )),
    run=_look_at, uses=drives("head"), needs=("camera",)))
