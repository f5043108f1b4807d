"""Which scenarios of a sweep are run again for the report's replays: failures first, one of each kind first."""
from __future__ import annotations

from pycram_cli.sweep.replays import chosen


def record(index: int, status: str = "succeeded", kind: str | None = None, path: str = "body/0") -> dict:
    failure = {"type": kind, "path": path, "message": "m"} if kind else None
    return {"index": index, "seed": index, "status": status, "failure": failure}


def test_one_of_every_failure_kind_comes_first_then_the_other_failures_then_two_successes():
    records = [record(0), record(1, "failed", "A"), record(2, "failed", "A"), record(3, "failed", "B"),
               record(4), record(5), record(6, "failed", "A", "body/1"), record(7, "timeout", "Timeout")]
    assert [r["index"] for r in chosen(records, 10)] == [1, 3, 6, 2, 0, 4]
    assert [r["index"] for r in chosen(records, 2)] == [1, 3]  # bounded: no room for successes
    assert chosen(records, 0) == []


def test_a_sweep_without_failures_replays_two_successes():
    assert [r["index"] for r in chosen([record(i) for i in range(5)], 10)] == [0, 1]
