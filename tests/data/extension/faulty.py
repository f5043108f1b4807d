"""Queries that go wrong on purpose, for the sweep's tests: a bug (`explode`), a crash of the whole
process (`crash`), a step that never ends (`spin`, in Python: a timeout interrupts the thread that
waits for it, not the step) and one that holds the interpreter (`block`, one long C call)."""
from __future__ import annotations

import os
import time

from pycram_cli.reasoning import Call, QueryAnswer, QuerySpec, declare_query, parameters


def _explode(call: Call) -> QueryAnswer:
    raise RuntimeError("boom")


def _crash(call: Call) -> QueryAnswer:
    os._exit(3)


def _spin(call: Call) -> QueryAnswer:
    while True:  # a busy step no cancellation reaches
        time.sleep(0.001)


def _block(call: Call) -> QueryAnswer:
    sum(range(10**12))  # no signal handler runs until this returns
    raise AssertionError("unreachable in a test")


for _name, _runner in (("explode", _explode), ("crash", _crash), ("spin", _spin), ("block", _block)):
    declare_query(QuerySpec(_name, f"A query that goes wrong: {_name}.", parameters(), _runner, lambda answer: "never"))
