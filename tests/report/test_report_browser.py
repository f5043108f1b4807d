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


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("browser") / "run.html"
    result = CliRunner().invoke(cli, ["run", "set_table", "--report", str(path)])
    assert result.exit_code == 0, result.output
    return path


def test_the_report_replays_to_the_last_step_in_chromium(report, tmp_path):
    url = report.as_uri() + "#step=last"
    dom = chromium(tmp_path / "dom", "--dump-dom", url).stdout.decode(errors="replace")
    body = re.search(r"<body([^>]*)>", dom)
    assert body, dom[:2000]
    attributes = dict(re.findall(r'data-([a-z]+)="([^"]*)"', body.group(1)))
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


def test_the_report_plays_by_itself(report, tmp_path):
    dom = chromium(tmp_path / "play", "--dump-dom", report.as_uri() + "#step=3&play").stdout.decode(errors="replace")
    body = re.search(r"<body([^>]*)>", dom)
    assert body
    attributes = dict(re.findall(r'data-([a-z]+)="([^"]*)"', body.group(1)))
    assert int(attributes["step"]) > 6, "playing did not move on from step 3"
