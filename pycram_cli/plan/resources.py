"""Which physical resources of the robot a step uses: from the designators' declarations and the robot's description.

Branches of a concurrent node that use disjoint resources run side by side; a branch
that shares a resource with an earlier sibling starts only when that sibling has ended
(in declaration order, so the outcome never depends on thread timing). A designator
declares the roles it drives (`base`, `head`, `arm:<name>`); the robot description says
which resource each role is (by default its own). The analysis is static and conservative:
a slot only known at run time (`arm: $arm`) or an omitted arm counts as every arm; a call
uses everything its subplan (transitively) uses.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..designators import ANY_ARM, DESIGNATORS, robot_resources
from .context import is_reference
from .syntax import Node, Plan

if TYPE_CHECKING:
    from ..robots import RobotDescription


def everything(description: RobotDescription | None) -> frozenset[str]:
    """Every resource of the robot: what an unknown step is assumed to use."""
    return robot_resources(frozenset({"base", "head", ANY_ARM}), description)


def designator_resources(type_name: str, slots: Mapping[str, Any],
                         description: RobotDescription | None = None) -> frozenset[str]:
    """The resources a motion designator drives, from its declaration, its literal slots and the robot."""
    spec = DESIGNATORS.get(type_name)
    if spec is None:
        return everything(description)
    known = {k: (None if is_reference(v) else v) for k, v in slots.items()}
    return robot_resources(spec.uses(known), description)


class ResourceAnalysis:
    """Resources of steps and of subplans (a fixpoint over calls, recursion included), for one robot."""

    def __init__(self, plan: Plan, description: RobotDescription | None = None) -> None:
        self.plan = plan
        self.description = description
        self.subplans: dict[str, frozenset[str]] = {name: frozenset() for name in plan.plans}
        changed = True
        while changed:
            changed = False
            for name, sub in plan.plans.items():
                used = frozenset().union(*(self.of(step) for step in sub.body)) if sub.body else frozenset()
                if used != self.subplans[name]:
                    self.subplans[name] = used
                    changed = True

    def designator(self, type_name: str, slots: Mapping[str, Any]) -> frozenset[str]:
        return designator_resources(type_name, slots, self.description)

    def of(self, node: Node) -> frozenset[str]:
        """What a step uses: its own resources and its child steps' (`Node.resources`)."""
        used: set[str] = set()
        for step in node.walk():
            used |= step.resources(self)
        return frozenset(used)

    def subplan(self, name: str | None) -> frozenset[str]:
        """What a call of subplan `name` uses (everything when there is no such subplan)."""
        return self.subplans.get(name or "", everything(self.description))

    def waits_for(self, nodes: list[Node]) -> dict[int, set[int]]:
        """For each branch, the earlier branches it shares a resource with."""
        used = [self.of(node) for node in nodes]
        return {j: {i for i in range(j) if used[i] & used[j]} for j in range(len(nodes))}
