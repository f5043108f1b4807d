"""The plan language as a whole: every built-in node type registered, and reading plan files.

`syntax.py` defines nodes and the registry but knows no node type; importing the node
modules here fills the registry, so anyone who reads a plan through `parse_plan` or
`load_plan` (or imports `pycram_cli.plan`, which imports this module) has them all.
"""
from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from ..paths import find_plan
from ..world import BulletWorld
from . import actions, composites, decorators, leaves, projecting  # noqa: F401  (importing them registers their node types)
from .syntax import NODE_TYPES, Plan, read_plan
from .validate import check_plan

__all__ = ["NODE_TYPES", "Plan", "load_plan", "parse_plan"]


def parse_plan(path: str | Path, errors: list[InputError] | None = None) -> Plan:
    """Read a plan file into nodes; every structural problem is reported together.

    With an `errors` list, problems are added to it instead of raised (so that later
    checks can report theirs in the same go).
    """
    return read_plan(path, errors)


def load_plan(path: str | Path, world: BulletWorld | None = None, check_world_file: bool = True) -> Plan:
    """Parse and check a plan file; every problem is reported together with file, line and column.

    `path` is a file, or a plan's name as the command line takes it (`set_table`: the working folder's `plans/`
    first, then the bundled plans)."""
    errors: list[InputError] = []
    plan = parse_plan(find_plan(str(path)), errors)
    return check_plan(plan, world, check_world_file, errors)
