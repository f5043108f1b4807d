"""Process modules by name: a designator names the module that performs it by default, and a robot
description may name another (`process_modules: {moving: my-navigation}`).

    @process_module("navigation")
    class Navigation(ProcessModule): ...
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, TypeVar

from ..errors import InputError, Location, did_you_mean
from .base import ProcessModule

if TYPE_CHECKING:
    from ..robots import RobotDescription

T = TypeVar("T", bound=type[ProcessModule])

#: every process module by name, filled by `process_module` (explicit imports in `process_modules/__init__.py`)
PROCESS_MODULES: dict[str, ProcessModule] = {}


def process_module(name: str) -> Callable[[T], T]:
    """Class decorator: register a process module under `name`."""

    def register(cls: T) -> T:
        if name in PROCESS_MODULES and type(PROCESS_MODULES[name]) is not cls:
            raise ValueError(f"process module '{name}' is registered twice")
        PROCESS_MODULES[name] = cls()
        return cls

    return register


def module_name(designator: str, default: str, description: RobotDescription | None) -> str:
    """The module that performs `designator` on a robot: its description's choice, else the designator's default."""
    if description is not None:
        return description.process_modules.get(designator, default)
    return default


def choose(designator: str, default: str, description: RobotDescription | None = None) -> ProcessModule:
    """The process module for `designator` on a robot; an unknown module name is an input error."""
    name = module_name(designator, default, description)
    module = PROCESS_MODULES.get(name)
    if module is None:
        where = Location(str(description.path)) if description is not None and name != default else Location("process modules")
        raise InputError(f"no process module '{name}' for '{designator}'", where, key=f"process_modules.{designator}",
                         suggestion=did_you_mean(name, PROCESS_MODULES) or f"modules: {', '.join(sorted(PROCESS_MODULES))}")
    return module
