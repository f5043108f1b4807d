"""Failure records: what a trace says of a failure, built once where it is met and frozen after."""
from __future__ import annotations

import dataclasses

import pytest

from pycram_cli.failures import FailureRecord, GripperFailure, PerceptionFailure


def test_a_record_is_frozen_and_its_json_is_the_traces_entry():
    record = FailureRecord.of(GripperFailure("slipped"), "body/1:fail")
    with pytest.raises(dataclasses.FrozenInstanceError):
        record.message = "something else"  # type: ignore[misc]  # the point: it cannot be changed
    assert record.to_json() == {"type": "GripperFailure", "message": "slipped", "path": "body/1:fail"}


def test_a_failure_that_gave_up_after_several_records_theirs_each_at_its_own_step():
    first, second = PerceptionFailure("not on the counter"), PerceptionFailure("not in the drawer")
    first.plan_path, second.plan_path = "body/0:try_in_order/0:fail", "body/0:try_in_order/1:fail"
    gave_up = PerceptionFailure("not found")
    gave_up.failures = [first, second]
    record = FailureRecord.of(gave_up, "body/0:try_in_order")
    assert record.path == "body/0:try_in_order" and [f.path for f in record.failures] == [first.plan_path, second.plan_path]
    assert record.to_json()["failures"][1] == {"type": "PerceptionFailure", "message": "not in the drawer",
                                              "path": "body/0:try_in_order/1:fail"}


def test_a_record_without_a_step_has_no_path_key_and_reads_as_its_json():
    record = FailureRecord("GripperFailure", "dropped")
    assert record.to_json() == {"type": "GripperFailure", "message": "dropped"}
    assert record["type"] == "GripperFailure" and record.get("path") is None
    assert record == {"type": "GripperFailure", "message": "dropped"}
