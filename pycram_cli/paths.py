"""Where the bundled data lives, both in a source checkout and in an installed package."""
from __future__ import annotations

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def bundled(name: str) -> Path:
    """The bundled folder `name` (`resources`, `worlds` or `plans`).

    An installed package carries it as `pycram_cli/_bundled/<name>`; a source
    checkout (editable install, tests) has it at the top of the repository.
    """
    installed = _PACKAGE / "_bundled" / name
    if installed.is_dir():
        return installed
    return _PACKAGE.parent / name


def resources_dir() -> Path:
    return bundled("resources")


def worlds_dir() -> Path:
    return bundled("worlds")


def plans_dir() -> Path:
    return bundled("plans")


def default_world() -> Path:
    """The world every command uses when none is given."""
    return worlds_dir() / "kitchen.yaml"


def cache_dir() -> Path:
    """A per-user folder for generated files (URDFs made from meshes, patched URDFs)."""
    import os

    base = os.environ.get("PYCRAM_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME")
    root = Path(base) if base else Path.home() / ".cache"
    folder = (root / "pycram") if not os.environ.get("PYCRAM_CACHE_DIR") else root
    folder.mkdir(parents=True, exist_ok=True)
    return folder
