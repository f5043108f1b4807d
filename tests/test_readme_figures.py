"""The README's and docs' benchmark figures are those of the last `bench/results.json` (bench/readme_figures.py)."""
from __future__ import annotations

import copy
import importlib.util
import json
import sys
from pathlib import Path
from types import ModuleType

import pytest

REPO = Path(__file__).resolve().parents[1]
BENCH = REPO / "bench"


def _module(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"bench_{name}", BENCH / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


figures = _module("readme_figures")
plans = _module("plans")


@pytest.fixture(scope="module")
def results() -> dict:
    return json.loads((BENCH / "results.json").read_text())


def test_the_readme_and_docs_say_what_the_last_results_say(results):
    stale = [str(path.relative_to(REPO)) for path, text in figures.render(results).items() if path.read_text() != text]
    assert not stale, f"figures differ from bench/results.json in {stale}: run `python bench/readme_figures.py`"


def test_every_shipped_plan_has_results(results):
    assert list(results["plans"]) == [case.name for case in plans.cases()], "run `python bench/plans.py`"


def test_each_result_says_when_and_under_what_load_it_was_measured(results):
    assert results["commit"] and results["date"] and results["machine"]["cpus"] >= 1
    for name, case in results["plans"].items():
        assert case["load"] >= 0 and case["unit_s"] > 0 and case["plan_s"] > 0, name
        assert case["process_s"] > case["plan_s"], name
        assert len(case["runs"]["plan_s"]) == len(case["runs"]["load"]) >= 1, name
    for name, table in results.get("tables", {}).items():
        assert table["commit"] and table["load"] >= 0 and table["table"].startswith("|"), name


def test_the_readme_shows_each_plan_as_it_ended(results):
    """The transcripts say succeeded or failed as the benchmark's runs did."""
    readme = (REPO / "README.md").read_text()
    for name in ("set_table", "set_table_actions", "fetch_milk"):
        assert results["plans"][name]["status"] == "succeeded"
        assert f"plan {name}.yaml succeeded in {results['plans'][name]['plan_s']:.2f} s" in readme
    assert results["plans"]["set_table@edge"]["failure"] == "ReasoningFailure"


def test_a_figure_that_differs_from_the_results_is_caught(results):
    changed = copy.deepcopy(results)
    changed["plans"]["set_table"]["plan_s"] += 1.0
    changed["plans"]["fetch_spoon"]["step_s"]["body/7:assert"] += 1.0
    rendered = figures.render(changed)
    assert rendered[REPO / "README.md"] != (REPO / "README.md").read_text()
    assert rendered[REPO / "docs" / "plans.md"] != (REPO / "docs" / "plans.md").read_text()


def test_a_figure_the_text_no_longer_holds_is_an_error(results):
    with pytest.raises(LookupError, match="found 0 times"):
        figures.fill_spots("plan set_table.yaml took a while", ["plan set_table.yaml succeeded in {cli:set_table} s"],
                           results, "README.md")


def test_a_template_matches_across_line_breaks_and_keeps_the_text_around_it(results):
    text = "The demo ends in about 9.99 s of\nplan time. Then it stops."
    assert figures.fill_spots(text, ["in about {s:set_table} s of plan time"], results, "x") == (
        f"The demo ends in about {figures.seconds(results['plans']['set_table']['plan_s'])} s of\nplan time. "
        "Then it stops.")


def test_seconds_are_given_to_two_significant_digits():
    assert [figures.seconds(x) for x in (0.074, 0.75, 3.24, 12.4)] == ["0.07", "0.75", "3.2", "12"]


def test_the_targets_table_says_met_or_missed(results):
    table = figures.plans_table(results)
    for name, (seconds, units) in figures.TARGETS.items():
        case = results["plans"][name]
        row = next(line for line in table.splitlines() if line.startswith(f"| `{case['plan']}` |")
                   and f"| {case['world'] or 'its own'} |" in line and "`-p" not in line)
        assert ("met" if case["plan_s"] <= seconds else "**missed**") in row.split("|")[-2].split(";")[0]
