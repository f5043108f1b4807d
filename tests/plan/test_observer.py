"""Observers of a run: a view derives from `Observing` and is told only what it overrides; the rest is a no-op."""
from __future__ import annotations

from pycram_cli.plan.observer import Observing


class Finished(Observing):
    def __init__(self) -> None:
        self.paths: list[str] = []

    def finished(self, node) -> None:
        self.paths.append(node.path)


class Folded(Observing):
    def __init__(self) -> None:
        self.summaries: list[str] = []

    def folded(self, summary, child) -> None:
        self.summaries.append(summary.path)


def test_a_view_that_overrides_only_finished_sees_every_step_end_and_nothing_breaks(plans, world):
    view = Finished()
    result = plans.run("""
        body:
          - log: hello
          - retry: 1
            body: [{fail: GripperFailure, message: slipped}]
    """, world, observer=view)
    assert result.status == "failed"
    assert view.paths[-1] == "body" and "body/0:log" in view.paths and "body/1:retry/attempt 2/0:fail" in view.paths


def test_a_view_told_of_folded_attempts_gets_each_fold_and_nothing_else(plans, world):
    view = Folded()
    result = plans.run("""
        body:
          - retry: 12
            body: [{fail: GripperFailure, message: slipped}]
    """, world, observer=view)
    assert result.status == "failed"
    assert view.summaries and set(view.summaries) == {"body/0:retry/folded attempts"}
