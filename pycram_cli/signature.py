"""One shape for what a motion designator, an action designator or a query takes, and one registry of each family.

    Signature((Param("object", "object", True, "the object to pick up"),
               Param("distance", "distance", doc="how far to open", default=0.3, default_doc="0.3 m")))

A `Signature` is the single truth about a declaration's parameters: their kinds (`pycram_cli.kinds`),
which are required, which go together (`one_of`), a check across parameters, and their defaults.
Validation (`check`, which returns `Problem`s that name their parameter), the CLI, the editor schema and
the docs read it; resolvers receive `bind(values)`, so a default lives here and nowhere else.
A `Registry` holds one family's declarations by name: a name declared twice is an error, and an
unknown name gets the closest known one.
"""
from __future__ import annotations

import copy
from collections.abc import Callable, Iterator, Mapping, MutableMapping
from dataclasses import dataclass
from typing import Any, Protocol, TypeVar

from .errors import did_you_mean
from .kinds import KINDS, NOTHING_KNOWN, Robots


@dataclass(frozen=True)
class Param:
    """One parameter (a designator's slot, a query's argument): its kind, whether it must be given, its default."""

    name: str
    kind: str
    required: bool = False
    doc: str = ""
    default: Any = None  # the value `bind` fills in when none is given (None: left open, found at run time)
    default_doc: str = ""  # how the default is found, for people (when it is not one value)
    positional: bool = False  # on the command line: an argument, not an option (queries)
    multiple: bool = False  # on the command line: a repeatable option collecting a list (queries)
    of: str | None = None  # for a link or joint: the parameter naming the object it belongs to

    @property
    def option(self) -> str:
        return f"--{self.name}"

    @property
    def default_text(self) -> str:
        """The default for people: how it is found, else its value, else '' (none)."""
        if self.default_doc:
            return self.default_doc
        return "" if self.default in (None, []) else str(self.default)


@dataclass(frozen=True)
class Problem:
    """One problem with the values given: what is wrong, the parameter it is about (None: the whole), a hint."""

    message: str
    param: str | None = None
    suggestion: str | None = None

    def __str__(self) -> str:
        return self.message + (f" ({self.suggestion})" if self.suggestion else "")


#: a check across parameters (e.g. two values that must agree), given the values known before the run
Across = Callable[[Mapping[str, Any], Robots], "list[Problem]"]
#: values not to check against their kind (only known at run time: plan variables, objects)
Skip = Callable[[Param, Any], bool]


def _never(param: Param, value: Any) -> bool:
    return False


@dataclass(frozen=True)
class Signature:
    """The parameters of one declaration, how they are checked together, and their defaults."""

    params: tuple[Param, ...] = ()
    one_of: tuple[str, ...] = ()  # at least one of these must be given
    across: Across | None = None  # checks across parameters
    noun: str = "slot"  # what a parameter is called in messages: "slot" (designators) or "parameter" (queries)
    #: value problems name the owner and repeat the value (a query's problems also show inside conditions)
    names_value: bool = False

    def param(self, name: str) -> Param | None:
        return next((p for p in self.params if p.name == name), None)

    @property
    def names(self) -> list[str]:
        return [p.name for p in self.params]

    def kind_problems(self) -> list[str]:
        """Parameters whose kind is unknown: a mistake in the declaration, not in a plan."""
        return [f"{self.noun} '{p.name}': unknown kind '{p.kind}'" for p in self.params if p.kind not in KINDS]

    def unknown(self, what: str, key: str) -> Problem:
        return Problem(f"{what} has no {self.noun} '{key}'", key,
                       did_you_mean(key, self.names) or f"{self.noun}s: {', '.join(self.names)}")

    def check(self, values: Mapping[str, Any], robots: Robots = NOTHING_KNOWN, what: str = "",
              skip: Skip = _never, across_values: Mapping[str, Any] | None = None) -> list[Problem]:
        """Problems found without running anything: unknown parameters (with the closest name), values against their
        kinds (unless `skip(param, value)`), required ones missing, `one_of`, and the check across parameters (given
        `across_values`, by default `values`). `what` names the owner in messages ("'moving'", "query 'stable'")."""
        problems: list[Problem] = []
        for key, value in values.items():
            param = self.param(key)
            if param is None:
                problems.append(self.unknown(what, key))
            elif not skip(param, value):
                message = KINDS[param.kind].check(value, robots)
                if message and self.names_value:
                    problems.append(Problem(f"{what}, {self.noun} '{key}': {message}, got {value!r}", key))
                elif message:
                    problems.append(Problem(f"{self.noun} '{key}': {message}", key))
        for param in self.params:
            if param.required and param.name not in values:
                problems.append(Problem(f"{what} needs {self.noun} '{param.name}' ({param.doc})", param.name))
        if self.one_of and not any(key in values for key in self.one_of):
            problems.append(Problem(f"{what} needs one of the {self.noun}s {', '.join(self.one_of)}"))
        if self.across is not None:
            problems.extend(self.across(values if across_values is None else across_values, robots))
        return problems

    def bind(self, values: Mapping[str, Any]) -> dict[str, Any]:
        """The values given, with each declared default filled in where none is (or None) given."""
        bound = dict(values)
        for param in self.params:
            if bound.get(param.name) is None and param.default is not None:
                bound[param.name] = copy.deepcopy(param.default)
        return bound


class Declared(Protocol):
    """What a registry holds: a named declaration with a signature."""

    @property
    def name(self) -> str: ...

    @property
    def signature(self) -> Signature: ...


T = TypeVar("T", bound=Declared)


class Registry(MutableMapping[str, T]):
    """One family's declarations by name, in the order declared (the order `pycram designators` and docs list)."""

    def __init__(self, what: str, listing: str) -> None:
        self.what = what  # "query", "action", "designator type": how an unknown name is reported
        self.listing = listing  # "queries": the heading of the list of known names
        self._items: dict[str, T] = {}

    def declare(self, item: T) -> T:
        """Add a declaration; its name must be new and every parameter's kind known."""
        if item.name in self._items:
            raise ValueError(f"{self.what} '{item.name}' is declared twice")
        wrong = item.signature.kind_problems()
        if wrong:
            raise ValueError(f"{self.what} '{item.name}', {wrong[0]}")
        self._items[item.name] = item
        return item

    def unknown(self, name: str) -> Problem:
        """The problem with a name that is not declared: the closest one, else the known ones."""
        return Problem(f"unknown {self.what} '{name}'", None, self.suggestion(name))

    def suggestion(self, name: str) -> str:
        return did_you_mean(name, self._items) or f"{self.listing}: {', '.join(self._items)}"

    def __getitem__(self, name: str) -> T:
        return self._items[name]

    def __setitem__(self, name: str, item: T) -> None:  # restoring a saved registry (tests); declare checks
        self._items[name] = item

    def __delitem__(self, name: str) -> None:
        del self._items[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __repr__(self) -> str:
        return f"Registry({self.what!r}, {list(self._items)})"
