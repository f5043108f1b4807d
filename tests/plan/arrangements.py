"""Seeded random arrangements of the breakfast things along the sink-area counter.

Each object stands (the spoon lies) at a random place on the counter top left of the sink, turned as
the world has it, where a person standing in front of the counter reaches it: its centre 5 to 27 cm
behind the front edge, apart from the other objects and the bottle, which stays where it is.
"""
from __future__ import annotations

import math

import numpy as np


#: the counter top's front edge (x) and its surface height; the part left of the sink basin (y)
FRONT_X = 1.2475
TOP_Z = 0.851
DEPTH = (0.03, 0.25)
SPAN_Y = (0.25, 1.25)
OBJECTS = ("bowl", "milk", "cereal", "spoon")


def arrangement(seed: int, world) -> dict[str, tuple[tuple[float, float, float], tuple[float, float, float, float]]]:
    """Poses for the objects (by name): rejection-sampled so that no two objects' footprints come closer than 3 cm."""
    rng = np.random.default_rng(seed)
    radii = {}
    for name in (*OBJECTS, "bottle"):
        lo, hi = world.get_object_by_name(name).get_aabb()
        radii[name] = math.hypot(hi[0] - lo[0], hi[1] - lo[1]) / 2.0
    bottle = world.get_object_by_name("bottle").get_position()
    placed: dict[str, tuple[float, float]] = {"bottle": (bottle[0], bottle[1])}
    poses = {}
    for name in OBJECTS:
        for _ in range(1000):
            x = FRONT_X + rng.uniform(*DEPTH) + 0.02
            y = rng.uniform(*SPAN_Y)
            if all(math.dist((x, y), at) > radii[name] + radii[other] + 0.03 for other, at in placed.items()):
                break
        else:  # pragma: no cover - the counter always has room for four things
            raise RuntimeError(f"no room for {name} (seed {seed})")
        placed[name] = (x, y)
        poses[name] = ((x, y, TOP_Z), world.get_object_by_name(name).get_orientation())
    return poses


def arrange(world, poses) -> None:
    for name, (position, orientation) in poses.items():
        world.get_object_by_name(name).set_position_and_orientation(position, orientation)
