#!/usr/bin/env python3
"""Work counted, not timed: collision checks, closest-point queries, IK searches and path searches per plan.

    python bench/counts.py                       # fetch_milk, set_table, set_table_actions on the PR2 and the Fetch
    python bench/counts.py --only fetch_milk     # a subset (case names as bench/plans.py names them)
    python bench/counts.py --json                # the counts as JSON

Each case runs in this process through `pycram run PLAN --json` (as bench/plans.py's child does), with the
functions that do the work wrapped to count their calls. Plans are deterministic, so the counts are the same on
every machine and under any load: a before/after comparison of a change to the checks needs no quiet machine.

- *checks*: collision checks of the moving part at one configuration (`Motion.clearances`: a path's checks, a
  goal's, a search's configurations);
- *queries*: PyBullet closest-point queries (`BulletWorld._closest_rows`: what a check measures exactly, and
  every other distance asked);
- *walks*: straight joint-space paths followed check by check (`Motion._follow`; remembered walks are not);
- *ik*: inverse-kinematics searches started (`ik_search.search_groups` as ik.py calls it, one per batch of queries
  not answered from memory), and *ik queries*, the targets asked of `ik.link_solutions` (from memory or not);
- *searches*: joint-space path searches run (`paths._Search.run`; remembered ones are not).
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import sys
from collections import Counter
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from pycram_cli.planning import motion, paths  # noqa: E402
from pycram_cli.reasoning import ik  # noqa: E402
from pycram_cli.world.bullet_world import BulletWorld  # noqa: E402

#: the cases counted: (name, plan, world or None for the plan's own) — names as bench/plans.py gives them
CASES = (("fetch_milk", "fetch_milk", None), ("set_table", "set_table", None),
         ("set_table_actions", "set_table_actions", None),
         ("set_table_actions@kitchen_fetch", "set_table_actions", "kitchen_fetch"))
#: what is counted: (column, owner, attribute, how many a call counts for)
COUNTED: tuple[tuple[str, Any, str, Callable[..., int]], ...] = (
    ("checks", motion.Motion, "clearances", lambda *a, **k: 1),
    ("queries", BulletWorld, "_closest_rows", lambda *a, **k: 1),
    ("walks", motion.Motion, "_follow", lambda *a, **k: 1),
    ("ik", ik, "search_groups", lambda *a, **k: 1),
    ("ik queries", ik, "link_solutions", lambda robot, link, queries, *a, **k: len(queries)),
    ("searches", paths._Search, "run", lambda *a, **k: 1),
)


@contextlib.contextmanager
def counting() -> Iterator[Counter[str]]:
    """Every function of COUNTED wrapped to count its calls while the block runs (put back after it)."""
    counts: Counter[str] = Counter()
    saved = []
    for column, owner, name, weight in COUNTED:
        original = getattr(owner, name, None)
        if original is None:  # renamed elsewhere: the column stays empty rather than the bench failing
            continue
        saved.append((owner, name, original))

        def counted(*args: Any, _original: Callable[..., Any] = original, _column: str = column,
                    _weight: Callable[..., int] = weight, **kwargs: Any) -> Any:
            counts[_column] += _weight(*args, **kwargs)
            return _original(*args, **kwargs)

        setattr(owner, name, counted)
    try:
        yield counts
    finally:
        for owner, name, original in saved:
            setattr(owner, name, original)


def count(plan: str, world: str | None) -> dict[str, Any]:
    """One run of `plan` (on `world`) through the command line's code, in this process: its status and counts."""
    from pycram_cli.cli.main import cli

    args = ["run", plan, *(["--world", world] if world else []), "--json", "-q"]
    out = io.StringIO()
    with counting() as counts, contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
        cli.main(args, prog_name="pycram", standalone_mode=False)
    answer = json.loads(out.getvalue())
    return {"status": answer["status"], **{column: counts[column] for column, *_ in COUNTED}}


def table(results: dict[str, dict[str, Any]]) -> str:
    """The counts as a plain-text table."""
    columns = ["status", *(column for column, *_ in COUNTED)]
    rows = [("case", *columns)] + [(name, *(str(r[c]) for c in columns)) for name, r in results.items()]
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    return "\n".join("  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() for row in rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", help="comma-separated case names: " + ", ".join(name for name, *_ in CASES))
    parser.add_argument("--json", action="store_true", help="print the counts as JSON")
    args = parser.parse_args()
    chosen = CASES
    if args.only:
        names = set(args.only.split(","))
        unknown = names - {name for name, *_ in CASES}
        if unknown:
            parser.error(f"--only: no case {', '.join(sorted(unknown))}")
        chosen = tuple(case for case in CASES if case[0] in names)
    results = {}
    for name, plan, world in chosen:
        print(f"{name} ...", file=sys.stderr, flush=True)
        results[name] = count(plan, world)
    print(json.dumps(results, indent=2) if args.json else table(results))


if __name__ == "__main__":
    main()
