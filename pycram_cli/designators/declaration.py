"""Declaring a motion designator once: its slots, how it is resolved, what it drives, who performs it.

    declare_designator(Designator(
        "moving", "Drive the robot base to a pose ...",
        (Slot("target", "position", True, "where the base goes"), ...),
        resolve=_resolve_moving, module="navigation", uses=drives("base"), needs=("mobile base",)))

Everything else is generated from the declarations in `DESIGNATORS`: plan validation
(`check_designator`), the scheduler's resources (`Designator.roles`), `pycram designators`,
and which process module performs it (`module`, unless the robot description names another).
Slot kinds are shared with query parameters (`pycram_cli.kinds`).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Mapping

from ..errors import InputError, did_you_mean
from ..kinds import KINDS, NOTHING_KNOWN, Robots

if TYPE_CHECKING:
    from ..robots import Robot
    from ..robots import RobotDescription

Resolver = Callable[["Robot", Mapping[str, Any]], dict[str, Any]]
#: the roles a designator drives, from its literal slot values (None where a value is only known at run time)
Uses = Callable[[Mapping[str, Any]], frozenset[str]]
#: a role for "every arm of the robot" (an arm slot left open, or only known at run time)
ANY_ARM = "arm:*"


@dataclass(frozen=True)
class Slot:
    name: str
    kind: str
    required: bool
    doc: str
    default: str | None = None  # how the default is found, for people
    of: str | None = None  # for a link or joint: the slot naming the object it belongs to


class HasSlots:
    """Looking slots up by name, for the declarations that have them (motion and action designators)."""

    name: str
    slots: tuple[Slot, ...]

    def slot(self, name: str) -> Slot | None:
        return next((s for s in self.slots if s.name == name), None)

    @property
    def slot_names(self) -> list[str]:
        return [s.name for s in self.slots]


@dataclass(frozen=True)
class Designator(HasSlots):
    """A motion designator type: the design's slots, its inference, its resources, its process module."""

    name: str
    doc: str
    slots: tuple[Slot, ...]
    resolve: Resolver  # fills in defaults and infers what is left open (design §4.6)
    module: str  # the process module that performs it, unless the robot description names another
    uses: Uses  # the roles it drives (base, head, arm:<name>), for the scheduler
    one_of: tuple[str, ...] = ()  # at least one of these slots must be given
    needs: tuple[str, ...] = ()  # what the robot must have: "mobile base", "head", "camera", "arms"
    resource: str = ""  # what it drives, for people
    check: "Callable[[Mapping[str, Any], Robots], list[SlotProblem]] | None" = None  # checks across slots


#: every designator by name, filled by `declare_designator` (explicit imports in `designators/__init__.py`)
DESIGNATORS: dict[str, Designator] = {}


def declare_designator(spec: Designator) -> Designator:
    """Register a designator; its name must be new and every slot's kind known."""
    if spec.name in DESIGNATORS:
        raise ValueError(f"designator '{spec.name}' is declared twice")
    for slot in spec.slots:
        if slot.kind not in KINDS:
            raise ValueError(f"designator '{spec.name}', slot '{slot.name}': unknown kind '{slot.kind}'")
    DESIGNATORS[spec.name] = spec
    return spec


# -- resources ------------------------------------------------------------------------------------


def drives(*roles: str) -> Uses:
    """Always the same roles (`base`, `head`); none for a designator that moves nothing."""
    fixed = frozenset(roles)
    return lambda slots: fixed


def drives_arm(slot: str) -> Uses:
    """The arm named in `slot`, or every arm when it is left open or only known at run time."""
    def uses(slots: Mapping[str, Any]) -> frozenset[str]:
        value = slots.get(slot)
        return frozenset({f"arm:{value}"}) if isinstance(value, str) and value else frozenset({ANY_ARM})

    return uses


def robot_resources(roles: frozenset[str], description: "RobotDescription | None") -> frozenset[str]:
    """The robot's physical resources behind some roles (`arm:*` is every arm; shared roles map to one resource).

    Without a description every arm role is one resource (`arm:*`), so that arm steps never overlap.
    """
    if description is None:
        return frozenset(ANY_ARM if role.startswith("arm:") else role for role in roles)
    expanded: set[str] = set()
    for role in roles:
        expanded |= {f"arm:{a}" for a in description.arms} if role == ANY_ARM else {role}
    return frozenset(description.resource(role) for role in expanded)


# -- static checks ---------------------------------------------------------------------------------


@dataclass
class SlotProblem:
    """A problem with one slot (or the designator itself when slot is None)."""

    message: str
    slot: str | None = None
    suggestion: str | None = None


def lacks(need: str, desc: "RobotDescription") -> str | None:
    """Why a robot lacks what a designator needs (`mobile base`, `head`, `camera`, `arms`), or None."""
    if need == "mobile base" and not desc.mobile:
        return "its base cannot move (mobile: false in its description)"
    if need == "head" and desc.head is None:
        return "it has no head (no head: in its description)"
    if need == "camera" and desc.camera is None:
        return "it has no camera (no camera: in its description)"
    if need == "arms" and not desc.arms:
        return "it has no arms"
    if need == "torso" and desc.torso_joint is None:
        return "it has no torso (no torso: in its description)"
    return None


def check_designator(type_name: str, slots: Mapping[str, Any], is_reference: Callable[[Any], bool] | None = None,
                     robots: Robots = NOTHING_KNOWN) -> list[SlotProblem]:
    """Static checks before anything runs: the type exists, slots are known, required ones present, values well-formed,
    and (when the robot is known) the robot has what the designator needs and the arms, grasps and poses named.

    `is_reference(value)` tells values only known at run time (plan variables); they skip the value check.
    """
    spec = DESIGNATORS.get(type_name)
    if spec is None:
        return [SlotProblem(f"unknown designator type '{type_name}'", None,
                            did_you_mean(type_name, DESIGNATORS) or f"known types: {', '.join(DESIGNATORS)}")]
    known = {k: v for k, v in slots.items() if not (is_reference is not None and is_reference(v))}
    return slot_problems(spec, f"'{type_name}'", slots, lambda slot, value: is_reference is not None and is_reference(value),
                         robots, known)


def slot_problems(spec: Any, what: str, slots: Mapping[str, Any], skip: Callable[[Slot, Any], bool],
                  robots: Robots, for_check: Mapping[str, Any]) -> list[SlotProblem]:
    """The checks motion and action designators share: what the robot needs, unknown slots (with the closest name),
    values against their kinds (unless `skip(slot, value)`: only known at run time), required slots, `one_of`,
    and the declaration's own check across slots (given `for_check`). `what` names the designator in messages."""
    name = spec.name
    problems: list[SlotProblem] = []
    if robots.known and len(robots.descriptions) == 1:
        for need in spec.needs:
            why = lacks(need, robots.descriptions[0])
            if why:
                problems.append(SlotProblem(f"robot '{robots.descriptions[0].name}' cannot perform '{name}': {why}"))
    for key, value in slots.items():
        slot = spec.slot(key)
        if slot is None:
            problems.append(SlotProblem(f"{what} has no slot '{key}'", key,
                                        did_you_mean(key, spec.slot_names) or f"slots: {', '.join(spec.slot_names)}"))
            continue
        if skip(slot, value):
            continue
        message = KINDS[slot.kind].check(value, robots)
        if message:
            problems.append(SlotProblem(f"slot '{key}': {message}", key))
    for slot in spec.slots:
        if slot.required and slot.name not in slots:
            problems.append(SlotProblem(f"{what} needs slot '{slot.name}' ({slot.doc})", slot.name))
    if spec.one_of and not any(key in slots for key in spec.one_of):
        problems.append(SlotProblem(f"{what} needs one of the slots {', '.join(spec.one_of)}", None))
    if spec.check is not None:
        problems.extend(spec.check(for_check, robots))
    return problems


def process_module_problems(desc: "RobotDescription") -> list[InputError]:
    """A description's `process_modules` keys that name no designator (each at its place, with the closest name)."""
    errors = []
    for designator in desc.process_modules:
        if designator not in DESIGNATORS:
            key = f"process_modules.{designator}"
            errors.append(InputError(f"no designator '{designator}'", desc.where(key), key=key,
                                     suggestion=did_you_mean(designator, DESIGNATORS)
                                     or f"designators: {', '.join(DESIGNATORS)}"))
    return errors
