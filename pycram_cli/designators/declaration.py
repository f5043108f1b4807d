"""Declaring a motion designator once: its slots, how it is resolved, what it drives, who performs it.

    declare_designator(Designator(
        "moving", "Drive the robot base to a pose ...",
        Signature((Param("target", "position", True, "where the base goes"), ...)),
        resolve=_resolve_moving, module="navigation", uses=drives("base"), needs=("mobile base",)))

Everything else is generated from the declarations in `DESIGNATORS`: plan validation
(`check_designator`), the scheduler's resources (`Designator.uses`), `pycram designators`,
and which process module performs it (`module`, unless the robot description names another).
Slots are `Param`s of a `Signature` (`pycram_cli.signature`), the shape queries and actions share;
its defaults are filled in (`bind`) before `resolve` sees the slots.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..errors import InputError, did_you_mean
from ..kinds import NOTHING_KNOWN, Robots
from ..signature import Param, Problem, Registry, Signature, Skip

if TYPE_CHECKING:
    from ..robots import Robot, RobotDescription

Resolver = Callable[["Robot", Mapping[str, Any]], dict[str, Any]]
#: the roles a designator drives, from its literal slot values (None where a value is only known at run time)
Uses = Callable[[Mapping[str, Any]], frozenset[str]]
#: a role for "every arm of the robot" (an arm slot left open, or only known at run time)
ANY_ARM = "arm:*"


class HasSlots:
    """A designator's slots by name (motion and action designators), from its signature."""

    name: str
    signature: Signature
    needs: tuple[str, ...]  # what the robot must have: "mobile base", "head", "camera", "arms"

    @property
    def slots(self) -> tuple[Param, ...]:
        return self.signature.params

    def slot(self, name: str) -> Param | None:
        return self.signature.param(name)

    @property
    def slot_names(self) -> list[str]:
        return self.signature.names

    @property
    def one_of(self) -> tuple[str, ...]:
        return self.signature.one_of


@dataclass(frozen=True)
class Designator(HasSlots):
    """A motion designator type: the design's slots (its signature), its inference, its resources, its process module."""

    name: str
    doc: str
    signature: Signature
    resolve: Resolver  # infers what the bound slots leave open (design §4.6): declared defaults are filled in already
    module: str  # the process module that performs it, unless the robot description names another
    uses: Uses  # the roles it drives (base, head, arm:<name>), for the scheduler
    needs: tuple[str, ...] = ()  # what the robot must have: "mobile base", "head", "camera", "arms"
    resource: str = ""  # what it drives, for people


#: every designator by name, filled by `declare_designator` (explicit imports in `designators/__init__.py`)
DESIGNATORS: Registry[Designator] = Registry("designator type", "known types")


def declare_designator(spec: Designator) -> Designator:
    """Register a designator; its name must be new and every slot's kind known."""
    return DESIGNATORS.declare(spec)


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


def robot_resources(roles: frozenset[str], description: RobotDescription | None) -> frozenset[str]:
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


def lacks(need: str, desc: RobotDescription) -> str | None:
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
                     robots: Robots = NOTHING_KNOWN) -> list[Problem]:
    """Static checks before anything runs: the type exists, slots are known, required ones present, values well-formed,
    and (when the robot is known) the robot has what the designator needs and the arms, grasps and poses named.

    `is_reference(value)` tells values only known at run time (plan variables); they skip the value check.
    """
    spec = DESIGNATORS.get(type_name)
    if spec is None:
        return [DESIGNATORS.unknown(type_name)]
    known = {k: v for k, v in slots.items() if not (is_reference is not None and is_reference(v))}
    return slot_problems(spec, f"'{type_name}'", slots, lambda slot, value: is_reference is not None and is_reference(value),
                         robots, known)


def slot_problems(spec: HasSlots, what: str, slots: Mapping[str, Any], skip: Skip, robots: Robots,
                  for_check: Mapping[str, Any]) -> list[Problem]:
    """The checks motion and action designators share: what the robot needs, then the signature's checks (values
    against their kinds unless `skip(slot, value)`, required slots, `one_of`, the check across slots given
    `for_check`). `what` names the designator in messages."""
    problems: list[Problem] = []
    if robots.known and len(robots.descriptions) == 1:
        for need in spec.needs:
            why = lacks(need, robots.descriptions[0])
            if why:
                problems.append(Problem(f"robot '{robots.descriptions[0].name}' cannot perform '{spec.name}': {why}"))
    return problems + spec.signature.check(slots, robots, what, skip, for_check)


def process_module_problems(desc: RobotDescription) -> list[InputError]:
    """A description's `process_modules` keys that name no designator (each at its place, with the closest name)."""
    errors = []
    for designator in desc.process_modules:
        if designator not in DESIGNATORS:
            key = f"process_modules.{designator}"
            errors.append(InputError(f"no designator '{designator}'", desc.where(key), key=key,
                                     suggestion=did_you_mean(designator, DESIGNATORS)
                                     or f"designators: {', '.join(DESIGNATORS)}"))
    return errors
