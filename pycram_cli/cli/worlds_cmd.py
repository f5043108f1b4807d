"""`pycram worlds`: the worlds a name can mean, the working folder's `worlds/` first, then the bundled ones, each
with its description, robot and objects, read from the world file (nothing is simulated). A world that cannot be
read is listed with its problem."""
from __future__ import annotations

from typing import Any

import click

from ..errors import PycramError, as_list
from ..paths import Found
from ..worldfile.spec import parse_world
from . import console
from .options import json_option


def world_entry(found: Found) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": found.name, "source": found.source, "path": str(found.path),
                             "shadowed": found.shadowed, "description": "", "robot": None, "objects": [],
                             "problems": []}
    try:
        spec = parse_world(found.path)
    except PycramError as exc:
        entry["problems"] = [e.format() for e in as_list(exc)]
        return entry
    robot = spec.robot
    entry.update(description=spec.description, objects=[{"name": o.name, "type": o.type} for o in spec.objects])
    if robot is not None:
        desc = spec.robot_description
        entry["robot"] = {"name": robot.name, "file": robot.file_text, "description": desc.name if desc else None,
                          "arms": list(desc.arms) if desc else []}
    return entry


def robot_text(robot: dict[str, Any] | None) -> str:
    if robot is None:
        return "no robot"
    arms = f", arms: {', '.join(robot['arms'])}" if robot["arms"] else ""
    return f"{robot['name']} ({robot['file']}{arms})"


def objects_text(entry: dict[str, Any]) -> str:
    robot = (entry["robot"] or {}).get("name")
    return ", ".join(o["name"] for o in entry["objects"] if o["name"] != robot) or "-"


@click.command("worlds")
@json_option
def worlds(as_json: bool) -> None:
    """List the worlds: the working folder's worlds/ first, then the bundled ones, with their robot and objects."""
    console.show_found("worlds", world_entry, as_json, ["description", "robot", "objects"],
                       lambda e: ("\n".join(about(e)), robot_text(e["robot"]) if not e["problems"] else "-",
                                  objects_text(e)),
                       lambda e: about(e) + ([f"robot: {robot_text(e['robot'])}", f"objects: {objects_text(e)}"]
                                             if not e["problems"] else []))


def about(entry: dict[str, Any]) -> list[str]:
    """What a world is: its description and, if it cannot be read, the first problem."""
    return [line for line in (entry["description"], *(f"not valid: {p}" for p in entry["problems"][:1])) if line]
