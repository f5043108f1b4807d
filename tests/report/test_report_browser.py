"""The replay report in a real browser: headless Chromium (Debian's `chromium`) opens the file from disk,
seeks to the last step, and the 3D view shows the scene while the plan tree lists the demo's steps."""
from __future__ import annotations

import io
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from PIL import Image

from pycram_cli.cli.main import cli

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = pytest.mark.skipif(
    CHROMIUM is None, reason="no headless browser: Debian's chromium is not installed (.ci/run installs it with apt)")

WINDOW = (1400, 900)


def chromium(profile: Path, *args: str) -> subprocess.CompletedProcess:
    """Headless Chromium as root on a machine without network: no sandbox, no GPU (WebGL in software),
    no background connections, a fresh profile; the page's timers get 10 s of virtual time."""
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic",
             "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={profile}", f"--window-size={WINDOW[0]},{WINDOW[1]}", "--hide-scrollbars",
             "--virtual-time-budget=10000"]
    return subprocess.run([CHROMIUM, *flags, *args], capture_output=True, timeout=180)


@pytest.fixture
def report(set_table_run: tuple[Path, Path]) -> Path:
    """set_table's report, made once for the report tests (tests/report/conftest.py)."""
    return set_table_run[0]


def body_of(dom: str) -> dict[str, str]:
    """The data attributes the page keeps on <body> (data-selected-pose as selectedpose)."""
    body = re.search(r"<body([^>]*)>", dom)
    assert body, dom[:2000]
    return {k.replace("-", ""): v for k, v in re.findall(r'data-([a-z-]+)="([^"]*)"', body.group(1))}


def dump(tmp_path: Path, name: str, url: str) -> tuple[str, dict[str, str]]:
    dom = chromium(tmp_path / name, "--dump-dom", url).stdout.decode(errors="replace")
    return dom, body_of(dom)


def screenshot(tmp_path: Path, name: str, url: str, size: tuple[int, int] = WINDOW) -> np.ndarray:
    shot = tmp_path / f"{name}.png"
    done = chromium(tmp_path / name, f"--screenshot={shot}", f"--window-size={size[0]},{size[1]}", url)
    assert shot.is_file(), done.stderr.decode(errors="replace")[-2000:]
    return np.asarray(Image.open(io.BytesIO(shot.read_bytes())).convert("RGB")).astype(int)


def test_the_report_replays_to_the_last_step_in_chromium(report, tmp_path):
    url = report.as_uri() + "#step=last"
    dom = chromium(tmp_path / "dom", "--dump-dom", url).stdout.decode(errors="replace")
    attributes = body_of(dom)
    assert attributes.get("ready") == "1", "the page's script did not finish"
    assert attributes.get("webgl") == "ok", "no WebGL: the 3D view cannot draw"
    assert attributes["step"] == attributes["steps"] == "67"  # seeked to the last step
    # the plan tree lists the demo's steps, and the last one is the current step
    for step in ("0:for_each", "0:world-state-detecting", "0:par", "1:moving", "3:detecting", "4:blocking",
                 "6:pick-up", "8:moving", "0:accessing", "0:place", "11:log", "12:assert"):
        assert f'<span class="label">{step}</span>' in dom, step
    current = re.search(r'<li class="([^"]*\bcurrent\b[^"]*)" data-path="([^"]+)"', dom)
    assert current and current.group(2).endswith("item 3/1:if/else/0:call move_object/12:assert")
    assert not re.search(r"<li class=\"st-pending", dom)  # at the last step everything has run
    # the final frame shows the result: the four placed objects are in view, each with its label
    for name in ("bowl", "milk", "cereal", "spoon"):
        tag = re.search(rf'<span class="label3d[^"]*" data-body="{name}"[^>]*>', dom)
        assert tag and "hidden" not in tag.group(0), f"{name} is not in view at the end"
    assert attributes["failures"] == "0" and not attributes.get("failure")  # a run without failures

    shot = tmp_path / "report.png"
    done = chromium(tmp_path / "shot", f"--screenshot={shot}", url)
    assert shot.is_file(), done.stderr.decode(errors="replace")[-2000:]
    image = np.asarray(Image.open(io.BytesIO(shot.read_bytes())).convert("RGB")).astype(int)
    left, top, width, height = (int(v) for v in attributes["view"].split(","))
    view = image[top + 30:top + height - 10, left + 10:left + width - 10]  # below the caption
    background = np.array([0xDD, 0xE3, 0xEA])
    drawn = np.abs(view - background).sum(axis=2) > 30
    assert drawn.mean() > 0.3, f"the 3D view is blank ({drawn.mean():.0%} of it drawn)"
    colours = len(np.unique(view.reshape(-1, 3) // 8, axis=0))
    assert colours > 40, f"the 3D view shows too few colours ({colours}) to be the kitchen"
    # the PR2's blue grippers are in view at the end
    blue = (view[:, :, 2] - view[:, :, 0] > 60) & (view[:, :, 2] > 100)
    assert blue.sum() > 20


def test_a_composite_opens_at_its_first_step(report, tmp_path):
    dom, attributes = dump(tmp_path, "node", report.as_uri() + "#node=body/0:for_each/item 1")
    current = re.search(r'<li class="([^"]*\bcurrent\b[^"]*)" data-path="([^"]+)"', dom)
    assert current and current.group(2) == "body/0:for_each/item 1/0:world-state-detecting"  # its first step
    assert 0 < int(attributes["step"]) < 67


def test_the_report_plays_by_itself(report, tmp_path):
    dom = chromium(tmp_path / "play", "--dump-dom", report.as_uri() + "#step=3&play").stdout.decode(errors="replace")
    body = re.search(r"<body([^>]*)>", dom)
    assert body
    attributes = dict(re.findall(r'data-([a-z]+)="([^"]*)"', body.group(1)))
    assert int(attributes["step"]) > 6, "playing did not move on from step 3"


def test_the_view_can_be_saved_as_a_png(report, tmp_path):
    dom, attributes = dump(tmp_path, "png", report.as_uri() + "#step=last&png")
    link = re.search(r'<a id="png-link"[^>]*href="data:image/png;base64,([^"]+)"', dom)
    assert link, "no image was made"
    image = Image.open(io.BytesIO(__import__("base64").b64decode(link.group(1))))
    assert image.format == "PNG" and image.width > 300 and image.height > 200
    assert len(np.unique(np.asarray(image.convert("RGB")).reshape(-1, 3) // 8, axis=0)) > 40  # the kitchen, not blank


def test_the_layout_holds_at_800_pixels(report, tmp_path):
    for width, height in ((1400, 900), (1024, 700), (800, 600)):
        dom = chromium(tmp_path / f"w{width}", "--dump-dom", f"--window-size={width},{height}",
                       report.as_uri() + "#step=last").stdout.decode(errors="replace")
        attributes = body_of(dom)
        assert attributes["fits"] == "true", (width, height, attributes.get("view"))
    image = screenshot(tmp_path, "narrow", report.as_uri() + "#step=last", (800, 600))
    left, top, w, h = (int(v) for v in attributes["view"].split(","))
    view = image[top + 30:top + h - 10, left + 10:left + w - 10]
    assert (np.abs(view - np.array([0xDD, 0xE3, 0xEA])).sum(axis=2) > 30).mean() > 0.3  # the scene is drawn


@pytest.fixture
def failed_report(failed_run: tuple[Path, Path]) -> Path:
    """The README's failing example: the milk placed over the island's edge falls while place settles it (the report
    made once for the report tests, tests/report/conftest.py)."""
    return failed_run[0]


def _page_data(path: Path) -> dict:
    import json as _json
    text = path.read_text(encoding="utf-8")
    return _json.loads(re.search(r'id="pycram-data">(.*?)</script>', text, re.S).group(1))


def test_a_failed_run_opens_at_its_failure_with_the_object_and_its_target_highlighted(failed_report, tmp_path):
    data = _page_data(failed_report)
    steps = len(data["frames"]) - 1
    dom, attributes = dump(tmp_path, "failed", failed_report.as_uri())
    assert attributes["ready"] == "1" and attributes["webgl"] == "ok" and attributes["failures"] == "1"
    assert attributes["step"] == attributes["failure"] == str(steps)  # opened at the failing step: the last
    assert attributes["highlighted"] == "milk" and attributes["ghost"] == "milk"
    failbox = re.search(r'<div id="failbox">(.*?)</div>\s*<div id="reasonbox"', dom, re.S)
    assert failbox and "ReasoningFailure" in failbox.group(1) and "milk is not stable where it was placed" in failbox.group(1)
    assert "where it was meant to go [-0.65, 1.00, 0.86]" in failbox.group(1)
    assert 'id="next-failure"' in dom and 'id="next-failure" hidden' not in dom
    # drawn: the milk glows (pink-red), its ghost stands green at the island's edge
    image = screenshot(tmp_path, "failed", failed_report.as_uri())
    left, top, width, height = (int(v) for v in attributes["view"].split(","))
    view = image[top + 80:top + height - 10, left + 10:left + width - 10]  # below the caption and the failure text
    pink = (view[:, :, 0] > 150) & (view[:, :, 0] - view[:, :, 1] > 50) & (view[:, :, 2] - view[:, :, 1] > 10)
    green = (view[:, :, 1] - view[:, :, 0] > 25) & (view[:, :, 1] - view[:, :, 2] > 15)
    assert pink.sum() > 30, "the failed object is not highlighted"
    assert green.sum() > 100, "the ghost of the target is not drawn"


def test_a_frame_in_the_middle_of_place_shows_the_milk_falling(failed_report, tmp_path):
    data = _page_data(failed_report)
    place = next(k for k, f in enumerate(data["frames"]) if f.get("physics"))
    assert data["frames"][place]["path"].endswith("0:place")
    standing = lying = None
    for at, name in ((place - 1, "before"), (place - 0.5, "middle"), (place, "after")):
        _, attributes = dump(tmp_path, f"at{name}", failed_report.as_uri() + f"#step={at}&select=milk")
        assert attributes["selected"] == "milk"
        x, y, z, tilt = (float(v) for v in attributes["selectedpose"].split(","))
        if name == "before":
            standing = (z, tilt)
        elif name == "after":
            lying = (z, tilt)
        else:
            middle = (z, tilt)
    assert lying[1] > 60 and lying[0] < standing[0] - 0.3  # it fell off the island
    # during the failed stable check, what it simulated on a copy of the world: the milk as an amber ghost
    last = len(data["frames"]) - 1
    assert data["frames"][last]["whatif"]["body"] == [b["name"] for b in data["scene"]["bodies"]].index("milk")
    _, attributes = dump(tmp_path, "whatif", failed_report.as_uri() + f"#step={last - 0.5}")
    assert attributes["whatif"] == "milk" and attributes["step"] == str(last)
    assert 10 < middle[1] < lying[1] - 10 or lying[0] + 0.05 < middle[0] < 0.85, (standing, middle, lying)


@pytest.fixture
def actions_report(actions_run: tuple[Path, Path]) -> tuple[Path, Path]:
    """set_table_actions: locate steps (candidate maps) and looking steps (view cones), made once for the report
    tests (tests/report/conftest.py)."""
    return actions_run


def test_the_candidate_map_and_the_view_cone_are_drawn_from_the_trace(actions_report, tmp_path):
    report, saved = actions_report
    assert report.stat().st_size < 2_000_000  # with a candidate map for every locate step
    data = _page_data(report)
    frames = data["frames"]
    locate = next(k for k, f in enumerate(frames) if f.get("candidates"))
    looking = next(k for k, f in enumerate(frames) if f["path"] and f["path"].endswith("looking"))
    assert frames[looking]["reasoning"]["kind"] == "view"
    assert frames[locate]["path"].endswith("locate") and frames[looking]["path"].endswith("looking")
    # the map: as many positions as the resolution had; the chosen pose is the trace's found pose
    node = {}
    stack = [data["trace"]["root"]]
    while stack:
        n = stack.pop()
        if n["path"] == frames[locate]["path"]:
            node = n
        stack.extend(n.get("children") or [])
    found = node["location"]["found"]["position"]
    assert frames[locate]["candidates"]["found"][0][:2] == pytest.approx(found[:2], abs=1e-3)
    assert "candidate_map" not in saved.read_text()[:saved.read_text().index('"replay"')]  # not in the trace's tree

    dom, attributes = dump(tmp_path, "locate", report.as_uri() + f"#step={locate}")
    # the first locate chooses where to stand to see the bowl: its candidates, and the view cone from the pose chosen
    assert attributes["step"] == str(locate) and attributes["reasoning"] == "view,candidates"
    legend = re.search(r'<div id="reasonbox">(.*?)</div>\s*<div id="tooltip"', dom, re.S)
    assert legend and f"{node['location']['candidates']} tried for where to stand" in legend.group(1)
    assert "view cone" in legend.group(1) and "from the pose chosen" in legend.group(1)
    planned = frames[locate]["reasoning"]
    assert planned["target"] == pytest.approx(node["location"]["found"]["look-at"], abs=1e-3)
    image = screenshot(tmp_path, "locate", report.as_uri() + f"#step={locate}")
    left, top, width, height = (int(v) for v in attributes["view"].split(","))
    view = image[top + 30:top + height - 100, left + 10:left + width - 10]
    red = (view[:, :, 0] > 180) & (view[:, :, 1] < 110) & (view[:, :, 2] < 110)  # "collides" squares
    r, g, b = view[:, :, 0], view[:, :, 1], view[:, :, 2]
    peach = (r > 170) & (r - g > 20) & (r - g < 90) & (g - b > 25)  # "out of reach" squares (over the floor)
    assert red.sum() > 200 and peach.sum() > 200, (red.sum(), peach.sum())

    dom, attributes = dump(tmp_path, "looking", report.as_uri() + f"#step={looking}")
    assert attributes["reasoning"] == "view"
    legend = re.search(r'<div id="reasonbox">(.*?)</div>\s*<div id="tooltip"', dom, re.S)
    assert legend and "view cone" in legend.group(1)
    cone = screenshot(tmp_path, "looking", report.as_uri() + f"#step={looking}")
    left, top, width, height = (int(v) for v in attributes["view"].split(","))
    view = cone[top + 30:top + height - 60, left + 10:left + width - 10]
    blue = (view[:, :, 2] > 150) & (view[:, :, 2] - view[:, :, 0] > 90) & (view[:, :, 1] > 90)  # the cone's lines
    assert blue.sum() > 100, blue.sum()


def test_next_failure_walks_through_recovered_failures_too(tmp_path):
    """fetch_spoon succeeds after a recovered PerceptionFailure: the page opens at the start, and the failure is
    one `#failure=1` (or ⚠ next failure) away, marked recovered, its object drawn through the drawer that hides it."""
    path = tmp_path / "spoon.html"
    result = CliRunner().invoke(cli, ["run", "fetch_spoon", "--report", str(path)])
    assert result.exit_code == 0, result.output
    _, attributes = dump(tmp_path, "open", path.as_uri())
    assert attributes["step"] == "0" and attributes["failures"] == "1" and not attributes.get("failure")
    dom, attributes = dump(tmp_path, "first", path.as_uri() + "#failure=1")
    assert attributes["failure"] == attributes["step"] != "0" and attributes["highlighted"] == "spoon"
    failbox = re.search(r'<div id="failbox">(.*?)</div>\s*<div id="reasonbox"', dom, re.S)
    assert failbox and "recovered" in failbox.group(1) and "PerceptionFailure" in failbox.group(1)
    # the caption says the action first; the failed detecting has slots but nothing resolved: no empty row
    caption = re.search(r'<div id="caption"><span><b>([^<]*)</b>', dom)
    assert caption and caption.group(1).strip() == f"step {attributes['step']}/15 1:detecting"
    details = re.search(r'<div id="details"[^>]*>(.*?)</div>', dom, re.S).group(1)
    assert "<td>slots</td>" in details and "<td>resolved</td>" not in details
    image = screenshot(tmp_path, "first", path.as_uri() + "#failure=1")
    left, top, width, height = (int(v) for v in attributes["view"].split(","))
    view = image[top + 100:top + height - 10, left + 10:left + width - 10]
    pink = (view[:, :, 0] > 150) & (view[:, :, 0] - view[:, :, 1] > 50) & (view[:, :, 2] - view[:, :, 1] > 10)
    assert pink.sum() > 30, "the spoon in the closed drawer is not shown"


PROJECTING = """\
world: kitchen
body:
  - moving: {target: [0.65, 0.7, 0], orientation: [0, 0, 0, 1]}
  - project:
      alternatives:
        front: [{pick-up: {object: cereal, arm: right, grasp: front}}]
        top: [{pick-up: {object: cereal, arm: right, grasp: top}}]
      runs: 2
"""

# A page holding the report in a frame: once the report is ready it clicks the first projected run in the
# table, and once the page that opens is ready it writes what that page shows on its own <body>.
CLICKER = """<!DOCTYPE html><html><body data-clicked="" data-opened="" data-opened-steps="" data-opened-labels="">
<iframe id="report" src="REPORT#step=last" style="width:1400px;height:860px"></iframe>
<script>
const frame = document.getElementById("report");
let clicked = false;
setInterval(() => {
  const page = frame.contentDocument;
  if (!page || !page.body || page.body.dataset.ready !== "1") return;
  if (!clicked) {
    const link = page.querySelector("header table.projection-table a.run");
    if (!link) return;
    clicked = true;
    document.body.dataset.clicked = link.getAttribute("href");
    link.click();
    return;
  }
  if (!page.body.dataset.projected) return;
  document.body.dataset.opened = page.body.dataset.projected;
  document.body.dataset.openedSteps = page.body.dataset.steps;
  document.body.dataset.openedFailure = page.body.dataset.failure || "";
  document.body.dataset.openedLabels = [...page.querySelectorAll("#tree .label")].map((e) => e.textContent).join(",");
  document.body.dataset.banner = (page.getElementById("projected-banner") || {}).textContent || "";
}, 50);
</script></body></html>
"""


def test_clicking_a_projected_run_in_the_table_opens_its_replay(tmp_path):
    (tmp_path / "plan.yaml").write_text(PROJECTING)
    report = tmp_path / "run.html"
    result = CliRunner().invoke(cli, ["run", str(tmp_path / "plan.yaml"), "--report", str(report)])
    assert result.exit_code == 0, result.output
    # the run's own page: the table, each run a link to its replay
    dom, attributes = dump(tmp_path, "run", report.as_uri() + "#step=last")
    assert attributes["ready"] == "1" and attributes["projected"] == ""
    assert "projected at body/1:project: chose top" in dom
    header, details = dom.split("</header>")[0], dom.split('id="details"')[1]
    links = re.findall(r'<a class="run st-(\w+)" href="([^"]+)"', header)
    assert [status for status, _ in links] == ["failed", "failed", "succeeded", "succeeded"]
    assert re.findall(r'<a class="run st-(\w+)" href="([^"]+)"', details) == links  # beside the chosen pick-up too
    # clicking the first (front, run 0) opens that run alone: its pick-up, failed, the banner saying what it is
    clicker = tmp_path / "clicker.html"
    clicker.write_text(CLICKER.replace("REPORT", report.name))
    dom = chromium(tmp_path / "click", "--allow-file-access-from-files", "--dump-dom",
                   clicker.as_uri()).stdout.decode(errors="replace")
    body = body_of(dom)
    assert body["clicked"] == links[0][1]  # both as the DOM dump escapes them
    assert body["opened"] == "body/1:project|front|0", dom[:3000]
    assert body["openedsteps"] == "1" and body["openedfailure"] == "1"
    assert body["openedlabels"] == "projected front 0,0:pick-up"
    assert body["banner"].startswith("Projected run 0 of “front” at body/1:project")
