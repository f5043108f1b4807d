"""The comparison page in a real browser (headless Chromium, as test_report_browser.py drives it): both reports load
in their frames, both are moved to the first divergence, and moving the page moves both."""
from __future__ import annotations

import re

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from test_report_browser import CHROMIUM, chromium

pytestmark = pytest.mark.skipif(
    CHROMIUM is None, reason="no headless browser: Debian's chromium is not installed (.ci/run installs it with apt)")



@pytest.fixture(scope="module")
def page(tmp_path_factory, set_table_run, failed_run):
    """set_table as it is (A, 67 steps) against the milk placed over the island's edge (B, 15 steps) (their traces
    made once for the report tests, tests/report/conftest.py)."""
    folder = tmp_path_factory.mktemp("compare-browser")
    result = CliRunner().invoke(cli, ["trace", "diff", str(set_table_run[1]), str(failed_run[1]),
                                      "--report", str(folder / "diff.html")])
    assert result.exit_code == 1, result.output
    return folder / "diff.html"


def body(dom: str) -> dict[str, str]:
    match = re.search(r"<body([^>]*)>", dom)
    assert match, dom[:2000]
    return dict(re.findall(r'data-([a-z-]+)="([^"]*)"', match.group(1)))


def test_both_runs_open_at_the_first_divergence_which_is_marked(page, tmp_path):
    dom = chromium(tmp_path / "dom", "--dump-dom", page.as_uri()).stdout.decode(errors="replace")
    shown = body(dom)
    assert shown.get("ready") == "1", "the two reports did not both load and answer"
    assert shown["divergence"] == shown["step"] == "1"
    assert shown["a-step"] == shown["b-step"] == "1", "the reports were not moved to the divergence"
    assert re.search(r'<span[^>]*class="divergence current"', dom), "the divergence is not marked on the step bar"
    assert "The runs differ first at step 1" in dom and "step 1: the first divergence" in dom
    assert "designator.resolved.object-type: &quot;bowl&quot; != &quot;milk&quot;" in dom


def test_a_step_beyond_the_shorter_run_shows_its_end(page, tmp_path):
    dom = chromium(tmp_path / "dom", "--dump-dom", page.as_uri() + "#step=40").stdout.decode(errors="replace")
    shown = body(dom)
    assert shown.get("ready") == "1"
    assert (shown["step"], shown["a-step"], shown["b-step"]) == ("40", "40", "15")
    assert "run B ended after 15 steps" in dom
