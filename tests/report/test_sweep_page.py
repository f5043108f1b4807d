"""`pycram sweep ... --report sweep.html`: the success map and the scenarios by outcome, the failed ones first
run again and linked to their replays, written beside the page."""
from __future__ import annotations

import json
import re
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli


def run(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.fixture(scope="module")
def small(tmp_path_factory) -> Path:
    """A box placed anywhere on a floor; with `drop: true` the plan fails at once."""
    folder = tmp_path_factory.mktemp("sweep-page")
    for name, text in {
        "small.yaml": """\
            objects:
              - {name: floor, type: environment, file: plane.urdf}
              - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
        """,
        "drop.yaml": """\
            world: small.yaml
            params: {drop: false}
            body:
              - if: $drop
                then: [{fail: ManipulationFailure, message: "dropped the box"}]
              - assert: {stable: {object: box}}
                message: "the box moves"
        """,
        "drop.vary.yaml": """\
            objects:
              box: {region: {box: [[0, -0.5, 0.025], [1, 0.5, 0.025]]}}
        """,
    }.items():
        (folder / name).write_text(textwrap.dedent(text))
    return folder


@pytest.fixture(scope="module")
def page(small) -> Path:
    result = run("sweep", small / "drop.yaml", "-n", "5", "--workers", "1", "--out", small / "out",
                 "--compare", "drop=false,true", "--report", small / "sweep.html", "--replays", "3")
    assert result.exit_code == 0, result.output
    assert "running 3 scenarios again to record their replays (--replays 3)" in result.stderr
    return small / "sweep.html"


def test_the_page_lists_the_scenarios_by_outcome_failures_first(page):
    text = page.read_text(encoding="utf-8")
    headings = re.findall(r"<h2>(.*?)</h2>", text)
    assert headings == ["ManipulationFailure at body/0:if/then/0:fail (5)", "succeeded (5)"]
    assert "succeeded 5 of 10, 50.0 %" in text
    assert text.count("dropped the box") == 5
    assert '<img alt="the outcomes over the varied start positions" src="data:image/png;base64,' in text
    assert not re.search(r"<(script|link)[^>]+(src|href)=", text)  # nothing loaded from elsewhere


def test_the_failed_scenarios_link_to_their_replays_written_beside_the_page(page, small):
    text = page.read_text(encoding="utf-8")
    links = sorted(set(re.findall(r'<a href="(sweep-replays/[^"]+)">replay</a>', text)))
    assert links == ["sweep-replays/scenario-0-1.html", "sweep-replays/scenario-1-1.html",
                     "sweep-replays/scenario-2-1.html"]  # alternative 1 (drop=true) of the first three: all failed
    for link in links:
        replay = (page.parent / link).read_text(encoding="utf-8")
        data = json.loads(re.search(r'id="pycram-data">(.*?)</script>', replay, re.S).group(1))
        assert data["trace"]["status"] == "failed" and data["trace"]["params"]["drop"] is True
        assert data["replayed"] and len(data["frames"]) >= 2
        assert f'<a href="{link}"><circle' in text  # its marker on the map opens it too
    # the others show the command that replays them
    assert re.search(r"<code>pycram run \S*drop.yaml --world \S*small.yaml --scenario \d+ -p drop=true</code>", text)


def test_every_marker_of_the_map_is_under_its_link(page):
    """The links over the map sit on the markers the plot drew: at each circle's centre the picture shows a marker
    in its outcome's colour (red for the failures, the map's first failure colour)."""
    import base64
    import io

    import numpy as np
    from PIL import Image

    text = page.read_text(encoding="utf-8")
    png = re.search(r'src="data:image/png;base64,([^"]+)"', text).group(1)
    image = np.asarray(Image.open(io.BytesIO(base64.b64decode(png))).convert("RGB")).astype(int)
    width, height = (int(v) for v in re.search(r'<svg viewBox="0 0 (\d+) (\d+)"', text).groups())
    assert (height, width) == image.shape[:2]
    linked = re.findall(r'<a href="sweep-replays/[^"]+"><circle cx="(\d+)" cy="(\d+)"', text)
    assert len(linked) == 3
    for x, y in linked:
        assert np.abs(image[int(y), int(x)] - (215, 40, 40)).sum() < 40, (x, y, image[int(y), int(x)])


def test_ten_replays_by_default_and_at_most_a_hundred():
    """As the README says."""
    from pycram_cli.cli.sweep_report import DEFAULT_REPLAYS, MAX_REPLAYS
    from pycram_cli.sweep.replays import SUCCESS_EXAMPLES

    assert (DEFAULT_REPLAYS, MAX_REPLAYS, SUCCESS_EXAMPLES) == (10, 100, 2)


@pytest.mark.parametrize("args, message", [
    (["--report", "{tmp}/sweep.png"], "cannot tell the report's format from '.png'"),
    (["--replays", "10"], "sets how many replays the sweep's report links to, but no --report FILE is given"),
    (["--report", "{tmp}/taken.html"], "which is not a folder"),
    (["--report", "{tmp}/s.html", "--replays", "1000"], "1000 is not in the range 0<=x<=100"),
])
def test_bad_report_options_are_refused_before_the_sweep(small, tmp_path, args, message):
    (tmp_path / "taken-replays").write_text("a file where the replays would go")
    result = run("sweep", small / "drop.yaml", "-n", "2", "--out", tmp_path / "out", *[a.format(tmp=tmp_path) for a in args])
    assert result.exit_code == 2 and message in result.stderr, result.stderr
    assert not (tmp_path / "out").exists()
