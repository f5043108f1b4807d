"""The map of a sweep: the floor and surfaces from above, each scenario's varied start positions
as a dot coloured by its outcome, so a person sees where the plan fails.

Rendered headless with the world's own renderer (TinyRenderer, only the fixed environment
objects: the things that were varied are drawn as dots), the markers and legend drawn over it with
`pycram_cli.drawing` (Pillow, as the location map is), and written with `camera.write_png`. Marker
shapes tell the varied objects apart (circle, square, triangle, diamond, ...), colours the outcomes
(green: succeeded; one colour per failure type); a legend with counts sits in a corner.
"""
from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..drawing import Picture, darker
from ..errors import InputError, Location
from ..world.camera import Camera, render, write_png
from ..worldfile.loader import load_spec
from .summary import outcome_of

if TYPE_CHECKING:
    from . import PreparedSweep

SUCCESS = (30, 160, 60)
PALETTE = [(215, 40, 40), (240, 140, 20), (130, 60, 190), (30, 110, 220), (150, 90, 40), (220, 60, 170),
           (0, 150, 150), (90, 90, 90)]
SPECIAL = {"Timeout": (0, 0, 0), "InternalError": (120, 120, 120)}
MARKERS = ("circle", "square", "triangle", "diamond", "cross", "ring")
CAMERA_HEIGHT = 20.0
PAD = 0.3  # m around the dots
RADIUS = 5  # px


def collect(records: list[dict[str, Any]]) -> list[tuple[str, tuple[float, float, float], str]]:
    """(object, start position, outcome) of every varied position in the records."""
    points = []
    for record in records:
        outcome = outcome_of(record)
        for name, varied in sorted((record.get("varied") or {}).items()):
            if isinstance(varied, dict) and "position" in varied:
                points.append((name, tuple(varied["position"]), outcome))
    return points


def colours(outcomes: list[str]) -> dict[str, tuple[int, int, int]]:
    table: dict[str, tuple[int, int, int]] = {"succeeded": SUCCESS}
    failures = [o for o, _ in Counter(o for o in outcomes if o != "succeeded").most_common()]
    for index, kind in enumerate(k for k in failures if k not in SPECIAL):
        table[kind] = PALETTE[index % len(PALETTE)]
    table.update({k: v for k, v in SPECIAL.items() if k in failures})
    return table


@dataclass
class OutcomeMap:
    """The map's picture, and where each scenario's varied objects are drawn on it."""

    image: np.ndarray
    #: (record, object, (x, y) pixel) of every varied start position
    markers: list[tuple[dict[str, Any], str, tuple[int, int]]] = field(default_factory=list)


def outcome_map(sweep: PreparedSweep, records: list[dict[str, Any]], width: int = 960,
                height: int = 720) -> OutcomeMap:
    """The map of the outcomes over the varied start positions (see the module docstring)."""
    points = collect(records)
    if not points:
        raise InputError("nothing to plot: the variation file moves no object (give one a noise or a region)",
                         Location("--plot"))
    xy = np.array([p[1] for p in points], dtype=float)
    lo, hi = xy[:, :2].min(axis=0) - PAD, xy[:, :2].max(axis=0) + PAD
    centre = (lo + hi) / 2.0
    span = np.maximum(hi - lo, 1.0)
    aspect = width / height
    half_y = max(span[1], span[0] / aspect) / 2.0
    z_ref = float(np.median(xy[:, 2]))
    fov = 2.0 * math.degrees(math.atan(half_y / (CAMERA_HEIGHT - z_ref)))
    camera = Camera((float(centre[0]), float(centre[1]), CAMERA_HEIGHT), (float(centre[0]), float(centre[1]), 0.0),
                    (0.0, 1.0, 0.0), fov, CAMERA_HEIGHT - 3.0, CAMERA_HEIGHT + 1.0)
    spec = sweep.scenario.world
    fixed = [o for o in spec.objects if o.type == "environment" or (o.fixed and o.type != "robot")]
    world = load_spec(replace(spec, objects=fixed, robot=None, robot_description=None))
    try:
        image = render(world, camera, width, height).copy()
    finally:
        world.exit()
    focal = (height / 2.0) / math.tan(math.radians(fov) / 2.0)

    def pixel(position: tuple[float, float, float]) -> tuple[int, int]:
        depth = CAMERA_HEIGHT - position[2]
        return (int(round(width / 2.0 + focal * (position[0] - centre[0]) / depth)),
                int(round(height / 2.0 - focal * (position[1] - centre[1]) / depth)))

    table = colours([p[2] for p in points])
    names = sorted({p[0] for p in points})
    shape = {name: MARKERS[i % len(MARKERS)] for i, name in enumerate(names)}
    # successes first, failures on top of them
    picture = Picture.of(image)
    for name, position, outcome in sorted(points, key=lambda p: p[2] != "succeeded"):
        draw_marker(picture, pixel(position), shape[name], table[outcome])
    counts = Counter(outcome_of(r) for r in records)
    rows: list[tuple[str, Any, str]] = [("circle", table[o], f"{o} {counts[o]}") for o in table if counts[o]]
    rows += [(shape[n], (60, 60, 60), n) for n in names]
    draw_legend(picture, rows, f"{Path(sweep.meta['plan']).stem}: {len({r['index'] for r in records})} scenarios")
    markers = [(record, name, pixel(tuple(varied["position"])))
               for record in records for name, varied in sorted((record.get("varied") or {}).items())
               if isinstance(varied, dict) and "position" in varied]
    return OutcomeMap(picture.rgb(), markers)


def plot_outcomes(sweep: PreparedSweep, records: list[dict[str, Any]], path: Path,
                  width: int = 960, height: int = 720) -> None:
    """Write the map of the outcomes as a PNG file."""
    write_png(path, outcome_map(sweep, records, width, height).image)


# -- drawing ------------------------------------------------------------------------------------------
def draw_marker(picture: Picture, at: tuple[int, int], shape: str, colour: tuple[int, int, int],
                radius: int = RADIUS) -> None:
    """One marker: the shape filled with the colour, its edge darker (a cross and a ring: the colour only)."""
    x, y = at
    r = radius
    edge = darker(colour)
    if shape == "circle":
        picture.circle(at, r, fill=colour, outline=edge)
    elif shape == "square":
        picture.rectangle((x - r + 1, y - r + 1), (x + r - 1, y + r - 1), outline=edge, fill=colour)
    elif shape == "triangle":
        picture.polygon([(x, y - r), (x + r, y + r - 1), (x - r, y + r - 1)], fill=colour, outline=edge)
    elif shape == "diamond":
        picture.polygon([(x, y - r), (x + r, y), (x, y + r), (x - r, y)], fill=colour, outline=edge)
    elif shape == "cross":
        picture.rectangle((x - r, y - 1), (x + r, y + 1), fill=colour)
        picture.rectangle((x - 1, y - r), (x + 1, y + r), fill=colour)
    else:  # ring
        picture.circle(at, r, outline=colour, width=2)


def draw_legend(picture: Picture, rows: list[tuple[str, Any, str]], title: str, size: int = 16) -> None:
    """The legend in the top left corner, over a light box: the title, then a marker and a text per row."""
    line = size + 6
    box_w = 36 + max(picture.text_width(t, size) for t in [title] + [text for _, _, text in rows])
    box_h = 10 + line * (len(rows) + 1)
    x0, y0 = 10, 10
    picture.rectangle((x0, y0), (x0 + box_w - 1, y0 + box_h - 1), fill=(255, 255, 255), alpha=0.85)
    picture.text((x0 + 8, y0 + 6), title, (20, 20, 20), size)
    for i, (shape, colour, text) in enumerate(rows, start=1):
        y = y0 + 6 + i * line
        draw_marker(picture, (x0 + 14, y + size // 2 + 1), shape, colour, radius=5)
        picture.text((x0 + 28, y), text, (20, 20, 20), size)
