"""A query and a designator declared only in a module of their own (tests/data/extension/waving.py) appear everywhere
once it is imported: validation, CLI help, editor schema, reference docs, and the run with their declared defaults."""
from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.cli.reference import render
from pycram_cli.designators import DESIGNATORS
from pycram_cli.process_modules import PROCESS_MODULES
from pycram_cli.reasoning import QUERIES
from pycram_cli.scenario import prepare

EXTENSION = Path(__file__).resolve().parent / "data" / "extension" / "waving.py"


@pytest.fixture
def extension():
    saved = dict(QUERIES), dict(DESIGNATORS), dict(PROCESS_MODULES)
    spec = importlib.util.spec_from_file_location("waving_extension", EXTENSION)
    module = importlib.util.module_from_spec(spec)
    sys.modules["waving_extension"] = module
    spec.loader.exec_module(module)
    yield module
    del sys.modules["waving_extension"]
    for registry, before in zip((QUERIES, DESIGNATORS, PROCESS_MODULES), saved):
        registry.clear()
        registry.update(before)


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def test_a_new_query_is_in_pycram_query_help_and_answers(extension):
    help_text = run("query", "--help").output
    assert "count TYPE" in help_text and "How many objects of a type are in the world?" in help_text
    result = run("query", "count", "milk")
    assert result.exit_code == 0, result.output
    assert result.stdout.strip() == "1 object(s) of type milk"
    assert json.loads(run("query", "count", "bowl", "--json").stdout)["details"] == {"objects": ["bowl"]}


def test_a_new_designator_is_in_pycram_designators(extension):
    listing = run("designators").output
    assert "waving" in listing and "Wave an arm a number of times." in listing
    data = json.loads(run("designators", "waving", "--json").stdout)
    assert data[0]["process_module"] == "wave" and [s["name"] for s in data[0]["slots"]] == ["arm", "times"]


def test_plans_validate_and_run_the_new_query_and_designator(extension, tmp_path: Path):
    plan = tmp_path / "wave.yaml"
    plan.write_text("body:\n  - waving: {arm: left, times: 2}\n    as: waved\n"
                    "  - assert: {count: {type: milk}}\n  - log: waved $waved times\n")
    result = prepare(plan).run()
    assert result.succeeded, result.failure
    log = result.trace["root"]["children"][2]
    assert log["message"] == "waved 2 times"


def test_validation_checks_the_new_declarations(extension, tmp_path: Path):
    plan = tmp_path / "bad.yaml"
    plan.write_text("body:\n  - waving: {arm: middle, tims: 2}\n  - count: {typ: milk}\n")
    result = run("validate", str(plan))
    assert result.exit_code == 2
    assert f"{plan}:2:" in result.stderr and "pr2 has no arm 'middle'" in result.stderr
    assert "'waving' has no slot 'tims' (did you mean 'times'?)" in result.stderr
    assert f"{plan}:3:" in result.stderr and "query 'count' has no parameter 'typ'" in result.stderr


def test_without_the_import_neither_exists():
    assert "count" not in QUERIES and "waving" not in DESIGNATORS
    assert run("query", "count", "milk").exit_code == 2


def test_a_new_query_and_designator_are_in_the_editor_schema(extension):
    plan = json.loads(run("schema", "plan").stdout)
    assert set(plan["$defs"]["designator.waving"]["properties"]) == {"arm", "times"}
    assert "How many objects of a type are in the world?" in plan["$defs"]["query.count"]["description"]


def test_a_new_query_and_designator_are_in_the_reference_docs(extension):
    reference = render()
    assert "### `count`" in reference and "    pycram query count TYPE" in reference
    assert "### `waving`" in reference and "| `times` | optional |" in reference and "| 3 |" in reference


def test_the_new_designator_resolves_with_its_declared_default(extension, tmp_path: Path):
    plan = tmp_path / "wave.yaml"
    plan.write_text("body:\n  - waving: {arm: left}\n    as: waved\n  - log: waved $waved times\n")
    result = prepare(plan).run()
    assert result.succeeded, result.failure
    assert result.trace["root"]["children"][1]["message"] == "waved 3 times"
