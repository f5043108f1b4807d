"""Every command excerpt in README.md and docs/ (a `$ pycram ...` line and the output below it) is what today's code
prints: each is run, in a fresh folder that sees the checkout's plans/ and worlds/, and its output compared line by line.

How an excerpt is read:

* each output line must appear in the command's output (stdout and stderr together), in order; lines between
  them may be left out, and a line `...` says so outright;
* `...` (or `…`) inside a line stands for any text; at its end, for the rest of the line;
* a comment after two or more spaces (`   # exit code 2`) is the reader's, not pycram's;
* timings (a number of seconds, `0.75 s`, or milliseconds) stand for any number: they vary from machine to machine;
  every other number must be as shown;
* tables are compared by their cells (the box-drawing lines a terminal shows may be left out);
* output after `--json` is compared with the JSON's one-line form, `{...}` standing for any value.

Commands that cannot run here are listed in SKIPPED with the reason (files only the reader has, a window, a sweep
of 200 scenarios whose figures the README's *Sweeps* section keeps by hand).
"""
from __future__ import annotations

import json
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli

REPO = Path(__file__).resolve().parents[1]
DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]

#: commands not run here, by a text they contain, and why
SKIPPED = {
    "pycram sweep set_table -n 200": "200 scenarios take minutes; the figures are the Sweeps section's own",
    "my_plan.yaml": "a file of the reader's",
    "out.json": "a file of the reader's",
    "a.json b.json": "files of the reader's",
    "head -1": "not a pycram command",
    "--gui": "needs a display",
    "python -m pycram_cli.scenario.golden": "rewrites the golden traces",
    "/tmp/zoo": "robots the reader generates with the zoo (tests/robots/test_zoo_runs.py runs zoo robots)",
}
TIMING = r"-?\d+(?:\.\d+)?"
BOX = str.maketrans({c: " " for c in "│┃║"})


@dataclass
class Excerpt:
    doc: str
    line: int
    command: str
    expected: list[str] = field(default_factory=list)

    @property
    def id(self) -> str:
        return f"{self.doc}:{self.line}"


def excerpts() -> list[Excerpt]:
    """Every `$ ` line of a code block in the docs, with the output lines below it."""
    found: list[Excerpt] = []
    for path in DOCS:
        lines = path.read_text().splitlines()
        inside = False
        current: Excerpt | None = None
        for number, line in enumerate(lines, 1):
            if line.startswith("```"):
                inside, current = not inside, None
                continue
            if not inside:
                continue
            if line.startswith("$ "):
                current = Excerpt(path.name, number, line[2:])
                found.append(current)
            elif current is not None:
                current.expected.append(line)
    return found


def without_comment(line: str) -> str:
    return re.sub(r"\s{2,}#(?!\d).*$", "", line).rstrip()


def skipped(command: str) -> str | None:
    return next((why for text, why in SKIPPED.items() if text in command), None)


def normalised(line: str) -> str:
    """A line as compared: table borders, tree branches and runs of spaces gone."""
    return " ".join(line.translate(BOX).replace("├──", " ").replace("└──", " ").split())


@dataclass
class Expected:
    """An expected line as a regular expression; the numbers it shows (not timings), each matched by a group."""

    regex: re.Pattern[str]
    numbers: list[float]

    def matches(self, text: str, prefix: bool = False) -> bool:
        found = self.regex.match(text) if prefix else self.regex.fullmatch(text)
        if found is None:
            return False
        got = [float(value) for value in found.groups()]
        return all(abs(a - b) <= NUMBER_TOLERANCE * max(1.0, abs(b)) for a, b in zip(got, self.numbers))


#: numbers (other than timings) may differ this much, relatively (floating point on another machine)
NUMBER_TOLERANCE = 1e-3
NUMBER = r"(?<![\w.])-?\d+(?:\.\d+)?(?![\w.])"


def pattern(line: str) -> Expected:
    """What an expected line stands for (see the module's docstring)."""
    parts = re.split(r"(\.\.\.|…|\{\.\.\.\})", normalised(line))
    regex, numbers = "", []
    for part in parts:
        if part in ("...", "…", "{...}"):
            regex += ".*"
            continue
        pieces = re.split(f"({NUMBER})", part)
        for index, piece in enumerate(pieces):
            if index % 2 == 0:
                regex += re.escape(piece)
            elif re.match(r" ?(?:s|ms)\b", pieces[index + 1]):  # a timing: any number
                regex += TIMING
            else:
                regex += f"({TIMING})"
                numbers.append(float(piece))
    return Expected(re.compile(regex), numbers)


def run(command: str, folder: Path) -> str:
    """Run one line of pycram commands (`a && b`, `2>&1 | cat`) in `folder`; their output, stdout and stderr."""
    output = []
    for part in command.split("&&"):
        words = shlex.split(part.replace("2>&1 | cat", ""))
        assert words[0] == "pycram", f"not a pycram command: {part}"
        result = CliRunner().invoke(cli, words[1:], catch_exceptions=False)
        output.append(result.output)
        if result.exit_code not in (0, 1, 2):
            raise AssertionError(f"{part}: exit {result.exit_code}\n{result.output}")
    return "\n".join(output)


def check(excerpt: Excerpt, output: str) -> None:
    expected = [without_comment(line) for line in excerpt.expected]
    expected = [line for line in expected if line and line != "..."]
    if "--json" in excerpt.command and expected and expected[0].startswith("{"):
        data = json.loads(output[output.index("{"):])
        compact = json.dumps(data, ensure_ascii=False)
        for line in expected:
            assert pattern(line).matches(compact, prefix=True), f"{excerpt.id}: $ {excerpt.command}\n  expected: {line}\n  got: {compact[:600]}"
        return
    actual = [normalised(line) for line in output.splitlines()]
    at, number = 0, 0
    while number < len(expected):
        # a line the docs wrap goes on in the next expected line (a long failure message)
        candidates = [(expected[number], 1)] + ([(f"{expected[number]} {expected[number + 1]}", 2)]
                                                if number + 1 < len(expected) else [])
        for index in range(at, len(actual)):
            hit = next((used for line, used in candidates if pattern(line).matches(
                actual[index], prefix=line.endswith(("...", "…")))), None)
            if hit:
                at, number = index + 1, number + hit
                break
        else:
            raise AssertionError(f"{excerpt.id}: $ {excerpt.command}\n  expected (in order): {expected[number]}\n"
                                 f"  got:\n" + "\n".join(f"    {a}" for a in actual[at:]))


ALL = excerpts()


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    for name in ("plans", "worlds"):
        (tmp_path / name).symlink_to(REPO / name)
    (tmp_path / "docs").mkdir()
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_docs_have_command_excerpts_to_check():
    runnable = [e for e in ALL if not skipped(e.command)]
    assert len(runnable) >= 25 and any(e.doc == "plans.md" for e in runnable)


@pytest.mark.parametrize("excerpt", [e for e in ALL if not skipped(e.command)], ids=lambda e: e.id)
def test_each_command_excerpt_prints_what_the_docs_show(excerpt: Excerpt, folder: Path):
    check(excerpt, run(without_comment(excerpt.command), folder))


@pytest.mark.parametrize("line, text, matches", [
    ("plan set_table.yaml succeeded in 0.75 s (67 steps)", "plan set_table.yaml succeeded in 4.69 s (67 steps)", True),
    ("plan set_table.yaml succeeded in 0.75 s (67 steps)", "plan set_table.yaml succeeded in 0.75 s (68 steps)", False),
    ("│ 1 │ 0.750 │ 1.150 │ 5°  │ right │ front │ 0.227 │", "│ 1 │ 0.750 │ 1.150 │ 5°  │ right │ top   │ 0.227 │", False),
    ("│ 1 │ 0.750 │ 1.150 │ 5°  │ right │ top │ 0.227 │", "│ 1 │ 0.750 │ 1.150 │ 5°  │ right │ top   │ 0.227 │", True),
    ("info: running .../plans/x.yaml on ...", "info: running /a/b/plans/x.yaml on /a/worlds/k.yaml", True),
    ("target=[1.3, 0.999999, 0.961]", "target=[1.299997, 1.0, 0.96099]", True),
    ("target=[1.3, 0.99, 0.961]", "target=[1.299997, 1.0, 0.96099]", False),
    ("├── ✓ 0:pick-up  arm=right", "│   │   ├── ✓ 0:pick-up  arm=right", True),
])
def test_how_an_expected_line_is_compared(line: str, text: str, matches: bool):
    assert pattern(line).matches(normalised(text)) is matches
