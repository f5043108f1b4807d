"""Possible starts: a drawn scenario whose objects start inside each other or in the air is drawn again.

A variation file draws poses without looking at the world: the cereal can land inside the bowl
(`separation` keeps centres apart, not shapes), a region's box can put the milk in the air or half
over a counter's edge, a swapped model can sink into the counter. Such a scenario tests nothing a
robot will meet, and its failure would be counted against the plan. So each drawn scenario is
checked on its loaded world before it runs (worldfile/starts.py): a varied or swapped object (or the
moved robot) more than 3 mm inside another body, or a varied object whose centre of mass is not
over something just below its bottom (past a counter's edge, or in the air).

An impossible draw is drawn again from `redraw_seed(seed, k)`, up to REDRAWS times, so a
scenario stays a function of its seed alone (the same on every worker, and for `pycram run
--scenario SEED`); the reasons of the rejected draws are kept in the scenario's record
(`varied["redrawn"]`). When no draw is possible, `ImpossibleStart` says why: the sweep records
the scenario as `invalid` (not counted in the success rate), `pycram run --scenario` exits 2.
"""
from __future__ import annotations

import hashlib
from collections.abc import Callable
from typing import TYPE_CHECKING

from ..worldfile.starts import start_problems

if TYPE_CHECKING:
    from ..world import BulletWorld
    from .variations import Variant, Variations

#: draws after the first before a scenario is given up as impossible
REDRAWS = 20


class ImpossibleStart(Exception):
    """No draw of a scenario gave a possible start; `reasons` has one line per draw."""

    def __init__(self, seed: int, reasons: list[str]) -> None:
        super().__init__(f"scenario {seed}: no possible start in {len(reasons)} draws (the first: {reasons[0]})")
        self.seed = seed
        self.reasons = reasons


def redraw_seed(seed: int, attempt: int) -> int:
    """The seed of scenario `seed`'s draw number `attempt` (1, 2, ...): the same on every machine."""
    return int.from_bytes(hashlib.sha256(f"pycram-redraw/{seed}/{attempt}".encode()).digest()[:4], "big")


def impossible(world: BulletWorld, variant: Variant) -> list[str]:
    """Why the variant, applied to `world`, cannot start (empty: it can): its moved and swapped objects."""
    names = sorted(set(variant.poses) | set(variant.swaps))
    objects = [world.robot if name == "robot" else world.get_object_by_name(name) for name in names]
    return start_problems(world, [obj for obj in objects if obj is not None])


def possible_variant(variations: Variations, seed: int, index: int | None,
                     world_for: Callable[[Variant], BulletWorld],
                     release: Callable[[BulletWorld], None] = lambda world: None,
                     ) -> tuple[Variant, BulletWorld]:
    """The first possible draw of scenario `seed` and the world it is applied to.

    `world_for(variant)` gives a world with the variant applied; `release(world)` is called on the
    worlds of rejected draws (a fresh world is exited; a kept one is reset by the next `world_for`).
    Raises ImpossibleStart when none of 1 + REDRAWS draws is possible (every world released).
    """
    reasons: list[str] = []
    for attempt in range(REDRAWS + 1):
        variant = variations.sample(seed if attempt == 0 else redraw_seed(seed, attempt), index)
        world = world_for(variant)
        problems = impossible(world, variant)
        if not problems:
            if reasons:
                variant.varied["redrawn"] = reasons
            return variant, world
        release(world)
        reasons.append("; ".join(problems))
    raise ImpossibleStart(seed, reasons)
