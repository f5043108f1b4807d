"""Which physical resources of the robot a step uses: the base, each arm, the head.

Branches of a concurrent node that use disjoint resources run side by side; a branch
that shares a resource with an earlier sibling starts only when that sibling has ended
(in declaration order, so the outcome never depends on thread timing). The analysis is
static and conservative: a slot only known at run time (`arm: $arm`) or an omitted arm
counts as both arms; a call uses everything its subplan (transitively) uses.
"""
from __future__ import annotations

from typing import Any, Mapping

from .context import is_reference
from .syntax import Node, Plan

BASE, HEAD = "base", "head"
ARMS = ("arm:left", "arm:right")
EVERYTHING = frozenset({BASE, HEAD, *ARMS})


def _arm(value: Any) -> frozenset[str]:
    if isinstance(value, str) and not is_reference(value) and f"arm:{value}" in ARMS:
        return frozenset({f"arm:{value}"})
    return frozenset(ARMS)


def designator_resources(type_name: str, slots: Mapping[str, Any]) -> frozenset[str]:
    """The resources a motion designator drives, from its type and literal slots."""
    if type_name == "moving":
        return frozenset({BASE})
    if type_name in ("pick-up", "place", "move-tcp", "accessing"):
        return _arm(slots.get("arm"))
    if type_name in ("opening-gripper", "closing-gripper"):
        return _arm(slots.get("gripper"))
    if type_name == "move-arm-joints":
        used: set[str] = set()
        if "left-arm" in slots:
            used.add("arm:left")
        if "right-arm" in slots:
            used.add("arm:right")
        return frozenset(used)
    if type_name in ("looking", "detecting"):
        return frozenset({HEAD})
    if type_name == "world-state-detecting":
        return frozenset()
    return EVERYTHING


class ResourceAnalysis:
    """Resources of steps and of subplans (a fixpoint over calls, recursion included)."""

    def __init__(self, plan: Plan) -> None:
        self.plan = plan
        self.subplans: dict[str, frozenset[str]] = {name: frozenset() for name in plan.plans}
        changed = True
        while changed:
            changed = False
            for name, sub in plan.plans.items():
                used = frozenset().union(*(self.of(step) for step in sub.body)) if sub.body else frozenset()
                if used != self.subplans[name]:
                    self.subplans[name] = used
                    changed = True

    def of(self, node: Node) -> frozenset[str]:
        """What a step uses: its own resources and its child steps' (`Node.resources`)."""
        used: set[str] = set()
        for step in node.walk():
            used |= step.resources(self)
        return frozenset(used)

    def subplan(self, name: str | None) -> frozenset[str]:
        """What a call of subplan `name` uses (everything when there is no such subplan)."""
        return self.subplans.get(name or "", EVERYTHING)

    def waits_for(self, nodes: list[Node]) -> dict[int, set[int]]:
        """For each branch, the earlier branches it shares a resource with."""
        used = [self.of(node) for node in nodes]
        return {j: {i for i in range(j) if used[i] & used[j]} for j in range(len(nodes))}
