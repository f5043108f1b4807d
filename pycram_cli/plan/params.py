"""Plan parameters from the command line (`-p object=milk`), and where a plan's world is."""
from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable, Mapping

import yaml

from ..errors import InputError, Location, did_you_mean, raise_if_any
from ..paths import default_world, plans_dir, worlds_dir
from .syntax import Plan, plain


def parse_assignments(items: Iterable[str], option: str = "-p") -> dict[str, Any]:
    """`name=value` strings; values are read as YAML scalars or lists (`-p target=[1, 0.5, 0]`)."""
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
            value = yaml.safe_load(text) if text.strip() else ""
        except yaml.YAMLError:
            value = text
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


def _bundled_names(folder: Path) -> list[str]:
    return sorted(p.stem for p in folder.glob("*.yaml")) if folder.is_dir() else []


def world_candidates(value: str, base: Path) -> list[Path]:
    names = [value] if value.endswith((".yaml", ".yml")) else [value, f"{value}.yaml"]
    return [base / n for n in names] + [worlds_dir() / n for n in names]


def find_world(value: str | None, base: Path, where: Location | None = None) -> Path:
    """A world named in a plan (`world:`) or given with `--world`: a path (relative to `base`) or a bundled name."""
    if value is None:
        return default_world()
    candidates = [Path(value)] if Path(value).is_absolute() else world_candidates(value, base)
    for path in candidates:
        if path.is_file():
            return path
    names = _bundled_names(worlds_dir())
    raise InputError(f"world file not found: '{value}' (looked next to the plan and in the bundled worlds)",
                     where or Location(value), key="world",
                     suggestion=did_you_mean(value, names) or (f"bundled worlds: {', '.join(names)}" if names else None))


def plan_world(plan: Plan, override: str | None = None) -> Path:
    """The world a run uses: `--world` (relative to the current folder) or else the plan's own `world:`."""
    if override is not None:
        return find_world(override, Path.cwd(), Location("--world"))
    return find_world(plan.world, plan.path.parent, plan.world_where)


def find_plan(value: str) -> Path:
    """A plan file path, or the name of a bundled plan (`set_table`)."""
    path = Path(value)
    if path.is_file():
        return path
    for candidate in (plans_dir() / value, plans_dir() / f"{value}.yaml"):
        if candidate.is_file():
            return candidate
    names = _bundled_names(plans_dir())
    raise InputError("plan file not found", Location(value),
                     suggestion=did_you_mean(value, names) or (f"bundled plans: {', '.join(names)}" if names else None))
