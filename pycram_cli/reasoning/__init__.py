"""Reasoning queries (design §4.4): stable, contact, visible, occluding, reachable, blocking, supporting.

Every query leaves the world exactly as it found it (poses, joint positions, velocities and
attachments, bitwise). Answers are dataclasses that are truthy when the answer is yes.

    from pycram_cli.reasoning import stable, visible, reachable
    stable(milk)                      # StableAnswer(stable=True, displacement=1e-05, ...)
    visible(bottle).fraction          # seen from the robot's camera
    reachable(milk, robot, "r_gripper_tool_frame", grasp="front")

Each query is declared once (`query.QuerySpec`: its parameters as a `Signature`, runner, answer
sentence) at the end of the module that computes it (`stable.py` declares `stable`);
`QUERIES` and `run_query` answer them by name with JSON-friendly results, for plans and
`pycram query`. A new query is a module ending with its `declare_query(...)`, imported here.
"""
# the design's seven queries, declared in this order (`pycram query` and the docs list them so): isort keeps off
# isort: off
from .stable import StableAnswer, stable
from .contact import ContactAnswer, contact
from .visibility import VisibleAnswer, occluding, visible
from .reachability import ReachableAnswer, blocking, reachable
from .supporting import supporting
# isort: on
from .ik import IKSolution, solve, solve_link
from .query import QUERIES, Call, QueryAnswer, QuerySpec, check_query_args, declare_query, parameters, run_query

__all__ = [
    "stable", "contact", "visible", "occluding", "reachable", "blocking", "supporting",
    "StableAnswer", "ContactAnswer", "VisibleAnswer", "ReachableAnswer", "IKSolution", "solve", "solve_link",
    "QUERIES", "QuerySpec", "QueryAnswer", "Call", "run_query", "check_query_args", "declare_query", "parameters",
]
