"""Options and helpers shared by several commands."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Callable, TypeVar

import click

from ..errors import InputError, Location
from ..paths import default_world, worlds_dir

if TYPE_CHECKING:
    from ..world import BulletWorld

F = TypeVar("F", bound=Callable[..., object])


def resolve_world_path(value: str | None) -> Path:
    """A world file path; a bare name like `kitchen` means a bundled world."""
    if value is None:
        return default_world()
    path = Path(value)
    if path.exists():
        return path
    bundled = worlds_dir() / (value if value.endswith((".yaml", ".yml")) else f"{value}.yaml")
    if bundled.exists():
        return bundled
    from ..errors import did_you_mean

    names = [p.stem for p in worlds_dir().glob("*.yaml")]
    raise InputError("world file not found", Location(value), suggestion=did_you_mean(value, names)
                     or (f"bundled worlds: {', '.join(sorted(names))}" if names else None))


def json_option(func: F) -> F:
    return click.option("--json", "as_json", is_flag=True, help="Machine-readable output on stdout.")(func)  # type: ignore[return-value]


def gui_option(func: F) -> F:
    return click.option("--gui", is_flag=True, help="Open PyBullet's window (needs a display, e.g. xvfb-run).")(func)  # type: ignore[return-value]


def wait_for_window(world: "BulletWorld") -> None:
    """Keep a GUI world open until its window is closed (or Ctrl-C)."""
    import time

    from . import console

    console.info("close the window or press Ctrl-C to exit")
    try:
        while world.is_connected():
            time.sleep(0.1)
    except KeyboardInterrupt:
        pass
