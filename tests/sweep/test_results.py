"""`sweep --resume` from a damaged results folder (issue 29): every damage is exit 2 naming the file (and the line),
at once — never a hang on a named pipe, a read of /dev/zero, an internal error, or a line silently dropped."""
from __future__ import annotations

import json
import os
import shutil
import textwrap
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from pycram_cli.cli.main import cli


def run(*args: object):
    started = time.monotonic()
    result = CliRunner().invoke(cli, [str(a) for a in args])
    assert time.monotonic() - started < 30
    assert "Traceback" not in result.output and "internal error" not in result.stderr, result.output
    return result


@pytest.fixture(scope="module")
def swept(tmp_path_factory) -> Path:
    """A finished sweep of two scenarios (in `out`), with its plan, world and variations."""
    folder = tmp_path_factory.mktemp("sweep")
    (folder / "w.yaml").write_text(textwrap.dedent("""\
        objects:
          - {name: floor, type: environment, file: plane.urdf}
          - {name: box, type: box, file: cube_small.urdf, position: [0.5, 0, 0.025]}
    """))
    (folder / "p.yaml").write_text("world: w.yaml\nbody:\n  - log: hi\n")
    (folder / "p.vary.yaml").write_text("objects:\n  box: {region: {box: [[0, -0.5, 0.025], [1, 0.5, 0.03]]}}\n")
    result = run("sweep", folder / "p.yaml", "--out", folder / "out", "-n", "2", "--workers", "1")
    assert result.exit_code == 0, result.output
    return folder


def resume(swept: Path, tmp_path: Path, *extra: str):
    folder = tmp_path / "out"
    if not folder.exists():
        shutil.copytree(swept / "out", folder)
    return run("sweep", swept / "p.yaml", "--out", folder, "-n", "3", "--workers", "1", "--resume", *extra)


GOOD = {"index": 2, "seed": 5, "status": "succeeded", "failure": None, "steps": 1, "trace": None,
        "varied": {"box": {"position": [0.5, 0.1, 0.025]}}, "timing": {"duration": 0.1, "setup": 0.1}}


def edited(**changes) -> str:
    record = {k: v for k, v in {**GOOD, **changes}.items() if v != "<absent>"}
    return json.dumps(record)


DAMAGED = {
    "a list": ("[1, 2]", "expected a JSON object"),
    "null": ("null", "expected a JSON object"),
    "not JSON": ("{index: 2", "not JSON"),
    "no index": (edited(index="<absent>"), "index"),
    "no seed": (edited(seed="<absent>"), "seed"),
    "no status": (edited(status="<absent>"), "status"),
    "index text": (edited(index="2"), "index"),
    "index true": (edited(index=True), "index"),
    "index negative": (edited(index=-1), "index"),
    "index 1e400": (edited().replace('"index": 2', '"index": 1e400'), "index"),
    "seed float": (edited(seed=1.5), "seed"),
    "status number": (edited(status=3), "status"),
    "failure text": (edited(status="failed", failure="boom"), "failure"),
    "varied list": (edited(varied=[1]), "varied"),
    "NaN position": (edited().replace("[0.5, 0.1, 0.025]", "[NaN, 0.1, 0.025]"), "NaN"),
    "short position": (edited(varied={"box": {"position": [1, 2]}}), "position"),
    "alternative without compare": (edited(alternative=1), "alternative"),
    "nested": ("[" * 10_000 + "]" * 10_000, "expected a JSON object"),
}


@pytest.mark.parametrize("case", sorted(DAMAGED))
def test_a_damaged_line_is_exit_2_at_its_line(swept, tmp_path, case):
    line, words = DAMAGED[case]
    shutil.copytree(swept / "out", tmp_path / "out")
    results = tmp_path / "out" / "results.jsonl"
    before = results.read_text()
    results.write_text(before + line + "\n")
    result = resume(swept, tmp_path, "--plot", tmp_path / "map.png")
    assert result.exit_code == 2, result.output
    assert f"{results}:3:" in result.stderr and words in result.stderr, result.stderr
    assert results.read_text() == before + line + "\n"  # nothing the user gave is dropped


@pytest.mark.parametrize("name", ["sweep.json", "results.jsonl"])
@pytest.mark.parametrize("kind", ["fifo", "dev-zero", "folder", "huge"])
def test_a_results_folder_file_that_is_not_a_file_is_refused_at_once(swept, tmp_path, name, kind):
    shutil.copytree(swept / "out", tmp_path / "out")
    target = tmp_path / "out" / name
    target.unlink()
    if kind == "fifo":
        os.mkfifo(target)
    elif kind == "dev-zero":
        target.symlink_to("/dev/zero")
    elif kind == "folder":
        target.mkdir()
    else:
        with open(target, "wb") as stream:
            stream.truncate(2 * 1024 * 1024 * 1024)  # sparse: 2 GiB that take no space
    result = resume(swept, tmp_path)
    assert result.exit_code == 2, result.output
    assert str(target) in result.stderr


def test_an_intact_folder_still_resumes(swept, tmp_path):
    result = resume(swept, tmp_path, "--json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["runs"] == 3
