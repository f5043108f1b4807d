"""The schema of a saved trace (format `pycram-trace`, version 1), checked before a trace is shown or compared.

A trace file comes from anywhere: a truncated copy, a hand edit, another program. `check`
walks the parsed JSON once (without recursion) and reports every problem as an input error
at its place in the file (line and column of the value), naming the entry and what is wrong
with it: `final_state.attachments[0]: an attachment needs 'parent'`. After the check, the
commands that read traces (`trace show`, `trace diff`) can rely on every field they use.

Numbers must be finite (JSON's NaN and Infinity are refused, and so are numbers too large
for a float); nesting is bounded (see `limits.py`).
"""
from __future__ import annotations

import json
import math
import re
from collections.abc import Callable
from typing import Any

from ..errors import InputError, InputErrors, Location
from ..limits import MAX_MAGNITUDE, MAX_NESTING, MAX_PHYSICS_FRAMES, MAX_STEP_DEPTH, MAX_TRACE_NODES
from ..status import NODE_STATUSES, RUN_STATUSES

#: candidate positions one locate step's map may hold in a trace's replay record
MAX_CANDIDATES = 200_000

Path = tuple[Any, ...]  # keys and indices from the top of the trace
#: JSON nesting a trace may have: the deepest run's step tree (two levels per step) and values inside its steps
MAX_JSON_DEPTH = 2 * MAX_STEP_DEPTH + MAX_NESTING + 10
MAX_PROBLEMS = 20


class NonFinite:
    """A number JSON cannot hold (NaN, Infinity, 1e999), kept in place so that it can be reported where it is."""

    def __init__(self, text: str) -> None:
        self.text = text

    def __repr__(self) -> str:
        return self.text


def _float(text: str) -> Any:
    value = float(text)
    return value if math.isfinite(value) else NonFinite(text)


def parse(text: str, filename: str) -> Any:
    """JSON text to data; non-finite numbers stay NonFinite, malformed or too deeply nested JSON is an InputError."""
    try:
        return json.loads(text, parse_constant=NonFinite, parse_float=_float)
    except json.JSONDecodeError as exc:
        raise InputError(f"not a JSON trace: {exc.msg}", Location(filename, exc.lineno, exc.colno)) from None
    except RecursionError:  # deeper than the JSON decoder goes (about 1000 levels): find where the limit is passed
        offset = _too_deep(text)
        where = Location(filename) if offset is None else _place(text, filename, offset)
        raise InputError(f"not a pycram trace: nested deeper than {MAX_JSON_DEPTH} levels (the limit)", where) \
            from None


_TOKENS = re.compile(r'"(?:[^"\\]|\\.)*"|[\[\]{}]')


def _too_deep(text: str) -> int | None:
    """The offset of the first bracket nested deeper than MAX_JSON_DEPTH (strings skipped), if any."""
    depth = 0
    for match in _TOKENS.finditer(text):
        token = match.group()
        if token in "[{":
            depth += 1
            if depth > MAX_JSON_DEPTH:
                return match.start()
        elif token in "]}":
            depth -= 1
    return None


def _place(text: str, filename: str, offset: int) -> Location:
    line = text.count("\n", 0, offset) + 1
    return Location(filename, line, offset - (text.rfind("\n", 0, offset) + 1) + 1)


# -- the schema -------------------------------------------------------------------------------------------

Problem = tuple[Path, str]


def _name(path: Path) -> str:
    """('final_state', 'attachments', 0, 'parent') -> 'final_state.attachments[0].parent'."""
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text or "the trace"


def _kind(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true or false"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "an object"
    return "a non-finite number"


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


class _Checker:
    def __init__(self) -> None:
        self.problems: list[Problem] = []
        self.paths: set[str] = set()  # the steps' paths (the replay's steps must be among them)

    def add(self, path: Path, message: str) -> None:
        self.problems.append((path, message))

    def typed(self, value: Any, path: Path, kind: type | tuple[type, ...], what: str) -> bool:
        ok = isinstance(value, kind) and not (isinstance(value, bool) and bool not in (kind if isinstance(kind, tuple)
                                                                                      else (kind,)))
        if not ok:
            self.add(path, f"expected {what}, got {_kind(value)}")
        return ok

    def fields(self, record: Any, path: Path, what: str, required: dict[str, Callable[[Any, Path], None]],
               optional: dict[str, Callable[[Any, Path], None]] | None = None) -> bool:
        if not isinstance(record, dict):
            self.add(path, f"{what} must be an object, got {_kind(record)}")
            return False
        missing = [key for key in required if key not in record]
        for key in missing:
            self.add(path, f"{what} needs '{key}'")
        for key, check in {**required, **(optional or {})}.items():
            if key in record:
                check(record[key], path + (key,))
        return True

    # -- value checks ---------------------------------------------------------------------------------
    def string(self, value: Any, path: Path) -> None:
        self.typed(value, path, str, "a string")

    def string_or_null(self, value: Any, path: Path) -> None:
        if value is not None:
            self.typed(value, path, str, "a string or null")

    def obj(self, value: Any, path: Path) -> None:
        self.typed(value, path, dict, "an object")

    def number_or_null(self, value: Any, path: Path) -> None:
        if value is not None and not _is_number(value):
            self.add(path, f"expected a number or null, got {_kind(value)}")

    def count(self, value: Any, path: Path) -> None:
        if not (isinstance(value, int) and not isinstance(value, bool) and value >= 0):
            self.add(path, f"expected a whole number (0 or more), got {_kind(value)}")

    def vector(self, size: int) -> Callable[[Any, Path], None]:
        def check(value: Any, path: Path) -> None:
            if not (isinstance(value, list) and len(value) == size and all(_is_number(v) for v in value)):
                self.add(path, f"expected a list of {size} numbers")
        return check

    def failure(self, value: Any, path: Path) -> None:
        if value is None:
            return
        if self.fields(value, path, "a failure", {"type": self.string, "message": self.string},
                       {"path": self.string, "failures": self.failures}):
            pass

    def failures(self, value: Any, path: Path) -> None:
        if self.typed(value, path, list, "a list of failures"):
            for index, item in enumerate(value):
                if item is None:
                    self.add(path + (index,), "expected a failure, got null")
                else:
                    self.failure(item, path + (index,))

    def status(self, allowed: tuple[str, ...]) -> Callable[[Any, Path], None]:
        def check(value: Any, path: Path) -> None:
            if value not in allowed:
                self.add(path, f"unknown status {json.dumps(value) if isinstance(value, str) else _kind(value)} "
                               f"(one of {', '.join(allowed)})")
        return check

    def timing(self, value: Any, path: Path) -> None:
        if self.typed(value, path, dict, "an object"):
            for key in ("started", "duration"):
                if key in value:
                    self.number_or_null(value[key], path + (key,))

    def designator(self, value: Any, path: Path) -> None:
        self.fields(value, path, "a designator record", {}, {"slots": self.obj, "resolved": self.obj})

    def query(self, value: Any, path: Path) -> None:
        self.fields(value, path, "a query record", {}, {"args": self.obj, "details": self.obj, "name": self.string})

    def condition(self, value: Any, path: Path) -> None:
        if not self.fields(value, path, "a condition", {}, {"query": self.query, "variable": self.string,
                                                             "not": self.condition}):
            return
        if "equal" in value and not (isinstance(value["equal"], list) and len(value["equal"]) == 2):
            self.add(path + ("equal",), "expected a list of two values")

    def call(self, value: Any, path: Path) -> None:
        self.fields(value, path, "a call record", {}, {"plan": self.string_or_null, "args": self.obj})

    def caught(self, value: Any, path: Path) -> None:
        self.fields(value, path, "a caught failure", {}, {"type": self.string, "message": self.string,
                                                          "path": self.string})

    def node(self, value: Any, path: Path, depth: int) -> list[tuple[Any, Path, int]]:
        """Check one step node; its children, to be checked next."""
        if not self.fields(value, path, "a step", {"path": self.string, "type": self.string,
                                                   "status": self.status(NODE_STATUSES)},
                           {"failure": self.failure, "timing": self.timing, "source": self.string,
                            "designator": self.designator, "query": self.query, "condition": self.condition,
                            "call": self.call, "caught": self.caught, "bound": self.obj, "message": self.string,
                            "retries": self.count, "items": self.list_of_anything, "folded": self.folded,
                            "projection": self.obj}):
            return []
        if depth > MAX_STEP_DEPTH + 2:
            self.add(path, f"steps nested deeper than {MAX_STEP_DEPTH} levels")
            return []
        if isinstance(value.get("path"), str):
            self.paths.add(value["path"])
        children = value.get("children")
        if children is None:
            return []
        if not self.typed(children, path + ("children",), list, "a list of steps"):
            return []
        return [(child, path + ("children", index), depth + 1) for index, child in enumerate(children)]

    def list_of_anything(self, value: Any, path: Path) -> None:
        self.typed(value, path, list, "a list")

    def folded(self, value: Any, path: Path) -> None:
        self.fields(value, path, "a summary of folded steps", {"steps": self.count}, {"failures": self.obj})

    def final_state(self, value: Any, path: Path) -> None:
        if not self.fields(value, path, "the final state", {}, {"objects": self.obj,
                                                                "attachments": self.attachments}):
            return
        objects = value.get("objects")
        if isinstance(objects, dict):
            for name, entry in objects.items():
                where = path + ("objects", name)
                if self.fields(entry, where, f"object '{name}'", {"position": self.vector(3)},
                               {"type": self.string, "orientation": self.vector(4), "joints": self.obj}):
                    joints = entry.get("joints")
                    if isinstance(joints, dict):
                        for joint, position in joints.items():
                            if not _is_number(position):
                                self.add(where + ("joints", joint), f"expected a number, got {_kind(position)}")

    def attachments(self, value: Any, path: Path) -> None:
        if not self.typed(value, path, list, "a list of attachments"):
            return
        for index, entry in enumerate(value):
            self.fields(entry, path + (index,), "an attachment",
                        {"parent": self.string, "child": self.string},
                        {"parent_link": self.string_or_null, "child_link": self.string_or_null})


    # -- the replay record (plan/replay.py): what `--report` draws, so checked as strictly as the rest ----------
    def replay(self, value: Any, path: Path, objects: set[str] | None, refs: bool) -> None:
        if value is None:
            return
        if not self.fields(value, path, "the replay record", {"initial": self.obj, "steps": self.replay_steps},
                           {"world_file": self.string_or_null, "root": self.obj}):
            return
        projections = value.get("projections")
        if projections is not None and self.typed(projections, path + ("projections",), dict, "an object"):
            for step, alternatives in projections.items():  # step path -> alternative -> run -> a replay of its own
                where = path + ("projections", step)
                if self.typed(alternatives, where, dict, "an object"):
                    for name, runs in alternatives.items():
                        if self.typed(runs, where + (name,), dict, "an object"):
                            for run, record in runs.items():
                                if len(self.problems) >= MAX_PROBLEMS:
                                    return
                                # its steps are the projected run's own (in its `root`), not the trace's
                                self.replay(record, where + (name, run), objects, False)
        initial = value.get("initial")
        if isinstance(initial, dict):
            for name, entry in initial.items():
                where = path + ("initial", name)
                if not refs or self.known_object(name, where, objects):
                    self.body_state(entry, where, f"the initial state of '{name}'", full=True)
        steps = value.get("steps")
        if isinstance(steps, list):
            for index, step in enumerate(steps):
                if len(self.problems) >= MAX_PROBLEMS:
                    return
                self.replay_step(step, path + ("steps", index), objects, refs)

    def replay_steps(self, value: Any, path: Path) -> None:
        if self.typed(value, path, list, "a list of steps") and len(value) > MAX_TRACE_NODES:
            self.add(path, f"more than {MAX_TRACE_NODES} steps (a run records at most that many)")

    def replay_step(self, step: Any, path: Path, objects: set[str] | None, refs: bool) -> None:
        if not self.fields(step, path, "a replayed step", {"path": self.string, "status": self.status(NODE_STATUSES),
                                                            "changed": self.obj},
                           {"folded": self.count, "physics": self.physics_frames, "prospection": self.physics_frames,
                            "candidates": self.candidate_map}):
            return
        if refs and isinstance(step.get("path"), str) and step["path"] not in self.paths:
            self.add(path + ("path",), f"no step of the trace has the path {json.dumps(step['path'])}")
        changes = [(path, step.get("changed"))]
        for key in ("physics", "prospection"):
            physics = step.get(key)
            if isinstance(physics, list):
                for index, frame in enumerate(physics):
                    if self.fields(frame, path + (key, index), "a physics frame", {"t": self.seconds, "changed": self.obj}):
                        changes.append((path + (key, index), frame.get("changed")))
        for where_from, changed in changes:
            if isinstance(changed, dict):
                for name, entry in changed.items():
                    where = where_from + ("changed", name)
                    if not refs or self.known_object(name, where, objects):
                        self.body_state(entry, where, f"the change of '{name}'", full=False)

    def candidate_map(self, value: Any, path: Path) -> None:
        """A locate step's candidate map (locations/plot.py `candidate_map`), which the report draws."""
        if not self.fields(value, path, "a candidate map",
                           {"kind": self.string, "z": self.place_number, "spacing": self.spacing, "xy": self.millimetres,
                            "outcome": self.outcome_indices, "outcomes": self.names, "found": self.found_poses},
                           {"why": self.reasons, "target": self.vector(3)}):
            return
        xy, outcome, names = value.get("xy"), value.get("outcome"), value.get("outcomes")
        if isinstance(xy, list) and isinstance(outcome, list) and len(xy) != 2 * len(outcome):
            self.add(path, "a candidate map needs two coordinates ('xy') for each outcome")
        if isinstance(outcome, list) and isinstance(names, list) and any(
                isinstance(v, int) and v >= len(names) for v in outcome):
            self.add(path + ("outcome",), f"an outcome beyond the {len(names)} named in 'outcomes'")
        if value.get("kind") not in ("base", "spot", None):
            self.add(path + ("kind",), "expected 'base' or 'spot'")

    def place_number(self, value: Any, path: Path) -> None:
        if not _is_number(value) or abs(value) > MAX_MAGNITUDE:
            self.add(path, f"expected a number between {-MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g}")

    def spacing(self, value: Any, path: Path) -> None:
        if not _is_number(value) or not 0 < value <= 1:
            self.add(path, "expected a spacing in metres, above 0 and at most 1")

    def millimetres(self, value: Any, path: Path) -> None:
        if not (isinstance(value, list) and len(value) <= 2 * MAX_CANDIDATES and all(
                isinstance(v, int) and not isinstance(v, bool) and abs(v) <= 32767 for v in value)):
            self.add(path, f"expected at most {2 * MAX_CANDIDATES} whole numbers of millimetres, each at most 32767 in size")

    def outcome_indices(self, value: Any, path: Path) -> None:
        if not (isinstance(value, list) and len(value) <= MAX_CANDIDATES and all(
                isinstance(v, int) and not isinstance(v, bool) and 0 <= v < 256 for v in value)):
            self.add(path, f"expected at most {MAX_CANDIDATES} whole numbers from 0 to 255")

    def names(self, value: Any, path: Path) -> None:
        if not (isinstance(value, list) and len(value) <= 256 and all(isinstance(v, str) for v in value)):
            self.add(path, "expected a list of at most 256 strings")

    def reasons(self, value: Any, path: Path) -> None:
        if not (isinstance(value, dict) and all(isinstance(v, str) for v in value.values())):
            self.add(path, "expected an object of strings")

    def found_poses(self, value: Any, path: Path) -> None:
        if not (isinstance(value, list) and all(isinstance(f, list) and len(f) == 3 and all(_is_number(v) for v in f)
                                                for f in value)):
            self.add(path, "expected a list of poses [x, y, yaw]")

    def physics_frames(self, value: Any, path: Path) -> None:
        if self.typed(value, path, list, "a list of physics frames") and len(value) > MAX_PHYSICS_FRAMES:
            self.add(path, f"more than {MAX_PHYSICS_FRAMES} physics frames (a step records at most that many)")

    def seconds(self, value: Any, path: Path) -> None:
        if not _is_number(value) or not 0 <= value <= MAX_MAGNITUDE:
            self.add(path, f"expected a number of seconds from 0 to {MAX_MAGNITUDE:g}")

    def known_object(self, name: str, path: Path, objects: set[str] | None) -> bool:
        if objects is not None and name not in objects:
            self.add(path, f"no object '{name}' in the trace's final state")
            return False
        return True

    def body_state(self, entry: Any, path: Path, what: str, full: bool) -> None:
        """A pose (position and orientation, together) and joint values: all there (`full`) or what changed."""
        if not self.fields(entry, path, what, {"position": self.place, "orientation": self.rotation} if full else {},
                           {"position": self.place, "orientation": self.rotation, "joints": self.joint_values}):
            return
        if not full and ("position" in entry) != ("orientation" in entry):
            self.add(path, f"{what} needs 'position' and 'orientation' together")

    def place(self, value: Any, path: Path) -> None:
        if not (isinstance(value, list) and len(value) == 3 and all(_is_number(v) for v in value)):
            self.add(path, "expected a position: a list of 3 numbers")
        elif any(abs(v) > MAX_MAGNITUDE for v in value):
            self.add(path, f"numbers must be between {-MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g}")

    def rotation(self, value: Any, path: Path) -> None:
        if not (isinstance(value, list) and len(value) == 4 and all(_is_number(v) for v in value)):
            self.add(path, "expected an orientation: a quaternion of 4 numbers")
        elif abs(math.sqrt(sum(v * v for v in value)) - 1.0) > 1e-3:
            self.add(path, "expected a quaternion of unit length")

    def joint_values(self, value: Any, path: Path) -> None:
        if not self.typed(value, path, dict, "an object of joint values"):
            return
        for joint, position in value.items():
            if not _is_number(position):
                self.add(path + (joint,), f"expected a number, got {_kind(position)}")
            elif abs(position) > MAX_MAGNITUDE:
                self.add(path + (joint,), f"numbers must be between {-MAX_MAGNITUDE:g} and {MAX_MAGNITUDE:g}")


def _non_finite_and_depth(data: Any, checker: _Checker) -> None:
    """Every NonFinite number, and nesting beyond the limit, anywhere in the data (no recursion)."""
    stack: list[tuple[Any, Path, int]] = [(data, (), 1)]
    while stack and len(checker.problems) < MAX_PROBLEMS:
        value, path, depth = stack.pop()
        if isinstance(value, NonFinite):
            checker.add(path, f"not a finite number: {value.text}")
        elif isinstance(value, (dict, list)):
            if depth > MAX_JSON_DEPTH:
                checker.add(path, f"nested deeper than {MAX_JSON_DEPTH} levels (the limit)")
                continue
            items = value.items() if isinstance(value, dict) else enumerate(value)
            stack.extend((item, path + (key,), depth + 1) for key, item in items)


def problems(data: Any, replay: bool = False) -> list[Problem]:
    """Every problem of a parsed trace against the schema (empty when it is a well-formed trace).

    The replay record's form is always checked; with `replay` (it is to be replayed: a report) also that
    its steps are steps of the tree and its objects those of the final state."""
    checker = _Checker()
    _non_finite_and_depth(data, checker)
    if checker.problems:
        return checker.problems
    if not isinstance(data, dict) or data.get("format") != "pycram-trace" or "root" not in data:
        return [((), "not a pycram trace (expected a JSON object with \"format\": \"pycram-trace\" and a \"root\")")]
    checker.fields(data, (), "a trace", {"version": checker.count, "root": lambda v, p: None},
                   {"plan": checker.string_or_null, "world": checker.string_or_null, "params": checker.obj,
                    "status": checker.status(RUN_STATUSES), "failure": checker.failure,
                    "final_state": checker.final_state, "timing": checker.timing, "interrupted": checker.obj})
    pending: list[tuple[Any, Path, int]] = [(data["root"], ("root",), 1)]
    while pending and len(checker.problems) < MAX_PROBLEMS:
        value, path, depth = pending.pop()
        pending.extend(reversed(checker.node(value, path, depth)))
    if "replay" in data and not checker.problems:  # its steps are checked against the tree's
        final = data.get("final_state")
        objects = final.get("objects") if isinstance(final, dict) else None
        checker.replay(data["replay"], ("replay",), set(objects) if isinstance(objects, dict) else None, replay)
    return checker.problems[:MAX_PROBLEMS]


# -- where a value is in the text ---------------------------------------------------------------------

_DECODER = json.JSONDecoder(parse_constant=lambda text: None)
_SPACE = " \t\n\r"


def offset_of(text: str, path: Path) -> int:
    """The offset in `text` (JSON) where the value at `path` starts; as deep as the path can be followed."""
    index = _skip(text, 0)
    for part in path:
        inner = _enter(text, index, part)
        if inner is None:
            break
        index = inner
    return index


def _skip(text: str, index: int) -> int:
    while index < len(text) and text[index] in _SPACE:
        index += 1
    return index


def _enter(text: str, index: int, part: Any) -> int | None:
    """The start of the member `part` of the object or list starting at `index`, or None."""
    if index >= len(text) or text[index] not in "{[":
        return None
    is_object = text[index] == "{"
    index = _skip(text, index + 1)
    position = 0
    try:
        while index < len(text) and text[index] not in "}]":
            if is_object:
                key, index = json.decoder.scanstring(text, index + 1)  # type: ignore[attr-defined]  # public, not in typeshed
                index = _skip(text, index)
                index = _skip(text, index + 1)  # the colon
                if key == part:
                    return index
            elif position == part:
                return index
            _, index = _DECODER.raw_decode(text, index)
            index = _skip(text, index)
            if index < len(text) and text[index] == ",":
                index = _skip(text, index + 1)
            position += 1
    except (ValueError, RecursionError):
        return None
    return None


def location(text: str, filename: str, path: Path) -> Location:
    return _place(text, filename, offset_of(text, path))


def check(data: Any, text: str, filename: str, within: Path = (), replay: bool = False) -> None:
    """Raise every problem of a parsed trace (InputErrors) at its place in the file; `within`: where in
    the file's JSON the trace is (`("trace",)` in the output of `pycram run --json`); `replay`: see `problems`."""
    found = problems(data, replay)
    errors = [InputError(message, location(text, filename, within + path), key=_name(path) if path else None)
              for path, message in found]
    if len(errors) == 1:
        raise errors[0]
    if errors:
        raise InputErrors(errors)
