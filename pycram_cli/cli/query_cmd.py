"""`pycram query QUERY ARGS`: ask a reasoning question about a world.

    pycram query visible bottle
    pycram query contact kitchen milk
    pycram query reachable 1.3,0.6,1.0 --arm left
    pycram query blocking milk --arm left --exclude-type environment --json

Exit 0 whatever the answer; 2 on bad input.
"""
from __future__ import annotations

import math
from typing import Any

import click

from ..errors import InputError, Location, did_you_mean
from ..reasoning import QUERIES, QueryAnswer, run_query
from ..reasoning.registry import parse_vector
from . import console
from .options import json_option, resolve_world_path

#: the positional arguments of each query, in order
POSITIONAL: dict[str, tuple[str, ...]] = {
    "stable": ("object",),
    "contact": ("a", "b"),
    "visible": ("object",),
    "occluding": ("object",),
    "reachable": ("target",),
    "blocking": ("target",),
    "supporting": ("a", "b"),
}

#: option -> parameter name
OPTIONS = {"--arm": "arm", "--grasp": "grasp", "--from": "from", "--exclude-type": "exclude-type",
           "--threshold": "threshold", "--link": "link"}


def _usage() -> str:
    width = max(len(n) for n in QUERIES)
    lines = []
    for name, spec in QUERIES.items():
        args = " ".join(p.upper() for p in POSITIONAL[name])
        options = " ".join(f"[{opt}]" for opt, param in OPTIONS.items() if spec.param(param) is not None)
        lines.append(f"  {name:<{width}}  {args} {options}".rstrip())
        lines.append(f"  {'':<{width}}  {spec.doc}")
    return "\n".join(lines)


def _help() -> str:
    return f"""Ask a reasoning question about a world (default: the bundled kitchen).

\b
Queries:
{_usage()}

\b
TARGET is an object name or a position x,y,z; --from is a robot link or a position x,y,z
(default: the robot's camera); --grasp is front, top, left, right or a quaternion x,y,z,w;
--threshold is the visible fraction (visible, default 0.8) or the distance in metres the
tool frame must come within (reachable, blocking, default 0.01).

\b
Examples:
  pycram query visible bottle
  pycram query contact kitchen milk
  pycram query reachable milk --arm right --grasp front
  pycram query blocking milk --arm left --exclude-type environment --json

Exit status: 0 whatever the answer, 2 on bad input."""


def build_args(query: str, values: tuple[str, ...], options: dict[str, Any]) -> dict[str, Any]:
    """The query's parameters from the command line (positional ARGS and options)."""
    spec = QUERIES.get(query)
    if spec is None:
        hint = did_you_mean(query, QUERIES)
        raise InputError(f"unknown query '{query}'", Location("query"), suggestion=hint or f"queries: {', '.join(QUERIES)}")
    names = POSITIONAL[query]
    for value in values:
        if value.startswith("-") and parse_vector(value, 3) is None:
            raise InputError(f"no such option: {value}", Location(f"query {query}"),
                             suggestion=did_you_mean(value, [*OPTIONS, "--world", "--json"]) or "see pycram query --help")
    usage = f"pycram query {query} {' '.join(n.upper() for n in names)}"
    if len(values) != len(names):
        what = "missing" if len(values) < len(names) else "too many"
        raise InputError(f"{what} arguments: expected {len(names)} ({', '.join(names)}), got {len(values)}",
                         Location(f"query {query}"), suggestion=f"usage: {usage}")
    args: dict[str, Any] = {}
    for name, value in zip(names, values):
        args[name] = value
    for option, value in options.items():
        if value is None or value == ():
            continue
        param = OPTIONS[option]
        if spec.param(param) is None:
            allowed = [o for o, p in OPTIONS.items() if spec.param(p) is not None]
            raise InputError(f"option {option} does not apply to '{query}'", Location(f"query {query}"),
                             suggestion=f"its options: {', '.join(allowed)}" if allowed else f"usage: {usage}")
        if param == "from":
            args[param] = parse_vector(value, 3) or value
        elif param == "grasp":
            args[param] = parse_vector(value, 4) or value
        elif param == "exclude-type":
            args[param] = list(value)
        else:
            args[param] = value
    return args


def _mm(value: float | None) -> str:
    if value is None:
        return "-"
    mm = value * 1000
    return f"{mm:.2f} mm" if abs(mm) < 10 else f"{mm:.1f} mm"


def _deg(value: float | None) -> str:
    return "-" if value is None else f"{math.degrees(value):.2f}°"


def _target_text(value: Any) -> str:
    if isinstance(value, list) and value and isinstance(value[0], (int, float)):
        return "(" + ", ".join(f"{v:g}" for v in value) + ")"
    return str(value)


def describe(answer: QueryAnswer) -> str:
    """One line for people: the answer and its key figure."""
    a, d = answer.args, answer.details
    q = answer.query
    if q == "stable":
        moved = f"moved {_mm(d['displacement'])} and {_deg(d['rotation'])} in {d['simulated']:.2f} s simulated"
        return f"{a['object']} is stable ({moved})" if answer.result else f"{a['object']} is NOT stable: it {moved}"
    if q == "contact":
        if answer.result:
            links = ", ".join(f"{x}–{y}" for x, y in d["links"])
            return f"{a['a']} and {a['b']} are in contact (distance {_mm(d['distance'])}; touching: {links})"
        far = "more than 0.5 m" if d["distance"] is None else _mm(d["distance"])
        return f"{a['a']} and {a['b']} are not in contact (distance {far})"
    if q == "visible":
        seen = f"{d['fraction']:.0%} of its pixels seen from {_target_text(d['camera'])} (threshold {a['threshold']:.0%})"
        return f"{a['object']} is visible: {seen}" if answer.result else f"{a['object']} is NOT visible: {seen}"
    if q == "occluding":
        if answer.result:
            return f"{a['object']} is occluded by: {', '.join(answer.result)} (seen from {_target_text(d['camera'])})"
        return f"nothing occludes {a['object']} (seen from {_target_text(d['camera'])})"
    if q == "reachable":
        grasp = f", {_target_text(a['grasp'])} grasp" if a.get("grasp") is not None else ""
        errors = f"{_mm(d['position_error'])} left" + (f", {_deg(d['orientation_error'])} off" if grasp else "")
        target = _target_text(a["target"])
        if answer.result:
            return f"{target} is reachable with the {d['arm']} arm{grasp} ({errors})"
        return f"{target} is NOT reachable (best: the {d['arm']} arm{grasp}, {errors})"
    if q == "blocking":
        target = _target_text(a["target"])
        reach = "" if d["reachable"] else f" (out of reach: best solution, {_mm(d['position_error'])} left)"
        if answer.result:
            return f"reaching {target} with the {d['arm']} arm touches: {', '.join(answer.result)}{reach}"
        return f"nothing blocks the {d['arm']} arm reaching {target}{reach}"
    if q == "supporting":
        if answer.result:
            links = sorted({c["link"] for c in d["contacts"]})
            return f"{a['a']} supports {a['b']} (at {', '.join(links)})"
        return f"{a['a']} does NOT support {a['b']}"
    return f"{q}: {answer.result}"  # pragma: no cover - every query is handled above


@click.command("query", help=_help(), context_settings={"ignore_unknown_options": True})
@click.argument("query_name", metavar="QUERY")
@click.argument("values", metavar="ARGS...", nargs=-1)
@click.option("--world", "world_file", metavar="WORLD", help="World file or bundled world name (default: kitchen).")
@click.option("--arm", metavar="ARM", help="Arm for reachable/blocking (default: left, then right).")
@click.option("--grasp", metavar="GRASP", help="front, top, left, right, or a quaternion x,y,z,w.")
@click.option("--from", "from_", metavar="LINK|x,y,z", help="Camera for visible/occluding (default: the robot's camera).")
@click.option("--exclude-type", "exclude_type", metavar="TYPE", multiple=True,
              help="Leave objects of this type out of blocking (repeatable).")
@click.option("--threshold", type=float, metavar="NUMBER",
              help="visible: fraction of pixels (0.8); reachable/blocking: distance in m (0.01).")
@click.option("--link", metavar="LINK", help="supporting: only count support by this link of the first object.")
@json_option
def query(query_name: str, values: tuple[str, ...], world_file: str | None, arm: str | None, grasp: str | None,
          from_: str | None, exclude_type: tuple[str, ...], threshold: float | None, link: str | None,
          as_json: bool) -> None:
    args = build_args(query_name, values, {"--arm": arm, "--grasp": grasp, "--from": from_,
                                           "--exclude-type": exclude_type, "--threshold": threshold, "--link": link})
    path = resolve_world_path(world_file)
    from ..worldfile.loader import load_world

    world = load_world(path)
    try:
        answer = run_query(world, query_name, args)
    finally:
        world.exit()
    if as_json:
        payload = answer.to_json()
        payload["world"] = str(path)
        console.emit_json(_jsonable(payload))
    else:
        console.plain(describe(answer))


def _jsonable(value: Any) -> Any:
    """JSON without NaN/Infinity (not valid JSON): non-finite numbers become null."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    return value


COMMANDS = [query]
