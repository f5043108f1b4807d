"""Every plan in plans/ behaves as its golden trace records (tests/golden/<plan>.trace.json).

When a change of behaviour is intended, regenerate the golden traces on purpose and review
their diff:  python -m pycram_cli.scenario.golden --update [PLAN...]   (see docs/plans.md)
"""
from __future__ import annotations

from pathlib import Path

import pytest
from shipped_runs import each_plan

from pycram_cli.scenario import golden

REPO = Path(__file__).resolve().parents[2]
GOLDEN = REPO / "tests" / "golden"
PLANS = golden.bundled_plans(REPO / "plans")
HOW = "python -m pycram_cli.scenario.golden --update"


def test_every_plan_has_a_golden_trace():
    missing = [p.stem for p in PLANS if not golden.golden_path(p, GOLDEN).is_file()]
    assert not missing, f"no golden trace for {', '.join(missing)}: create it with `{HOW} {' '.join(missing)}`"


def test_no_golden_trace_without_its_plan():
    plans = {p.stem for p in PLANS}
    orphans = [g.name for g in GOLDEN.glob("*.trace.json") if g.name[:-len(".trace.json")] not in plans]
    assert not orphans, f"golden traces of plans that no longer exist: {', '.join(orphans)}"


@pytest.mark.parametrize("plan", each_plan())
def test_plan_matches_its_golden_trace(plan, pycram_golden, shipped_runs):
    """The run compared is the one other tests read too (tests/shipped_runs.py): the plan runs once."""
    if not golden.golden_path(plan, GOLDEN).is_file():
        pytest.skip("no golden trace yet (see test_every_plan_has_a_golden_trace)")
    pycram_golden(plan, golden=golden.golden_path(plan, GOLDEN), trace=shipped_runs(plan.stem).result.trace)
