"""bench/profile.py attributes a plan's whole time to phases: every entry point it names exists (a renamed function
would silently drop out of its phase), and the phases' own times add up to the plan's time."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def profiled(plan: str, *options: str) -> dict:
    out = subprocess.run([sys.executable, str(REPO / "bench" / "profile.py"), plan, "--json", *options],
                         capture_output=True, text=True, timeout=600, cwd=REPO)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def test_the_phases_add_up_to_the_plan_time_and_every_entry_point_exists():
    report = profiled("inspect_counter", "--no-cprofile")
    assert report["status"] == "succeeded"
    assert report["missing_entry_points"] == []
    own = sum(row["self"] for row in report["phases"].values())
    assert abs(own - report["plan_time"]) <= 0.01 * report["plan_time"] + 1e-3
    assert report["phases"]["perception (rendering)"]["self"] > 0  # a perception tour renders
    assert all(row["self"] <= row["incl"] + 1e-9 for row in report["phases"].values())


def test_under_cprofile_it_names_the_top_functions():
    report = profiled("inspect_counter", "--top", "5")
    assert len(report["top"]["own"]) == 5 and len(report["top"]["cumulative"]) == 5
    assert any("pycram_cli" in row["function"] for row in report["top"]["cumulative"])
