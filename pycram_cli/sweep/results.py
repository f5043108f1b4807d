"""A sweep's folder: `sweep.json` (what was swept) and `results.jsonl` (one outcome per line).

Lines are appended as scenarios finish, each with a single write of the whole line on a file
opened for appending, so an interrupted sweep (Ctrl-C, a killed process) keeps every line it
finished; `--resume` reads them back (a torn last line is dropped) and runs only the rest.
When the sweep completes, the file is rewritten in scenario order (atomically), so the same
sweep gives the same file whatever the number of workers, apart from the `timing` fields.
"""
from __future__ import annotations

import errno
import hashlib
import json
import math
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..errors import InputError, Location, setting
from ..files import probe, read_bytes, reason, write_atomic
from ..limits import MAX_SWEEP_META_BYTES, MAX_SWEEP_RESULTS_BYTES, MAX_SWEEP_RUNS

RESULTS = "results.jsonl"
META = "sweep.json"
#: settings that may change between a sweep and its resumption
FREE = ("n", "timeout", "workers", "backend")


def file_digest(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]


def key_of(record: dict[str, Any], alternatives: list[dict[str, Any]] | None) -> tuple[int, int]:
    alt = 0
    if alternatives and "alternative" in record:
        alt = alternatives.index(record["alternative"]) if record["alternative"] in alternatives else -1
    return (int(record["index"]), alt)


def _not_a_number(constant: str) -> Any:
    raise ValueError(f"{constant} is not a number JSON allows")


def _json_reason(exc: BaseException) -> str:
    return "nested too deeply" if isinstance(exc, RecursionError) else str(exc).split(":")[0]


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _is_text(value: Any) -> bool:
    return value is None or isinstance(value, str)


def _kind(value: Any) -> str:
    return {dict: "an object", list: "a list", str: "text", bool: "true or false", type(None): "null"}.get(
        type(value), "a number")


def record_problem(record: Any, alternatives: list[Any] | None) -> str | None:
    """Why a line of results.jsonl is not an outcome a sweep writes (see worker.outcome), or None."""
    if not isinstance(record, dict):
        return f"expected a JSON object (a scenario's outcome), got {_kind(record)}"
    for key in ("index", "seed", "status"):
        if key not in record:
            return f"the outcome has no '{key}'"
    if not _is_int(record["index"]) or not 0 <= record["index"] < MAX_SWEEP_RUNS:
        return f"'index' must be a whole number from 0 to {MAX_SWEEP_RUNS - 1}, got {_kind(record['index'])}"
    if not _is_int(record["seed"]):
        return f"'seed' must be a whole number, got {_kind(record['seed'])}"
    if not isinstance(record["status"], str) or not record["status"]:
        return f"'status' must be a name, got {_kind(record['status'])}"
    failure = record.get("failure")
    if failure is not None and (not isinstance(failure, dict)
                                or not all(_is_text(failure.get(k)) for k in ("type", "message", "path"))):
        return "'failure' must be null or an object of type, message and path (text)"
    if alternatives is None and "alternative" in record:
        return "'alternative' is given, but this sweep compares no alternatives"
    if alternatives is not None and record.get("alternative") not in alternatives:
        return f"'alternative' must be one of the sweep's {setting('compare')} values"
    return _varied_problem(record.get("varied"))


def _varied_problem(varied: Any) -> str | None:
    if varied is None:
        return None
    if not isinstance(varied, dict) or not all(isinstance(v, dict) for v in varied.values()):
        return "'varied' must be an object of object name to what was varied"
    for name, change in varied.items():
        position = change.get("position")
        if position is not None and not (isinstance(position, list) and len(position) == 3 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in position)):
            return f"'varied.{name}.position' must be three finite numbers"
    return None


class ResultsFile:
    """The results of one sweep in `folder`; `done` holds the outcomes already there (by task key)."""

    def __init__(self, folder: Path, meta: dict[str, Any], resume: bool, force: bool = False) -> None:
        self.folder = Path(folder)
        self.path = self.folder / RESULTS
        self.meta_path = self.folder / META
        self.meta = meta
        self.alternatives = meta.get("compare", {}).get("alternatives") if meta.get("compare") else None
        self.done: dict[tuple[int, int], dict[str, Any]] = {}
        self._fd = -1
        try:  # the folder is the user's: any operating-system problem with it is an input error naming `out`
            self.folder.mkdir(parents=True, exist_ok=True)
            for path in (self.meta_path, self.path):  # a named pipe would block, a device be read without end
                problem = probe(path)
                if problem is not None and problem != "not found":
                    raise InputError(f"cannot use it as part of the results folder: {problem}", Location(str(path)),
                                     suggestion=f"give another {setting('out')}")
            existing = self.path.is_file() and self.path.stat().st_size > 0
            if existing and force:  # asked for: the sweep starts again, its earlier results replaced
                self.path.unlink()
                existing = False
            if existing and not resume:
                raise InputError(f"{self.path} holds the results of a sweep already", Location(setting("out")),
                                 suggestion=f"add {setting('resume')} to go on with it, {setting('force')} to run it again "
                                            f"from the start (its results are replaced), or give another {setting('out')}")
            if existing:
                self._check_same_sweep()
                self._load()
            write_atomic(self.meta_path, json.dumps(meta, indent=2) + "\n", key=setting("out"))
            self._fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        except OSError as exc:
            why = "it cannot be made there" if exc.errno == errno.ENOENT else reason(exc)
            raise InputError(f"cannot use '{self.folder}' as the results folder: {why}", Location(setting("out")),
                             suggestion=f"give {setting('out')} a folder that can be made and written") from None
        except ValueError:  # a NUL character in the name
            raise InputError("cannot use the results folder: its name contains a NUL character",
                             Location(setting("out"))) from None

    def _check_same_sweep(self) -> None:
        if probe(self.meta_path) == "not found":
            raise InputError(f"cannot resume: {self.meta_path} is missing", Location(setting("resume")))
        text = read_bytes(self.meta_path, MAX_SWEEP_META_BYTES, "the sweep's settings")
        try:
            before = json.loads(text, parse_constant=_not_a_number)
        except (ValueError, RecursionError) as exc:
            raise InputError(f"cannot resume: not the JSON a sweep writes ({_json_reason(exc)})",
                             Location(str(self.meta_path))) from None
        if not isinstance(before, dict):
            raise InputError("cannot resume: not the settings a sweep writes (expected a JSON object)",
                             Location(str(self.meta_path)))
        differ = sorted(k for k in set(before) | set(self.meta) if k not in FREE and before.get(k) != self.meta.get(k))
        if differ:
            raise InputError(f"cannot resume: this sweep differs from the one in {self.folder} in "
                             + ", ".join(differ), Location(setting("resume")),
                             suggestion=f"run it with the same plan, world, variations, seed and {setting('compare')}, "
                                        f"or give another {setting('out')}")

    def _load(self) -> None:
        """The outcomes already in the file; a damaged line is an InputError at its line (never dropped), only a
        last line torn by an interruption is (that scenario runs again)."""
        text = read_bytes(self.path, MAX_SWEEP_RESULTS_BYTES, "the sweep's results").decode(errors="replace")
        kept: list[str] = []
        for number, line in enumerate(text.splitlines(keepends=True), start=1):
            if not line.endswith("\n"):
                continue  # torn by an interruption: that scenario runs again
            kept.append(line)
            if not line.strip():
                continue
            record = self._record(line, Location(str(self.path), number, 1))
            self.done[key_of(record, self.alternatives)] = record
        if "".join(kept) != text:
            write_atomic(self.path, "".join(kept), key=setting("out"))

    def _record(self, line: str, where: Location) -> dict[str, Any]:
        """One line's outcome, checked to be what a sweep writes (InputError at the line otherwise)."""
        try:
            record = json.loads(line, parse_constant=_not_a_number)
        except RecursionError:
            record = []  # lists or mappings nested thousands deep: not an outcome either
        except ValueError as exc:
            raise InputError(f"not JSON ({_json_reason(exc)}): a damaged line of the sweep's results", where,
                             suggestion=f"remove or repair the line, then {setting('resume')} again") from None
        problem = record_problem(record, self.alternatives)
        if problem is not None:
            raise InputError(f"{problem}: a damaged line of the sweep's results", where,
                             suggestion=f"remove or repair the line, then {setting('resume')} again")
        return record

    def append(self, record: dict[str, Any]) -> None:
        self.done[key_of(record, self.alternatives)] = record
        os.write(self._fd, (json.dumps(record, sort_keys=False, separators=(", ", ": ")) + "\n").encode())

    def records(self) -> list[dict[str, Any]]:
        return [self.done[k] for k in sorted(self.done)]

    def finish(self, keys: Iterable[tuple[int, int]] | None = None) -> None:
        """Rewrite the file in scenario order (only when every task of the sweep is in it)."""
        self.close()
        if keys is not None and not set(keys) <= set(self.done):
            return
        lines = [json.dumps(r, sort_keys=False, separators=(", ", ": ")) + "\n" for r in self.records()]
        write_atomic(self.path, "".join(lines), key=setting("out"))  # a temporary file of its own: two sweeps never share it

    def close(self) -> None:
        if self._fd >= 0:
            os.close(self._fd)
            self._fd = -1

