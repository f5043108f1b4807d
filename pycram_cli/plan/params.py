"""Plan parameters: from the command line (`-p object=milk`), bound to a plan; and which world a plan runs in."""
from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable, Mapping

from ..errors import InputError, Location, did_you_mean, raise_if_any
from ..paths import find_world
from ..yamlsource import load_yaml_text
from .syntax import Plan, plain


def parse_assignments(items: Iterable[str], option: str = "-p") -> dict[str, Any]:
    """`name=value` strings; values are read as YAML (`-p target=[1, 0.5, 0]`), strictly: a value that is not
    well-formed YAML (`-p 'types=[milk'`) is an input error, not a string."""
    values: dict[str, Any] = {}
    errors: list[InputError] = []
    for item in items:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            errors.append(InputError(f"expected NAME=VALUE, got '{item}'", Location(option),
                                     suggestion="e.g. -p object=milk"))
            continue
        try:
            value = load_yaml_text(text, f"{option} {name}") if text.strip() else ""
        except InputError as exc:
            exc.key = exc.key or name
            exc.suggestion = exc.suggestion or f"quote a value meant as text: {option} '{name}=\"{text}\"'"
            errors.append(exc)
            continue
        if name in values:
            errors.append(InputError(f"parameter '{name}' is given twice", Location(option)))
            continue
        values[name] = value
    raise_if_any(errors)
    return values


def bind_params(plan: Plan, given: Mapping[str, Any], where: str = "-p") -> dict[str, Any]:
    """The plan's parameter values: defaults overridden by `given`; unknown or missing ones are input errors."""
    errors: list[InputError] = []
    known = [p.name for p in plan.params]
    for name in given:
        if name not in known:
            errors.append(InputError(f"plan '{plan.name}' has no parameter '{name}'", Location(where), key=name,
                                     suggestion=did_you_mean(name, known)
                                     or (f"its parameters: {', '.join(known)}" if known else "it takes no parameters")))
    values: dict[str, Any] = {}
    for param in plan.params:
        if param.name in given:
            values[param.name] = plain(given[param.name])
        elif param.required:
            errors.append(InputError(f"plan '{plan.name}' needs parameter '{param.name}'", Location(where),
                                     key=param.name, suggestion=f"give it with -p {param.name}=VALUE"))
        else:
            values[param.name] = plain(param.default)
    raise_if_any(errors)
    return values


def plan_world(plan: Plan, override: str | None = None) -> Path:
    """The world a run uses: `--world` (relative to the current folder) or else the plan's own `world:`."""
    if override is not None:
        return find_world(override, Path.cwd(), Location("--world"))
    return find_world(plan.world, plan.path.parent, plan.world_where)


