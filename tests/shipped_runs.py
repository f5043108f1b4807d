"""One run of each shipped plan per test process, shared by the tests that only read it.

The golden trace of a shipped plan, its motions ending clear of everything, and what it leaves on the island are
checked by different tests; each used to run the plan again (set_table_actions alone takes tens of seconds). The
`shipped_runs` fixture (tests/conftest.py) runs a plan the first time a test asks for it, with `StepChecker`
looking at the world after every step, and keeps the result, the checker and the world until the session ends.
Tests take the world only to read it (a query that simulates restores what it moved). The tests of one plan share
a pytest-xdist group (`group`), so that the suite runs each plan once, not once per worker.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import pytest

from pycram_cli.plan import RunResult
from pycram_cli.plan.observer import Observing
from pycram_cli.planning.contacts import supports_from_below
from pycram_cli.scenario import golden, prepare
from pycram_cli.world import BulletWorld

#: every shipped plan (those with a golden trace)
PLANS = golden.bundled_plans()
#: deeper than this is inside (resting contact sits at about 1e-5 m)
PENETRATION = 0.001


def inside(world: BulletWorld) -> list[tuple]:
    """Robot links and held objects inside another body: (link or object, other body, its link, depth)."""
    robot = world.robot
    held = [child for child, att in robot.attachments.items() if att.parent is robot]
    found: list[tuple] = []
    for other in world.objects:
        if other is robot:
            continue
        if not supports_from_below(robot, other):  # the floor the base stands on
            found += [(robot.get_link_name(p.link_a), other.name, other.get_link_name(p.link_b), round(-p.distance, 4))
                      for p in world.closest_points(robot, other, 0.0) if p.distance < -PENETRATION]
        for obj in held:
            if obj is not other:
                found += [(obj.name, other.name, other.get_link_name(p.link_b), round(-p.distance, 4))
                          for p in world.closest_points(obj, other, 0.0) if p.distance < -PENETRATION]
    return found


class StepChecker(Observing):
    """Looks at the world after every step of the plan that moved something or asked about it."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self.steps = 0
        self.problems: list[tuple[str, list]] = []

    def started(self, node) -> None:
        pass

    def log(self, node, message) -> None:
        pass

    def finished(self, node) -> None:
        if node.children or node.status != "succeeded":
            return
        with self.world.lock:
            self.steps += 1
            found = inside(self.world)
        if found:
            self.problems.append((node.path, found))


@dataclass
class ShippedRun:
    """A shipped plan's run: its result, the world it left (read only) and what the step checker found."""

    result: RunResult
    world: BulletWorld
    checker: StepChecker


@dataclass
class ShippedRuns:
    """The runs made so far in this process, by (plan name, world name or None for the plan's own)."""

    runs: dict[tuple[str, str | None], ShippedRun] = field(default_factory=dict)

    def __call__(self, plan: str, world: str | None = None) -> ShippedRun:
        """The run of shipped plan `plan` (a name in plans/) on `world`, made now if it is the first ask."""
        key = (plan, world)
        if key not in self.runs:
            scenario = prepare(_path(plan), world)
            sim = scenario.load_world()
            try:
                checker = StepChecker(sim)
                self.runs[key] = ShippedRun(scenario.run(world=sim, observer=checker), sim, checker)
            except BaseException:
                sim.exit()
                raise
        return self.runs[key]

    def close(self) -> None:
        for run in self.runs.values():
            run.world.exit()
        self.runs.clear()


def _path(plan: str) -> Path:
    return next(p for p in PLANS if p.stem == plan)


def group(plan: str, world: str | None = None) -> pytest.MarkDecorator:
    """The pytest-xdist group of the tests that read one shipped run: they go to one worker, which runs it once."""
    return pytest.mark.xdist_group(f"shipped-{plan}" + (f"-{world}" if world else ""))


def each_plan() -> list:
    """`PLANS` as parameters named by plan, each in its plan's group."""
    return [pytest.param(p, id=p.stem, marks=group(p.stem)) for p in PLANS]
