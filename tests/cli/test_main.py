"""What every pycram command shares: global flags anywhere on the line, quiet mode, JSON errors with --json."""
from __future__ import annotations

import json

from click.testing import CliRunner

from pycram_cli.cli import console
from pycram_cli.cli.main import cli
from pycram_cli import quiet


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def test_verbose_may_follow_the_command():
    try:
        assert run("designators", "moving", "--verbose").exit_code == 0
        assert quiet.is_verbose()
    finally:
        quiet.set_verbose(False)


def test_quiet_leaves_only_the_result():
    try:
        result = run("run", "inspect_counter", "-q")
        assert result.exit_code == 0, result.output
        assert result.stderr == ""
        assert "succeeded" in result.stdout
    finally:
        console.set_quiet(False)


def test_with_json_bad_input_is_a_json_error_object_on_stdout():
    result = run("query", "visible", "botle", "--json")
    assert result.exit_code == 2
    data = json.loads(result.stdout)
    assert data["status"] == "error" and data["exit_code"] == 2
    assert data["errors"] == [{"file": "query visible", "line": None, "column": None, "key": "object",
                               "message": "no object 'botle'", "suggestion": "did you mean 'bottle'?"}]
    assert "did you mean 'bottle'?" in result.stderr  # the diagnostic is still on stderr


def test_json_errors_carry_the_place_in_the_file(tmp_path):
    plan = tmp_path / "p.yaml"
    plan.write_text("body:\n  - movng: {target: [0, 0, 0]}\n")
    data = json.loads(run("run", str(plan), "--json").stdout)
    assert data["errors"][0]["file"] == str(plan) and data["errors"][0]["line"] == 2
    assert data["errors"][0]["suggestion"] == "did you mean 'moving'?"


def test_help_lists_every_command_with_its_own_one_line_help_without_loading_the_simulator():
    import subprocess
    import sys

    import click

    from pycram_cli.cli.main import COMMANDS

    ctx = click.Context(cli)
    for name, (_, _, help_text) in COMMANDS.items():
        assert cli.get_command(ctx, name).get_short_help_str(limit=300) == help_text
    code = ("import sys; from click.testing import CliRunner; from pycram_cli.cli.main import cli; "
            "r = CliRunner().invoke(cli, ['--help']); assert r.exit_code == 0 and 'designators' in r.output; "
            "print(sorted(m for m in ('pybullet', 'numpy') if m in sys.modules))")
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip() == "[]"
