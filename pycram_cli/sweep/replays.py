"""Running some of a sweep's scenarios again, recording their replays: what `sweep --report` links to.

`chosen(records, limit)` picks which: the failed scenarios first (one of every failure type and node
first, then the others by index), then, if there is room, two successes to compare with. `rerun` runs
one again exactly as the sweep ran it (the same draw from its seed, the same `--compare` value), with
the replay record on, and checks that it did the same as in the sweep (the trace's digest).
"""
from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from ..scenario.worlds import LoadedWorlds
from .summary import outcome_of
from .worker import trace_digest

if TYPE_CHECKING:
    from . import PreparedSweep

SUCCESS_EXAMPLES = 2
RUN_STATUSES = ("succeeded", "failed")  # timeouts, crashes and impossible starts have no run to replay


def chosen(records: list[dict[str, Any]], limit: int) -> list[dict[str, Any]]:
    """At most `limit` records to replay, failures first (see the module docstring), in a stable order."""
    ran = sorted((r for r in records if r.get("status") in RUN_STATUSES),
                 key=lambda r: (r["index"], str(r.get("alternative"))))
    failed = [r for r in ran if r["status"] != "succeeded"]
    picked: list[dict[str, Any]] = []
    seen: set[tuple[str, Any]] = set()
    for record in failed:  # one of every failure type and node
        group = (outcome_of(record), (record.get("failure") or {}).get("path"))
        if group not in seen:
            seen.add(group)
            picked.append(record)
    picked += [r for r in failed if r not in picked]
    picked = picked[:limit]
    room = min(SUCCESS_EXAMPLES, limit - len(picked))
    picked += [r for r in ran if r["status"] == "succeeded"][:max(0, room)]
    return picked


def rerun(sweep: PreparedSweep, records: list[dict[str, Any]]) -> Iterator[tuple[dict[str, Any], dict[str, Any], bool]]:
    """(record, trace with its replay record, whether the run did the same as in the sweep) of each record."""
    worlds = LoadedWorlds(sweep.scenario)
    try:
        for record in records:
            variant, world = worlds.possible(sweep.variations, record["seed"], record["index"])
            scenario = sweep.scenario.varied(variant)
            if record.get("alternative") is not None:
                scenario = scenario.with_params(record["alternative"])
            result = scenario.run(world, replay=True)
            yield record, result.trace, trace_digest(result.trace) == record.get("trace")
    finally:
        worlds.close()
