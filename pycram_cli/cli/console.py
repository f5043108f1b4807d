"""The one place that owns terminal output.

Results go to stdout, diagnostics (info, warnings, errors) to stderr; colours only on a
terminal; `emit_json` writes machine output to stdout with nothing else mixed in.
"""
from __future__ import annotations

import json
import shutil
import sys
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from rich.console import Console
from rich.table import Table
from rich.text import Text

from ..errors import InputError
from ..jsonable import jsonable
from ..paths import Found, available

# Piped output is not cut to 80 columns: tables stay one row per line for grep and friends.
# No emoji codes: `file:100:3` must not print as `file💯3`.
out = Console(highlight=False, soft_wrap=True, emoji=False, width=None if sys.stdout.isatty() else 240)
err = Console(stderr=True, highlight=False, soft_wrap=True, emoji=False, width=None if sys.stderr.isatty() else 240)


_quiet = False


def set_quiet(value: bool) -> None:
    """`-q`: only results and errors (no info lines, no progress views)."""
    global _quiet
    _quiet = value


def is_quiet() -> bool:
    return _quiet


def _diagnostic(label: str, style: str, message: str) -> None:
    """`label: message` on stderr, the label coloured on a terminal."""
    if err.is_terminal:
        err.print(_labelled(label, style, message))
    else:
        err.print(f"{label}: {message}", markup=False)


def info(message: str) -> None:
    if not _quiet:
        _diagnostic("info", "cyan", message)


def warning(message: str) -> None:
    _diagnostic("warning", "yellow", message)


def error(message: str) -> None:
    _diagnostic("error", "bold red", message)


def success(message: str) -> None:
    if out.is_terminal:
        out.print(_labelled("✓", "bold green", message, ""))
    else:
        out.print(message, markup=False)


def show_found(kind: str, entry: Callable[[Found], dict[str, Any]], as_json: bool, columns: Sequence[str],
               cells: Callable[[dict[str, Any]], Sequence[str]], lines: Callable[[dict[str, Any]], list[str]]) -> None:
    """List the plans or worlds (`kind`) a name can mean as `pycram plans` and `pycram worlds` do: each `paths.Found`
    and its `entry`; with --json the entries, else a table on a terminal (name, origin, then `cells(entry)`), else a
    line a name with `lines(entry)` indented below it."""
    found = available(kind)
    entries = [entry(item) for item in found]
    if as_json:
        emit_json(entries)
    elif out.is_terminal:
        table(f"{len(entries)} {kind}", ["name", "from", *columns],
              [(e["name"], f.origin.replace("  ", "\n", 1), *cells(e)) for f, e in zip(found, entries)])
    else:
        for f, e in zip(found, entries):
            plain(f"{e['name']}  {f.origin}")
            for line in lines(e):
                plain(f"  {line}")


def input_errors(errors: Sequence[InputError]) -> None:
    for problem in errors:
        error(problem.format())
    if len(errors) > 1:
        err.print(f"{len(errors)} problems found", markup=False)


def table(title: str | None, columns: Sequence[str], rows: Iterable[Sequence[Any]]) -> None:
    """A table of plain text: every cell is plain Text, so `[x, y, z]` is shown, not taken for markup."""
    grid = Table(title=Text(title) if title else None, show_lines=False, header_style="bold")
    for column in columns:
        grid.add_column(Text(column), overflow="fold")
    for row in rows:
        grid.add_row(*(Text(str(c)) for c in row))
    out.print(grid)


def text_width(limit: int = 100) -> int:
    """The width to fold text at: the terminal's (when stdout is not one: COLUMNS, else `limit`), at most `limit`."""
    columns = out.width if out.is_terminal else shutil.get_terminal_size((limit, 24)).columns
    return max(40, min(columns, limit))


def emit_json(data: Any) -> None:
    """Machine output: strict JSON (a non-finite number becomes null, never a bare NaN)."""
    sys.stdout.write(json.dumps(jsonable(data, digits=None, nonfinite=None), indent=2, sort_keys=False,
                                allow_nan=False) + "\n")
    sys.stdout.flush()


def plain(text: str) -> None:
    out.print(text, markup=False)


def _labelled(label: str, style: str, message: str, colon: str = ":") -> Text:
    """`label: message` with the label styled and the message as plain text (never read as markup: a file named
    `[/].yaml`, a value `[bold]` or a trailing backslash is shown as it is)."""
    return Text.assemble((label, style), f"{colon} ", message)
