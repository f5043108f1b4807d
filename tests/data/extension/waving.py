"""An extension as a user writes one: a query and a designator, each declared only here.

Importing this module is all it takes: plans, validation, `pycram query` (and its help) and
`pycram designators` pick them up from the registries.
"""
from __future__ import annotations

from typing import Any, Mapping

from pycram_cli.designators import Designator, declare_designator, drives_arm
from pycram_cli.process_modules import ProcessModule, process_module
from pycram_cli.reasoning import Call, QueryAnswer, QuerySpec, declare_query, parameters
from pycram_cli.robots import Robot
from pycram_cli.signature import Param, Signature


def _count(call: Call) -> QueryAnswer:
    kind = call.checked("type")
    found = sorted(o.name for o in call.world.objects if o.type == kind)
    return QueryAnswer("count", call.resolved, len(found), {"objects": found}, len(found))


declare_query(QuerySpec(
    "count", "How many objects of a type are in the world?",
    parameters(Param("type", "object-type", True, "an object type", positional=True)),
    _count, lambda answer: f"{answer.result} object(s) of type {answer.args['type']}"))


@process_module("wave")
class Wave(ProcessModule):
    """Swings the arm's first joint back and forth and leaves it where it was."""

    def execute(self, robot: Robot, slots: Mapping[str, Any]) -> int:
        joint = robot.description.arm(slots["arm"]).joints[0]
        start = robot.body.get_joint_position(joint)
        for _ in range(int(slots["times"])):
            robot.body.set_joint_position(joint, start + 0.2)
            robot.body.set_joint_position(joint, start)
        return int(slots["times"])


declare_designator(Designator(
    "waving", "Wave an arm a number of times.",
    Signature((Param("arm", "arm", True, "the arm that waves"), Param("times", "number", False, "how often", default=3))),
    resolve=lambda robot, slots: {"arm": slots["arm"], "times": slots["times"]},  # `times` bound to its default
    module="wave", uses=drives_arm("arm"), needs=("arms",), resource="arm"))
