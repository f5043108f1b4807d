"""The README says what a user needs once, and what it says about settings is what pycram does."""
from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.paths import cache_dir

REPO = Path(__file__).resolve().parents[1]
README = (REPO / "README.md").read_text()


def prose(text: str) -> str:
    """The text without its code blocks and tables."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    return "\n".join(line for line in text.splitlines() if not line.lstrip().startswith(("|", "    ")))


def test_the_readme_starts_with_the_two_set_up_commands():
    assert README.splitlines()[2:4] == [
        "    python3 -m venv .venv && . .venv/bin/activate && pip install . && pycram run plans/set_table.yaml",
        "    python3 -m venv .venv && . .venv/bin/activate && pip install '.[test,ray]' && pytest -q",
    ]


def test_no_sentence_of_the_readme_is_said_twice():
    sentences = [" ".join(s.split()) for s in re.split(r"(?<=[.:;])\s+", prose(README))]
    repeated = [s for s, n in Counter(s for s in sentences if len(s) > 40).items() if n > 1]
    assert not repeated


def test_the_readme_names_the_log_levels_the_command_line_has():
    for flag in ("-q", "--quiet", "--verbose"):
        assert f"`{flag}`" in README
        assert flag in CliRunner().invoke(cli, ["--help"]).output
    assert "current folder's `plans/` or `worlds/`" in README  # names resolve locally first


def test_the_cache_folder_is_where_the_readme_says(tmp_path, monkeypatch: pytest.MonkeyPatch):
    assert "`$PYCRAM_CACHE_DIR`" in README and "`$XDG_CACHE_HOME/pycram`" in README and "`~/.cache/pycram`" in README
    monkeypatch.setenv("PYCRAM_CACHE_DIR", str(tmp_path / "mine"))
    assert cache_dir() == tmp_path / "mine"
    monkeypatch.delenv("PYCRAM_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert cache_dir() == tmp_path / "xdg" / "pycram"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert cache_dir() == tmp_path / "home" / ".cache" / "pycram"
