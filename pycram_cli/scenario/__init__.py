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

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable, Mapping

from ..errors import InputError, PycramError, as_list, raise_if_any
from ..paths import find_plan, find_world
from ..plan import Plan, RunResult, WorldFacts, bind_params, check_plan, parse_assignments, parse_plan, run_plan
from ..plan.executor import Observer
from ..world import BulletWorld
from ..worldfile.loader import load_spec
from ..worldfile.spec import WorldSpec, parse_world


@dataclass
class Scenario:
    """A validated plan with its world file and bound parameters; run it any number of times."""

    plan: Plan
    world: WorldSpec
    params: dict[str, Any] = field(default_factory=dict)

    @property
    def world_path(self) -> Path:
        return self.world.path

    def load_world(self, mode: str = "direct") -> BulletWorld:
        """A fresh simulation of the scenario's world (the caller exits it)."""
        return load_spec(self.world, mode=mode)

    def run(self, world: BulletWorld | None = None, observer: Observer | None = None, mode: str = "direct") -> RunResult:
        """Run the plan: on `world` if given (left open), else on a freshly loaded world (exited afterwards)."""
        if world is not None:
            return run_plan(self.plan, world, self.params, observer, world_name=self.world_path.name, bound=True)
        sim = self.load_world(mode)
        try:
            return run_plan(self.plan, sim, self.params, observer, world_name=self.world_path.name, bound=True)
        finally:
            sim.exit()


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
            world_path = find_world(parsed.world, parsed.path.parent, parsed.world_where)
        spec = parse_world(world_path)
    except PycramError as exc:
        errors.extend(as_list(exc))
    values: dict[str, Any] = {}
    try:
        given = dict(params or {})
        given.update(parse_assignments(assignments))
        values = bind_params(parsed, given)
    except PycramError as exc:
        errors.extend(as_list(exc))
    try:
        check_plan(parsed, facts=WorldFacts.of_spec(spec) if spec is not None else None, check_world_file=False,
                   errors=errors, values=values or None)
    except PycramError as exc:
        raise_if_any(as_list(exc))
    raise_if_any(errors)
    assert spec is not None
    return Scenario(parsed, spec, values)
