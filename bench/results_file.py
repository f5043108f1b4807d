"""bench/results.json: where every benchmark keeps its last figures, with when, where and under what load it ran.

The README and docs quote these figures; bench/readme_figures.py writes them in, and a test fails when the
text and the file disagree. Each benchmark replaces only its own key.
"""
from __future__ import annotations

import json
import os
import subprocess
import time
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[1]
RESULTS = Path(__file__).resolve().parent / "results.json"
CODE = ("pycram_cli", "plans", "worlds", "resources")


def provenance() -> dict[str, Any]:
    """The commit measured (and whether its code had changes beside it), the date, and the load average now."""
    def git(*args: str) -> str:
        return subprocess.run(["git", *args], cwd=REPO, capture_output=True, text=True).stdout.strip()

    return {"commit": git("rev-parse", "--short=12", "HEAD"),
            "dirty": bool(git("status", "--porcelain", "--untracked-files=no", "--", *CODE)),
            "date": time.strftime("%Y-%m-%d", time.gmtime()), "load": round(os.getloadavg()[0], 2)}


def read() -> dict[str, Any]:
    """The last results (an empty set when there are none)."""
    return json.loads(RESULTS.read_text()) if RESULTS.exists() else {}


def update(key: str, value: Any) -> Path:
    """Replace one benchmark's results, keeping the others'."""
    results = read()
    results[key] = value
    RESULTS.write_text(json.dumps(results, indent=2, ensure_ascii=False) + "\n")
    return RESULTS


def record_table(name: str, table: str, load_before: float) -> Path:
    """A benchmark's Markdown table as the README shows it, with its provenance (`tables.NAME`)."""
    results = read()
    tables = results.get("tables", {})
    tables[name] = {**provenance(), "load_before": round(load_before, 2), "table": table.rstrip("\n") + "\n"}
    results["tables"] = dict(sorted(tables.items()))
    RESULTS.write_text(json.dumps(results, indent=2, ensure_ascii=False) + "\n")
    return RESULTS
