"""Errors about what the user gave us: each names the file, line, column and key.

Every layer raises `InputError` (or `InputErrors` for several at once) for bad
input; the CLI prints them without a traceback and exits with code 2.
"""
from __future__ import annotations

import difflib
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field


def closest(word: str, candidates: Iterable[str], cutoff: float = 0.6) -> str | None:
    """The candidate closest to `word`, if any is close enough to suggest."""
    pool = [c for c in candidates if isinstance(c, str)]
    match = difflib.get_close_matches(word, pool, n=1, cutoff=cutoff)
    if match:
        return match[0]
    lowered = {c.lower(): c for c in pool}
    return lowered.get(word.lower())


def did_you_mean(word: object, candidates: Iterable[str]) -> str | None:
    """`did you mean 'x'?` or None (None too for a word that is not a string: a YAML key read as null or a number)."""
    if not isinstance(word, str):
        return None
    match = closest(word, candidates)
    return f"did you mean '{match}'?" if match is not None and match != word else None


def setting(name: str) -> str:
    """How an error names a field or parameter its caller set (a sweep's `out`, a query's `from`): in backticks.
    The library knows no command line; the CLI shows the option that sets it instead (cli/flags.py)."""
    return f"`{name}`"


def key_text(key: object) -> str:
    """How a mapping key reads in a message: a name as it is, others as YAML writes them (null, true, 1, 2.5)."""
    if isinstance(key, str):
        return key
    if key is None:
        return "null"
    if isinstance(key, bool):
        return "true" if key else "false"
    return str(key)


def not_a_name(key: object) -> tuple[str, str] | None:
    """(message, suggestion) when a key of a mapping of names (slots, arguments, objects' fields) is not a name.

    YAML reads `~:` or an empty key as null, `1:` as a number and `yes:`/`true:` as true.
    """
    if isinstance(key, str):
        return None
    if key is None:
        return "keys must be names, got null", "a key written ~, null or left empty is null"
    if isinstance(key, bool):
        return (f"keys must be names, got {key_text(key)}",
                "YAML reads yes, no, on, off, true and false as true or false: quote it to mean the name")
    return f"keys must be names, got the number {key_text(key)}", f"quote it to mean the name: '{key_text(key)}'"


@dataclass
class Location:
    """A place in a user's file (1-based line and column)."""

    file: str | None = None
    line: int | None = None
    column: int | None = None

    def __str__(self) -> str:
        parts = [self.file or "<input>"]
        if self.line is not None:
            parts.append(str(self.line))
            if self.column is not None:
                parts.append(str(self.column))
        return ":".join(parts)


class PycramError(Exception):
    """Base of every error pycram raises on purpose. At run time, a step that meets one fails (a plan failure a
    `retry` or `try` can handle); anything else a step raises is a bug in pycram: an internal error (exit 3)."""


class BadValue(PycramError, ValueError):
    """A value pycram cannot use (a pose of the wrong size, a threshold out of range, two objects where two
    different ones are needed). A ValueError too, for callers of the library that catch those."""


class UnknownName(PycramError, KeyError):
    """A name the robot or the world does not have (an arm, a grasp), the message saying which ones it has.
    A KeyError too, for callers of the library that catch those."""


@dataclass
class InputError(PycramError):
    """One problem with user input."""

    message: str
    location: Location = field(default_factory=Location)
    key: str | None = None
    suggestion: str | None = None

    def __post_init__(self) -> None:
        super().__init__(self.format())

    def format(self) -> str:
        head = str(self.location)
        key = f" {self.key}:" if self.key else ""
        hint = f" ({self.suggestion})" if self.suggestion else ""
        return f"{head}:{key} {self.message}{hint}"

    def __str__(self) -> str:
        return self.format()

    def to_json(self) -> dict[str, object]:
        """The problem as data: where (file, line, column), which key, what, and a suggestion."""
        return {"file": self.location.file, "line": self.location.line, "column": self.location.column,
                "key": self.key, "message": self.message, "suggestion": self.suggestion}


class InputErrors(PycramError):
    """Several problems found together (validation reports them all at once)."""

    def __init__(self, errors: Sequence[InputError]):
        self.errors = list(errors)
        super().__init__("\n".join(e.format() for e in self.errors))


def raise_if_any(errors: Sequence[InputError]) -> None:
    """Raise the problems found (in file order), if any."""
    errors = sorted(errors, key=lambda e: (e.location.file or "", e.location.line or 0, e.location.column or 0))
    if len(errors) == 1:
        raise errors[0]
    if errors:
        raise InputErrors(errors)


def as_list(error: PycramError) -> list[InputError]:
    """The individual problems inside an `InputError` or `InputErrors`."""
    if isinstance(error, InputErrors):
        return error.errors
    if isinstance(error, InputError):
        return [error]
    return [InputError(str(error))]
