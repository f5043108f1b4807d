"""Reasoning queries (design §4.4): stable, contact, visible, occluding, reachable, blocking, supporting.

Every query leaves the world exactly as it found it (poses, joint positions, velocities and
attachments, bitwise). Answers are dataclasses that are truthy when the answer is yes.

    from pycram_cli.reasoning import stable, visible, reachable
    stable(milk)                      # StableAnswer(stable=True, displacement=1e-05, ...)
    visible(bottle).fraction          # seen from the robot's camera
    reachable(milk, robot, "r_gripper_tool_frame", grasp="front")

Each query is declared once (`query.QuerySpec`: parameters, runner, answer sentence) in
`queries.py`; `QUERIES` and `run_query` answer them by name with JSON-friendly results, for
plans and `pycram query`. A new query is a module with its `declare_query(...)`, imported here.
"""
from . import queries  # noqa: F401  (declares the design's seven queries)
from .contact import ContactAnswer, contact
from .ik import IKSolution, solve, solve_link
from .query import QUERIES, Call, QueryAnswer, QueryParam, QuerySpec, check_query_args, declare_query, run_query
from .reachability import ReachableAnswer, blocking, reachable
from .stable import StableAnswer, stable
from .supporting import supporting
from .visibility import VisibleAnswer, occluding, visible

__all__ = [
    "stable", "contact", "visible", "occluding", "reachable", "blocking", "supporting",
    "StableAnswer", "ContactAnswer", "VisibleAnswer", "ReachableAnswer", "IKSolution", "solve", "solve_link",
    "QUERIES", "QuerySpec", "QueryParam", "QueryAnswer", "Call", "run_query", "check_query_args", "declare_query",
]
