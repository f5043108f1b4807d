"""The failures a plan can raise and catch by name (CRAM's failure hierarchy).

Every failure carries a message a person understands: which object, which arm, how far off.
"""
from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from .errors import InputError, InputErrors, PycramError


class Failure(Exception):
    """Base of every plan failure; a handler for `Failure` catches them all."""

    plan_path: str | None = None  # the step that raised it (the executor sets it where it is raised)
    failures: list[Failure]  # a failure that gave up after several (a try_all, an action's choices): theirs

    def __init__(self, message: str, **details: Any) -> None:
        super().__init__(message)
        self.message = message
        self.details = details

    @property
    def type_name(self) -> str:
        return type(self).__name__

    def __str__(self) -> str:
        return self.message


class PerceptionFailure(Failure):
    """The robot could not see what it was asked to detect."""


class ReasoningFailure(Failure):
    """A reasoning check the plan relies on did not hold (e.g. the placed object is not stable)."""


class NavigationFailure(Failure):
    """The robot could not stand at the requested pose (collision, invalid target)."""


class ReachabilityFailure(Failure):
    """No arm configuration brings the tool frame to the target (inverse kinematics)."""


class GripperFailure(Failure):
    """The gripper could not open, close or hold what it should."""


class ManipulationFailure(Failure):
    """Manipulating an object or an articulated part failed (wrong object held, drawer stuck, ...)."""


class LocationFailure(Failure):
    """No pose satisfies a location designator; the message says which tests ruled the candidates out
    ("412 candidates: 380 collide, 32 out of reach")."""


class ProjectionFailure(Failure):
    """No alternative of a `project` step succeeded often enough in prospection; `details["table"]` has the
    outcomes of every alternative."""


FAILURES: dict[str, type[Failure]] = {
    cls.__name__: cls
    for cls in (Failure, PerceptionFailure, ReasoningFailure, NavigationFailure, ReachabilityFailure,
                GripperFailure, ManipulationFailure, LocationFailure, ProjectionFailure)
}
# the design's own names for two of them (in plans, and as Python names: `raise ReasoningError`)
ALIASES = {"PerceptionError": "PerceptionFailure", "ReasoningError": "ReasoningFailure"}
PerceptionError = PerceptionFailure
ReasoningError = ReasoningFailure


@dataclass(frozen=True, eq=False)
class FailureRecord(Mapping[str, Any]):
    """A failure as a trace records it: its type and message, the path of the step that raised it and, for one that
    gave up after several (a `try_all`, an action's choices), theirs. Frozen, built once where the failure is met
    (`FailureRecord.of`); `to_json()` is the trace's entry. It also reads as that mapping (`record["type"]`, `==` a
    dict), for code and tests that read a run's failure as the trace's JSON."""

    type: str
    message: str
    path: str | None = None  # None: a record that names no step (an action's own record of its children)
    failures: tuple[FailureRecord, ...] = ()

    @classmethod
    def of(cls, error: BaseException, path: str) -> FailureRecord:
        """The record of `error`, raised at step `path` (unless it knows the step it came from: `plan_path`)."""
        nested = getattr(error, "failures", None) or ()
        return cls(type(error).__name__, str(error), getattr(error, "plan_path", None) or path,
                   tuple(cls.of(f, path) for f in nested))

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {"type": self.type, "message": self.message}
        if self.path is not None:
            data["path"] = self.path
        if self.failures:
            data["failures"] = [f.to_json() for f in self.failures]
        return data

    def __getitem__(self, key: str) -> Any:
        return self.to_json()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.to_json())

    def __len__(self) -> int:
        return len(self.to_json())


class InternalError(Exception):
    """A bug inside a step: anything a step raises that is not pycram's own (a `Failure`, a `PycramError` met as
    one, a limit, a cancellation). Not a failure: no `retry` or `try` handles it; the run stops (`pycram run` exits
    3, saying it is a bug). `record` is the failing step's failure record; `result` the run's `RunResult` with its
    trace (status `error`), set when the run has ended (plan/executor.py)."""

    def __init__(self, message: str, record: FailureRecord | None = None) -> None:
        super().__init__(message)
        self.record = record
        self.result: Any = None


def failure_class(name: str) -> type[Failure] | None:
    return FAILURES.get(ALIASES.get(name, name))


def as_failure(exc: PycramError, what: str) -> Failure:
    """A bad value met at run time (an unknown object, link, arm) as a plan failure that names it, never a traceback.
    Only pycram's own errors: anything else a step raises is a bug (an internal error, see plan/executor.py)."""
    if isinstance(exc, (InputError, InputErrors)):
        message = "; ".join(e.message + (f" ({e.suggestion})" if e.suggestion else "")
                            for e in (exc.errors if isinstance(exc, InputErrors) else [exc]))
    else:
        message = f"{_kind(exc)}: {exc}"
    return Failure(f"{what}: {message}")


def _kind(exc: BaseException) -> str:
    """The error's kind in a failure message: the built-in one it is (ValueError for a BadValue, KeyError for an
    UnknownName: the words plans and traces have always shown), else its own name."""
    builtin = next((c for c in type(exc).__mro__ if c.__module__ == "builtins" and c is not Exception), None)
    return builtin.__name__ if builtin is not None and builtin is not BaseException else type(exc).__name__
