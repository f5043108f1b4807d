"""`pycram designators`: a table on a terminal; piped, one field a line, as `pycram plans` and `pycram worlds` print."""
from __future__ import annotations

from click.testing import CliRunner

from pycram_cli.cli.main import cli


def test_piped_output_is_one_field_a_line():
    result = CliRunner().invoke(cli, ["designators", "pick-up", "--motions"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[:3] == [
        "pick-up — Grasp an object with an arm and attach it to the gripper's tool frame.",
        "  object  required: the object to pick up",
        "    value: an object name (or a $variable bound to an object)",
    ]
    assert "    default: an arm that can reach the object (in the description's order)" in lines
    assert max(len(line) for line in lines) < 200  # no table as wide as every column together
    assert not any(ch in result.stdout for ch in "┃│┏")


def test_one_of_is_said_under_the_slots():
    result = CliRunner().invoke(cli, ["designators", "detect", "--actions"])
    assert "  give at least one of: object-type, object" in result.stdout.splitlines()
