"""`pycram locate GOAL TARGET`: resolve a location designator and say what was found and what was ruled out.

    pycram locate reachable-for milk [--arm A] [--grasp G] [--visible-for milk]
    pycram locate visible-for milk [--reachable-for milk]
    pycram locate on kitchen_island_surface --for milk [--near x,y,z]
    pycram locate accessing sink_area_left_upper_drawer_handle [--arm A]
    ... [--world W] [-n N] [--json] [--plot map.png]

Exit status: 0 when a pose is found, 1 when the location cannot be satisfied (the LocationFailure
says which tests ruled the candidates out), 2 on bad input (unknown objects, links, keys).
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click
from click.shell_completion import CompletionItem

from ..errors import InputError, Location
from ..failures import LocationFailure
from ..jsonable import jsonable
from ..kinds import LOCATION_GOALS, POSITION_FORMS, looks_like_numbers, parse_vector
from ..locations import BasePose, locate
from ..locations.plot import COLOURS, draw
from ..world.camera import write_png
from . import console
from .complete import link_names, object_names
from .files import check_plot
from .options import is_number, joined, open_world, world_option

EXIT_FAILED = 1


def _location(goal: str, target: str, arm: str | None, grasp: str | None, visible_for: str | None,
              reachable_for: str | None, for_object: str | None, near: str | None) -> dict[str, Any]:
    location: dict[str, Any] = {goal: parse_vector(target, 3) or target}
    for key, value in (("arm", arm), ("grasp", grasp), ("visible-for", visible_for), ("for", for_object)):
        if value is not None:
            location[key] = parse_vector(value, 4) if key == "grasp" and parse_vector(value, 4) else value
    if reachable_for is not None:
        location["reachable-for"] = parse_vector(reachable_for, 3) or reachable_for
    if near is not None:
        vector = parse_vector(near, 3)
        if vector is None:
            raise InputError(f"expected a position x,y,z, got {near!r}", Location("--near"), key="near",
                             suggestion=f"a position is written {POSITION_FORMS}")
        location["near"] = vector
    return location


def target_text(words: tuple[str, ...]) -> str:
    """TARGET from its words: one name or position, or a position split by the shell (`1.3, 0.6, 1.0`) or written
    as three numbers (`1.3 0.6 1.0`); anything else is an input error that shows how a position is written."""
    values = joined(words)
    if len(values) == 3 and all(map(is_number, values)):
        return ",".join(values)
    if len(values) != 1 or (looks_like_numbers(values[0]) and parse_vector(values[0], 3) is None):
        shown = " ".join(words)
        raise InputError(f"expected one TARGET (an object, a link or a position), got {shown!r}", Location("TARGET"),
                         suggestion=f"a position is written {POSITION_FORMS}")
    return values[0]


def target_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """TARGET: a link for `on` and `accessing` (handles first for `accessing`), else an object."""
    goal = ctx.params.get("goal")
    if goal not in ("on", "accessing"):
        return object_names(ctx, param, incomplete)
    links = link_names(ctx, incomplete)
    if goal == "accessing":
        links.sort(key=lambda item: "handle" not in str(item.value))
    return (object_names(ctx, param, incomplete) if goal == "on" else []) + links


def _row(rank: int, found: Any) -> tuple[str, ...]:
    x, y, z = found.position
    if isinstance(found, BasePose):
        return (str(rank), f"{x:.3f}", f"{y:.3f}", f"{math.degrees(found.yaw):.0f}°", found.arm or "-",
                (found.grasp if isinstance(found.grasp, str) else "-") if found.grasp is not None else "-",
                f"{found.score:.3f}")
    return (str(rank), f"{x:.3f}", f"{y:.3f}", f"{z:.3f}", found.surface, f"{found.score:.3f}")


@click.command("locate", short_help="Resolve a location designator: where to stand, or a free spot on a surface.")
@click.argument("goal", metavar="GOAL", type=click.Choice(LOCATION_GOALS))
@click.argument("target_words", metavar="TARGET", nargs=-1, required=True, shell_complete=target_names)
@click.option("--arm", metavar="ARM", help="reachable-for, accessing: the arm that must reach.")
@click.option("--grasp", metavar="GRASP", help="reachable-for: the grasp (front, top, ... or x,y,z,w).")
@click.option("--visible-for", "visible_for", metavar="OBJECT", shell_complete=object_names,
              help="reachable-for: seeing this object too.")
@click.option("--reachable-for", "reachable_for", metavar="TARGET", shell_complete=object_names,
              help="visible-for: reaching this too.")
@click.option("--for", "for_object", metavar="OBJECT", shell_complete=object_names,
              help="on: the object that must fit.")
@click.option("--near", metavar="X,Y,Z", help="on: a position the spot should be close to.")
@click.option("-n", "--count", default=3, show_default=True, metavar="N", type=click.IntRange(1, 50),
              help="How many poses (or spots) to find, best first.")
@click.option("--plot", "plot", metavar="PNG", type=click.Path(dir_okay=False),
              help="Draw the floor map from above: candidates coloured by the test that ruled them out.")
@world_option
@click.option("--json", "as_json", is_flag=True, help="Machine-readable output on stdout.")
@click.pass_context
def locate_cmd(ctx: click.Context, goal: str, target_words: tuple[str, ...], arm: str | None, grasp: str | None,
               visible_for: str | None, reachable_for: str | None, for_object: str | None, near: str | None,
               count: int, plot: str | None, world_file: str | None, as_json: bool) -> None:
    """Resolve a location designator in a world (default: the bundled kitchen) and show the poses found.

    \b
    GOAL is reachable-for, visible-for, on or accessing; TARGET an object, a position (reachable-for:
    1.3,0.6,1.0, [1.3,0.6,1.0], '1.3, 0.6, 1.0' or 1.3 0.6 1.0), a surface link or object (on), or a
    handle link (accessing).

    \b
    Examples:
      pycram locate reachable-for milk
      pycram locate reachable-for milk --visible-for milk --plot map.png
      pycram locate on kitchen_island_surface --for milk --json
      pycram locate accessing sink_area_left_upper_drawer_handle --world kitchen_fetch

    Exit status: 0 found, 1 cannot be satisfied, 2 bad input.
    """
    check_plot(Path(plot) if plot is not None else None)
    target = target_text(target_words)
    location = _location(goal, target, arm, grasp, visible_for, reachable_for, for_object, near)
    found: list[Any] = []
    failure: LocationFailure | None = None
    with open_world(world_file) as (world, path):
        resolution = locate(world, location)
        try:
            for _ in range(count):
                found.append(resolution.next())
        except LocationFailure as exc:
            failure = exc
        counts = resolution.counts()
        if plot is not None:
            write_png(Path(plot), draw(resolution))
        spec = resolution.spec
    status = "found" if found else "failed"
    if as_json:
        console.emit_json(jsonable({
            "location": spec.to_json(), "world": str(path), "status": status,
            "found": [f.to_json() for f in found], "candidates": len(resolution.candidates) if resolution.prepared else 0,
            "tried": resolution.cursor, "ruled_out": dict(sorted(counts.items())),
            "failure": failure.message if failure is not None and not found else None,
            **({"plot": plot} if plot else {})}, nonfinite=None))
    else:
        if found:
            base = isinstance(found[0], BasePose)
            columns = (["#", "x", "y", "yaw", "arm", "grasp", "score"] if base
                       else ["#", "x", "y", "z", "surface", "score"])
            console.table(f"{spec.describe()}: {len(found)} found", columns,
                          [_row(k + 1, f) for k, f in enumerate(found)])
            console.plain(f"{resolution.summary()} ({resolution.cursor} tried)")
        if failure is not None and not found:
            console.error(failure.message)
        if plot is not None:
            legend = ", ".join(f"{name}: rgb{colour}" for name, colour in COLOURS.items())
            console.info(f"wrote {plot} (from above, +x to the right; {legend})")
    if not found:
        ctx.exit(EXIT_FAILED)



