"""The design's `pycram.designator.MotionDesignator`: a motion designator written as a list of (key, value) pairs,
`MotionDesignator([("type", "moving"), ("target", [0.65, 0.7, 0]), ("orientation", [0, 0, 0, 1])])`; performed by
`ProcessModule.perform` (pycram's designators check, resolve and perform it)."""
from __future__ import annotations

from collections.abc import Iterable
from typing import Any


class MotionDesignator:
    """The type and slots of a motion designator, from the design's list of pairs."""

    def __init__(self, description: Iterable[tuple[str, Any]]) -> None:
        pairs = [(str(key), value) for key, value in description]
        types = [value for key, value in pairs if key == "type"]
        if len(types) != 1:
            raise ValueError("a motion designator needs exactly one ('type', ...) pair")
        self.type: str = str(types[0])
        self.slots: dict[str, Any] = {key: value for key, value in pairs if key != "type"}

    def __repr__(self) -> str:
        return f"MotionDesignator({[('type', self.type), *self.slots.items()]!r})"
