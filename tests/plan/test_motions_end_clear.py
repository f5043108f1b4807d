"""Every shipped plan's motions end with no robot link and no held object inside any other body: after every step
of the trace, the world's closest points say so (deeper than 1 mm is inside; resting contact sits at about 1e-5 m).
The step checker (tests/shipped_runs.py) looks during the one run of each plan that the golden tests compare too."""
from __future__ import annotations

import pytest
from shipped_runs import each_plan


@pytest.mark.parametrize("plan", each_plan())
def test_no_step_of_a_shipped_plan_ends_with_the_robot_or_what_it_holds_inside_anything(plan, shipped_runs):
    run = shipped_runs(plan.stem)
    assert run.result.status == "succeeded", run.result.failure
    assert run.checker.steps >= 5
    assert run.checker.problems == []
