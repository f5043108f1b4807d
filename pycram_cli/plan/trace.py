"""Traces: what a plan run did, as a tree in declaration order, saved as JSON and compared.

Every node of the run is recorded with its path in the tree (`body/1:for_each/item 0/
0:call fetch/2:detecting`), type, status (succeeded, failed, cancelled, skipped),
resolved designator slots, reasoning answers, bound values and failure (type, message
and the path of the node where it arose). The final state of the world closes the trace.

Wall-clock data lives only under `timing` keys (and `source` names the line in the plan
file); `comparable()` drops them, and the replay record (`replay`, see replay.py) too. Everything else is a function
of the plan and the world: the tree is built in declaration order (concurrent branches by index, never by
finishing order), floats are rounded to 6 decimals and keys sorted, so the same plan on
the same world gives byte-identical comparable traces.
"""
from __future__ import annotations

import json
import math
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from ..errors import InputError, Location
from ..failures import FailureRecord
from ..files import read_text, write_atomic
from ..limits import MAX_STEP_DEPTH, MAX_TRACE_BYTES, MAX_TRACE_NODES
from ..status import Status
from . import trace_schema
from .context import jsonable
from .runtime import LimitExceeded

if TYPE_CHECKING:
    from ..world import BulletWorld
    from .runtime import Record

FORMAT = "pycram-trace"
VERSION = 1
IGNORED_KEYS = frozenset({"timing", "source"})
REPLAY_KEY = "replay"  # the world's state after every step (replay.py); a top-level key comparable() drops
DIGITS = 6


class Budget:
    """How many trace nodes a run may hold (shared by every node of one run's tree)."""

    def __init__(self, limit: int = MAX_TRACE_NODES) -> None:
        self.limit = limit
        self.used = 0
        self._lock = threading.Lock()

    def take(self, path: str) -> None:
        with self._lock:
            if self.used >= self.limit:
                raise LimitExceeded(f"the run recorded more than {self.limit} steps (the limit)", path)
            self.used += 1

    def give_back(self, count: int) -> None:
        with self._lock:
            self.used -= count


#: folded attempts remember at most this many different failure messages (the rest are counted as "other")
FOLDED_MESSAGES = 10


class TraceNode:
    """One node of a run; mutated while running, read by live views and `to_dict`.

    A tree made from one root shares its `Budget` (the number of nodes a run may hold) and
    knows its depth: making a child beyond either limit raises LimitExceeded.
    """

    def __init__(self, path: str, type: str, source: Location | None = None, budget: Budget | None = None,
                 depth: int = 0) -> None:
        self.path = path
        self.type = type
        self.status = Status.PENDING
        self.info: dict[str, Any] = {}
        self.failure: FailureRecord | None = None
        self.children: list[TraceNode] = []
        self.started: float | None = None
        self.duration: float | None = None
        self.source = f"{source.line}:{source.column}" if source is not None and source.line else None
        self.depth = depth
        self._budget = budget if budget is not None else Budget()
        self._lock = threading.Lock()

    def child(self, label: str, type: str, source: Location | None = None) -> TraceNode:
        path = f"{self.path}/{label}"
        if self.depth + 1 > MAX_STEP_DEPTH:
            raise LimitExceeded(f"steps nested more than {MAX_STEP_DEPTH} levels deep (the limit; endless "
                                "recursion?)", self.path)
        self._budget.take(path)
        node = TraceNode(path, type, source, self._budget, self.depth + 1)
        with self._lock:
            self.children.append(node)
        return node

    def detached(self, label: str, type: str, source: Location | None = None) -> TraceNode:
        """A new entry with a child's path, in no tree and with a budget of its own (runtime.Record.detached)."""
        return TraceNode(f"{self.path}/{label}", type, source, None, self.depth + 1)

    def summarise(self, entry: Record, label: str) -> TraceNode | None:
        """Replace `entry` by a count in the summary node `label` ("folded"), made at the child's place; the summary.
        (A `Record` for the runtime's protocol: the runtime only ever hands back the trace nodes it was given.)"""
        child = cast(TraceNode, entry)
        with self._lock:
            if child not in self.children:
                return None
            index = self.children.index(child)
            summary = next((c for c in self.children if c.type == "folded" and c.label == label), None)
            if summary is None:
                summary = TraceNode(f"{self.path}/{label}", "folded", None, self._budget, self.depth + 1)
                summary.status = Status.SUCCEEDED  # until a failed step is folded in (a retry folds only failed attempts)
                summary.info["folded"] = {"steps": 0, "failures": {}}
                self._budget.used += 1  # cannot fail: the child it replaces is given back below
                self.children.insert(index, summary)
                index += 1
            self.children.pop(index)
        self._budget.give_back(sum(1 for _ in child.walk()))
        folded = summary.info["folded"]
        folded["steps"] += 1
        if child.status != Status.SUCCEEDED:
            summary.status = Status.FAILED
        if child.failure is not None:
            text = f"{child.failure.type}: {child.failure.message}"
            failures = folded["failures"]
            if text not in failures and len(failures) >= FOLDED_MESSAGES:
                text = "(other failures)"
            failures[text] = failures.get(text, 0) + 1
        return summary

    @property
    def label(self) -> str:
        return self.path.rsplit("/", 1)[-1]

    def walk(self) -> Iterator[TraceNode]:
        yield self
        for child in list(self.children):
            yield from child.walk()

    def to_dict(self, timing: bool = True) -> dict[str, Any]:
        data: dict[str, Any] = {"path": self.path, "type": self.type, "status": str(self.status)}  # plain data
        data.update(self.info)
        if self.failure is not None:
            data["failure"] = self.failure.to_json()
        children = list(self.children)
        if children:
            data["children"] = [c.to_dict(timing) for c in children]
        if timing:
            if self.source:
                data["source"] = self.source
            if self.started is not None:
                data["timing"] = {"started": self.started, "duration": self.duration}
        return data


# -- the world's final state ---------------------------------------------------------------
def canonical_quaternion(q: Any) -> list[float]:
    """q and -q are the same rotation: pick the one with w >= 0 (first non-zero component positive if w = 0)."""
    values = [float(v) for v in q]
    lead = next((v for v in (values[3], values[0], values[1], values[2]) if abs(v) > 1e-9), 1.0)
    return [-v for v in values] if lead < 0 else values


def final_state(world: BulletWorld) -> dict[str, Any]:
    """Object poses, attachments, and the joints of non-robot objects that are not at 0 (opened drawers)."""
    objects: dict[str, Any] = {}
    attachments: list[dict[str, Any]] = []
    seen: set[int] = set()
    with world.lock:
        for obj in world.objects:
            position, orientation = obj.get_pose()
            entry: dict[str, Any] = {"type": obj.type, "position": list(position),
                                     "orientation": canonical_quaternion(orientation)}
            if obj.type != "robot":
                joints = {name: value for name, value in obj.get_joint_positions().items() if abs(value) > 1e-6}
                if joints:
                    entry["joints"] = joints
            objects[obj.name] = entry
            for att in obj.attachments.values():
                if id(att) in seen:
                    continue
                seen.add(id(att))
                attachments.append({"parent": att.parent.name, "child": att.child.name,
                                    "parent_link": att.parent.get_link_name(att.parent_link),
                                    "child_link": att.child.get_link_name(att.child_link)})
    attachments.sort(key=lambda a: (a["parent"], a["child"]))
    return {"objects": objects, "attachments": attachments}


# -- (de)serialisation ------------------------------------------------------------------------
def normalised(data: Any) -> Any:
    """JSON-ready: floats rounded, -0.0 as 0.0, tuples as lists, objects by name."""
    return jsonable(data, DIGITS)


def dumps(data: dict[str, Any]) -> str:
    """Deterministic JSON: sorted keys, rounded floats, two-space indent, short lists of scalars on one line."""
    return _encode(normalised(data), 0) + "\n"


def _scalar(value: Any) -> bool:
    return not isinstance(value, (dict, list))


def _encode(value: Any, depth: int) -> str:
    pad, inner = "  " * depth, "  " * (depth + 1)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{inner}{json.dumps(str(k), ensure_ascii=False)}: {_encode(value[k], depth + 1)}"
                 for k in sorted(value, key=str)]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if not value:
            return "[]"
        if all(_scalar(v) for v in value):
            line = "[" + ", ".join(json.dumps(v, ensure_ascii=False) for v in value) + "]"
            if len(line) <= 100:
                return line
        return "[\n" + ",\n".join(inner + _encode(v, depth + 1) for v in value) + "\n" + pad + "]"
    return json.dumps(value, ensure_ascii=False)


def comparable(data: Any) -> Any:
    """The trace without its wall-clock parts (`timing`), source places and replay record."""
    if isinstance(data, dict) and data.get("format") == FORMAT:
        data = {k: v for k, v in data.items() if k != REPLAY_KEY}
    if isinstance(data, dict):
        return {k: comparable(v) for k, v in data.items() if k not in IGNORED_KEYS}
    if isinstance(data, list):
        return [comparable(v) for v in data]
    return data


def save(data: dict[str, Any], path: str | Path, timing: bool = True) -> None:
    """Write a trace atomically: a reader sees the previous file or this one whole, never a part."""
    write_atomic(path, dumps(data if timing else comparable(data)), key="trace")


def load(path: str | Path, replay: bool = False) -> dict[str, Any]:
    """Read a saved trace, checked against the trace schema of its version (`trace_schema.py`): a file
    `pycram run --trace` wrote, or what `pycram run --json` printed (the trace is its `trace` key).
    `replay`: it is to be replayed (a report), so its replay record must fit its tree and final state too.

    Every problem is an input error at its place in the file: a missing file, malformed JSON,
    another format or version, a field of the wrong kind or missing ("which entry, what is missing").
    """
    path = Path(path)
    text = read_text(path, MAX_TRACE_BYTES, "trace file")
    data = trace_schema.parse(text, str(path))
    within: tuple[str, ...] = ()
    if isinstance(data, dict) and "format" not in data and isinstance(data.get("trace"), dict) \
            and data["trace"].get("format") == FORMAT:
        data, within = data["trace"], ("trace",)  # what `pycram run --json` printed: the trace is inside
    if not isinstance(data, dict) or data.get("format") != FORMAT or "root" not in data:
        raise InputError(f"not a pycram trace (expected a JSON object with \"format\": \"{FORMAT}\" and a \"root\")",
                         Location(str(path), 1, 1), suggestion="write one with `pycram run PLAN --trace FILE`")
    if data.get("version") != VERSION:
        version = data.get("version")
        shown = version if isinstance(version, (int, float, str)) or version is None else "?"
        raise InputError(f"unsupported trace version {shown!r} (this pycram reads version {VERSION})",
                         trace_schema.location(text, str(path), within + ("version",)), key="version")
    trace_schema.check(data, text, str(path), within, replay)
    return data


# -- comparing ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class Difference:
    where: str        # a node path, or a dotted place in the trace
    field: str        # what differs there
    a: Any
    b: Any
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        def value(v: Any) -> Any:
            return "(absent)" if v is _MISSING else v

        return {"where": self.where, "field": self.field, "a": value(self.a), "b": value(self.b), "note": self.note}

    def __str__(self) -> str:
        head = f"{self.where}: {self.field}" if self.field else self.where
        note = f" ({self.note})" if self.note else ""
        return f"{head}: {_show(self.a)} != {_show(self.b)}{note}"


_MISSING = object()


def _show(value: Any) -> str:
    if value is _MISSING:
        return "(absent)"
    text = json.dumps(value, sort_keys=True, ensure_ascii=False)
    return text if len(text) <= 120 else text[:117] + "..."


def diff(a: dict[str, Any], b: dict[str, Any], atol: float = 1e-3) -> list[Difference]:
    """What differs between two traces, ignoring timings and source places; numbers within `atol` are equal."""
    found: list[Difference] = []
    _diff(comparable(a), comparable(b), "trace", "", atol, found)
    return found


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _diff(a: Any, b: Any, where: str, field: str, atol: float, found: list[Difference]) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        if "path" in a and "path" in b and a.get("path") == b.get("path") and "status" in a:
            where, field = a["path"], ""  # a trace node: name differences by its path
        a_children, b_children = a.get("children"), b.get("children")
        for key in sorted(set(a) | set(b)):
            if key == "children" and isinstance(a_children, list) and isinstance(b_children, list) and "status" in a:
                _diff_children(a_children, b_children, where, atol, found)
                continue
            sub = f"{field}.{key}" if field else key
            _diff(a.get(key, _MISSING), b.get(key, _MISSING), where, sub, atol, found)
        return
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            found.append(Difference(where, field, a, b, f"{len(a)} items != {len(b)} items"))
            return
        for index, (x, y) in enumerate(zip(a, b)):
            _diff(x, y, where, f"{field}[{index}]", atol, found)
        return
    if _is_number(a) and _is_number(b):
        delta = abs(float(a) - float(b))
        if delta > atol or (math.isnan(delta)):
            found.append(Difference(where, field, a, b, f"|difference| {delta:.3g} > {atol:g}"))
        return
    if a != b or type(a) is not type(b):
        found.append(Difference(where, field, a, b))


def _diff_children(a: list[Any], b: list[Any], where: str, atol: float, found: list[Difference]) -> None:
    a_paths = [c.get("path") if isinstance(c, dict) else None for c in a]
    b_paths = [c.get("path") if isinstance(c, dict) else None for c in b]
    if a_paths != b_paths:
        only_a = [p for p in a_paths if p not in b_paths]
        only_b = [p for p in b_paths if p not in a_paths]
        if only_a or only_b:
            found.append(Difference(where, "children", only_a or "(none extra)", only_b or "(none extra)",
                                    "steps only in A != steps only in B"))
    by_path = {p: c for p, c in zip(b_paths, b)}
    for path, child in zip(a_paths, a):
        if path in by_path:
            _diff(child, by_path[path], path or where, "", atol, found)
