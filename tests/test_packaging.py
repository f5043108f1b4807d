"""Packaging: pyproject.toml alone (static settings, no setup.py) builds a wheel that carries every module, the
bundled plans, worlds and resources under pycram_cli/_bundled/, the report's assets, the licence and the entry
points, and that wheel runs a bundled plan without the checkout."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SOURCES = ("pyproject.toml", "README.md", "LICENSE", "pycram_cli", "plans", "worlds", "resources")
DATA = ("plans", "worlds", "resources")
JUNK = ("__pycache__", "*.pyc", "*.egg-info", "build")
#: what pip says when it cannot get the build backend (offline, no cache): a reason to skip, not a failure
NO_BACKEND = ("Could not find a version that satisfies the requirement", "No matching distribution found",
              "Failed to establish a new connection", "Temporary failure in name resolution",
              "Network is unreachable")


def _files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc")


def _backend_here() -> bool:
    """Whether this interpreter has the build backend pyproject.toml asks for (then no download is needed)."""
    try:
        import setuptools
        import wheel  # noqa: F401
    except ImportError:
        return False
    major = re.match(r"\d+", setuptools.__version__)
    return major is not None and int(major.group()) >= 77


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A wheel built from a copy of the sources (so that the checkout gets no build/ or egg-info)."""
    if subprocess.run([sys.executable, "-m", "pip", "--version"], capture_output=True).returncode != 0:
        pytest.skip("cannot build a wheel: pip is not available to this interpreter")
    tmp = tmp_path_factory.mktemp("packaging")
    source, out = tmp / "src", tmp / "dist"
    for name in SOURCES:
        if (ROOT / name).is_dir():
            shutil.copytree(ROOT / name, source / name, ignore=shutil.ignore_patterns(*JUNK))
        else:
            source.mkdir(exist_ok=True)
            shutil.copy2(ROOT / name, source / name)
    command = [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(out), str(source)]
    if _backend_here():
        command.insert(5, "--no-build-isolation")  # offline: the backend is installed here
    done = subprocess.run(command, capture_output=True, text=True, timeout=600,
                          env={**os.environ, "PIP_DISABLE_PIP_VERSION_CHECK": "1"})
    if done.returncode != 0:
        said = done.stdout + done.stderr
        if any(text in said for text in NO_BACKEND):
            pytest.skip("cannot build a wheel: pip cannot get the build backend (setuptools>=77, wheel) - offline "
                        "and not in pip's cache:\n" + said[-2000:])
        pytest.fail("building the wheel failed:\n" + said[-4000:])
    wheels = list(out.glob("pycram_cli-*.whl"))
    assert len(wheels) == 1, wheels
    return wheels[0]


@pytest.fixture(scope="module")
def names(built) -> set[str]:
    with zipfile.ZipFile(built) as archive:
        return set(archive.namelist())


def test_the_package_is_built_from_static_settings_without_setup_py():
    assert not (ROOT / "setup.py").exists()
    text = (ROOT / "pyproject.toml").read_text()
    assert "[tool.setuptools.package-dir]" in text and "[tool.setuptools.package-data]" in text


def test_the_wheel_holds_every_module(names):
    modules = [p.relative_to(ROOT).as_posix() for p in _files(ROOT / "pycram_cli") if p.suffix == ".py"]
    missing = [m for m in modules if m not in names]
    assert not missing, f"not in the wheel (a package missing from [tool.setuptools] packages?): {missing}"


def test_the_wheel_bundles_the_plans_worlds_and_resources_under_pycram_cli_bundled(names):
    for folder in DATA:
        for path in _files(ROOT / folder):
            assert f"pycram_cli/_bundled/{path.relative_to(ROOT).as_posix()}" in names
    for name in ("plans/set_table.yaml", "plans/set_table.vary.yaml", "worlds/kitchen.yaml",
                 "worlds/kitchen_fetch.yaml", "resources/robots/pr2/pr2.yaml", "resources/robots/pr2/pr2.urdf",
                 "resources/robots/fetch/fetch.yaml", "resources/robots/fetch/fetch.urdf",
                 "resources/objects/grasps.yaml", "resources/objects/milk.obj",
                 "resources/environments/kitchen/kitchen.urdf"):
        assert f"pycram_cli/_bundled/{name}" in names


def test_the_wheel_holds_the_reports_assets_the_licence_and_the_entry_points(built, names):
    for name in ("report.html", "report.js", "report.css", "three.min.js", "three.LICENSE"):
        assert f"pycram_cli/report/assets/{name}" in names
    # nothing outside the package and its metadata (no top-level plans/ or resources/)
    assert {n.split("/")[0] for n in names} == {"pycram_cli", f"{built.name.split('-py3')[0]}.dist-info"}
    info = next(n.rsplit("/", 1)[0] for n in names if n.endswith(".dist-info/METADATA"))
    assert f"{info}/licenses/LICENSE" in names
    with zipfile.ZipFile(built) as archive:
        entry_points = archive.read(f"{info}/entry_points.txt").decode()
    assert "pycram = pycram_cli.cli.launch:main" in entry_points
    assert "[pytest11]" in entry_points and "pycram = pycram_cli.scenario.pytest_plugin" in entry_points


def test_the_unpacked_wheel_runs_a_bundled_plan_away_from_the_checkout(built, tmp_path):
    unpacked, elsewhere = tmp_path / "site", tmp_path / "elsewhere"
    elsewhere.mkdir()
    with zipfile.ZipFile(built) as archive:
        archive.extractall(unpacked)
    env = {**os.environ, "PYTHONPATH": str(unpacked), "PYCRAM_CACHE_DIR": str(tmp_path / "cache")}
    done = subprocess.run([sys.executable, "-m", "pycram_cli.cli.main", "run", "set_table", "-q"], cwd=elsewhere,
                          env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "plan set_table.yaml succeeded" in done.stdout
    where = subprocess.run([sys.executable, "-c", "import pycram_cli.paths as p; print(p.plans_dir())"],
                           cwd=elsewhere, env=env, capture_output=True, text=True, timeout=120)
    assert where.stdout.strip() == str(unpacked / "pycram_cli" / "_bundled" / "plans")
