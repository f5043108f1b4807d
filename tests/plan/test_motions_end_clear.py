"""Every shipped plan's motions end with no robot link and no held object inside any other body: after every step
of the trace, the world's closest points say so (deeper than 1 mm is inside; resting contact sits at about 1e-5 m)."""
from __future__ import annotations

import pytest

from pycram_cli.plan.observer import Observing
from pycram_cli.planning.contacts import supports_from_below
from pycram_cli.scenario import golden, prepare

PLANS = golden.bundled_plans()  # every shipped plan (those with a golden trace)
PENETRATION = 0.001


def inside(world):
    robot = world.robot
    held = [child for child, att in robot.attachments.items() if att.parent is robot]
    found = []
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

    def __init__(self, world) -> None:
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


@pytest.mark.parametrize("plan", PLANS, ids=[p.stem for p in PLANS])
def test_no_step_of_a_shipped_plan_ends_with_the_robot_or_what_it_holds_inside_anything(plan):
    scenario = prepare(plan)
    world = scenario.load_world()
    try:
        checker = StepChecker(world)
        result = scenario.run(world=world, observer=checker)
        assert result.status == "succeeded", result.failure
        assert checker.steps >= 5
        assert checker.problems == []
    finally:
        world.exit()
