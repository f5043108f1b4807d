"""Options and helpers shared by several commands."""
from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, TypeVar

import click

from ..errors import InputError, Location, did_you_mean
from ..kinds import parse_vector
from ..limits import MAX_MAGNITUDE
from ..paths import find_world
from ..world import BulletWorld, Object
from ..world.camera import VIEWS, Camera, named_camera
from ..worldfile.loader import load_world
from .complete import world_names

F = TypeVar("F", bound=Callable[..., object])


class Number(click.ParamType):
    """A finite number in [low, high]; anything else is an input error naming the option (exit 2)."""

    name = "number"

    def __init__(self, low: float, high: float) -> None:
        self.low, self.high = low, high

    def convert(self, value: Any, param: click.Parameter | None, ctx: click.Context | None) -> float:
        option = param.opts[0] if param is not None and param.opts else "value"
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise InputError(f"expected a number, got '{value}'", Location(option)) from None
        if not math.isfinite(number) or not self.low <= number <= self.high:
            raise InputError(f"expected a finite number from {self.low:g} to {self.high:g}, got '{value}'",
                             Location(option))
        return number


def json_option(func: F) -> F:
    return click.option("--json", "as_json", is_flag=True, help="Machine-readable output on stdout.")(func)


def gui_option(func: F) -> F:
    return click.option("--gui", is_flag=True, help="Open PyBullet's window (needs a display, e.g. xvfb-run).")(func)


def wait_for_window(world: BulletWorld) -> None:
    """Keep a GUI world open until its window is closed (or Ctrl-C)."""
    import time

    from . import console

    console.info("close the window or press Ctrl-C to exit")
    try:
        while world.is_connected():
            time.sleep(0.1)
    except KeyboardInterrupt:
        pass


def joined(tokens: tuple[str, ...] | list[str]) -> list[str]:
    """Words the shell split inside one value joined again: `1.3, 0.6, 1.0` and `[1.3, 0.6, 1.0]` unquoted are
    one value (a word ending in a comma or an open bracket goes on in the next)."""
    values: list[str] = []
    for token in tokens:
        if values and (_goes_on(values[-1]) or token.startswith((",", "]", ")"))):
            values[-1] += token
        else:
            values.append(token)
    return values


def _goes_on(text: str) -> bool:
    """A word that says the value goes on in the next one: a trailing comma, an open bracket."""
    return text.endswith(",") or text.count("[") > text.count("]") or text.count("(") > text.count(")")


def is_number(text: str) -> bool:
    """A finite number, as a command-line word."""
    try:
        return math.isfinite(float(text))
    except ValueError:
        return False


def world_option(func: F) -> F:
    return click.option("--world", "world_file", metavar="WORLD", shell_complete=world_names,
                        help="World file or bundled world name (default: kitchen).")(func)


@contextlib.contextmanager
def open_world(value: str | None, mode: str = "direct") -> Iterator[tuple[BulletWorld, Path]]:
    """Load a world file (or bundled world) for one command; it exits when the command is done."""
    path = find_world(value)
    world = load_world(path, mode=mode)
    try:
        yield world, path
    finally:
        world.exit()


# -- images: camera and size ----------------------------------------------------------------------
def camera_option(func: F) -> F:
    return click.option(
        "--camera", metavar="VIEW|EYE:TARGET",
        help="Camera of the image: a view (overview: the whole scene; robot: the robot over its shoulder; "
             "target: the objects worked on) or EYE:TARGET, each x,y,z, e.g. -1.5,-1.5,2.5:1,0.8,0.9. "
             "Default: overview.")(func)


def size_option(func: F) -> F:
    return click.option("--size", metavar="WxH", default="960x720", show_default=True,
                        help="Image size in pixels (16 to 4096 each way).")(func)


def parse_size(text: str, option: str = "--size") -> tuple[int, int]:
    """`960x720` -> (960, 720); an InputError naming the option otherwise."""
    try:
        width, height = (int(v) for v in text.lower().split("x"))
        if not (16 <= width <= 4096 and 16 <= height <= 4096):
            raise ValueError
    except ValueError:
        raise InputError(f"expected WIDTHxHEIGHT between 16 and 4096, e.g. 960x720, got '{text}'",
                         Location(option)) from None
    return width, height


def _point(text: str, what: str) -> tuple[float, float, float]:
    values = parse_vector(text, 3)
    if values is None:
        raise ValueError(f"{what}: expected x,y,z (three finite numbers), got {text!r}")
    if not all(abs(v) <= MAX_MAGNITUDE for v in values):
        raise ValueError(f"{what}: numbers must be between {-MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g}, got {text!r}")
    return (values[0], values[1], values[2])


def parse_camera(text: str) -> Camera:
    """`EYE:TARGET`, each `x,y,z`, e.g. `-1.5,-1.5,2.5:1,0.8,0.9`."""
    eye, sep, target = text.partition(":")
    if not sep:
        raise ValueError(f"expected EYE:TARGET such as -1.5,-1.5,2.5:1,0.8,0.9, or a view ({', '.join(VIEWS)}), "
                         f"got {text!r}")
    camera = Camera(_point(eye, "camera eye"), _point(target, "camera target"))
    if math.dist(camera.eye, camera.target) < 1e-6:  # no direction to look in: the image would be blank
        raise ValueError(f"the camera's eye and target must differ, got {text!r}")
    return camera


def parse_view(text: str | None, option: str = "--camera") -> str | Camera:
    """A named view (overview, robot, target) or a Camera from EYE:TARGET; an InputError otherwise."""
    if text is None:
        return "overview"
    if text in VIEWS:
        return text
    try:
        return parse_camera(text)
    except ValueError as exc:
        hint = did_you_mean(text, VIEWS) if ":" not in text else None
        raise InputError(str(exc), Location(option), suggestion=hint) from None


def image_camera(world: BulletWorld, view: str | Camera, size: tuple[int, int],
                 targets: list[Object] | None = None) -> Camera:
    """The camera of an image: a named view computed on `world` as it is now, or the given camera."""
    if isinstance(view, Camera):
        return view
    return named_camera(world, view, targets, aspect=size[0] / size[1])
