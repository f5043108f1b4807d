"""A pytest plugin for golden traces of your own plans (installed with pycram; pytest loads it by itself).

    def test_my_plan(pycram_golden):
        pycram_golden("plans/my_plan.yaml")                     # world: the plan's own; default parameters
        pycram_golden("plans/my_plan.yaml", world="kitchen", params={"object": "bowl"}, name="my_plan-bowl")
        pycram_golden("plans/my_plan.yaml", trace=result.trace)  # a run the test made already: not run again

The golden trace lives beside the test, in `golden/<name>.trace.json`. The first run writes it
and fails (look at it, then commit it); later runs compare with `pycram trace diff` semantics
(numbers within `atol`, differences named by the node's path). After an intended change of
behaviour: `pytest --pycram-update-golden`, then review the diff of the golden files.

Why not pytest-regressions or syrupy: both compare snapshots exactly or as flat data; a trace
needs numbers compared within a tolerance and differences reported by plan node, which is
what pycram's own trace diff does, so the plugin is a thin layer over it.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import pytest

from ..plan import trace as traces
from . import prepare

ATOL = 1e-3


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("pycram")
    group.addoption("--pycram-update-golden", action="store_true", default=False,
                    help="write the golden traces of pycram plans from fresh runs instead of comparing")


def recorded(plan: str | Path, world: str | Path | None = None, params: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The comparable trace of one run: no timings, no source places."""
    result = prepare(plan, world, params).run()
    return traces.normalised(traces.comparable(result.trace))


@pytest.fixture
def pycram_golden(request: pytest.FixtureRequest) -> Callable[..., None]:
    """Check a plan's run against its golden trace (see the module docstring)."""
    update = bool(request.config.getoption("--pycram-update-golden"))
    folder = Path(str(request.node.path)).parent / "golden"

    def check(plan: str | Path, world: str | Path | None = None, params: Mapping[str, Any] | None = None,
              name: str | None = None, golden: str | Path | None = None, atol: float = ATOL,
              trace: Mapping[str, Any] | None = None) -> None:
        path = Path(golden) if golden is not None else folder / f"{name or Path(plan).stem}.trace.json"
        # a trace given: the test ran the plan itself (and checks more of that run), which is not run again
        actual = recorded(plan, world, params) if trace is None else traces.normalised(traces.comparable(trace))
        if update or not path.is_file():
            existed = path.is_file()
            path.parent.mkdir(parents=True, exist_ok=True)
            traces.save(actual, path, timing=False)
            if not update and not existed:
                pytest.fail(f"no golden trace yet: wrote {path}; look at it and commit it", pytrace=False)
            return
        differences = traces.diff(traces.load(path), actual, atol)
        if differences:
            lines = "\n".join(f"  {d}" for d in differences[:40]) + ("\n  ..." if len(differences) > 40 else "")
            pytest.fail(f"{Path(plan).name} no longer behaves as {path} records:\n{lines}\n"
                        "if this change is intended, run pytest --pycram-update-golden and review the diff",
                        pytrace=False)

    return check
