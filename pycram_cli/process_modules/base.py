"""What every process module is: an executor of one kind of resolved designator on a robot."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..robots import Robot


class ProcessModule:
    """Executes one kind of resolved designator on a robot. Subclasses implement `execute`."""

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> Any:  # pragma: no cover - interface
        raise NotImplementedError
