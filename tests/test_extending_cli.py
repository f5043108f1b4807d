"""A command written in one module of its own (tests/data/extension/types_cmd.py) plus one `COMMANDS` entry is a
whole command: `pycram --help` lists it, its own `--help` and shell completion know it, it runs, and docs/reference.md's
generator writes its section. No other place of pycram needs to be edited for it."""
from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest
from click.shell_completion import ShellComplete
from click.testing import CliRunner

from pycram_cli.cli import main
from pycram_cli.cli.main import cli
from pycram_cli.cli.reference import render

EXTENSION = Path(__file__).resolve().parent / "data" / "extension" / "types_cmd.py"
MODULE = "pycram_cli.cli.types_cmd"  # where the file would be put in pycram's tree


@pytest.fixture
def types_command(monkeypatch: pytest.MonkeyPatch):
    """The command's module as if it were pycram_cli/cli/types_cmd.py, and its one entry in `COMMANDS`."""
    spec = importlib.util.spec_from_file_location(MODULE, EXTENSION)
    module = importlib.util.module_from_spec(spec)
    monkeypatch.setitem(sys.modules, MODULE, module)
    spec.loader.exec_module(module)
    monkeypatch.setitem(main.COMMANDS, "types", ("types_cmd", "types", module.HELP))
    return module


def run(*args: str):
    return CliRunner().invoke(cli, list(args), prog_name="pycram")


def test_pycram_help_lists_the_new_command_with_its_one_line_help(types_command):
    result = run("--help")
    assert result.exit_code == 0, result.output
    listed = [line.split(None, 1) for line in result.output.splitlines() if line.startswith("  types ")]
    assert listed and listed[0][1].strip() == types_command.HELP


def test_its_own_help_shows_its_usage_and_options(types_command):
    result = run("types", "--help")
    assert result.exit_code == 0, result.output
    assert "Usage: pycram types [OPTIONS]" in result.output and types_command.HELP in result.output
    assert "--at-least N" in result.output and "--world WORLD" in result.output


def test_it_runs_and_its_input_errors_are_pycrams(types_command, tmp_path: Path):
    result = run("types", "--json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["milk"] == 1
    missing = run("types", "--world", str(tmp_path / "nowhere.yaml"))
    assert missing.exit_code == 2 and "Traceback" not in missing.output and "nowhere.yaml" in missing.stderr


def test_shell_completion_offers_it(types_command):
    completions = ShellComplete(cli, {}, "pycram", "_PYCRAM_COMPLETE").get_completions([], "ty")
    assert [c.value for c in completions] == ["types"]
    assert types_command.HELP.startswith(completions[0].help.rstrip("."))  # click shortens it to fit a line


def test_the_generated_reference_has_its_section(types_command):
    reference = render()
    section = reference[reference.index("### `pycram types`"):reference.index("## Motion designators")]
    assert types_command.HELP in section and "    pycram types [OPTIONS]" in section
    assert "| `--at-least N` | Only types with at least N objects.  [default: 1; x>=1] |" in section


def test_without_the_entry_it_is_nowhere():
    assert "types" not in main.COMMANDS
    assert "types" not in run("--help").output.split("Commands:")[1]
    assert run("types").exit_code == 2
    assert "`pycram types`" not in render()
