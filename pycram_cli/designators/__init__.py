"""Motion designators: symbolic descriptions of motions, checked, resolved and performed."""
from .spec import DESIGNATORS, DesignatorType, Slot, SlotProblem, check_designator

__all__ = ["DESIGNATORS", "DesignatorType", "Slot", "SlotProblem", "check_designator"]
