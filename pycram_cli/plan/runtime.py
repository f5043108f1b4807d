"""What a node may ask of the run that executes it: the contract between the two floors.

Node classes (syntax, composites, decorators, leaves) belong to the language floor and
never import the running floor (executor, scheduler, trace). Their `execute(ex, tn)`
methods get the runtime through `ex` and `tn` only; this module says what those offer.
"""
from __future__ import annotations


class Cancelled(BaseException):
    """A branch was cancelled. Not a Failure: no handler or retry catches it."""
