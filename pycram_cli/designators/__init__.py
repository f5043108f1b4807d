"""Motion designators: symbolic descriptions of motions, checked, resolved and performed."""
from __future__ import annotations

from typing import Any, Mapping

from .result import Performed
from .spec import DESIGNATORS, DesignatorType, Slot, SlotProblem, check_designator


def perform(world: Any, designator: str, slots: Mapping[str, Any]) -> Performed:
    """Perform one motion designator with the world's robot (see `designators.perform`)."""
    from .perform import perform as _perform  # process modules load on first use

    return _perform(world, designator, slots)


__all__ = ["DESIGNATORS", "DesignatorType", "Performed", "Slot", "SlotProblem", "check_designator", "perform"]
