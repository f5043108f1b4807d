"""Declaring an action designator once: its slots, what it does, the roles it drives.

    declare_action(Action(
        "navigate", "Drive to a location ...",
        (Slot("target", "location", True, "where to go"),),
        run=_navigate, uses=drives("base")))

An action is one level above the motion designators: its `run(actor, slots)` expands it into
motion designators, reasoning queries, location resolutions and other actions, each performed
through the `Actor` (`actor.py`), which records them as the action's children in the trace.
Action designators have a registry of their own (`ACTIONS`), apart from the motion designators'
(`DESIGNATORS`): two names exist in both (`pick-up`, `place`), and in plans an action is written
under its own head (`action: pick-up`), so that the motion designators keep their meaning.
Slot kinds are the ones motion designators and queries use (`pycram_cli.kinds`), including
`location` for location designators.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping

from ...errors import did_you_mean
from ...kinds import KINDS, NOTHING_KNOWN, Robots
from ..declaration import HasSlots, Slot, SlotProblem, Uses, slot_problems

if TYPE_CHECKING:
    from .actor import Actor

Run = Callable[["Actor", Mapping[str, Any]], Any]


@dataclass(frozen=True)
class Action(HasSlots):
    """An action designator type: its slots, how it expands (`run`), and the roles it drives (for the scheduler)."""

    name: str
    doc: str
    slots: tuple[Slot, ...]
    run: Run
    uses: Uses
    one_of: tuple[str, ...] = ()
    needs: tuple[str, ...] = ()  # what the robot must have: "mobile base", "head", "camera", "arms"
    returns: str = ""  # what `as:` binds, for people
    check: "Callable[[Mapping[str, Any], Robots], list[SlotProblem]] | None" = None  # checks across slots


#: every action designator by name, filled by `declare_action` (explicit imports in `actions/__init__.py`)
ACTIONS: dict[str, Action] = {}


def declare_action(spec: Action) -> Action:
    """Register an action; its name must be new and every slot's kind known."""
    if spec.name in ACTIONS:
        raise ValueError(f"action '{spec.name}' is declared twice")
    for slot in spec.slots:
        if slot.kind not in KINDS:
            raise ValueError(f"action '{spec.name}', slot '{slot.name}': unknown kind '{slot.kind}'")
    ACTIONS[spec.name] = spec
    return spec


def check_action(type_name: str, slots: Mapping[str, Any], is_reference: Callable[[Any], bool] | None = None,
                 robots: Robots = NOTHING_KNOWN) -> list[SlotProblem]:
    """Static checks before anything runs: the action exists, its slots are known, required ones given, values
    well-formed (a location mapping is checked key by key, even when some of its values are variables)."""
    spec = ACTIONS.get(type_name)
    if spec is None:
        return [SlotProblem(f"unknown action '{type_name}'", None,
                            did_you_mean(type_name, ACTIONS) or f"actions: {', '.join(ACTIONS)}")]
    def skip(slot: Slot, value: Any) -> bool:  # a location mapping is checked key by key, even around variables
        whole = is_reference is not None and isinstance(value, str) and is_reference(value)
        return whole or (is_reference is not None and slot.kind != "location" and is_reference(value))

    return slot_problems(spec, f"action '{type_name}'", slots, skip, robots, slots)
