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
import os
from pathlib import Path
from typing import Any, Iterable

from ..errors import InputError, Location
from ..files import reason, write_atomic

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
        try:  # the folder is the user's: any operating-system problem with it is an input error naming --out
            self.folder.mkdir(parents=True, exist_ok=True)
            existing = self.path.is_file() and self.path.stat().st_size > 0
            if existing and force:  # asked for: the sweep starts again, its earlier results replaced
                self.path.unlink()
                existing = False
            if existing and not resume:
                raise InputError(f"{self.path} holds the results of a sweep already", Location("--out"),
                                 suggestion="add --resume to go on with it, --force to run it again from the start "
                                            "(its results are replaced), or give another --out")
            if existing:
                self._check_same_sweep()
                self._load()
            write_atomic(self.meta_path, json.dumps(meta, indent=2) + "\n", key="--out")
            self._fd = os.open(self.path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        except OSError as exc:
            why = "it cannot be made there" if exc.errno == errno.ENOENT else reason(exc)
            raise InputError(f"cannot use '{self.folder}' as the results folder: {why}", Location("--out"),
                             suggestion="give --out a folder that can be made and written") from None
        except ValueError:  # a NUL character in the name
            raise InputError("cannot use the results folder: its name contains a NUL character",
                             Location("--out")) from None

    def _check_same_sweep(self) -> None:
        try:
            before = json.loads(self.meta_path.read_text())
        except (OSError, ValueError):
            raise InputError(f"cannot resume: {self.meta_path} is missing or unreadable", Location("--resume")) from None
        differ = sorted(k for k in set(before) | set(self.meta) if k not in FREE and before.get(k) != self.meta.get(k))
        if differ:
            raise InputError(f"cannot resume: this sweep differs from the one in {self.folder} in "
                             + ", ".join(differ), Location("--resume"),
                             suggestion="run it with the same plan, world, variations, seed and --compare, "
                                        "or give another --out")

    def _load(self) -> None:
        text = self.path.read_bytes().decode(errors="replace")
        kept: list[str] = []
        for line in text.splitlines(keepends=True):
            if not line.endswith("\n"):
                continue  # torn by an interruption: that scenario runs again
            try:
                record = json.loads(line)
            except ValueError:
                continue
            self.done[key_of(record, self.alternatives)] = record
            kept.append(line)
        if "".join(kept) != text:
            write_atomic(self.path, "".join(kept), key="--out")

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
        write_atomic(self.path, "".join(lines), key="--out")  # a temporary file of its own: two sweeps never share it

    def close(self) -> None:
        if self._fd >= 0:
            os.close(self._fd)
            self._fd = -1

