"""The page of a sweep: `pycram sweep ... --report sweep.html`.

One self-contained HTML file (no script): the success rate, the map of the outcomes over the varied
start positions (sweep/plot.py's picture, with a link on every marker), and the scenarios grouped by
outcome, failures first. A scenario whose replay was recorded (sweep/replays.py: run again with its
seed, written beside the page) links to its replay report; every other one shows the `pycram run ...
--scenario SEED` command that replays it.
"""
from __future__ import annotations

import base64
import html
import json
from collections import defaultdict
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..sweep.plot import OutcomeMap
from ..sweep.summary import outcome_of
from ..world.camera import encode_image

MAX_ROWS = 200  # scenarios listed per outcome; the rest are counted
Key = tuple[int, str]

STYLE = """
body { margin: 0; font: 13px/1.4 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; color: #1d232b; background: #f4f5f7; }
header { background: #1f2933; color: #f5f7fa; padding: 10px 16px; }
header h1 { font-size: 17px; margin: 0 0 4px; }
main { padding: 12px 16px; }
#map { position: relative; background: #fff; border: 1px solid #d9dde3; max-width: 960px; margin-bottom: 12px; }
#map img, #map svg { display: block; width: 100%; height: auto; }
#map svg { position: absolute; left: 0; top: 0; height: 100%; }
#map circle { fill: transparent; stroke: none; }
#map a circle { stroke: #1c7ed6; stroke-width: 1.5; }
#map a:hover circle { stroke-width: 3; }
section.outcome { background: #fff; border: 1px solid #d9dde3; margin-bottom: 12px; }
section.outcome h2 { font-size: 14px; margin: 0; padding: 6px 10px; background: #e9ecef; }
section.outcome.failed h2 { background: #ffe3e3; color: #c92a2a; }
section.outcome.succeeded h2 { background: #d3f9d8; color: #2b8a3e; }
table { border-collapse: collapse; width: 100%; }
td, th { text-align: left; padding: 3px 8px; border-top: 1px solid #eef0f2; vertical-align: top; }
td.message { color: #5c2b29; }
code { font: 12px ui-monospace, "DejaVu Sans Mono", monospace; }
.more { padding: 4px 10px; color: #6c757d; }
"""  # noqa: E501 (a style sheet, written out as it stands)


def key_of(record: dict[str, Any]) -> Key:
    return record["index"], json.dumps(record.get("alternative"), sort_keys=True)


def _e(text: Any) -> str:
    return html.escape(str(text), quote=True)


def _varied(record: dict[str, Any]) -> str:
    parts = []
    for name, varied in sorted((record.get("varied") or {}).items()):
        if isinstance(varied, dict) and isinstance(varied.get("position"), list):
            parts.append(f"{name} at (" + ", ".join(f"{float(v):.2f}" for v in varied["position"][:2]) + ")")
    return "; ".join(parts)


def _map(outcome_map: OutcomeMap | None, replays: dict[Key, str]) -> str:
    if outcome_map is None:
        return "<p>No map: the variation file moves no object.</p>"
    height, width, _ = outcome_map.image.shape
    png = base64.b64encode(encode_image(outcome_map.image, ".png")).decode("ascii")
    links = []
    for record, name, (x, y) in outcome_map.markers:
        href = replays.get(key_of(record))
        title = f"scenario {record['index']} (seed {record['seed']}), {name}: {outcome_of(record)}"
        circle = f'<circle cx="{x}" cy="{y}" r="8"><title>{_e(title)}</title></circle>'
        links.append(f'<a href="{_e(href)}">{circle}</a>' if href else f"<g>{circle}</g>")
    return (f'<div id="map"><img alt="the outcomes over the varied start positions" src="data:image/png;base64,{png}">'
            f'<svg viewBox="0 0 {width} {height}" preserveAspectRatio="none">{"".join(links)}</svg></div>')


def _groups(records: list[dict[str, Any]]) -> list[tuple[str, list[dict[str, Any]]]]:
    """(heading, records) by outcome and failing node, the largest failure groups first, successes last."""
    groups: dict[tuple[str, str], list[dict[str, Any]]] = defaultdict(list)
    for record in records:
        outcome = outcome_of(record)
        path = (record.get("failure") or {}).get("path") or ""
        groups[(outcome, path)].append(record)
    order = sorted(groups.items(), key=lambda item: (item[0][0] == "succeeded", -len(item[1]), item[0]))
    return [(outcome + (f" at {path}" if path else ""), sorted(members, key=key_of))
            for (outcome, path), members in order]


def build_sweep_page(summary: dict[str, Any], records: list[dict[str, Any]], outcome_map: OutcomeMap | None,
                     replays: dict[Key, str], command: Callable[[dict[str, Any]], str]) -> str:
    """The page (see the module docstring); `replays`: the replay reports' links by record, `command`: the
    command that replays a record."""
    lo, hi = summary["interval"]
    rate = "-" if summary["rate"] is None else f"{100 * summary['rate']:.1f} %"
    head = (f"<h1>Sweep of {_e(Path(summary['plan']).name)} on {_e(Path(summary['world']).name)}</h1>"
            f"<div>{summary['scenarios']} scenarios (seed {_e(summary['seed'])}, {_e(Path(summary['vary']).name)}): "
            f"succeeded {summary['succeeded']} of {summary['runs']}, {rate} "
            f"(95 % interval {100 * lo:.1f}-{100 * hi:.1f} %); {len(replays)} replays recorded</div>")
    sections = []
    for heading, members in _groups(records):
        kind = "succeeded" if members[0]["status"] == "succeeded" else "failed"
        rows = []
        for record in members[:MAX_ROWS]:
            href = replays.get(key_of(record))
            replay = f'<a href="{_e(href)}">replay</a>' if href else f"<code>{_e(command(record))}</code>"
            alternative = record.get("alternative")
            rows.append(f"<tr><td>{record['index']}</td><td>{record['seed']}</td>"
                        f"<td>{_e(_varied(record))}" + (f" <code>{_e(json.dumps(alternative))}</code>" if alternative else "")
                        + f"</td><td class=\"message\">{_e((record.get('failure') or {}).get('message') or '')}</td>"
                        f"<td>{replay}</td></tr>")
        more = len(members) - MAX_ROWS
        sections.append(f'<section class="outcome {kind}"><h2>{_e(heading)} ({len(members)})</h2><table>'
                        "<tr><th>scenario</th><th>seed</th><th>start</th><th>message</th><th>replay</th></tr>"
                        + "".join(rows) + "</table>"
                        + (f'<div class="more">and {more} more (results.jsonl has them all)</div>' if more > 0 else "")
                        + "</section>")
    title = f"sweep of {Path(summary['plan']).name}: {rate}"
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><meta name=\"generator\" content=\"pycram\">"
            f"<title>{_e(title)}</title><style>{STYLE}</style></head><body>"
            f"<header>{head}</header><main><div>{_map(outcome_map, replays)}</div><div id=\"outcomes\">"
            + "".join(sections) + "</div></main></body></html>\n")
