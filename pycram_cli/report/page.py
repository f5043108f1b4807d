"""The report page: one self-contained HTML file (no network, no server) that replays a run.

The file holds the page's own script and style (assets/report.js, assets/report.css), three.js
(assets/three.min.js, a bundle of the npm package made by assets/build-three.sh) and the data:
the trace (its tree with statuses, timings, failures and reasoning answers), the world's
visual shapes with each mesh stored once, and the frames (see scene.py).
"""
from __future__ import annotations

import json
import re
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

from ..errors import InputError, Location, setting
from ..files import probe
from ..paths import find_world
from ..plan.trace import REPLAY_KEY
from ..worldfile.loader import load_world
from .scene import Replayer, Scene

ASSETS = Path(__file__).resolve().parent / "assets"
REPORT_FORMATS = {".html": "HTML", ".htm": "HTML"}


def _asset(name: str) -> str:
    return (ASSETS / name).read_text(encoding="utf-8")


def _pycram_version() -> str:
    try:
        return version("pycram-cli")
    except PackageNotFoundError:  # running from a checkout that is not installed
        return "dev"


def report_world(trace: dict[str, Any], override: str | None = None) -> Path:
    """The world file to draw a trace's run in: `override` if given, else the file the replay record names,
    else the trace's world by name (a bundled world)."""
    if override is not None:
        return find_world(override)
    recorded = (trace.get(REPLAY_KEY) or {}).get("world_file")
    if isinstance(recorded, str) and recorded and probe(recorded) is None:  # a regular file (no OSError)
        return Path(recorded)
    name = trace.get("world")
    try:
        return find_world(str(name)) if name else find_world(None)
    except InputError:
        raise InputError(f"cannot find the world the trace ran in ('{recorded or name}')", Location(setting("world")),
                         suggestion=f"name it ({setting('world')})") from None


def _index(node: dict[str, Any], into: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    into[node.get("path", "")] = node
    for child in node.get("children") or []:
        _index(child, into)
    return into


def report_data(trace: dict[str, Any], world_path: Path) -> dict[str, Any]:
    """Everything the page shows, as one JSON-ready dict."""
    replay = trace.get(REPLAY_KEY)
    world = load_world(world_path)
    try:
        scene = Scene(world)
        replayer = Replayer(scene, replay, _index(trace.get("root") or {}, {}), trace.get("root") or {})
        steps = replayer.frames()
        projections = projected_runs(scene, replay)
        drawn = scene.to_dict()
    finally:
        world.exit()
    shown = {k: v for k, v in trace.items() if k != REPLAY_KEY}
    return {"trace": shown, "scene": drawn, "frames": steps, "failures": replayer.failures, "replayed": bool(replay),
            "projections": projections, "world_file": world_path.name, "generator": f"pycram {_pycram_version()}"}


def projected_runs(scene: Scene, replay: dict[str, Any] | None) -> dict[str, Any]:
    """The replays a `project` step kept of its projected runs (plan/replay.py), each as the page plays a run:
    step path -> alternative -> run -> {root: the run's tree, status, failure, frames, failures}."""
    found: dict[str, Any] = {}
    for path, alternatives in ((replay or {}).get("projections") or {}).items():
        for name, runs in alternatives.items():
            for run, record in runs.items():
                root = record.get("root") or {}
                replayer = Replayer(scene, record, _index(root, {}), root)
                frames = replayer.frames()
                found.setdefault(path, {}).setdefault(name, {})[run] = {
                    "root": root, "status": root.get("status"), "failure": root.get("failure"), "frames": frames,
                    "failures": replayer.failures}
    return found


def _script_safe(json_text: str) -> str:
    """JSON that cannot end, or change how the browser reads, the <script> element it is put in: `<`, `>` and `&`
    only occur inside its strings, where `\\u003c`, `\\u003e` and `\\u0026` mean the same (so `</script>`,
    `<!--<script>` and `-->` in a name or a message stay text)."""
    return json_text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def build_report(trace: dict[str, Any], world_path: Path) -> str:
    """The report of a run (a trace, with or without its replay record) in the world file `world_path`."""
    data = report_data(trace, world_path)
    three = _asset("three.min.js")
    if "</script" in three.lower():
        raise RuntimeError("the bundled three.js contains '</script': it cannot be inlined")
    title = f"{trace.get('plan', 'plan')} on {trace.get('world', world_path.name)}: {trace.get('status', '?')}"
    page = _asset("report.html")
    parts = {
        "{{TITLE}}": _html(title),
        "{{STYLE}}": _asset("report.css"),
        "{{THREE}}": three,
        "{{DATA}}": _script_safe(json.dumps(data, separators=(",", ":"), ensure_ascii=False, allow_nan=False)),
        "{{APP}}": _asset("report.js"),
    }
    # one pass over the template: what is put in is never searched for placeholders itself
    return re.sub(r"\{\{[A-Z]+\}\}", lambda match: parts.get(match.group(0), match.group(0)), page)


def _html(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")
