"""A picture of a location's resolution, seen from above: the floor map, the candidates, the answer, the target.

    rgb = draw(resolution)                  # (height, width, 3) uint8; write it with world.camera.write_png

* the floor: white where the robot's base may stand, grey where obstacles are (at any height the
  robot has), every object's outline darker;
* the candidates: one square per position, coloured by the test that ruled it out (the
  furthest test any of its turns reached), green for the poses found; spots on a surface the same;
* the poses found: the robot's footprint outline with an arrow for its heading (the first one
  thicker), the target as a black cross;
* a legend with the colours and how many candidates each test ruled out.

Drawn with `pycram_cli.drawing` (Pillow), as the sweep's map is.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..drawing import TEXT_SIZE, Picture
from .base_poses import BasePoseResolution
from .candidates import OUTCOMES, REASONS
from .floor import floor_map as build_floor_map
from .spots import SpotResolution

#: the key under which a locate step's record holds its `candidate_map` while a replay is recorded (the replay
#: record takes it out of the step: the trace itself never holds it)
MAP_KEY = "candidate_map"
#: colour of each outcome (RGB)
COLOURS: dict[str, tuple[int, int, int]] = {
    "ok": (30, 160, 60),
    "collides": (220, 60, 50),
    "occupied": (220, 60, 50),
    "out of reach": (250, 190, 120),
    "out of view": (200, 170, 230),
    "cannot hold": (150, 100, 60),
    "blocked": (200, 40, 200),
    "not visible": (60, 110, 230),
    "unstable": (240, 150, 20),
    "not tried": (205, 205, 205),
}
FLOOR = (255, 255, 255)
OBSTACLE = (150, 150, 150)
OUTLINE = (90, 90, 90)
#: which outcome a position shows when its turns differ: the one furthest along the tests
RANK = ["", "not tried", "out of reach", "out of view", "collides", "occupied", "cannot hold", "blocked",
        "not visible", "unstable", "ok"]


def draw(resolution: BasePoseResolution | SpotResolution, pixels_per_metre: float = 120.0,
         margin: float = 0.4) -> np.ndarray:
    """The picture of a (partly) resolved location."""
    resolution.prepare()
    robot = resolution.robot
    world = robot.world
    held = robot.held_objects()
    floor_map = resolution.map if isinstance(resolution, BasePoseResolution) else None
    if floor_map is None:  # a spot resolution keeps no map: the (cached) one of the world as it is
        floor_map = build_floor_map(robot, held)
    cand = resolution.candidates
    target = _target(resolution)
    xs = np.concatenate([cand.xs, [target[0]], [robot.body.get_position()[0]]])
    ys = np.concatenate([cand.ys, [target[1]], [robot.body.get_position()[1]]])
    lo = np.array([xs.min(), ys.min()]) - margin - floor_map.radius
    hi = np.array([xs.max(), ys.max()]) + margin + floor_map.radius
    width = int(math.ceil((hi[0] - lo[0]) * pixels_per_metre))
    height = int(math.ceil((hi[1] - lo[1]) * pixels_per_metre))
    canvas = Canvas(Picture(width, height, FLOOR), lo, pixels_per_metre)
    # the floor map: every cell occupied at some height the robot has
    cx, cy = floor_map.cell_centres()
    px = canvas.to_px(np.stack(np.meshgrid(cx, cy, indexing="ij"), axis=-1).reshape(-1, 2))
    occupied = floor_map.any_occupied.reshape(-1)
    canvas.picture.dots(px[occupied], OBSTACLE, radius=max(1, int(round(floor_map.resolution * pixels_per_metre / 2))))
    # the candidates, one square per position
    step = 0.05 if isinstance(resolution, BasePoseResolution) else 0.025
    best = {key: code for key, (code, _) in best_outcomes(resolution).items()}
    half = max(1, int(step * pixels_per_metre * 0.35))
    for (kx, ky), code in sorted(best.items(), key=lambda kv: RANK.index(OUTCOMES[kv[1]] or "not tried")):
        outcome = OUTCOMES[code] or "not tried"
        canvas.picture.dots(canvas.to_px(np.array([[kx * 0.005, ky * 0.005]])), COLOURS[outcome], radius=half,
                            alpha=0.7)
    for obj in world.objects:  # every object's outline (but the floor's, the robot's and what it holds)
        if obj is robot.body or obj in held:
            continue
        lo_b, hi_b = obj.get_aabb()
        if hi_b[0] - lo_b[0] > 20 or hi_b[1] - lo_b[1] > 20:
            continue
        if obj.joints:
            for index in [-1, *range(len(obj.joints))]:
                llo, lhi = obj.get_aabb(index)
                if lhi[0] - llo[0] > 0.01 and lhi[1] - llo[1] > 0.01 and lhi[2] > floor_map.floor_z + 0.01:
                    canvas.rectangle(llo[:2], lhi[:2], OUTLINE)
        else:
            canvas.rectangle(lo_b[:2], hi_b[:2], OUTLINE)
    # the poses (or spots) found, the first one last (on top), and the target
    for index, found in reversed(list(enumerate(resolution.found))):
        if isinstance(resolution, BasePoseResolution):
            _pose(canvas, floor_map.base_boxes, found.position, found.yaw, thick=index == 0)
        else:
            canvas.picture.dots(canvas.to_px(np.array([found.position[:2]])), COLOURS["ok"], radius=half + 2)
    canvas.cross(target[:2], (0, 0, 0), 7)
    _legend(canvas.picture, resolution)
    return canvas.picture.rgb()


def best_outcomes(resolution: BasePoseResolution | SpotResolution) -> dict[tuple[int, int], tuple[int, int]]:
    """Per candidate position (x, y in 5 mm units): the outcome code furthest along the tests of its turns, and the
    index of the candidate that reached it (the first such)."""
    cand = resolution.candidates
    if not len(cand):
        return {}
    kx = np.round(np.asarray(cand.xs) / 0.005).astype(np.int64)
    ky = np.round(np.asarray(cand.ys) / 0.005).astype(np.int64)
    rank_of = np.array([RANK.index(name or "not tried") for name in OUTCOMES])
    rank = rank_of[np.asarray(cand.outcome, dtype=np.int64)]
    index = np.arange(len(cand))
    order = np.lexsort((index, -rank, ky, kx))  # by position, then the best outcome first, then the first
    first = np.ones(len(order), dtype=bool)
    first[1:] = (kx[order][1:] != kx[order][:-1]) | (ky[order][1:] != ky[order][:-1])
    chosen = order[first]
    codes = np.asarray(cand.outcome, dtype=np.int64)
    return {(int(kx[i]), int(ky[i])): (int(codes[i]), int(i)) for i in chosen}


def candidate_map(resolution: BasePoseResolution | SpotResolution) -> dict[str, Any]:
    """The floor map of `draw` as data, for a replay to draw in 3D: every candidate position (x, y in mm) with its
    outcome (an index into `outcomes`) and why (the test's detail, where it said one), the height they stand at,
    the spacing, the poses found ([x, y, yaw]) and the target."""
    resolution.prepare()
    best = best_outcomes(resolution)
    names = [name for name in RANK[1:] if name in COLOURS]
    index = {name: k for k, name in enumerate(names)}
    xy: list[int] = []
    outcome: list[int] = []
    why: dict[str, str] = {}
    for (kx, ky), (code, i) in sorted(best.items()):
        xy.extend((kx * 5, ky * 5))
        outcome.append(index[OUTCOMES[code] or "not tried"])
        detail = resolution.candidates.detail.get(i)
        if detail:
            why[str(len(outcome) - 1)] = detail
    base = isinstance(resolution, BasePoseResolution)
    z = float(resolution.robot.body.get_position()[2]) if base else float(getattr(resolution, "top", 0.0))
    found = [[round(float(f.position[0]), 3), round(float(f.position[1]), 3),
              round(float(getattr(f, "yaw", 0.0)), 3)] for f in resolution.found]
    return {"kind": "base" if base else "spot", "z": round(z, 3), "spacing": 0.05 if base else 0.025,
            "xy": xy, "outcome": outcome, "outcomes": names, "why": why, "found": found,
            "target": [round(float(v), 3) for v in _target(resolution)]}


def _target(resolution: BasePoseResolution | SpotResolution) -> np.ndarray:
    if isinstance(resolution, BasePoseResolution):
        assert resolution.target is not None
        return resolution.target
    spec = resolution.spec
    if spec.near is not None:
        return np.asarray(spec.near)
    assert spec.on is not None
    lo, hi = spec.on.box()
    return (np.asarray(lo) + np.asarray(hi)) / 2.0


def _pose(canvas: Canvas, boxes: list[tuple[np.ndarray, np.ndarray]], position: Any, yaw: float,
          thick: bool) -> None:
    """The robot's base outline at a pose, and an arrow for its heading."""
    c, s = math.cos(yaw), math.sin(yaw)

    def world(x: float, y: float) -> tuple[float, float]:
        return position[0] + c * x - s * y, position[1] + s * x + c * y

    colour = (0, 110, 30) if thick else (110, 190, 130)
    if thick:
        for lo, hi in boxes:
            corners = [world(lo[0], lo[1]), world(hi[0], lo[1]), world(hi[0], hi[1]), world(lo[0], hi[1])]
            for a, b in zip(corners, corners[1:] + corners[:1]):
                canvas.line(a, b, colour, 1)
    tip = world(0.3, 0.0)
    canvas.line(position[:2], tip, colour, 2 if thick else 1)
    for side in (0.08, -0.08):
        canvas.line(tip, world(0.22, side), colour, 2 if thick else 1)
    canvas.picture.dots(canvas.to_px(np.array([position[:2]])), colour, radius=3 if thick else 2)


def _legend(picture: Picture, resolution: BasePoseResolution | SpotResolution) -> None:
    """What the colours mean and how many candidates each test ruled out, in the top left corner."""
    counts = resolution.counts()
    rows = [("found", COLOURS["ok"], len(resolution.found))]
    if isinstance(resolution, BasePoseResolution):
        rows[0] = ("pose found (base, heading)", COLOURS["ok"], len(resolution.found))
    rows += [(REASONS[key], COLOURS[key], counts[key]) for key in REASONS if counts.get(key)]
    lines: list[tuple[str, tuple[int, int, int] | None]] = [(resolution.spec.describe(), None)]
    lines += [(f"{text} {number}", colour) for text, colour, number in rows]
    lines += [("x target", None), ("grey: obstacles", OBSTACLE)]
    x, y, line = 6, 6, TEXT_SIZE + 3
    box_w = 12 + max(picture.text_width(text) for text, _ in lines) + 8
    picture.rectangle((x - 3, y - 3), (x - 3 + box_w, y + line * len(lines) + 2), fill=(250, 250, 250))
    for text, colour in lines:
        if colour is not None:
            picture.rectangle((x, y + 2), (x + 8, y + 10), fill=colour)
            picture.text((x + 12, y), text, (20, 20, 20))
        else:
            picture.text((x + 1, y), text, (20, 20, 20))
        y += line


class Canvas:
    """A picture with world (x, y) coordinates: +x to the right, +y up (`origin`: the world point at the bottom
    left, `scale`: pixels per metre)."""

    def __init__(self, picture: Picture, origin: np.ndarray, scale: float) -> None:
        self.picture, self.origin, self.scale = picture, origin, scale

    def to_px(self, points: np.ndarray) -> np.ndarray:
        """(n, 2) world points -> (n, 2) integer (column, row)."""
        col = np.floor((points[:, 0] - self.origin[0]) * self.scale).astype(int)
        row = self.picture.size[1] - 1 - np.floor((points[:, 1] - self.origin[1]) * self.scale).astype(int)
        return np.stack([col, row], axis=-1)

    def line(self, a: Any, b: Any, colour: tuple[int, int, int], radius: int = 0) -> None:
        """A line between two world points, 2 radius + 1 pixels wide."""
        ends = self.to_px(np.array([a[:2], b[:2]], dtype=float))
        self.picture.line([tuple(ends[0]), tuple(ends[1])], colour, width=2 * radius + 1)

    def rectangle(self, lo: Any, hi: Any, colour: tuple[int, int, int]) -> None:
        """The outline of a box's footprint (its lowest and highest corner)."""
        corners = self.to_px(np.array([lo[:2], hi[:2]], dtype=float))
        self.picture.rectangle(tuple(corners[0]), tuple(corners[1]), outline=colour)

    def cross(self, at: Any, colour: tuple[int, int, int], size: int) -> None:
        d = size / self.scale
        self.line((at[0] - d, at[1] - d), (at[0] + d, at[1] + d), colour, 1)
        self.line((at[0] - d, at[1] + d), (at[0] + d, at[1] - d), colour, 1)
