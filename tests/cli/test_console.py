"""User text in coloured output is shown as it is (issue 29): file names and values with rich markup in them
(`[/].yaml`, `[bold]`, a trailing backslash) are never read as markup, lost or changed."""
from __future__ import annotations

import io
import re

import pytest
from rich.console import Console

from pycram_cli.cli import console

ODD = ["/tmp/[/].yaml:2:5: lgo: unknown", "a [bold]b[/bold] c", "C:\\dir\\", "x \\[/] y", "[link=http://x]y[/link]"]


def coloured(monkeypatch: pytest.MonkeyPatch) -> tuple[io.StringIO, io.StringIO]:
    streams = io.StringIO(), io.StringIO()
    for name, stream in zip(("out", "err"), streams):
        monkeypatch.setattr(console, name, Console(file=stream, force_terminal=True, highlight=False, soft_wrap=True,
                                                   emoji=False, width=200))
    return streams


def plain(text: str) -> str:
    return re.sub(r"\x1b\[[0-9;]*m", "", text)


@pytest.mark.parametrize("text", ODD)
def test_messages_show_user_text_as_it_is_in_colour(monkeypatch, text):
    out, err = coloured(monkeypatch)
    console.error(text)
    console.warning(text)
    console.info(text)
    console.success(text)
    assert plain(err.getvalue()).splitlines() == [f"error: {text}", f"warning: {text}", f"info: {text}"]
    assert plain(out.getvalue()).splitlines() == [f"✓ {text}"]


def test_table_cells_show_user_text_as_it_is(monkeypatch):
    out, _ = coloured(monkeypatch)
    console.table(None, ["name"], [[text] for text in ODD])
    shown = plain(out.getvalue())
    for text in ODD:
        assert re.search(re.escape(text) + r" *│", shown), shown
