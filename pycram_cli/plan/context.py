"""Values in a plan: `$name` references, string interpolation, attribute access and scopes.

A string that is exactly a reference (`$obj`, `$blockers.0.type`) evaluates to the bound
value itself (an Object, a list, a number...). A string that merely contains references
(`"$object is not stable"`, `"${object}s"`) is interpolated into a string. `$$` is a
literal dollar sign.

Scopes are function scopes, like Python's: plan parameters are global and read-only;
every call of a subplan (and the plan body) gets its own frame of local variables, into
which `as:`, `for_each` and `set` bind. Each branch of a concurrent step (par, pursue,
try_all) gets a frame of its own on top (CPL's branches have their own bindings): reads see
the enclosing frames, writes stay in the branch, unless the step binds with `scope: plan`,
which writes into the invocation's own frame.
"""
from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

from ..failures import Failure
from ..jsonable import jsonable  # noqa: F401  (plan modules take it from here)
from ..limits import MAX_VALUE_CHARS, MAX_VALUE_ITEMS, MAX_VALUE_NESTING
from ..world import Object

NAME = r"[A-Za-z_][A-Za-z0-9_-]*"
PATH = rf"{NAME}(?:\.[A-Za-z0-9_-]+)*"
REFERENCE = re.compile(rf"^\$({PATH})$")
INTERPOLATION = re.compile(rf"\$\$|\$\{{({PATH})\}}|\$({PATH})")
IDENTIFIER = re.compile(rf"^{NAME}$")


@dataclass(frozen=True)
class Ref:
    """One `$name.attr.attr` reference."""

    name: str
    attrs: tuple[str, ...]

    @classmethod
    def parse(cls, text: str) -> Ref:
        head, *rest = text.split(".")
        return cls(head, tuple(rest))

    def __str__(self) -> str:
        return "$" + ".".join((self.name, *self.attrs))


def is_reference(value: Any) -> bool:
    """Whether `value` is only known at run time (it is or contains a `$reference`)."""
    return bool(references(value))


def references(value: Any) -> list[Ref]:
    """Every reference inside `value` (strings, lists and mappings, recursively)."""
    found: list[Ref] = []
    _collect(value, found)
    return found


def _collect(value: Any, found: list[Ref]) -> None:
    if isinstance(value, str):
        for match in INTERPOLATION.finditer(value):
            text = match.group(1) or match.group(2)
            if text:
                found.append(Ref.parse(text))
    elif isinstance(value, Mapping):
        for item in value.values():
            _collect(item, found)
    elif isinstance(value, (list, tuple)):
        for item in value:
            _collect(item, found)


class UnboundVariable(Failure):
    """A `$variable` that has no value at run time (bound in a branch that did not run)."""


@dataclass(frozen=True)
class FailureInfo:
    """What a `catch` handler sees as `$failure`: `.type`, `.message`, `.path`."""

    type: str
    message: str
    path: str
    error: Failure

    def __str__(self) -> str:
        return f"{self.type}: {self.message}"

    def to_json(self) -> dict[str, str]:
        return {"type": self.type, "message": self.message, "path": self.path}


class Frame:
    """Variables of one plan invocation (or of one branch of a concurrent step); what encloses it behind it."""

    def __init__(self, values: Mapping[str, Any] | None = None, parent: Frame | None = None,
                 branch: bool = False) -> None:
        self.values: dict[str, Any] = dict(values or {})
        self.parent = parent
        self.branch = branch  # a branch's own bindings, on top of the invocation's frame

    def plan_frame(self) -> Frame:
        """The frame of the plan invocation this frame belongs to (itself, unless it is a branch's)."""
        frame = self
        while frame.branch and frame.parent is not None:
            frame = frame.parent
        return frame

    def binder(self, scope: str | None) -> Frame:
        """Where a step binds: here, or with `scope: plan` in the invocation's frame."""
        return self.plan_frame() if scope == "plan" else self

    def lookup(self, name: str) -> Any:
        frame: Frame | None = self
        while frame is not None:
            if name in frame.values:
                return frame.values[name]
            frame = frame.parent
        raise UnboundVariable(f"variable ${name} has no value here (it is bound by a step that did not run)")

    def bind(self, name: str, value: Any) -> None:
        self.values[name] = value

    def names(self) -> Iterator[str]:
        frame: Frame | None = self
        while frame is not None:
            yield from frame.values
            frame = frame.parent


def attribute(value: Any, attr: str, ref: Ref) -> Any:
    """`value.attr`: list index or `length`, mapping key, Object/failure attribute."""
    if isinstance(value, Object):
        table = {"name": lambda o: o.name, "type": lambda o: o.type,
                 "position": lambda o: list(o.get_position()), "orientation": lambda o: list(o.get_orientation())}
        if attr in table:
            return table[attr](value)
    elif isinstance(value, FailureInfo):
        if attr in ("type", "message", "path"):
            return getattr(value, attr)
    elif isinstance(value, (list, tuple)):
        if attr == "length":
            return len(value)
        if attr.lstrip("-").isdigit():
            index = int(attr)
            if -len(value) <= index < len(value):
                return value[index]
            raise UnboundVariable(f"{ref}: index {index} is out of range (the list has {len(value)} items)")
    elif isinstance(value, Mapping):
        return value.get(attr)  # an absent key reads as null (optional fields of records)
    raise UnboundVariable(f"{ref}: {display(value)} has no attribute '{attr}'")


def lookup(ref: Ref, frame: Frame) -> Any:
    value = frame.lookup(ref.name)
    for attr in ref.attrs:
        value = attribute(value, attr, ref)
    return value


def evaluate(value: Any, frame: Frame) -> Any:
    """The run-time value of a plan value: references looked up, strings interpolated, recursively."""
    if isinstance(value, str):
        whole = REFERENCE.match(value)
        if whole:
            return lookup(Ref.parse(whole.group(1)), frame)
        if "$" not in value:
            return value
        return INTERPOLATION.sub(lambda m: _interpolated(m, frame), value)
    if isinstance(value, Mapping):
        return {key: evaluate(item, frame) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [evaluate(item, frame) for item in value]
    return value


def size_problem(value: Any) -> str | None:
    """Why a run-time value is too large to keep (more items, characters or nesting than the limits allow), or None.

    Values share their parts (`[$x, $x]` holds $x twice without copying it), so a value doubled step after
    step stays cheap to make but not to record or show: parts are counted each time they appear, and
    counting stops at the limit, so it costs at most the limit whatever the value."""
    items = chars = 0
    stack: list[tuple[Any, int]] = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        items += 1
        if items > MAX_VALUE_ITEMS:
            return f"a value of more than {MAX_VALUE_ITEMS} items (the limit; a value that grows at each step?)"
        if isinstance(item, str):
            chars += len(item)
        elif isinstance(item, (Mapping, list, tuple)):
            if depth >= MAX_VALUE_NESTING:
                return f"a value nested more than {MAX_VALUE_NESTING} levels deep (the limit)"
            if isinstance(item, Mapping):
                chars += sum(len(key) for key in item if isinstance(key, str))
                stack.extend((child, depth + 1) for child in item.values())
            else:
                stack.extend((child, depth + 1) for child in item)
        if chars > MAX_VALUE_CHARS:
            return f"a value of more than {MAX_VALUE_CHARS} characters of text (the limit; a value that grows at each step?)"
    return None


def _interpolated(match: re.Match[str], frame: Frame) -> str:
    if match.group(0) == "$$":
        return "$"
    return display(lookup(Ref.parse(match.group(1) or match.group(2)), frame))


def display(value: Any) -> str:
    """How a value reads in a message: objects by name, numbers short."""
    if isinstance(value, Object):
        return value.name
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(display(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{k}: {display(v)}" for k, v in value.items()) + "}"
    if value is None:
        return "null"
    return str(value)


def truthy(value: Any) -> bool:
    """Conditions: false, null, 0, "" and empty lists are false; everything else (objects too) is true."""
    if value is None:
        return False
    if isinstance(value, (list, tuple, dict, str)):
        return len(value) > 0
    if isinstance(value, (int, float)):
        return value != 0
    return bool(value)
