"""Spots on a surface: where an object put down fits, touches nothing and stands stably, best first.

`{on: SURFACE, for: OBJECT, near: POSE?}` resolves to positions on a SPOT_STEP lattice of the surface's top,
nearest the point given (or the robot) first. Whatever stands where the object would be rules a spot out cheaply
(`occupied`, from bounding boxes); the rest are tried as place will stand the object, the object's own collision
shapes against everything (`collides`) and a short simulation (`unstable`).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..planning.pick_place import level, resting_on
from ..reasoning import stable
from ..robots import Robot
from ..world import Object
from . import floor
from .candidates import CODE, Candidates, Spot
from .ranked import Resolution
from .spec import LocationSpec
from .touching import quiet_let_go

#: spots on a surface are looked for within this distance (m, along x and y) of `near` or of the robot
SPOT_REACH = 3.0
#: spots on a surface: lattice spacing (m) and the free margin kept around the object (m)
SPOT_STEP = 0.025
SPOT_MARGIN = 0.06


class SpotResolution(Resolution):
    """Free spots on a surface where an object fits, touches nothing and stands stably, best first."""

    def __init__(self, robot: Robot, spec: LocationSpec, limit: int = 8) -> None:
        assert spec.on is not None and spec.for_object is not None
        super().__init__(robot, spec, limit)
        self.radius = 0.0

    def _prepare(self) -> None:
        spec = self.spec
        surface, obj = spec.on, spec.for_object
        assert surface is not None and obj is not None
        lo, hi = surface.box()
        self.top = float(hi[2])
        self.surface_link = surface.obj.get_link_id(surface.link) if surface.link is not None else None
        self.upright = level(obj.get_orientation(), obj.upright)
        position = obj.get_position()  # inside the caller's snapshot: the object stood upright where it is
        quiet_let_go(obj)
        obj.set_position_and_orientation(position, self.upright)
        olo, ohi = obj.get_aabb()
        corners = np.array([[olo[0], olo[1]], [olo[0], ohi[1]], [ohi[0], olo[1]], [ohi[0], ohi[1]]]) - np.asarray(position[:2])
        self.radius = float(np.max(np.hypot(corners[:, 0], corners[:, 1])))
        self.height = float(ohi[2] - olo[2])
        inset = self.radius + SPOT_MARGIN
        reference = np.asarray(spec.near[:2]) if spec.near is not None else np.asarray(self.robot.body.get_position()[:2])
        # a surface as large as a floor: only the part within SPOT_REACH of its point nearest the reference (millions
        # of spots else); a table across the room is searched whole
        nearest = np.clip(reference, np.asarray(lo[:2]), np.asarray(hi[:2]))
        lo = (max(lo[0], nearest[0] - SPOT_REACH), max(lo[1], nearest[1] - SPOT_REACH), lo[2])
        hi = (min(hi[0], nearest[0] + SPOT_REACH), min(hi[1], nearest[1] + SPOT_REACH), hi[2])
        ix = np.arange(math.ceil((lo[0] + inset) / SPOT_STEP - 1e-9), math.floor((hi[0] - inset) / SPOT_STEP + 1e-9) + 1)
        iy = np.arange(math.ceil((lo[1] + inset) / SPOT_STEP - 1e-9), math.floor((hi[1] - inset) / SPOT_STEP + 1e-9) + 1)
        gx, gy = np.meshgrid(ix * SPOT_STEP, iy * SPOT_STEP, indexing="ij")
        xs, ys = gx.ravel(), gy.ravel()
        scores = np.hypot(xs - reference[0], ys - reference[1])
        outcome = np.zeros(len(xs), dtype=np.int8)
        detail: dict[int, str] = {}
        for name, (blo, bhi) in self._obstacles():
            near = ((xs > blo[0] - inset) & (xs < bhi[0] + inset) & (ys > blo[1] - inset) & (ys < bhi[1] + inset)
                    & (outcome == 0))
            for k in np.flatnonzero(near):
                detail[int(k)] = name
            outcome[near] = CODE["occupied"]
        self.candidates = Candidates(xs, ys, np.zeros(len(xs)), scores, outcome)
        self.candidates.detail = detail

    def _obstacles(self) -> list[tuple[str, tuple[np.ndarray, np.ndarray]]]:
        """Boxes of whatever stands (or hangs) where the object would be: other objects, other links of the surface's object."""
        spec = self.spec
        surface, obj = spec.on, spec.for_object
        assert surface is not None and obj is not None
        robot = self.robot
        skip = {robot.body.id, obj.id, *(o.id for o in robot.held_objects())}
        low, high = self.top + 0.002, self.top + self.height
        found = []
        for other in robot.world.objects:
            if other.id in skip or (other is surface.obj and surface.link is None):
                continue
            if other is surface.obj:
                links: list[int | None] = [i for i in [-1, *range(len(other.joints))] if other.get_link_name(i) != surface.link]
            else:
                links = [None]
            for link in links:
                blo, bhi = other.get_aabb(link) if link is not None else other.get_aabb()
                if bhi[2] > low and blo[2] < high and bhi[0] - blo[0] > floor.THIN and bhi[1] - blo[1] > floor.THIN:
                    name = other.name if link is None else f"{other.name}/{other.get_link_name(link)}"
                    found.append((name, (np.asarray(blo), np.asarray(bhi))))
        return found

    def next(self) -> Spot:
        world = self.robot.world
        obj, surface = self.spec.for_object, self.spec.on
        assert obj is not None and surface is not None
        with world.lock, world.snapshot() as saved:
            self._prepared_inside()
            cand = self.candidates
            while self.cursor < len(cand) and self.expensive < self.limit:
                i = int(cand.order[self.cursor])
                self.cursor += 1
                if cand.outcome[i] != 0:
                    continue
                self.expensive += 1
                position = (float(cand.xs[i]), float(cand.ys[i]), self.top)
                world.restore_state(saved)
                quiet_let_go(obj)
                # as place will stand it: its lowest point on the surface, wherever the model's origin is
                obj.set_position_and_orientation(resting_on(obj, self.upright, position, self.top, surface.obj,
                                                            self.surface_link), self.upright)
                hits = self._touching(obj, surface)
                if hits:
                    cand.mark(i, "collides", ", ".join(hits))
                    continue
                answer = stable(obj, observe=0.0)  # the verdict only: how it moves on is not asked
                if not answer.stable:
                    cand.mark(i, "unstable", f"moved {answer.displacement * 1000:.1f} mm")
                    continue
                cand.outcome[i] = CODE["ok"]
                spot = Spot(position, self.upright, float(cand.scores[i]), surface.name, len(self.found))
                self.found.append(spot)
                return spot
        raise self._fail(self.failure_message())

    def _touching(self, obj: Object, surface: Any) -> list[str]:
        world = obj.world
        held = self.robot.held_objects()
        found = []
        for other in world.objects:
            if other is obj or other is self.robot.body or other in held:
                continue
            points = world.closest_points(obj, other, 0.0)
            if any(p.distance < -floor.PENETRATION
                   and not (other is surface.obj and (surface.link is None or other.get_link_name(p.link_b) == surface.link))
                   for p in points):
                found.append(other.name)
        return sorted(found)

    def failure_message(self) -> str:
        assert self.spec.on is not None and self.spec.for_object is not None
        what = f"no spot on {self.spec.on.name} for {self.spec.for_object.name}"
        if not len(self.candidates):
            return f"{what}: the surface is smaller than the object with its margins ({self.radius * 200:.0f} cm across)"
        return f"{what}: {self.summary()}"
