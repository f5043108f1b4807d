"""`pycram trace show|diff`: look at saved plan traces and compare them."""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import click
from rich.markup import escape
from rich.tree import Tree

from ..errors import InputError, Location
from ..files import check_writable
from ..plan import trace as traces
from ..report import MCAP_FORMATS, REPORT_FORMATS, build_comparison, report_world
from . import console
from .complete import world_names
from .files import check_output, distinct_outputs, same_file, write_mcap, write_output, write_report
from .options import Number

STYLE = {"succeeded": ("✓", "green"), "failed": ("✗", "bold red"), "recovered": ("↺", "yellow"),
         "cancelled": ("⊘", "yellow"), "skipped": ("·", "dim"), "running": ("▶", "cyan"), "pending": ("○", "dim")}
PLAIN = {"succeeded": "ok", "failed": "FAILED", "recovered": "recovered", "cancelled": "cancelled",
         "skipped": "skipped", "running": "running", "pending": "pending"}


def short(value: Any, limit: int = 70) -> str:
    text = json.dumps(value, ensure_ascii=False, separators=(", ", ": ")) if not isinstance(value, str) else value
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _slots(values: dict[str, Any]) -> str:
    return ", ".join(f"{k}={short(v, 40)}" for k, v in values.items())


def describe_node(node: dict[str, Any], timing: bool = True) -> str:
    """The details shown after a node's label: slots, answers, bound values, failures."""
    parts: list[str] = []
    if "designator" in node:
        data = node["designator"]
        parts.append(_slots(data.get("resolved") or data.get("slots") or {}))
    if "query" in node:
        q = node["query"]
        parts.append(f"{_slots(q.get('args', {}))} → {short(q.get('result'))}")
    if "action" in node:
        parts.append(_slots(node["action"].get("slots", {})))
    if "location" in node:
        parts.append(describe_location(node["location"]))
    if "condition" in node:
        parts.append(describe_condition(node["condition"]))
    if "call" in node:
        parts.append(_slots(node["call"].get("args", {})))
    if "item" in node:
        parts.append(f"= {short(node['item'])}")
    if "message" in node:
        parts.append(f"“{node['message']}”")
    if "caught" in node:
        parts.append(f"caught {node['caught'].get('type')}")
    if isinstance(node.get("folded"), dict):
        folded = node["folded"]
        counts = "; ".join(f"{text} ×{count}" for text, count in (folded.get("failures") or {}).items())
        parts.append(f"{folded.get('steps')} entries folded" + (f" ({counts})" if counts else ""))
    if isinstance(node.get("projection"), dict):
        parts.append(describe_projection(node["projection"]))
    if "retries" in node and node["retries"]:
        parts.append(f"{node['retries']} retr{'y' if node['retries'] == 1 else 'ies'}")
    if "bound" in node:
        parts.append("; ".join(f"${k} = {short(v, 50)}" for k, v in node["bound"].items()))
    failure = node.get("failure")
    if failure and node.get("status") == "failed" and failure.get("path") == node.get("path"):
        parts.append(f"{failure.get('type')}: {failure.get('message')}")
    if timing and isinstance(node.get("timing"), dict) and node["timing"].get("duration") is not None:
        parts.append(f"{node['timing']['duration']:.2f} s")
    return "  ".join(p for p in parts if p)


def describe_projection(record: dict[str, Any]) -> str:
    """`projected: left 18/20 (2 GripperFailure), right 20/20 → right (the most successful (20 of 20 runs))`."""
    rows = []
    for name, row in (record.get("alternatives") or {}).items():
        causes = ", ".join(f"{count} {kind}" for kind, count in (row.get("failures") or {}).items())
        rows.append(f"{name} {row.get('succeeded')}/{row.get('runs')}" + (f" ({causes})" if causes else ""))
    choice = record.get("choice")
    return f"projected: {', '.join(rows)} → {choice if choice else 'none'} ({record.get('why')})"


def describe_location(record: dict[str, Any]) -> str:
    """`{reachable-for: milk} → (0.75, 0.95) 5° left front (14 of 5845 tried)`."""
    spec = ", ".join(f"{k}: {short(v, 30)}" for k, v in (record.get("spec") or {}).items())
    found = record.get("found")
    where = "none"
    if isinstance(found, dict):
        position = found.get("position") or []
        where = "(" + ", ".join(f"{v:.2f}" for v in position[:2]) + ")"
        if "yaw" in found:
            where += f" {math.degrees(found['yaw']):.0f}°"
        where += "".join(f" {found[k]}" for k in ("arm", "grasp") if isinstance(found.get(k), str))
    return f"{{{spec}}} → {where} ({record.get('tried', 0)} of {record.get('candidates', 0)} tried)"


def describe_condition(record: dict[str, Any]) -> str:
    holds = record.get("holds", record.get("value"))
    verdict = "holds" if holds else "does not hold"
    if "query" in record:
        q = record["query"]
        return f"{q.get('name')}({_slots(q.get('args', {}))}) → {short(q.get('result'))}: {verdict}"
    if "variable" in record:
        return f"{record['variable']} = {short(record.get('value'), 50)}: {verdict}"
    if "not" in record:
        return f"not ({describe_condition(record['not'])})"
    if "equal" in record:
        a, b = record["equal"]
        return f"{short(a, 30)} = {short(b, 30)}: {verdict}"
    return verdict


def shown_status(node: dict[str, Any], saved: bool = False) -> str:
    """A node's status as the tree shows it: a failure is `recovered` when something above it succeeded
    (`saved`: a retry, catch or try_all that went on after it), else the node's own status."""
    status = str(node.get("status", "pending"))
    return "recovered" if status == "failed" and saved else status


def saves_children(node: dict[str, Any], saved: bool = False) -> bool:
    """Whether the failures below `node` were recovered from: it, or something above it, succeeded."""
    return saved or node.get("status") == "succeeded"


def node_label(node: dict[str, Any], rich_markup: bool = True, timing: bool = True, saved: bool = False) -> str:
    """A node's line in the tree; `saved`: something above it succeeded, so its failure was recovered from."""
    status = shown_status(node, saved)
    label = node.get("path", "?").rsplit("/", 1)[-1]
    details = describe_node(node, timing)
    if not rich_markup:
        return f"[{PLAIN.get(status, status)}] {label}" + (f"  {details}" if details else "")
    icon, style = STYLE.get(status, ("?", ""))
    text = f"[{style}]{icon}[/] [bold]{escape(label)}[/]"
    if details:
        text += f"  [dim]{escape(details)}[/]" if status != "failed" else f"  {escape(details)}"
    return text


def build_tree(root: dict[str, Any], collapse: bool = False, timing: bool = True) -> Tree:
    """The plan tree as the live view and `trace show` print it: a rich Tree of a trace's nodes, each
    with its status (a failure that something above recovered from as recovered); with `collapse`,
    finished successful subtrees are folded."""
    tree = Tree(node_label(root, timing=timing), guide_style="dim")
    _add(tree, root, collapse, timing, saves_children(root))
    return tree


def _add(tree: Tree, node: dict[str, Any], collapse: bool, timing: bool, saved: bool = False) -> None:
    children = node.get("children") or []
    if collapse and node.get("status") in ("succeeded", "skipped") and children and node.get("path") != "body":
        tree.add(f"[dim]… {len(children)} step{'s' if len(children) != 1 else ''}[/]")
        return
    pending = 0
    for child in children:
        if collapse and child.get("status") == "pending":
            pending += 1  # upcoming steps are summed up in one line
            continue
        branch = tree.add(node_label(child, timing=timing, saved=saved))
        _add(branch, child, collapse, timing, saves_children(child, saved))
    if pending:
        tree.add(f"[dim]○ {pending} more step{'s' if pending != 1 else ''}[/]")


def find_node(root: dict[str, Any], path: str) -> dict[str, Any] | None:
    if root.get("path") == path:
        return root
    for child in root.get("children") or []:
        if path == child.get("path") or path.startswith(f"{child.get('path')}/"):
            return find_node(child, path)
    return None


def state_rows(state: dict[str, Any]) -> list[tuple[str, ...]]:
    rows: list[tuple[str, ...]] = []
    for name, obj in (state.get("objects") or {}).items():
        position = ", ".join(f"{v:.3f}" for v in obj.get("position", []))
        joints = ", ".join(f"{k}={v:.3f}" for k, v in (obj.get("joints") or {}).items())
        rows.append((name, obj.get("type", ""), f"({position})", joints or "-"))
    return rows


@click.group()
def trace() -> None:
    """Show saved plan traces and compare them."""


@trace.command("show")
@click.argument("file", type=click.Path(path_type=Path))
@click.option("--no-timing", is_flag=True, help="Leave durations out.")
@click.option("--report", "report_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Also write the run's replay report (HTML), as `pycram run --report` does.")
@click.option("--mcap", "mcap_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Also write the run's replay as an MCAP file for Foxglove, as `pycram run --mcap` does.")
@click.option("--world", "world_file", metavar="WORLD", shell_complete=world_names,
              help="With --report or --mcap: the world file the run used (default: the one the trace names).")
def show(file: Path, no_timing: bool, report_file: Path | None, mcap_file: Path | None, world_file: str | None) -> None:
    """Print the trace in FILE as a tree (as the live view of `pycram run` shows it), then the world's final state."""
    outputs = [(report_file, REPORT_FORMATS, "report", "report"), (mcap_file, MCAP_FORMATS, "MCAP file", "mcap")]
    for output, kinds, what, key in outputs:
        if output is not None:
            check_output(output, kinds, what)
            if same_file(Path(file), output):
                raise InputError(f"the {what} would replace the trace it is made from: give it another name",
                                 Location(str(output)))
            check_writable(output, key)
    distinct_outputs([(report_file, "report"), (mcap_file, "MCAP file")])
    replayed = report_file is not None or mcap_file is not None
    data = traces.load(file, replay=replayed)
    timing = not no_timing
    status = data.get("status", "?")
    header = f"{data.get('plan')} on {data.get('world')}: {status}"
    if data.get("params"):
        header += "  (" + ", ".join(f"{k}={short(v, 30)}" for k, v in data["params"].items()) + ")"
    console.out.print(f"[bold]{escape(header)}[/]")
    console.out.print(build_tree(data["root"], timing=timing))
    failure = data.get("failure")
    if failure:
        console.plain(f"failure: {failure.get('type')} at {failure.get('path')}: {failure.get('message')}")
    attachments = (data.get("final_state") or {}).get("attachments") or []
    rows = state_rows(data.get("final_state") or {})
    if rows:
        console.table("final state", ["object", "type", "position", "joints"], rows)
    for att in attachments:
        console.plain(f"attached: {att['child']} to {att['parent']} ({att['parent_link']})")
    if replayed and not data.get(traces.REPLAY_KEY):
        console.warning(f"{file} has no replay record (written by `pycram run --trace`): the replay "
                        "shows the world as loaded")
    if report_file is not None:
        write_report(report_file, data, report_world(data, world_file))
    if mcap_file is not None:
        write_mcap(mcap_file, data, report_world(data, world_file))


@trace.command("diff")
@click.argument("a", type=click.Path(path_type=Path))
@click.argument("b", type=click.Path(path_type=Path))
@click.option("--atol", type=Number(0.0, 1e6), default=1e-3, show_default=True,
              help="Numbers closer than this are equal (a finite number, 0 or more).")
@click.option("--json", "as_json", is_flag=True, help="The differences as JSON on stdout.")
@click.option("--report", "report_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Also write a page (HTML) with both runs' replays side by side, moved together step by step, "
                   "the first step at which they differ marked.")
@click.pass_context
def diff_cmd(ctx: click.Context, a: Path, b: Path, atol: float, as_json: bool, report_file: Path | None) -> None:
    """Compare traces A and B, ignoring timings; exit 0 when they match, 1 when they differ."""
    if report_file is not None:
        check_output(report_file, REPORT_FORMATS, "report")
        for trace_file in (a, b):
            if same_file(Path(trace_file), report_file):
                raise InputError("the report would replace a trace it is made from: give it another name",
                                 Location(str(report_file)))
        check_writable(report_file, "report")
    replayed = report_file is not None
    first, second = traces.load(a, replay=replayed), traces.load(b, replay=replayed)
    found = traces.diff(first, second, atol)
    if as_json:
        console.emit_json({"same": not found, "atol": atol,
                           "differences": [d.to_dict() for d in found]})
    elif not found:
        console.success(f"{a} and {b} match (atol {atol:g})")
    else:
        for difference in found:
            console.plain(str(difference))
        console.plain(f"{len(found)} difference{'s' if len(found) != 1 else ''} (A = {a}, B = {b})")
    if report_file is not None:
        for path, data in ((a, first), (b, second)):
            if not data.get(traces.REPLAY_KEY):
                console.warning(f"{path} has no replay record (written by `pycram run --trace`): its replay "
                                "shows the world as loaded")
        names = (a.name, b.name) if a.name != b.name else (str(a), str(b))
        page = build_comparison(first, second, (report_world(first), report_world(second)), names, atol)
        write_output(report_file, page, f"comparison report, {len(page.encode()) / 1e6:.1f} MB")
    if found:
        ctx.exit(1)
