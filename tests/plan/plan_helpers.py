"""Helpers for plan tests: write a plan from text and run it, find trace nodes by path."""
from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

from pycram_cli.plan import load_plan, run_plan


class Runner:
    def __init__(self, tmp_path: Path) -> None:
        self.tmp_path = tmp_path
        self.count = 0

    def write(self, text: str, name: str | None = None) -> Path:
        self.count += 1
        path = self.tmp_path / (name or f"plan{self.count}.yaml")
        path.write_text(textwrap.dedent(text))
        return path

    def load(self, text: str):
        return load_plan(self.write(text))

    def run(self, text: str, world, params: dict[str, Any] | None = None, observer=None):
        return run_plan(self.load(text), world, params or {}, observer)


def nodes(trace: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """Every trace node by its path."""
    found: dict[str, dict[str, Any]] = {}

    def walk(node: dict[str, Any]) -> None:
        found[node["path"]] = node
        for child in node.get("children", []):
            walk(child)

    walk(trace["root"])
    return found


def statuses(trace: dict[str, Any]) -> dict[str, str]:
    return {path: node["status"] for path, node in nodes(trace).items()}


def messages(trace: dict[str, Any]) -> list[str]:
    return [n["message"] for n in nodes(trace).values() if n["type"] == "log" and "message" in n]
