"""Action designators: plan steps one level above the motion designators ("transport the milk to the island").

Each action is one `Action` declaration (slots with kinds, the roles it drives, its `run`) in a
module of its family, imported here; `run(actor, slots)` expands it into motion designators,
reasoning queries, location designators and other actions, performed and recorded by an `Actor`.
Slots left open are inferred (where to stand, which arm, which grasp: `pycram_cli.locations`),
and when one choice fails the next candidate is tried before the action fails.

Actions have their own registry, `ACTIONS`: `pick-up` and `place` are names of motion
designators too, so in plans an action is written under the head `action:` with its slots beside
it (`- action: pick-up` / `  object: milk`), and the motion designators keep their meaning.

    from pycram_cli.designators.actions import perform_action
    milk = perform_action(world, "transport", {"object": "milk", "target": {"on": "kitchen_island_surface"}})
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ...errors import InputError, Location, raise_if_any
from ...kinds import Robots
from ...robots import Robot

# isort: off
from . import moving, perceiving, handling  # noqa: F401  (declares the actions, in this order)
# isort: on
from .actor import Actor, DirectActor, Finder
from .declaration import ACTIONS, Action, check_action, declare_action


def perform_action(world: Any, name: str, slots: Mapping[str, Any], record: dict[str, Any] | None = None) -> Any:
    """Perform an action with the world's robot; `record` (a dict) receives its expansion. Failures raise."""
    robot = Robot.of(world)
    problems = check_action(name, slots, robots=Robots((robot.description,), True))
    raise_if_any([InputError(p.message, Location(f"action {name}"), key=p.param, suggestion=p.suggestion)
                  for p in problems])
    actor = DirectActor(world, record)
    return actor.action(name, slots)


__all__ = ["ACTIONS", "Action", "Actor", "DirectActor", "Finder", "check_action", "declare_action", "perform_action"]
