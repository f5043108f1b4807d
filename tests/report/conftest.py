"""The runs the report tests read, each made once per test process (session scope) instead of once per module:
set_table (A), the README's failing example (B, the milk placed over the island's edge) and set_table_actions, each
with its replay report and its trace. The tests only read the files; what they write goes to their own tmp_path."""
from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli

#: the README's failing example: set_table's milk job with the target 1.7 cm beyond the island's edge
FAILING = "jobs=[{type: milk, target: [-0.65, 1.0, 0.862], arm: left, look: [1.3, 0.8, 0.95]}]"


def _run(folder: Path, code: int, *args: str) -> tuple[Path, Path]:
    """`pycram run ARGS --report run.html --trace run.json` in `folder`: the report and the trace."""
    report, trace = folder / "run.html", folder / "run.json"
    result = CliRunner().invoke(cli, ["run", *args, "--report", str(report), "--trace", str(trace)])
    assert result.exit_code == code, result.output
    assert f"wrote {report} (replay report" in result.stderr
    return report, trace


@pytest.fixture(scope="session")
def set_table_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """set_table as it is: its report and its trace."""
    return _run(tmp_path_factory.mktemp("set_table"), 0, "set_table")


@pytest.fixture(scope="session")
def failed_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """set_table with the milk over the island's edge (exit 1, a ReasoningFailure): its report and its trace."""
    return _run(tmp_path_factory.mktemp("failed"), 1, "set_table", "-p", FAILING)


@pytest.fixture(scope="session")
def actions_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """set_table_actions (locate steps with candidate maps, looking steps with view cones): report and trace."""
    return _run(tmp_path_factory.mktemp("actions"), 0, "set_table_actions")
