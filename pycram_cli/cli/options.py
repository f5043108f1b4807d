"""Options and helpers shared by several commands."""
from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Callable, Iterator, TypeVar

import click

from ..paths import find_world
from ..world import BulletWorld
from ..worldfile.loader import load_world

F = TypeVar("F", bound=Callable[..., object])


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


def world_option(func: F) -> F:
    return click.option("--world", "world_file", metavar="WORLD",
                        help="World file or bundled world name (default: kitchen).")(func)  # type: ignore[return-value]


@contextlib.contextmanager
def open_world(value: str | None, mode: str = "direct") -> Iterator[tuple[BulletWorld, Path]]:
    """Load a world file (or bundled world) for one command; it exits when the command is done."""
    path = find_world(value)
    world = load_world(path, mode=mode)
    try:
        yield world, path
    finally:
        world.exit()
