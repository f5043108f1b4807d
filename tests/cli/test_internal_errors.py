"""A bug inside pycram is an internal error, never a plan failure: no `retry` or `try` handles it, the run stops,
`pycram run` exits 3 with one line saying it is a bug and where to report it (the traceback under --verbose), and
the trace, when asked for, records where it happened. pycram's own errors met at run time stay plan failures."""
from __future__ import annotations

import dataclasses
import json
import textwrap

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import EXIT_INTERNAL, cli
from pycram_cli.designators.declaration import DESIGNATORS
from pycram_cli.errors import BadValue, PycramError, UnknownName
from pycram_cli.failures import as_failure

PLAN = """
    world: kitchen
    body:
      - retry: 2
        body:
          - moving-torso: {position: 0.1}
"""


@pytest.fixture
def torso_calls(monkeypatch):
    """The torso designator with a bug: its resolver raises KeyError; the list counts its calls."""
    calls: list[int] = []

    def broken(robot, slots):
        calls.append(1)
        return {}["no such key"]

    spec = DESIGNATORS["moving-torso"]
    monkeypatch.setitem(DESIGNATORS._items, "moving-torso", dataclasses.replace(spec, resolve=broken))
    return calls


def run_plan(tmp_path, *options: str):
    plan = tmp_path / "p.yaml"
    plan.write_text(textwrap.dedent(PLAN))
    return CliRunner().invoke(cli, [*options, "run", str(plan), "--trace", str(tmp_path / "t.json")])


def test_a_key_error_in_a_designator_is_not_retried_and_exits_3(tmp_path, torso_calls):
    result = run_plan(tmp_path)
    assert result.exit_code == EXIT_INTERNAL, result.output
    assert len(torso_calls) == 1  # the retry did not try again
    lines = [line for line in result.stderr.splitlines() if "internal error" in line]
    assert len(lines) == 1, result.stderr
    assert "KeyError: 'no such key'" in lines[0] and "body/0:retry/attempt 1/0:moving-torso" in lines[0]
    assert "This is a bug in pycram" in lines[0] and "please report it" in lines[0] and "--verbose" in lines[0]
    assert "Traceback" not in result.stderr


def test_the_trace_records_the_internal_error_where_it_happened(tmp_path, torso_calls):
    run_plan(tmp_path)
    trace = json.loads((tmp_path / "t.json").read_text())
    assert trace["status"] == "error"
    assert trace["failure"] == {"type": "InternalError", "message": "KeyError: 'no such key'",
                                "path": "body/0:retry/attempt 1/0:moving-torso"}


def test_verbose_shows_the_traceback_and_still_exits_3(tmp_path, torso_calls):
    result = run_plan(tmp_path, "--verbose")
    assert result.exit_code == EXIT_INTERNAL
    assert "Traceback" in result.stderr and "in broken" in result.stderr
    assert "with the traceback above" in result.stderr


def test_pycram_errors_met_at_run_time_are_plan_failures_with_the_words_they_always_had():
    assert isinstance(BadValue("x"), ValueError) and isinstance(UnknownName("x"), KeyError)
    assert str(as_failure(BadValue("threshold must be positive"), "visible")) == \
        "visible: ValueError: threshold must be positive"
    assert str(as_failure(UnknownName("robot 'pr2' has no arm 'middle'"), "reachable")) == \
        "reachable: KeyError: \"robot 'pr2' has no arm 'middle'\""
    assert str(as_failure(PycramError("no world"), "detecting")) == "detecting: PycramError: no world"
