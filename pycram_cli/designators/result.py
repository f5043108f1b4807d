"""What performing a designator gives back."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass
class Performed:
    """What a performed designator did: its resolved slots (JSON-friendly, for traces) and its result."""

    designator: str
    resolved: dict[str, Any] = field(default_factory=dict)
    result: Any = None
