"""Scenarios: a plan, the world it runs in and its parameters, checked once and then run.

    scenario = prepare("plans/set_table.yaml", params={"jobs": [...]})   # every problem at once, nothing simulated
    result = scenario.run()                                              # loads the world, runs, exits the world
    result.status, result.failure, result.trace

This is the one place that owns "world + plan + parameters -> prepared run -> result and
trace": `pycram run`, the golden traces (`golden.py`), the benchmarks and the tests all go through it, so
the plan is validated against the world file (its objects, its robot's description) and the
parameters are bound exactly once. A scenario holds no simulation: `run()` loads a fresh
world (one PyBullet client) and exits it afterwards, or uses a world it is given and leaves
it open, so any number of scenarios can run one after another, or side by side, in a process.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from ..errors import InputError, PycramError, as_list, raise_if_any
from ..failures import InternalError
from ..kinds import NOTHING_KNOWN
from ..paths import find_plan, find_world
from ..plan import Plan, RunResult, WorldFacts, bind_params, check_plan, parse_assignments, parse_plan, run_plan
from ..plan.executor import Observer
from ..plan.replay import Recorder
from ..plan.runtime import Projector
from ..plan.trace import REPLAY_KEY
from ..world import BulletWorld
from ..world.state import WorldState
from ..worldfile.loader import load_spec
from ..worldfile.spec import WorldSpec, parse_world
from .variations import Variant


def reset(world: BulletWorld, state: WorldState) -> None:
    """Put `world` back to `state` as if it had just been loaded (`BulletWorld.reset_to`)."""
    world.reset_to(state)


@dataclass
class Scenario:
    """A validated plan with its world file and bound parameters; run it any number of times."""

    plan: Plan
    world: WorldSpec
    params: dict[str, Any] = field(default_factory=dict)
    variant: Variant | None = None  # one drawn variation of the world and parameters (see variations.py)

    @property
    def world_path(self) -> Path:
        return self.world.path

    def load_world(self, mode: str = "direct") -> BulletWorld:
        """A fresh simulation of the scenario's world, varied by its variant if any (the caller exits it)."""
        if self.variant is None:
            return load_spec(self.world, mode=mode)
        world = load_spec(self.variant.world_spec(self.world), mode=mode, check_start=False)
        try:
            state = world.save_state()
            reset(world, state)  # exactly the state a sweep's kept world starts every scenario from
            world.release_state(state)
            self.variant.apply(world)
        except BaseException:
            world.exit()
            raise
        return world

    def varied(self, variant: Variant) -> Scenario:
        """This scenario with a variant's parameter values and world (checked when the variations were read)."""
        return replace(self, params={**self.params, **variant.params}, variant=variant)

    def with_params(self, values: Mapping[str, Any]) -> Scenario:
        """This scenario with some parameters set otherwise (values checked by `bind_params`)."""
        robots = WorldFacts.of_spec(self.world).robots
        return replace(self, params={**self.params, **bind_params(self.plan, {**self.params, **values}, robots=robots)})

    def run(self, world: BulletWorld | None = None, observer: Observer | None = None, mode: str = "direct",
            replay: bool = False, projector: Projector | None = None) -> RunResult:
        """Run the plan: on `world` if given (left open), else on a freshly loaded world (exited afterwards).

        With `replay`, the trace also records the world's state after every step (its `replay` key,
        see plan/replay.py), which `pycram run --report` and `trace show --report` replay.
        """
        if world is not None:
            return self._run(world, observer, replay, projector)
        sim = self.load_world(mode)
        try:
            return self._run(sim, observer, replay, projector)
        finally:
            sim.exit()

    def _run(self, world: BulletWorld, observer: Observer | None, replay: bool,
             projector: Projector | None = None) -> RunResult:
        recorder = Recorder(world, observer, self.world_path) if replay else None
        try:
            result = run_plan(self.plan, world, self.params, recorder or observer, world_name=self.world_path.name,
                              bound=True, projector=projector)
        except InternalError as exc:  # a bug stopped the run: its trace (exc.result) gets the replay too
            if recorder is not None and exc.result is not None:
                exc.result.trace[REPLAY_KEY] = recorder.record()
            raise
        finally:
            if recorder is not None:
                recorder.close()
        if recorder is not None:
            result.trace[REPLAY_KEY] = recorder.record()
        return result


def prepare(plan: str | Path, world: str | Path | None = None, params: Mapping[str, Any] | None = None,
            assignments: Iterable[str] = ()) -> Scenario:
    """Every check that needs no simulation, all problems reported together (InputErrors).

    `plan`: a plan file or a bundled plan's name; `world`: a world file or a bundled world's
    name (default: the plan's own `world:`, else the kitchen); `params`: parameter values;
    `assignments`: `NAME=VALUE` strings as given with `-p` (values read as YAML).
    """
    errors: list[InputError] = []
    path = find_plan(str(plan))
    parsed = parse_plan(path, errors)
    spec: WorldSpec | None = None
    try:
        if world is not None:
            world_path = find_world(str(world), Path.cwd())
        else:
            world_path = find_world(parsed.world, parsed.path.parent, parsed.world_where, naming=parsed.path)
        spec = parse_world(world_path)
    except PycramError as exc:
        errors.extend(as_list(exc))
    facts = WorldFacts.of_spec(spec) if spec is not None else None
    values: dict[str, Any] = {}
    try:
        given = dict(params or {})
        given.update(parse_assignments(assignments))
        values = bind_params(parsed, given, robots=facts.robots if facts is not None else NOTHING_KNOWN)
    except PycramError as exc:
        errors.extend(as_list(exc))
    try:
        check_plan(parsed, facts=facts, check_world_file=False, errors=errors, values=values or None)
    except PycramError as exc:
        raise_if_any(as_list(exc))
    raise_if_any(errors)
    assert spec is not None
    return Scenario(parsed, spec, values)
