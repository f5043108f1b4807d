"""Plan parameters: from the command line (`-p object=milk`), bound to a plan and checked against their declared
types; and which world a plan runs in."""
from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import yaml

from ..errors import InputError, Location, did_you_mean, raise_if_any, setting
from ..kinds import NOTHING_KNOWN, Robots, param_kind
from ..paths import find_world
from ..schema import describe
from ..yamlsource import load_yaml_text
from .syntax import Param, Plan, plain


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


def type_problem(param: Param, value: Any, robots: Robots = NOTHING_KNOWN) -> str | None:
    """Why `value` does not fit the declared type of `param`, or None (also for a parameter without a type).

    A parameter whose default is null also takes null. Robot-dependent kinds (arm, grasp, poses) are
    checked against `robots`, what is known of the robot the plan runs on.
    """
    kind = param_kind(param.type)
    if kind is None or (value is None and not param.required and param.default is None):
        return None
    problem = kind.check(value, robots)
    if problem is None:
        return None
    shown = describe(value)
    return f"parameter '{param.name}' is {_article(param.type or '')} {param.type}: {problem}" + (
        "" if shown in problem else f", got {shown}")


def value_text(value: Any) -> str:
    """A value as it is written on the command line or in a plan (YAML flow style)."""
    return yaml.safe_dump(value, default_flow_style=True, width=10_000, sort_keys=False).strip().removesuffix("...").strip()


def param_hint(param: Param) -> str:
    """How a value of `param` is written: `-p target=[1, 0.5, 0.9]` (its default) or its kind's description."""
    kind = param_kind(param.type)
    if not param.required and param.default is not None:
        return f"e.g. -p {param.name}={value_text(param.default)}"
    return f"give it with -p {param.name}=VALUE" + (f" ({kind.doc})" if kind is not None else "")


def bind_params(plan: Plan, given: Mapping[str, Any], where: str = "-p", robots: Robots = NOTHING_KNOWN) -> dict[str, Any]:
    """The plan's parameter values: defaults overridden by `given`; unknown or missing ones, and values that do
    not fit a parameter's declared type, are input errors (the defaults are checked by `check_plan`)."""
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
            problem = type_problem(param, values[param.name], robots)
            if problem:
                errors.append(InputError(problem, Location(where), key=param.name, suggestion=param_hint(param)))
        elif param.required:
            errors.append(InputError(f"plan '{plan.name}' needs parameter '{param.name}'", Location(where),
                                     key=param.name, suggestion=param_hint(param)))
        else:
            values[param.name] = plain(param.default)
    raise_if_any(errors)
    return values


def _article(word: str) -> str:
    return "an" if word[:1].lower() in "aeiou" else "a"


def plan_world(plan: Plan, override: str | None = None) -> Path:
    """The world a run uses: `override` (relative to the current folder) or else the plan's own `world:`."""
    if override is not None:
        return find_world(override, Path.cwd(), Location(setting("world")))
    return find_world(plan.world, plan.path.parent, plan.world_where, naming=plan.path)


