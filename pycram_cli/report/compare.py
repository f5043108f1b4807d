"""Two runs side by side: `pycram trace diff A B --report diff.html`.

The page holds the two runs' replay reports (page.py), each in an iframe (`srcdoc`), and one set of
controls that moves both to the same step: the parent posts `{pycram: "goto", step: N}` to each report,
and each report posts `{pycram: "step", step: N}` back when it shows a step (the listener at the end of
assets/report.js), so stepping in either report moves the other too. Step k is the world after the
k-th recorded step of each run (0: before the first).

`step_differences` compares the runs step by step: the step's path, its outcome, what the step node
recorded (its resolved designator, query answer, failure; timings left out, numbers within `atol` equal),
and the world's state after it (poses and joint values within `atol`). The first step that differs is the
first divergence; the page opens there and marks it.
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..plan import trace as traces
from ..plan.trace import REPLAY_KEY
from .page import _asset, _html, _script_safe, build_report

State = dict[str, dict[str, Any]]
MAX_NOTES = 6  # what differs at one step, at most (the rest is counted)


@dataclass(frozen=True)
class StepDifference:
    """How runs A and B differ at step `step` (0: before the first step)."""

    step: int
    notes: tuple[str, ...]

    def to_dict(self) -> dict[str, Any]:
        return {"step": self.step, "notes": list(self.notes)}


def _nodes(node: dict[str, Any], into: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    into[str(node.get("path", ""))] = node
    for child in node.get("children") or []:
        _nodes(child, into)
    return into


def _apply(state: State, changed: State) -> None:
    for name, delta in changed.items():
        entry = state.setdefault(name, {})
        if "position" in delta:
            entry["position"], entry["orientation"] = delta["position"], delta.get("orientation")
        if delta.get("joints"):
            entry.setdefault("joints", {}).update(delta["joints"])


def _close(a: Any, b: Any, atol: float) -> bool:
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_close(x, y, atol) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(float(a) - float(b)) <= atol
    return a == b


def state_notes(a: State, b: State, atol: float) -> list[str]:
    """What differs between two world states: objects only in one, poses and joint values beyond `atol`."""
    notes = []
    for name in sorted(set(a) | set(b)):
        if name not in a or name not in b:
            notes.append(f"{name} is only in {'A' if name in a else 'B'}")
            continue
        x, y = a[name], b[name]
        if not _close(x.get("position"), y.get("position"), atol):
            notes.append(f"{name} is at {_point(x.get('position'))} in A, {_point(y.get('position'))} in B")
        elif not _close(x.get("orientation"), y.get("orientation"), atol):
            notes.append(f"{name} is turned differently")
        ja, jb = x.get("joints") or {}, y.get("joints") or {}
        moved = sorted(k for k in set(ja) | set(jb) if not _close(ja.get(k), jb.get(k), atol))
        if moved:
            notes.append(f"{name}'s joints differ: {', '.join(moved[:4])}" + (" …" if len(moved) > 4 else ""))
    return notes


def _point(values: Any) -> str:
    if not isinstance(values, list):
        return "?"
    return "(" + ", ".join(f"{float(v):.2f}" for v in values) + ")"


def _leaf(node: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in node.items() if k != "children"}


def step_differences(a: dict[str, Any], b: dict[str, Any], atol: float = 1e-3) -> list[StepDifference]:
    """Every step (0: the start) at which the runs of traces `a` and `b` differ, in order (see the module docstring)."""
    replay_a, replay_b = a.get(REPLAY_KEY) or {}, b.get(REPLAY_KEY) or {}
    state_a = json.loads(json.dumps(replay_a.get("initial") or {}))
    state_b = json.loads(json.dumps(replay_b.get("initial") or {}))
    found = []
    start = state_notes(state_a, state_b, atol)
    if start:
        found.append(StepDifference(0, _bounded(["the worlds differ before the first step", *start])))
    nodes_a, nodes_b = _nodes(a.get("root") or {}, {}), _nodes(b.get("root") or {}, {})
    steps_a, steps_b = replay_a.get("steps") or [], replay_b.get("steps") or []
    for k in range(1, max(len(steps_a), len(steps_b)) + 1):
        if k > len(steps_a) or k > len(steps_b):
            shorter, count = ("A", len(steps_a)) if k > len(steps_a) else ("B", len(steps_b))
            found.append(StepDifference(k, (f"run {shorter} ended after {count} steps",)))
            continue
        x, y = steps_a[k - 1], steps_b[k - 1]
        _apply(state_a, x.get("changed") or {})
        _apply(state_b, y.get("changed") or {})
        notes = []
        if x.get("path") != y.get("path"):
            notes.append(f"A ran {x.get('path')}, B ran {y.get('path')}")
        else:
            if x.get("status") != y.get("status"):
                notes.append(f"the step {x.get('status')} in A, {y.get('status')} in B")
            node_a, node_b = nodes_a.get(str(x.get("path")), {}), nodes_b.get(str(y.get("path")), {})
            notes += [_difference(d) for d in traces.diff(_leaf(node_a), _leaf(node_b), atol) if d.field != "status"]
        notes += state_notes(state_a, state_b, atol)
        if notes:
            found.append(StepDifference(k, _bounded(notes)))
    return found


def _difference(difference: traces.Difference) -> str:
    text = str(difference)
    return text.split(": ", 1)[1] if text.startswith(difference.where + ": ") else text


def _bounded(notes: list[str]) -> tuple[str, ...]:
    if len(notes) <= MAX_NOTES:
        return tuple(notes)
    return (*notes[:MAX_NOTES], f"and {len(notes) - MAX_NOTES} more")


def _summary(trace: dict[str, Any], other: dict[str, Any], name: str) -> dict[str, Any]:
    """What the page's header says of a run; of its parameters only those the other run gave another value."""
    failure = trace.get("failure") or None
    params, others = trace.get("params") or {}, other.get("params") or {}
    return {"name": name, "plan": trace.get("plan"), "world": trace.get("world"), "status": trace.get("status"),
            "params": {k: v for k, v in params.items() if others.get(k) != v},
            "failure": f"{failure.get('type')}: {failure.get('message')}" if isinstance(failure, dict) else None,
            "steps": len((trace.get(REPLAY_KEY) or {}).get("steps") or [])}


def build_comparison(a: dict[str, Any], b: dict[str, Any], worlds: tuple[Path, Path], names: tuple[str, str],
                     atol: float = 1e-3) -> str:
    """The page comparing the runs of traces `a` and `b` (drawn in the world files `worlds`), named `names`."""
    differences = step_differences(a, b, atol)
    data = {"a": _summary(a, b, names[0]), "b": _summary(b, a, names[1]), "atol": atol,
            "differences": [d.to_dict() for d in differences],
            "divergence": differences[0].step if differences else None}
    pages = [build_report(a, worlds[0]), build_report(b, worlds[1])]
    parts = {
        "{{TITLE}}": _html(f"{names[0]} and {names[1]} compared"),
        "{{DATA}}": _script_safe(json.dumps(data, separators=(",", ":"), ensure_ascii=False, allow_nan=False)),
        "{{PAGE_A}}": _script_safe(json.dumps(pages[0], ensure_ascii=False)),
        "{{PAGE_B}}": _script_safe(json.dumps(pages[1], ensure_ascii=False)),
        "{{APP}}": _asset("compare.js"),
    }
    template = _asset("compare.html")
    return re.sub(r"\{\{[A-Z_]+\}\}", lambda match: parts.get(match.group(0), match.group(0)), template)
