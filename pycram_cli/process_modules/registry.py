"""Choosing a process module: a registry keyed by designator type and robot.

A module registered for a robot name wins over one registered for any robot (None);
the default modules are description-driven and serve every robot that has a description.
"""
from __future__ import annotations

from typing import Callable, TypeVar

from .base import ProcessModule

T = TypeVar("T", bound=type[ProcessModule])

PROCESS_MODULES: dict[tuple[str, str | None], ProcessModule] = {}


def process_module(designator: str, robot: str | None = None) -> Callable[[T], T]:
    """Class decorator: register a process module for `designator` on `robot` (None: any robot)."""

    def register(cls: T) -> T:
        PROCESS_MODULES[(designator, robot)] = cls()
        return cls

    return register


def choose(designator: str, robot: str | None) -> ProcessModule:
    module = PROCESS_MODULES.get((designator, robot)) or PROCESS_MODULES.get((designator, None))
    if module is None:
        raise LookupError(f"no process module for '{designator}' on robot '{robot}'")
    return module
