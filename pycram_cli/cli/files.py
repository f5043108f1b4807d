"""The files commands write (traces, images, reports): checked before any work, written in one place.

`check_output` runs when a command starts, so a missing folder or an unknown image type is
reported at once (exit 2, the file named) instead of after a whole plan has run.
`write_output` is the one function that puts bytes on disk and says so on stderr.
"""
from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .. import interrupts
from ..errors import InputError, Location
from ..files import check_writable, reason, write_atomic
from ..report import MCAP_FORMATS, REPORT_FORMATS, build_mcap, build_report
from . import console

__all__ = ["MCAP_FORMATS", "PLOT_FORMATS", "REPORT_FORMATS", "check_output", "check_outputs", "check_plot", "distinct_outputs",
           "same_file", "write_mcap", "write_output", "write_report"]

#: the maps `locate --plot` and `sweep --plot` draw
PLOT_FORMATS = {".png": "PNG"}


def check_output(path: Path, kinds: dict[str, str] | None = None, what: str = "file") -> None:
    """`path` can be written: it is not a folder, its folder exists (a missing folder is an input error,
    never made silently), and (with `kinds`, extension -> format) its extension names a format we write."""
    where = Location(str(path))
    folder = path.parent if str(path.parent) else Path(".")
    try:  # probing a path can fail too: a name too long, a folder on the way that cannot be searched
        if path.is_dir():
            raise InputError(f"is a folder, expected a {what} to write", where)
        if not folder.exists():
            raise InputError(f"cannot write the {what}: folder '{folder}' does not exist", where)
        if not folder.is_dir():
            raise InputError(f"cannot write the {what}: '{folder}' is not a folder", where)
    except OSError as exc:
        raise InputError(f"cannot write the {what}: {reason(exc)}", where) from None
    except ValueError:  # a NUL character in the name
        raise InputError(f"cannot write the {what}: the file name contains a NUL character", where) from None
    if kinds is not None and path.suffix.lower() not in kinds:
        known = ", ".join(sorted(kinds))
        got = f"'{path.suffix}'" if path.suffix else "no extension"
        raise InputError(f"cannot tell the {what}'s format from {got} (expected {known})", where)


def check_outputs(items: Iterable[tuple[Path | None, dict[str, str] | None, str]]) -> None:
    """`check_output` for each (path, kinds, what) whose path is given."""
    for path, kinds, what in items:
        if path is not None:
            check_output(path, kinds, what)


def check_plot(path: Path | None) -> None:
    """`--plot FILE` of `locate` and `sweep`, checked like every other output before any work: a PNG file whose
    folder exists (a missing folder is refused, never made) and that can be written."""
    if path is not None:
        check_output(path, PLOT_FORMATS, "plot")
        check_writable(path, "plot")


def same_file(first: Path, second: Path) -> bool:
    """Whether two paths name one file: the same after links and `.`/`..` are followed, or one file twice."""
    try:
        if os.path.realpath(first) == os.path.realpath(second):
            return True
        return first.exists() and second.exists() and os.path.samefile(first, second)
    except (OSError, ValueError):
        return False


def distinct_outputs(items: Iterable[tuple[Path | None, str]]) -> None:
    """InputError when two of the outputs given (path, what) name the same file: one would silently replace the other."""
    given = [(Path(path), what) for path, what in items if path is not None]
    for index, (path, what) in enumerate(given):
        for earlier, earlier_what in given[:index]:
            if same_file(earlier, path):
                raise InputError(f"the {earlier_what} and the {what} name the same file: give each its own",
                                 Location(str(path)))


def write_output(path: Path, data: bytes | str, what: str) -> None:
    """Write `data` to `path` (its folder must exist) and report it on stderr: `wrote PATH (WHAT)`."""
    try:
        folder_there = Path(path).parent.is_dir()
    except (OSError, ValueError):
        folder_there = True  # write_atomic says what is wrong
    if not folder_there:
        raise InputError("cannot write the file: its folder does not exist", Location(str(path)))
    write_atomic(path, data)  # a temporary file renamed over it: readers see the old or the new file, never a part
    interrupts.paid(str(path))
    console.info(f"wrote {path} ({what})")


def write_report(path: Path, trace: dict[str, Any], world_path: Path) -> None:
    """Build the replay report of a run (see pycram_cli/report) and write it."""
    page = build_report(trace, world_path)
    size = len(page.encode())
    write_output(path, page, f"replay report, {size / 1e6:.1f} MB" if size >= 1e5 else f"replay report, {size // 1000} kB")


def write_mcap(path: Path, trace: dict[str, Any], world_path: Path) -> None:
    """Write the run's replay as an MCAP file for Foxglove (see pycram_cli/report/foxglove.py)."""
    data = build_mcap(trace, world_path)
    size = len(data)
    write_output(path, data, f"MCAP replay, {size / 1e6:.1f} MB" if size >= 1e5 else f"MCAP replay, {size // 1000} kB")
