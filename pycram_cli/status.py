"""The status of a plan step or of a whole run: one enum instead of strings spelt in many places.

A `StrEnum`: each status is the string traces have always written (`"succeeded"`), so traces,
JSON and comparisons with plain strings (a trace read back from a file) stay as they were.
"""
from __future__ import annotations

from enum import StrEnum


class Status(StrEnum):
    PENDING = "pending"  # not started yet
    RUNNING = "running"
    SUCCEEDED = "succeeded"
    FAILED = "failed"
    CANCELLED = "cancelled"  # stopped from outside (a concurrent sibling decided, a limit, a signal)
    SKIPPED = "skipped"  # never started: an earlier step decided the outcome
    INTERRUPTED = "interrupted"  # a whole run stopped by a signal (Ctrl-C); runs only
    ERROR = "error"  # a whole run stopped by an internal error (a bug in pycram, not a plan failure); runs only


#: what a step of a trace can be
NODE_STATUSES = (Status.PENDING, Status.RUNNING, Status.SUCCEEDED, Status.FAILED, Status.CANCELLED, Status.SKIPPED)
#: how a run can end
RUN_STATUSES = (Status.SUCCEEDED, Status.FAILED, Status.CANCELLED, Status.INTERRUPTED, Status.ERROR)
