"""pycram: plans for mobile pick-and-place robots, run in a lightweight PyBullet world.

    from pycram_cli import BulletWorld, Object, load_world

The names are loaded on first use, so that importing the package (the `pycram` command
does, before it handles Ctrl-C) does not start PyBullet.
"""
from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

_EXPORTS = {"BulletWorld": ".world", "Object": ".world", "Event": ".world", "WorldState": ".world",
            "current_world": ".world", "load_world": ".worldfile.loader"}

__all__ = ["BulletWorld", "Object", "Event", "WorldState", "current_world", "load_world", "__version__"]


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'pycram_cli' has no attribute '{name}'")
    value = getattr(importlib.import_module(module, __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
