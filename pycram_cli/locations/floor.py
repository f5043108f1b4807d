"""The floor map: where the robot's base can stand, as a 2-D grid built from the world.

Everything is made of axis-aligned boxes: the collision shapes of every object but the robot, what it
holds and the floor (a box per shape, `world/shapes.py`: a cabinet of panels leaves the room under its handle bar
that its link's one bounding box would fill), and the robot's own links (a box per link), read with its
base turned to yaw 0 in its current configuration (arms parked or carrying). The height
from the floor to the robot's top is cut into *bands* at every height where the set of
robot links or the set of obstacles changes; bands with the same obstacles share one
footprint (the union of the robot's links there) and bands with the same footprint share
one occupancy grid, which keeps the test exact at box level and cheap: a base pose
(x, y, yaw) collides when any sample of a band's footprint (its outline, and its inside
every few cells), turned by yaw and moved to (x, y), falls on an occupied cell of that band.

The grid is a prefilter, conservative by about one cell: the robot's true collision shapes
decide (`exact_collisions`), as the navigation process module does. A map is kept per world while
nothing in it moves (`floor_map`): the next location in the same state reuses it.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..planning.contacts import PENETRATION, SUPPORT_SLACK, collisions, ground_z, support_links, supports_from_below
from ..world.pose import yaw_quaternion
from ..world.shapes import shape_boxes

if TYPE_CHECKING:
    from ..robots import Robot
    from ..world import Object

#: grid cell size (m)
RESOLUTION = 0.02
#: how far the map reaches beyond the obstacles (m)
MARGIN = 1.0
#: inside a footprint, one sample every this many cells (the outline is sampled at every cell)
INTERIOR_STRIDE = 5
#: bands thinner than this (m) are left out
THIN = 1e-3
#: heights are rounded outwards to this step (m) before the bands are cut: fewer, slightly fuller bands
HEIGHT_STEP = 0.02
#: the outline of a footprint is sampled every this many cells
OUTLINE_STRIDE = 2
#: the robot's base: its links that start in this lowest fraction of its height
BASE_FRACTION = 0.2

Box = tuple[np.ndarray, np.ndarray]  # (lo xyz, hi xyz)


@dataclass
class Band:
    """One height band: the cells occupied by obstacles and the robot's footprint samples (base frame)."""

    low: float
    high: float
    occupied: np.ndarray  # (nx, ny) bool
    samples: np.ndarray  # (k, 2) points of the footprint in the base frame
    robot_links: tuple[str, ...] = ()
    obstacles: tuple[str, ...] = ()


@dataclass
class FloorMap:
    """Occupancy of the floor for one robot configuration; `collides` answers for many base poses at once."""

    origin: np.ndarray  # (x, y) of cell (0, 0)'s corner
    shape: tuple[int, int]
    resolution: float
    bands: list[Band]
    floor_z: float
    #: every obstacle box projected on the floor (for plots): (nx, ny) bool
    any_occupied: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), dtype=bool))
    #: the robot's footprint at the floor (all bands), base frame: (k, 2) samples
    footprint: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    radius: float = 0.0  # the farthest point of the robot from its base origin (horizontally)
    core: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))  # a few samples inside the lowest band
    #: the rectangles (lo xy, hi xy) of the robot's base links, base frame (the cheap test, plots)
    base_boxes: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    #: cells occupied at the height of the base
    core_occupied: np.ndarray = field(default_factory=lambda: np.zeros((0, 0), dtype=bool))

    def cell_centres(self) -> tuple[np.ndarray, np.ndarray]:
        xs = self.origin[0] + (np.arange(self.shape[0]) + 0.5) * self.resolution
        ys = self.origin[1] + (np.arange(self.shape[1]) + 0.5) * self.resolution
        return xs, ys

    def index(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Cell indices (ix, iy) of world points (..., 2) and whether they fall on the map."""
        ix = np.floor((points[..., 0] - self.origin[0]) / self.resolution).astype(np.int64)
        iy = np.floor((points[..., 1] - self.origin[1]) / self.resolution).astype(np.int64)
        inside = (ix >= 0) & (iy >= 0) & (ix < self.shape[0]) & (iy < self.shape[1])
        return np.clip(ix, 0, self.shape[0] - 1), np.clip(iy, 0, self.shape[1] - 1), inside

    def collides(self, x: np.ndarray, y: np.ndarray, yaw: np.ndarray) -> np.ndarray:
        """For base poses (arrays of x, y, yaw): whether the map says the robot would hit something.

        Samples off the map are clipped to its border cells, which are free (the map reaches
        `MARGIN` beyond every obstacle).
        """
        x, y, yaw = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (x, y, yaw))
        hit = np.zeros(x.shape, dtype=bool)
        c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
        x0, y0 = x[:, None] - self.origin[0], y[:, None] - self.origin[1]
        for band in self.bands:
            px, py = band.samples[None, :, 0], band.samples[None, :, 1]
            ix = np.floor((x0 + c * px - s * py) / self.resolution).astype(np.int32)
            iy = np.floor((y0 + s * px + c * py) / self.resolution).astype(np.int32)
            np.clip(ix, 0, self.shape[0] - 1, out=ix)
            np.clip(iy, 0, self.shape[1] - 1, out=iy)
            hit |= band.occupied[ix, iy].any(axis=1)
        return hit

    def core_collides(self, x: np.ndarray, y: np.ndarray, yaw: np.ndarray) -> np.ndarray:
        """The cheap first pass, for every candidate at once: the inside of the base's footprint (a few
        samples) on a cell occupied at the base's height — the base would stand in the furniture."""
        x, y, yaw = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (x, y, yaw))
        if not len(self.core):
            return np.zeros(x.shape, dtype=bool)
        c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
        px, py = self.core[None, :, 0], self.core[None, :, 1]
        ix = np.clip(np.floor((x[:, None] - self.origin[0] + c * px - s * py) / self.resolution).astype(np.int32),
                     0, self.shape[0] - 1)
        iy = np.clip(np.floor((y[:, None] - self.origin[1] + s * px + c * py) / self.resolution).astype(np.int32),
                     0, self.shape[1] - 1)
        return self.core_occupied[ix, iy].any(axis=1)

# -- building --------------------------------------------------------------------------------------------


def _link_box(obj: Object, index: int) -> Box:
    lo, hi = obj.get_aabb(index)
    return np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)


def _link_boxes(obj: Object, skip: frozenset[int] = frozenset(), shapes: bool = True) -> list[tuple[str, Box]]:
    """A box per collision shape of every solid link (`shape_boxes`: a cabinet of panels leaves the room under its
    handle that its one bounding box would fill), each named by its link; `shapes=False`: a box per link."""
    boxes: list[tuple[str, Box]] = []
    solid = obj.solid_links()
    for index in [-1, *range(len(obj.joints))]:
        if index not in solid or index in skip:  # a frame without geometry (PyBullet still gives it a box of a few mm)
            continue
        name = obj.get_link_name(index)
        found = shape_boxes(obj, index) if shapes else [_link_box(obj, index)]
        boxes.extend((f"{obj.name}/{name}" if obj.joints else obj.name, box) for box in found)
    return boxes


def robot_boxes(robot: Object, held: Sequence[Object]) -> list[tuple[str, Box]]:
    """The robot's links (and what it holds) as boxes in its base frame, read with the base at yaw 0.

    The robot is turned in place and put back (position, orientation and held objects as they were).
    """
    position, orientation = robot.get_pose()
    robot.set_position_and_orientation(position, (0.0, 0.0, 0.0, 1.0))
    try:
        base = np.array([position[0], position[1], position[2]])
        boxes = [(name, (lo - base, hi - base)) for name, (lo, hi) in _link_boxes(robot, shapes=False)]
        for obj in held:
            lo, hi = obj.get_aabb()
            boxes.append((obj.name, (np.asarray(lo) - base, np.asarray(hi) - base)))
    finally:
        robot.set_position_and_orientation(position, orientation)
    return boxes


def obstacle_boxes(robot: Object, held: Sequence[Object], extra_ignore: Iterable[Object] = ()) -> list[tuple[str, Box]]:
    """The boxes of everything the base could hit: every object's links but the robot's, what it holds and the floor."""
    skip = {robot.id, *(o.id for o in held), *(o.id for o in extra_ignore)}
    ground = ground_z(robot)
    boxes = []
    for obj in robot.world.objects:
        if obj.id in skip or supports_from_below(robot, obj, ground):
            continue
        boxes.extend(_placed_boxes(obj, support_links(robot, obj, ground)))
    return boxes


#: the world's cache table of each object's boxes (`_link_boxes`) where it last stood
PLACED = "floor map boxes"


def _placed_boxes(obj: Object, skip: frozenset[int]) -> list[tuple[str, Box]]:
    """`_link_boxes(obj, skip)`, kept while the object stands where it stood (`Object.placement`: its base's pose
    and joints, exactly): the kitchen's hundreds of shapes are read once, not at every map rebuilt after a motion."""
    return obj.world.cache.kept(PLACED, obj, (obj.placement(), skip), lambda: _link_boxes(obj, skip=skip))


def _footprint_samples(boxes: Sequence[Box], resolution: float) -> np.ndarray:
    """Sample points of the union of boxes' (x, y) rectangles: every outline cell, every few inside cells. A robot
    whose configuration has not changed has the same footprints at every map rebuilt after a motion: remembered
    (`_FOOTPRINTS`, by the boxes' values), the array shared and read-only."""
    rounded = np.round(np.array([[b[0][:2], b[1][:2]] for b in boxes], dtype=float), KEY_DIGITS)
    key = (resolution, rounded.tobytes())
    known = _FOOTPRINTS.get(key)
    if known is None:
        if len(_FOOTPRINTS) >= FOOTPRINTS_KEPT:
            _FOOTPRINTS.pop(next(iter(_FOOTPRINTS)))
        known = _FOOTPRINTS[key] = _sampled_footprint([(lo, hi) for lo, hi in rounded], resolution)
        known.setflags(write=False)
    return known


#: the footprints sampled lately (`_footprint_samples`), the oldest forgotten first beyond FOOTPRINTS_KEPT
_FOOTPRINTS: dict[tuple[float, bytes], np.ndarray] = {}
FOOTPRINTS_KEPT = 512
#: the boxes are rounded to this many decimals (m) before they are sampled: the same robot read again after a motion
#: of its base differs in the 16th, and the samples must not depend on which came first
KEY_DIGITS = 9


def _sampled_footprint(boxes: Sequence[Box], resolution: float) -> np.ndarray:
    lo = np.min([b[0][:2] for b in boxes], axis=0)
    hi = np.max([b[1][:2] for b in boxes], axis=0)
    n = np.maximum(np.ceil((hi - lo) / resolution).astype(int), 1)
    xs = lo[0] + (np.arange(n[0]) + 0.5) * (hi[0] - lo[0]) / n[0]
    ys = lo[1] + (np.arange(n[1]) + 0.5) * (hi[1] - lo[1]) / n[1]
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    mask = np.zeros(gx.shape, dtype=bool)
    for blo, bhi in boxes:
        mask |= (gx >= blo[0]) & (gx <= bhi[0]) & (gy >= blo[1]) & (gy <= bhi[1])
    padded = np.pad(mask, 1)
    inner = padded[1:-1, 1:-1] & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
    outline = mask & ~inner
    ii, jj = np.meshgrid(np.arange(n[0]), np.arange(n[1]), indexing="ij")
    sparse = mask & (ii % INTERIOR_STRIDE == 0) & (jj % INTERIOR_STRIDE == 0)
    keep = (outline & ((ii + jj) % OUTLINE_STRIDE == 0)) | sparse
    # the corners of every box exactly, so that a footprint is never smaller than its boxes
    corners = np.array([[b[i][0], b[j][1]] for b in boxes for i in (0, 1) for j in (0, 1)])
    return np.concatenate([np.stack([gx[keep], gy[keep]], axis=-1), corners])


def _rasterise(boxes: Sequence[Box], origin: np.ndarray, shape: tuple[int, int], resolution: float) -> np.ndarray:
    """The cells (shape) that the boxes' (x, y) rectangles cover, a cell wherever a rectangle touches it. The grids
    of a map rebuilt after a motion are mostly those of the map before it (the same furniture at the same heights):
    remembered (`_GRIDS`, by the cells' index ranges, which decide the grid), shared and read-only."""
    if not len(boxes):
        return np.zeros(shape, dtype=bool)
    corners = np.array([(lo[0], lo[1], hi[0], hi[1]) for lo, hi in boxes], dtype=float)
    cells = np.floor((corners - np.array([origin[0], origin[1], origin[0], origin[1]])) / resolution).astype(np.int64)
    cells[:, :2] = np.maximum(cells[:, :2], 0)
    cells[:, 2:] = np.minimum(cells[:, 2:] + 1, shape)
    cells = cells[(cells[:, 0] < cells[:, 2]) & (cells[:, 1] < cells[:, 3])]
    key = (shape, cells.tobytes())
    grid = _GRIDS.get(key)
    if grid is None:
        if len(_GRIDS) >= GRIDS_KEPT:
            _GRIDS.pop(next(iter(_GRIDS)))
        grid = np.zeros(shape, dtype=bool)
        for i0, j0, i1, j1 in cells.tolist():
            grid[i0:i1, j0:j1] = True
        grid.setflags(write=False)
        _GRIDS[key] = grid
    return grid


#: the occupancy grids made lately (`_rasterise`), the oldest forgotten first beyond GRIDS_KEPT (a few MB)
_GRIDS: dict[tuple[tuple[int, int], bytes], np.ndarray] = {}
GRIDS_KEPT = 64


# long: one pass from boxes to bands to grids, each step's arrays feeding the next
def build(robot: Object, held: Sequence[Object] = (), resolution: float = RESOLUTION,
          ignore: Iterable[Object] = ()) -> FloorMap:
    """The floor map of the robot's world for its current configuration (the world is left as it was)."""
    own = robot_boxes(robot, held)
    obstacles = obstacle_boxes(robot, held, ignore)
    floor_z = float(robot.get_position()[2])
    robot_top = max(float(b[1][2]) for _, b in own) if own else 1.0
    # what the base rests on (its ground, relative to the base origin) is not an obstacle
    low_limit = ground_z(robot) - floor_z + SUPPORT_SLACK
    if obstacles:
        lo = np.min([b[0][:2] for _, b in obstacles], axis=0) - MARGIN
        hi = np.max([b[1][:2] for _, b in obstacles], axis=0) + MARGIN
    else:
        here = np.asarray(robot.get_position()[:2])
        lo, hi = here - 3.0, here + 3.0
    shape = (int(math.ceil((hi[0] - lo[0]) / resolution)), int(math.ceil((hi[1] - lo[1]) / resolution)))
    # heights where something changes (relative to the floor under the robot), rounded outwards
    def down(z: float) -> float:
        return math.floor(z / HEIGHT_STEP + 1e-9) * HEIGHT_STEP

    def up(z: float) -> float:
        return math.ceil(z / HEIGHT_STEP - 1e-9) * HEIGHT_STEP

    mine_z = [(down(float(b[0][2])), up(float(b[1][2]))) for _, b in own]
    theirs_z = [(down(float(b[0][2]) - floor_z), up(float(b[1][2]) - floor_z)) for _, b in obstacles]
    cuts = {low_limit, robot_top, *(z for pair in mine_z + theirs_z for z in pair)}
    levels = sorted(c for c in cuts if low_limit <= c <= robot_top)
    by_obstacles: dict[frozenset[int], set[int]] = {}
    spans: dict[frozenset[int], list[float]] = {}
    mine_lo, mine_hi = (np.array([pair[k] for pair in mine_z], dtype=float) for k in (0, 1))
    theirs_lo, theirs_hi = (np.array([pair[k] for pair in theirs_z], dtype=float) for k in (0, 1))
    for a, b in zip(levels, levels[1:]):
        if b - a < THIN:
            continue
        mine = frozenset(np.flatnonzero((mine_lo < b) & (mine_hi > a)).tolist())
        theirs = frozenset(np.flatnonzero((theirs_lo < b) & (theirs_hi > a)).tolist())
        if not mine or not theirs:
            continue
        by_obstacles.setdefault(theirs, set()).update(mine)
        span = spans.setdefault(theirs, [a, b])
        span[0], span[1] = min(span[0], a), max(span[1], b)
    # bands with the same footprint share one occupancy grid (the union of their obstacles): still exact
    by_footprint: dict[frozenset[int], set[int]] = {}
    heights: dict[frozenset[int], list[float]] = {}
    for blocking, moving in by_obstacles.items():
        key = frozenset(moving)
        by_footprint.setdefault(key, set()).update(blocking)
        span = heights.setdefault(key, list(spans[blocking]))
        span[0], span[1] = min(span[0], spans[blocking][0]), max(span[1], spans[blocking][1])
    bands = []
    for parts, blockers in sorted(by_footprint.items(), key=lambda kv: (heights[kv[0]][0], sorted(kv[0]))):
        occupied = _rasterise([obstacles[i][1] for i in sorted(blockers)], lo, shape, resolution)
        samples = _footprint_samples([own[i][1] for i in sorted(parts)], resolution)
        bands.append(Band(heights[parts][0], heights[parts][1], occupied, samples,
                          tuple(dict.fromkeys(own[i][0] for i in sorted(parts))),
                          tuple(dict.fromkeys(obstacles[i][0] for i in sorted(blockers)))))
    reachable_boxes = [b for _, b in obstacles if b[0][2] - floor_z < robot_top and b[1][2] - floor_z > low_limit]
    everything = _rasterise(reachable_boxes, lo, shape, resolution)
    footprint = _footprint_samples([b for _, b in own], resolution) if own else np.zeros((0, 2))
    corners = np.array([[b[i][0], b[j][1]] for _, b in own for i in (0, 1) for j in (0, 1)]) if own else np.zeros((1, 2))
    radius = float(np.max(np.hypot(corners[:, 0], corners[:, 1])))
    # the base: the robot's links in the lowest fifth of its height, and what stands in their way
    base = [b for _, b in own if float(b[0][2]) < BASE_FRACTION * robot_top]
    core = _inside_samples(base, 5 * resolution) if base else np.zeros((0, 2))
    base_top = max((float(b[1][2]) for b in base), default=0.0)
    core_occupied = _rasterise([b for _, b in obstacles if b[0][2] - floor_z < base_top and b[1][2] - floor_z > low_limit],
                               lo, shape, resolution)
    return FloorMap(np.asarray(lo, dtype=float), shape, resolution, bands, floor_z, everything, footprint, radius, core,
                    [(b[0][:2], b[1][:2]) for b in base], core_occupied)


def _inside_samples(boxes: Sequence[Box], spacing: float) -> np.ndarray:
    """Points on a coarse lattice inside the union of boxes' (x, y) rectangles, kept off their edges."""
    points = []
    for lo, hi in boxes:
        nx = max(int((hi[0] - lo[0]) / spacing), 1)
        ny = max(int((hi[1] - lo[1]) / spacing), 1)
        xs = lo[0] + (np.arange(nx) + 0.5) * (hi[0] - lo[0]) / nx
        ys = lo[1] + (np.arange(ny) + 0.5) * (hi[1] - lo[1]) / ny
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        points.append(np.stack([gx.ravel(), gy.ravel()], axis=-1))
    return np.concatenate(points) if points else np.zeros((0, 2))


# -- the exact test ------------------------------------------------------------------------------------------


def exact_collisions(robot: Object, held: Sequence[Object], x: float, y: float, yaw: float,
                     ignore: Iterable[Object] = ()) -> list[str]:
    """Teleport the robot to (x, y, yaw) and name what it (or what it holds) penetrates; the caller restores the world.

    The robot's own test is the navigation process module's (`collisions`); held objects count too.
    """
    skip = set(held) | set(ignore)
    robot.set_position_and_orientation((x, y, robot.get_position()[2]), yaw_quaternion(yaw))
    hits = sorted(o.name for o in collisions(robot, ignore=skip))
    ground = ground_z(robot) if held else 0.0
    for obj in held:
        for other in robot.world.objects:
            if other is robot or other in skip or supports_from_below(robot, other, ground):
                continue
            if robot.world.distance(obj, other, 0.0) < -PENETRATION and other.name not in hits:
                hits.append(other.name)
    return sorted(hits)


# -- the floor map, kept while the world stands still ----------------------------------------------------------

#: the world's cache table of its floor map (world/cache.py)
MAPS = "floor map"


def _signature(robot: Robot, held: Sequence[Object]) -> tuple:
    """What the floor map depends on, exactly (a map is reused only for the very same state): every object's
    pose and joints but the robot's base pose (the map is in world coordinates, the robot's footprint in its
    own frame), and what the robot holds, with how it holds it."""
    parts: list[Any] = [tuple((o.id, tuple(robot.body.attachments[o].transform)) for o in held
                              if o in robot.body.attachments)]
    for obj in robot.world.objects:
        joints = tuple(obj.get_joint_positions().values())
        if obj is robot.body or obj in held:
            parts.append((obj.id, joints))
            continue
        pose = obj.get_com_pose()
        parts.append((obj.id, tuple(pose[0]), tuple(pose[1]), joints))
    return tuple(parts)


def floor_map(robot: Robot, held: Sequence[Object], saved: bool = False) -> FloorMap:
    """The floor map for the world as it is (built again whenever anything has moved). `saved`: the caller
    restores the world afterwards (building turns the robot in place)."""
    world = robot.world

    def built() -> FloorMap:
        if saved:
            return build(robot.body, held)
        with world.snapshot():
            return build(robot.body, held)

    return world.cache.kept(MAPS, world, _signature(robot, held), built)


def forget(world: Any) -> None:
    """Forget the world's floor map and everything a map is built from that is kept (its objects' boxes, the
    grids and footprints made lately): the next map is built from nothing, as a benchmark of a first map wants."""
    world.cache.forget(MAPS, PLACED)
    _GRIDS.clear()
    _FOOTPRINTS.clear()
