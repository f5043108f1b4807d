"""Statuses are one enum that reads, compares and serialises as the strings traces have always held."""
from __future__ import annotations

import json
from pathlib import Path

from pycram_cli.plan.trace import TraceNode
from pycram_cli.scenario import prepare
from pycram_cli.status import NODE_STATUSES, RUN_STATUSES, Status


def test_a_status_is_its_string_in_json_text_and_comparisons():
    assert json.dumps({"status": Status.SUCCEEDED}) == '{"status": "succeeded"}'
    assert f"{Status.FAILED}" == str(Status.FAILED) == "failed"
    assert Status.CANCELLED == "cancelled" and "skipped" in NODE_STATUSES
    assert Status("interrupted") is Status.INTERRUPTED and Status.INTERRUPTED in RUN_STATUSES
    assert Status.INTERRUPTED not in NODE_STATUSES and Status.PENDING not in RUN_STATUSES


def test_a_run_and_its_steps_carry_statuses(tmp_path: Path):
    plan = tmp_path / "p.yaml"
    plan.write_text("body:\n  - log: hello\n  - fail: PerceptionFailure\n  - log: never\n")
    result = prepare(plan).run()
    assert result.status is Status.FAILED and not result.succeeded
    steps = result.trace["root"]["children"]
    assert [step["status"] for step in steps] == [Status.SUCCEEDED, Status.FAILED, Status.SKIPPED]
    assert json.loads(json.dumps(result.trace))["status"] == "failed"


def test_a_new_step_is_pending():
    assert TraceNode("body", "sequence").status is Status.PENDING
