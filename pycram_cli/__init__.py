"""pycram: plans for mobile pick-and-place robots, run in a lightweight PyBullet world.

    from pycram_cli import BulletWorld, Object, load_world

The names are loaded on first use, so that `pycram --help` and other commands that need no
simulation start without loading PyBullet.
"""
from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

_LAZY = {"BulletWorld": ".world", "Object": ".world", "Event": ".world", "WorldState": ".world",
         "current_world": ".world", "load_world": ".worldfile.loader"}


def __getattr__(name: str) -> Any:
    """`pycram_cli.BulletWorld` and friends, imported when first asked for (PEP 562)."""
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'pycram_cli' has no attribute {name!r}")


__all__ = ["BulletWorld", "Object", "Event", "WorldState", "current_world", "load_world", "__version__"]
