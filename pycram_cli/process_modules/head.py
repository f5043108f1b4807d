"""The head executor: point the camera at a target (`planning/head.py` says how, for every camera mount)."""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..planning.head import look_at
from ..robots import Robot
from .base import ProcessModule
from .registry import process_module


@process_module("head")
class MoveHead(ProcessModule):

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> None:
        look_at(robot, slots["target"])
