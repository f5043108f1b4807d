"""Drawing the program's own pictures (the location map, the sweep map) with Pillow: lines, points, shapes, text.

    picture = Picture(640, 480)                                # white; or Picture.of(rgb) to draw over a rendering
    picture.line([(10, 10), (100, 40)], (200, 0, 0), width=2)
    picture.dots(np.array([[50, 60], [52, 61]]), (30, 160, 60), radius=3, alpha=0.7)
    picture.text((12, 12), "3 found", (20, 20, 20))
    rgb = picture.rgb()                                        # (height, width, 3) uint8, for camera.write_png

Pixel coordinates: (column, row) from the top left. Text uses Pillow's default font, so no font file ships with
the package; the same Pillow draws the same pixels, so the maps stay reproducible.
"""
from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache

import numpy as np
from PIL import Image, ImageDraw, ImageFont

Colour = tuple[int, int, int]
Point = tuple[float, float]

#: the legend's text height (px)
TEXT_SIZE = 12


@lru_cache(maxsize=8)
def font(size: int = TEXT_SIZE) -> ImageFont.ImageFont | ImageFont.FreeTypeFont:
    """Pillow's default font at `size` px (Pillow before 10.1, or without FreeType: its fixed bitmap font)."""
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1 takes no size
        return ImageFont.load_default()


def _rgba(colour: Colour, alpha: float) -> tuple[int, int, int, int]:
    return (*(int(c) for c in colour), int(round(alpha * 255)))  # type: ignore[return-value]


def darker(colour: Colour, factor: float = 0.55) -> Colour:
    """The colour darkened (a marker's edge)."""
    return (int(colour[0] * factor), int(colour[1] * factor), int(colour[2] * factor))


class Picture:
    """An RGB picture to draw on; every shape may be drawn translucent (`alpha`, blended over what is under it)."""

    def __init__(self, width: int, height: int, background: Colour = (255, 255, 255)) -> None:
        self.image = Image.new("RGB", (width, height), background)
        self._draw = ImageDraw.Draw(self.image, "RGBA")

    @classmethod
    def of(cls, rgb: np.ndarray) -> Picture:
        """A picture starting from an (height, width, 3) uint8 array (a rendering)."""
        picture = cls(1, 1)
        picture.image = Image.fromarray(np.ascontiguousarray(rgb[..., :3], dtype=np.uint8))
        picture._draw = ImageDraw.Draw(picture.image, "RGBA")
        return picture

    @property
    def size(self) -> tuple[int, int]:
        """(width, height) in pixels."""
        return self.image.size

    def rgb(self) -> np.ndarray:
        """The picture as a (height, width, 3) uint8 array."""
        return np.asarray(self.image, dtype=np.uint8).copy()

    def line(self, points: Sequence[Point], colour: Colour, width: int = 1, alpha: float = 1.0) -> None:
        """A polyline through `points`."""
        self._draw.line([(float(x), float(y)) for x, y in points], fill=_rgba(colour, alpha), width=width)

    def dots(self, points: np.ndarray, colour: Colour, radius: int = 0, alpha: float = 1.0) -> None:
        """A filled square of side 2 radius + 1 at each (column, row) of `points` (n, 2): cells, candidates."""
        fill = _rgba(colour, alpha)
        for x, y in np.asarray(points, dtype=int).tolist():
            self._draw.rectangle((x - radius, y - radius, x + radius, y + radius), fill=fill)

    def rectangle(self, corner: Point, opposite: Point, outline: Colour | None = None, fill: Colour | None = None,
                  alpha: float = 1.0, width: int = 1) -> None:
        """An axis-aligned rectangle between two corners (any two opposite ones)."""
        box = (min(corner[0], opposite[0]), min(corner[1], opposite[1]),
               max(corner[0], opposite[0]), max(corner[1], opposite[1]))
        self._draw.rectangle(box, outline=None if outline is None else _rgba(outline, alpha),
                             fill=None if fill is None else _rgba(fill, alpha), width=width)

    def polygon(self, points: Sequence[Point], fill: Colour | None = None, outline: Colour | None = None,
                width: int = 1) -> None:
        """A closed polygon."""
        self._draw.polygon([(float(x), float(y)) for x, y in points], fill=None if fill is None else _rgba(fill, 1.0),
                           outline=None if outline is None else _rgba(outline, 1.0), width=width)

    def circle(self, centre: Point, radius: float, fill: Colour | None = None, outline: Colour | None = None,
               width: int = 1) -> None:
        """A circle (filled, outlined or both)."""
        x, y = centre
        self._draw.ellipse((x - radius, y - radius, x + radius, y + radius),
                           fill=None if fill is None else _rgba(fill, 1.0),
                           outline=None if outline is None else _rgba(outline, 1.0), width=width)

    def text(self, at: Point, text: str, colour: Colour, size: int = TEXT_SIZE) -> None:
        """Text with its top left at `at`, in Pillow's default font."""
        self._draw.text(at, text, fill=_rgba(colour, 1.0), font=font(size))

    def text_width(self, text: str, size: int = TEXT_SIZE) -> int:
        """How wide `text` is drawn (px)."""
        return int(round(self._draw.textlength(text, font=font(size))))
