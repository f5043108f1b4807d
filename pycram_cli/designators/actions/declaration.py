"""Declaring an action designator once: its slots, what it does, the roles it drives.

    declare_action(Action(
        "navigate", "Drive to a location ...",
        Signature((Param("target", "location", True, "where to go"),)),
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

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ...kinds import NOTHING_KNOWN, Robots
from ...signature import Param, Problem, Registry, Signature
from ..declaration import HasSlots, Uses, slot_problems

if TYPE_CHECKING:
    from .actor import Actor

Run = Callable[["Actor", Mapping[str, Any]], Any]


@dataclass(frozen=True)
class Action(HasSlots):
    """An action designator type: its slots (its signature), how it expands (`run`, given the bound slots), and the
    roles it drives (for the scheduler)."""

    name: str
    doc: str
    signature: Signature
    run: Run
    uses: Uses
    needs: tuple[str, ...] = ()  # what the robot must have: "mobile base", "head", "camera", "arms"
    returns: str = ""  # what `as:` binds, for people

    def perform(self, actor: Actor, slots: Mapping[str, Any]) -> Any:
        """Run the action with its declared defaults filled in."""
        return self.run(actor, self.signature.bind(slots))


#: every action designator by name, filled by `declare_action` (explicit imports in `actions/__init__.py`)
ACTIONS: Registry[Action] = Registry("action", "actions")


def declare_action(spec: Action) -> Action:
    """Register an action; its name must be new and every slot's kind known."""
    return ACTIONS.declare(spec)


def check_action(type_name: str, slots: Mapping[str, Any], is_reference: Callable[[Any], bool] | None = None,
                 robots: Robots = NOTHING_KNOWN) -> list[Problem]:
    """Static checks before anything runs: the action exists, its slots are known, required ones given, values
    well-formed (a location mapping is checked key by key, even when some of its values are variables)."""
    spec = ACTIONS.get(type_name)
    if spec is None:
        return [ACTIONS.unknown(type_name)]
    def skip(slot: Param, value: Any) -> bool:  # a location mapping is checked key by key, even around variables
        whole = is_reference is not None and isinstance(value, str) and is_reference(value)
        return whole or (is_reference is not None and slot.kind != "location" and is_reference(value))

    return slot_problems(spec, f"action '{type_name}'", slots, skip, robots, slots)
