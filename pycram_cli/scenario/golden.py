"""Golden traces: the recorded behaviour of every bundled plan, checked by the test suite.

For each `plans/<name>.yaml` there is `tests/golden/<name>.trace.json`: the comparable
part of its trace (no timings, no source places) when run on its own world with its
default parameters. `tests/plan/test_golden.py` runs each plan again and compares with
`trace diff` semantics (numbers within 1e-3), so a change in behaviour fails CI.

When a change of behaviour is intended, regenerate on purpose and review the diff:

    python -m pycram_cli.scenario.golden --update            # every plan
    python -m pycram_cli.scenario.golden --update set_table  # one plan
    python -m pycram_cli.scenario.golden                     # only check, print differences
"""
from __future__ import annotations

import argparse
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..paths import plans_dir
from ..plan import trace as traces
from . import prepare
from .variation_files import SUFFIX as VARIATIONS

ATOL = 1e-3


def _checkout() -> Path:
    """The source checkout: the one this package lives in, else the current folder."""
    here = Path(__file__).resolve().parents[2]
    return here if (here / "tests").is_dir() and (here / "plans").is_dir() else Path.cwd()


def golden_dir() -> Path:
    """`tests/golden` of the source checkout."""
    return _checkout() / "tests" / "golden"


def bundled_plans(folder: Path | None = None) -> list[Path]:
    """The plans of the checkout's `plans/` (the installed ones when there is no checkout)."""
    if folder is None:
        folder = _checkout() / "plans"
        if not folder.is_dir():
            folder = plans_dir()
    return sorted(p for p in folder.glob("*.yaml") if not p.name.endswith(VARIATIONS))


def golden_path(plan: Path, folder: Path | None = None) -> Path:
    return (folder or golden_dir()) / f"{plan.stem}.trace.json"


def record(plan_path: Path) -> dict[str, Any]:
    """Run a plan on its own world with its default parameters; the comparable trace."""
    result = prepare(plan_path).run()
    return traces.normalised(traces.comparable(result.trace))


def check(plan_path: Path, folder: Path | None = None, atol: float = ATOL) -> list[traces.Difference]:
    """Differences between a fresh run and the golden trace (raises FileNotFoundError without one)."""
    expected = traces.load(golden_path(plan_path, folder))
    return traces.diff(expected, record(plan_path), atol)


def update(plan_path: Path, folder: Path | None = None) -> Path:
    path = golden_path(plan_path, folder)
    traces.save(record(plan_path), path, timing=False)
    return path


def _select(names: Iterable[str]) -> list[Path]:
    plans = bundled_plans()
    chosen = list(names)
    if not chosen:
        return plans
    by_name = {p.stem: p for p in plans}
    result = []
    for name in chosen:
        stem = Path(name).stem
        if stem not in by_name:
            raise SystemExit(f"no bundled plan '{name}' (plans: {', '.join(by_name)})")
        result.append(by_name[stem])
    return result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pycram_cli.scenario.golden",
                                     description="Check (or, with --update, regenerate) the golden traces of the bundled plans.")
    parser.add_argument("plans", nargs="*", help="plan names (default: every plan in plans/)")
    parser.add_argument("--update", action="store_true", help="write the golden traces from fresh runs")
    parser.add_argument("--atol", type=float, default=ATOL, help="float tolerance when checking (default 1e-3)")
    parser.add_argument("--dir", type=Path, default=None, help="golden folder (default: tests/golden)")
    args = parser.parse_args(argv)
    status = 0
    for plan in _select(args.plans):
        if args.update:
            print(f"wrote {update(plan, args.dir)}")
            continue
        try:
            found = check(plan, args.dir, args.atol)
        except Exception as exc:  # report and go on
            print(f"{plan.stem}: {exc}")
            status = 1
            continue
        if found:
            status = 1
            print(f"{plan.stem}: {len(found)} difference(s) from {golden_path(plan, args.dir)}")
            for difference in found:
                print(f"  {difference}")
        else:
            print(f"{plan.stem}: matches its golden trace")
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
