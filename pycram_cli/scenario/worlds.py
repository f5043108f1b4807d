"""Running many variants of one scenario on worlds kept loaded.

    worlds = LoadedWorlds(scenario)
    for seed in seeds:
        variant, world = worlds.possible(variations, seed)   # redrawn while impossible (starts.py)
        result = scenario.varied(variant).run(world)         # same result as on a freshly loaded world
    worlds.close()

A world is loaded once per *structure* (which bodies exist: see `Variant.structure`) and its
state saved; every run starts by putting it back with `scenario.reset` (the same reset a
varied `Scenario.load_world` does on a fresh world), so traces on a kept world are
byte-identical to those of the scenario run alone, whatever ran before
(tests/scenario/test_variations.py checks it): a sweep's outcomes are the same whatever the
number of workers or the order of the scenarios.
"""
from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Any

from ..plan import RunResult
from ..plan.executor import Observer
from ..world import BulletWorld
from ..world.state import WorldState
from ..worldfile.loader import load_spec
from . import Scenario, reset
from .starts import possible_variant
from .variations import Variant, Variations

#: worlds of different structures a process keeps loaded (a variation that drops two objects makes four)
KEEP = 4


@dataclass
class _Loaded:
    world: BulletWorld
    state: WorldState


@dataclass
class LoadedWorlds:
    """The worlds one process keeps for the variants of a scenario, by structure (least recently used go)."""

    scenario: Scenario
    keep: int = KEEP
    loads: int = 0  # how many worlds were loaded (for the benchmarks)
    _worlds: OrderedDict[Any, _Loaded] = field(default_factory=OrderedDict)

    def world_for(self, variant: Variant) -> BulletWorld:
        """A world of the variant's structure in its freshly loaded state, the variant applied."""
        loaded = self._worlds.get(variant.structure)
        if loaded is None or not loaded.world.alive:
            world = load_spec(variant.world_spec(self.scenario.world), check_start=False)
            loaded = _Loaded(world, world.save_state())
            self.loads += 1
            self._worlds[variant.structure] = loaded
            while len(self._worlds) > self.keep:
                _, oldest = self._worlds.popitem(last=False)
                oldest.world.exit()
        self._worlds.move_to_end(variant.structure)
        reset(loaded.world, loaded.state)
        variant.apply(loaded.world)
        return loaded.world

    def possible(self, variations: Variations, seed: int, index: int | None = None) -> tuple[Variant, BulletWorld]:
        """Scenario `seed`'s first possible draw (see starts.py) and its world; raises ImpossibleStart."""
        return possible_variant(variations, seed, index, self.world_for)

    def run(self, variant: Variant, scenario: Scenario | None = None,
            observer: Observer | None = None) -> tuple[RunResult, float]:
        """Run the scenario (or `scenario`, the same plan and world with other parameters) on the variant;
        the result and the seconds spent preparing the world."""
        started = time.perf_counter()
        world = self.world_for(variant)
        setup = time.perf_counter() - started
        return (scenario or self.scenario).varied(variant).run(world, observer), setup

    def discard(self, variant: Variant | None = None) -> None:
        """Exit the world of `variant`'s structure (all worlds when None): the next run loads it anew."""
        keys = list(self._worlds) if variant is None else [variant.structure]
        for key in keys:
            loaded = self._worlds.pop(key, None)
            if loaded is not None:
                loaded.world.exit()

    def close(self) -> None:
        self.discard()
