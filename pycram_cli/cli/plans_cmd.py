"""`pycram plans`: the plans a name can mean, the working folder's `plans/` first, then the bundled ones, each with
its description, world and parameters (types, defaults). Nothing is run; a plan that cannot be read is listed with
its problem."""
from __future__ import annotations

from typing import Any

import click

from ..errors import InputError, PycramError, as_list
from ..paths import Found
from ..plan import parse_plan
from ..plan.params import value_text
from ..plan.syntax import Param
from . import console
from .options import json_option


def param_entry(param: Param) -> dict[str, Any]:
    return {"name": param.name, "type": param.type, "required": param.required,
            "default": None if param.required else param.default, "description": param.description}


def param_text(param: dict[str, Any]) -> str:
    """`target: position = [-0.8, 1.4, 0.862]  where it goes` (or `required`)."""
    typed = f": {param['type']}" if param["type"] else ""
    value = " (required)" if param["required"] else f" = {_short(value_text(param['default']))}"
    return f"{param['name']}{typed}{value}" + (f"  {param['description']}" if param["description"] else "")


def _short(text: str, limit: int = 60) -> str:
    return text if len(text) <= limit else text[: limit - 3] + "..."


def plan_entry(found: Found) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": found.name, "source": found.source, "path": str(found.path),
                             "shadowed": found.shadowed, "description": "", "world": None, "params": [],
                             "problems": []}
    errors: list[InputError] = []
    try:
        plan = parse_plan(found.path, errors)
    except PycramError as exc:
        errors.extend(as_list(exc))
    else:
        entry.update(description=plan.description, world=plan.world, params=[param_entry(p) for p in plan.params])
    entry["problems"] = [e.format() for e in errors]
    return entry


def about(entry: dict[str, Any]) -> list[str]:
    """What a plan is for: its description, its world and, if it cannot be read, the first problem."""
    return [line for line in (entry["description"], f"world: {entry['world']}" if entry["world"] else "",
                              *(f"not valid: {p}" for p in entry["problems"][:1])) if line]


@click.command("plans")
@json_option
def plans(as_json: bool) -> None:
    """List the plans: the working folder's plans/ first, then the bundled ones, with descriptions and parameters."""
    console.show_found("plans", plan_entry, as_json, ["description", "parameters"],
                       lambda e: ("\n".join(about(e)), "\n".join(param_text(p) for p in e["params"]) or "-"),
                       lambda e: [*about(e), *(param_text(p) for p in e["params"])])
