"""Variations: how the scenarios of a sweep differ from the world file and the plan's defaults.

A variation file (YAML, checked like worlds and plans: every problem with file:line:column
and key) says, per object, where it may start and whether it is there at all, where the
robot starts, and which values the plan's parameters take:

    description: breakfast things anywhere near their places, the robot a little off
    plan: set_table                     # optional: the plan it is made for (`pycram validate`)
    separation: 0.12                    # optional: varied objects start at least this far (m, x-y)
                                        #   from every other free object
    objects:
      milk:
        region: {on: kitchen/sink_area_surface, margin: 0.05}   # x-y uniform on the link's top
        yaw: 3.1416                     # turned by a uniform angle in ±yaw (rad) about z
      cereal:
        noise: [0.05, 0.05, 0]          # uniform in ± per axis around its position (or one number: x, y)
      bowl:
        region: {box: [[1.25, 0.6, 0.851], [1.4, 1.0, 0.851]]}  # uniform in the box
      bottle:
        present: 0.5                    # probability that it is in the scenario
        swap:                           # equally likely: as in the world (keep) or another model
          - keep
          - {type: milk, file: objects/milk.obj, color: [1, 1, 1]}
    robot:
      noise: [0.05, 0.05, 0]
      yaw: 0.1
    params:
      arm: [left, right]                # one of these, equally likely
      offset: {range: [0.0, 0.1]}       # uniform (integers when both ends are integers)

Reading and checking the file is `variation_files.py`'s job. `Variations.sample(seed)` draws one `Variant` from its
own `random.Random(seed)`, in file order, so a scenario is a function of its seed alone; `scenario_seed(sweep_seed, i)` gives
scenario i's seed. A variant changes the world's *structure* (which bodies exist: presence,
swaps) through `Variant.world_spec`, and the rest (poses) through `Variant.apply` on a
loaded world of that structure.
"""
from __future__ import annotations

import hashlib
import math
import random
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from ..errors import Location
from ..jsonable import jsonable
from ..world import BulletWorld
from ..world.pose import quat_multiply, yaw_quaternion
from ..worldfile.spec import ObjectSpec, WorldSpec

#: a region's free margin from its surface's edges when the file gives none (m)
DEFAULT_MARGIN = 0.05
#: draws of a position before giving up on `separation` (the last draw is kept)
TRIES = 50
KEEP = "keep"


def scenario_seed(seed: int, index: int) -> int:
    """Scenario `index`'s own seed (32 bits) in a sweep seeded with `seed`: the same on every machine."""
    return int.from_bytes(hashlib.sha256(f"pycram-sweep/{seed}/{index}".encode()).digest()[:4], "big")


# -- what a file says ---------------------------------------------------------------------------------
@dataclass
class Region:
    box: tuple[tuple[float, float, float], tuple[float, float, float]] | None = None
    on: tuple[str, str] | None = None  # (object, link): x-y on its top face
    margin: float = DEFAULT_MARGIN


@dataclass
class Swap:
    type: str
    file: Path
    color: list[float] | None = None
    mass: float | None = None

    def describe(self) -> str:
        return self.type


@dataclass
class Varied:
    """How one object (or the robot) varies."""

    name: str
    noise: tuple[float, float, float] | None = None
    region: Region | None = None
    yaw: float = 0.0
    present: float = 1.0
    swaps: list[Swap | None] = field(default_factory=list)  # None: keep the world's model

    @property
    def moves(self) -> bool:
        return self.noise is not None or self.region is not None or self.yaw > 0


@dataclass
class ParamDraw:
    name: str
    choices: list[Any] | None = None
    range: tuple[float, float] | None = None
    integer: bool = False


@dataclass
class Variations:
    path: Path
    world: WorldSpec
    objects: list[Varied]
    robot: Varied | None = None
    params: list[ParamDraw] = field(default_factory=list)
    separation: float = 0.0
    description: str = ""
    plan: str | None = None
    plan_where: Location = field(default_factory=Location)
    #: (object, link) -> the link's axis-aligned box in the world as loaded (see `bind_surfaces`)
    surfaces: dict[tuple[str, str], tuple[tuple[float, ...], tuple[float, ...]]] = field(default_factory=dict)

    @property
    def structural(self) -> bool:
        """Whether some scenarios add or remove bodies (presence, swaps): worlds then differ in structure."""
        return any(v.present < 1.0 or v.swaps for v in self.objects)

    def needs_surfaces(self) -> list[tuple[str, str]]:
        return [v.region.on for v in self._all() if v.region is not None and v.region.on is not None]

    def bind_surfaces(self, world: BulletWorld) -> None:
        """Read the boxes of the surfaces regions stand `on` from a loaded world of the base structure."""
        for name, link in self.needs_surfaces():
            obj = world.get_object_by_name(name)
            assert obj is not None
            self.surfaces[(name, link)] = obj.get_aabb(link)

    def _all(self) -> list[Varied]:
        return self.objects + ([self.robot] if self.robot is not None else [])

    # -- drawing ------------------------------------------------------------------------------
    def sample(self, seed: int, index: int | None = None) -> Variant:
        """The variant of scenario `seed`: every draw from one generator, in the file's order."""
        missing = [s for s in self.needs_surfaces() if s not in self.surfaces]
        if missing:
            raise RuntimeError(f"surfaces not bound (call bind_surfaces first): {missing}")
        rng = random.Random(seed)
        by_name = {o.name: o for o in self.world.objects}
        absent: list[str] = []
        swaps: dict[str, Swap] = {}
        varied: dict[str, dict[str, Any]] = {}
        for item in self.objects:
            record: dict[str, Any] = {}
            if item.present < 1.0:
                record["present"] = rng.random() < item.present
                if not record["present"]:
                    absent.append(item.name)
                    varied[item.name] = record
                    continue
            if item.swaps:
                choice = item.swaps[rng.randrange(len(item.swaps))]
                record["type"] = by_name[item.name].type if choice is None else choice.type
                if choice is not None:
                    swaps[item.name] = choice
            varied[item.name] = record
        # positions after presence: an absent object keeps nothing apart
        placed: dict[str, tuple[float, float, float]] = {
            o.name: tuple(o.position) for o in self.world.objects  # type: ignore[misc]
            if o.name not in absent and not is_fixed(o) and o is not self.world.robot}
        poses: dict[str, tuple[tuple[float, float, float], tuple[float, float, float, float]]] = {}
        for item in self._all():
            if item.name in absent or not item.moves:
                continue
            spec = by_name[item.name]
            others = [pos for name, pos in placed.items() if name != item.name]
            position = tuple(spec.position)
            for _ in range(TRIES if self.separation > 0 and item is not self.robot else 1):
                position = self._position(rng, item, spec)
                if all(math.dist(position[:2], other[:2]) >= self.separation for other in others):
                    break
            yaw = rng.uniform(-item.yaw, item.yaw) if item.yaw > 0 else 0.0
            orientation = quat_multiply(yaw_quaternion(yaw), spec.orientation) if yaw else tuple(spec.orientation)
            if item is not self.robot:
                placed[item.name] = position  # type: ignore[assignment]
            poses[item.name] = (position, orientation)  # type: ignore[assignment]
            record = varied.setdefault(item.name, {}) if item is not self.robot else varied.setdefault("robot", {})
            if item.noise is not None or item.region is not None:
                record["position"] = [round(c, 6) for c in position]
            if item.yaw > 0:
                record["yaw"] = round(yaw, 6)
        params: dict[str, Any] = {}
        for draw in self.params:
            if draw.choices is not None:
                params[draw.name] = draw.choices[rng.randrange(len(draw.choices))]
            else:
                assert draw.range is not None
                lo, hi = draw.range
                params[draw.name] = rng.randint(int(lo), int(hi)) if draw.integer else rng.uniform(lo, hi)
        if params:
            varied["params"] = jsonable(params)
        return Variant(seed, tuple(absent), swaps, poses, params, varied, index)

    def _position(self, rng: random.Random, item: Varied, spec: ObjectSpec) -> tuple[float, float, float]:
        if item.region is not None and item.region.box is not None:
            box_lo, box_hi = item.region.box
            return (rng.uniform(box_lo[0], box_hi[0]), rng.uniform(box_lo[1], box_hi[1]),
                    rng.uniform(box_lo[2], box_hi[2]))
        if item.region is not None and item.region.on is not None:
            lo, hi = self.surfaces[item.region.on]
            m = item.region.margin
            x = rng.uniform(lo[0] + m, hi[0] - m) if hi[0] - lo[0] > 2 * m else (lo[0] + hi[0]) / 2
            y = rng.uniform(lo[1] + m, hi[1] - m) if hi[1] - lo[1] > 2 * m else (lo[1] + hi[1]) / 2
            return (x, y, float(hi[2]))
        if item.noise is not None:
            return tuple(spec.position[k] + (rng.uniform(-item.noise[k], item.noise[k]) if item.noise[k] else 0.0)
                         for k in range(3))  # type: ignore[return-value]
        return tuple(spec.position)  # type: ignore[return-value]


def is_fixed(spec: ObjectSpec) -> bool:
    """Whether an object of the world file stays put (a robot or the environment, unless it says otherwise)."""
    return spec.fixed if spec.fixed is not None else spec.type in ("robot", "environment")


# -- one scenario ---------------------------------------------------------------------------------------
@dataclass
class Variant:
    """One drawn scenario: which bodies exist, where things start, the parameter values."""

    seed: int
    absent: tuple[str, ...] = ()
    swaps: dict[str, Swap] = field(default_factory=dict)
    poses: dict[str, tuple[tuple[float, float, float], tuple[float, float, float, float]]] = field(default_factory=dict)
    params: dict[str, Any] = field(default_factory=dict)
    varied: dict[str, Any] = field(default_factory=dict)  # what was drawn, JSON-ready (the results' record)
    index: int | None = None

    @property
    def structure(self) -> tuple[Any, ...]:
        """What decides which bodies a world of this variant holds (equal: one loaded world serves both)."""
        return (self.absent, tuple(sorted((name, str(s.file), s.type) for name, s in self.swaps.items())))

    def world_spec(self, base: WorldSpec) -> WorldSpec:
        """`base` with absent objects left out and swapped models put in (poses are set by `apply`)."""
        if not self.absent and not self.swaps:
            return base
        objects = []
        for obj in base.objects:
            if obj.name in self.absent:
                continue
            swap = self.swaps.get(obj.name)
            if swap is not None:
                obj = replace(obj, type=swap.type, file=swap.file, file_text=str(swap.file),
                              color=swap.color if swap.color is not None else obj.color,
                              mass=swap.mass if swap.mass is not None else obj.mass)
            objects.append(obj)
        robot = next((o for o in objects if o.type == "robot"), None)
        return replace(base, objects=objects, robot=robot)

    def apply(self, world: BulletWorld) -> None:
        """Put the varied objects (and the robot) at their drawn poses."""
        for name, (position, orientation) in self.poses.items():
            obj = world.robot if name == "robot" else world.get_object_by_name(name)
            if obj is None:
                raise RuntimeError(f"variant {self.seed}: no object '{name}' in the world")
            obj.set_position_and_orientation(position, orientation)
