"""Options and helpers shared by several commands."""
from __future__ import annotations

import contextlib
import math
from pathlib import Path
from typing import Callable, Iterator, TypeVar

import click

from ..errors import InputError, Location
from ..paths import find_world
from ..world import BulletWorld
from ..worldfile.loader import load_world

F = TypeVar("F", bound=Callable[..., object])


class Number(click.ParamType):
    """A finite number in [low, high]; anything else is an input error naming the option (exit 2)."""

    name = "number"

    def __init__(self, low: float, high: float) -> None:
        self.low, self.high = low, high

    def convert(self, value: object, param: click.Parameter | None, ctx: click.Context | None) -> float:
        option = param.opts[0] if param is not None and param.opts else "value"
        try:
            number = float(value)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise InputError(f"expected a number, got '{value}'", Location(option)) from None
        if not math.isfinite(number) or not self.low <= number <= self.high:
            raise InputError(f"expected a finite number from {self.low:g} to {self.high:g}, got '{value}'",
                             Location(option))
        return number


def resolve_world_path(value: str | None) -> Path:
    """A world file path; a bare name like `kitchen` means a bundled world (None: the default world)."""
    return find_world(value)


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
    path = resolve_world_path(value)
    world = load_world(path, mode=mode)
    try:
        yield world, path
    finally:
        world.exit()
