"""Reasoning queries (design §4.4): stable, contact, visible, occluding, reachable, blocking, supporting.

Every query leaves the world exactly as it found it (poses, joint positions, velocities and
attachments, bitwise). Answers are dataclasses that are truthy when the answer is yes.

    from pycram_cli.reasoning import stable, visible, reachable
    stable(milk)                      # StableAnswer(stable=True, displacement=1e-05, ...)
    visible(bottle).fraction          # seen from the robot's camera
    reachable(milk, robot, "r_gripper_tool_frame", grasp="front")

`QUERIES` and `run_query` answer the same queries by name with JSON-friendly results, for
plans and `pycram query`.
"""
from .contact import ContactAnswer, contact
from .ik import IKSolution, solve
from .reachability import ReachableAnswer, blocking, reachable
from .registry import QUERIES, QueryAnswer, QueryParam, QuerySpec, check_query_args, run_query
from .stable import StableAnswer, stable
from .supporting import supporting
from .visibility import VisibleAnswer, occluding, visible

__all__ = [
    "stable", "contact", "visible", "occluding", "reachable", "blocking", "supporting",
    "StableAnswer", "ContactAnswer", "VisibleAnswer", "ReachableAnswer", "IKSolution", "solve",
    "QUERIES", "QuerySpec", "QueryParam", "QueryAnswer", "run_query", "check_query_args",
]
