"""The eleven motion designators of the design (tables 4.4–4.14) and their slots.

This is the single source of truth for plan validation, `pycram designators` and
resolution. Slot names are written as in the design (`drawer-joint`, `object-type`, ...).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

from ..errors import did_you_mean
from .slots import KINDS


@dataclass(frozen=True)
class Slot:
    name: str
    kind: str
    required: bool
    doc: str
    default: str | None = None  # how the default is found, for people


@dataclass(frozen=True)
class DesignatorType:
    name: str
    doc: str
    slots: tuple[Slot, ...]
    one_of: tuple[str, ...] = ()  # at least one of these must be given
    resource: str = ""  # the physical resource its process module drives (for people)

    def slot(self, name: str) -> Slot | None:
        return next((s for s in self.slots if s.name == name), None)

    @property
    def slot_names(self) -> list[str]:
        return [s.name for s in self.slots]


DESIGNATORS: dict[str, DesignatorType] = {d.name: d for d in (
    DesignatorType("moving", "Drive (teleport) the robot base to a pose; fails if the robot then collides with anything but the floor.", (
        Slot("target", "position", True, "where the base goes (z is ignored: the base stays on the floor)"),
        Slot("orientation", "quaternion", False, "base orientation", "the current orientation"),
    ), resource="base"),
    DesignatorType("pick-up", "Grasp an object with an arm and attach it to the gripper's tool frame.", (
        Slot("object", "object", True, "the object to pick up"),
        Slot("arm", "arm", False, "the arm to use", "an arm that can reach the object (left first)"),
        Slot("grasp", "grasp", False, "the side to grasp from", "the first of front, top, left, right that works"),
    ), resource="arm"),
    DesignatorType("place", "Bring a held object to a target position, open the gripper and let go.", (
        Slot("object", "object", True, "the held object"),
        Slot("target", "position", True, "where the object's origin (its bottom centre) goes"),
        Slot("arm", "arm", False, "the arm holding the object", "the arm that holds it"),
    ), resource="arm"),
    DesignatorType("accessing", "Open a drawer: grasp its handle and pull it open by a distance.", (
        Slot("drawer-handle", "link", True, "the handle link, as named in the URDF"),
        Slot("drawer-joint", "joint", True, "the drawer's prismatic joint"),
        Slot("part-of", "object", True, "the object the drawer belongs to (e.g. kitchen)"),
        Slot("distance", "number", False, "how far to open, in metres", "0.3, or the joint's upper limit if smaller"),
        Slot("arm", "arm", False, "the arm that pulls", "an arm that can reach the handle (left first)"),
    ), resource="arm"),
    DesignatorType("looking", "Turn the head so that the camera looks at a position or an object.", (
        Slot("target", "position", False, "the point to look at"),
        Slot("object", "object", False, "the object to look at", "looks at its position"),
    ), one_of=("target", "object"), resource="head"),
    DesignatorType("opening-gripper", "Open a gripper.", (
        Slot("gripper", "arm", True, "which gripper: left or right"),
    ), resource="gripper"),
    DesignatorType("closing-gripper", "Close a gripper.", (
        Slot("gripper", "arm", True, "which gripper: left or right"),
    ), resource="gripper"),
    DesignatorType("detecting", "Find a visible object of a type with the robot's camera; fails with PerceptionFailure if none is seen.", (
        Slot("object-type", "object-type", True, "the type of object to find"),
    ), resource="camera"),
    DesignatorType("move-tcp", "Move an arm's tool centre point (tool frame) to a position.", (
        Slot("target", "position", True, "where the tool frame goes"),
        Slot("orientation", "grasp", False, "tool orientation: front, top, left, right or a quaternion", "any orientation"),
        Slot("arm", "arm", False, "the arm to move", "an arm that can reach the target (left first)"),
    ), resource="arm"),
    DesignatorType("move-arm-joints", "Set the joints of one or both arms to a named pose (park) or to joint values.", (
        Slot("left-arm", "arm-config", False, "configuration of the left arm"),
        Slot("right-arm", "arm-config", False, "configuration of the right arm"),
    ), one_of=("left-arm", "right-arm"), resource="arms"),
    DesignatorType("world-state-detecting", "Find an object of a type from the world state, whether visible or not.", (
        Slot("object-type", "object-type", True, "the type of object to find"),
    ), resource="belief"),
)}


@dataclass
class SlotProblem:
    """A problem with one slot (or the designator type itself when slot is None)."""

    message: str
    slot: str | None = None
    suggestion: str | None = None


def check_designator(type_name: str, slots: Mapping[str, Any], is_reference: Any = None) -> list[SlotProblem]:
    """Static checks before anything runs: type exists, slots known, required present, values well-formed.

    `is_reference(value)` tells values that are only known at run time (plan variables); they skip the value check.
    """
    spec = DESIGNATORS.get(type_name)
    if spec is None:
        return [SlotProblem(f"unknown designator type '{type_name}'", None,
                            did_you_mean(type_name, DESIGNATORS) or f"known types: {', '.join(DESIGNATORS)}")]
    problems: list[SlotProblem] = []
    for name, value in slots.items():
        slot = spec.slot(name)
        if slot is None:
            problems.append(SlotProblem(f"'{type_name}' has no slot '{name}'", name,
                                        did_you_mean(name, spec.slot_names) or f"slots: {', '.join(spec.slot_names)}"))
            continue
        if is_reference is not None and is_reference(value):
            continue
        message = KINDS[slot.kind].check(value)
        if message:
            problems.append(SlotProblem(f"slot '{name}': {message}", name))
    for slot in spec.slots:
        if slot.required and slot.name not in slots:
            problems.append(SlotProblem(f"'{type_name}' needs slot '{slot.name}' ({slot.doc})", slot.name))
    if spec.one_of and not any(name in slots for name in spec.one_of):
        problems.append(SlotProblem(f"'{type_name}' needs one of the slots {', '.join(spec.one_of)}", None))
    return problems
