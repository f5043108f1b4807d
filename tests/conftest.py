"""Shared fixtures: fresh worlds, test data, and the real ROS models when they are present."""
from __future__ import annotations

import os
import signal
import tempfile
from pathlib import Path
from typing import Iterator

import pytest

# A suite started in the background by a non-interactive shell (`pytest &`, `nohup`) inherits SIGINT ignored,
# and so would every pycram it starts: pycram rightly keeps an ignored SIGINT, as a background job should, and the
# interrupt and GUI tests would wait for a Ctrl-C that never arrives. A handler of ours is reset for children.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

os.environ.setdefault("PYCRAM_CACHE_DIR", tempfile.mkdtemp(prefix="pycram-test-cache-"))

import slow_first  # noqa: E402
from shipped_runs import ShippedRuns  # noqa: E402
from pycram_cli import BulletWorld  # noqa: E402
from pycram_cli.paths import default_world  # noqa: E402
from pycram_cli.worldfile.loader import load_world  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
SHARED_MODELS = REPO.parent / "shared" / "models"


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The longest tests first (tests/slow_first.py), after pytest's own ordering by shared fixtures; on a
    pytest-xdist worker, each `xdist_group` test's id names its group first."""
    for item in items:
        _name_the_group(item)
    slow_first.order(items, slow_first.read())


def _name_the_group(item: pytest.Item) -> None:
    """Give the test the id `--dist loadgroup` meant it to have. pytest-xdist 3.8 appends `@group` to a grouped test's
    id by setting `item._nodeid`, which pytest 9 no longer reads (it keeps the id in `item._id`): the controller
    then saw no group, and a group's tests (the two window tests, the readers of one shipped run) went to any
    worker. Where xdist's id and pytest's differ, pytest's is set to xdist's."""
    grouped = getattr(item, "_nodeid", None)
    if isinstance(grouped, str) and grouped != item.nodeid and hasattr(item, "_id"):
        item._id = type(item._id).parse(grouped)


@pytest.fixture
def world() -> Iterator[BulletWorld]:
    w = BulletWorld()
    yield w
    w.exit()


@pytest.fixture(scope="module")
def kitchen() -> Iterator[BulletWorld]:
    """The bundled kitchen, loaded once per test module: tests take it through a snapshot, or only read it."""
    world = load_world()
    yield world
    world.exit()


@pytest.fixture(scope="session")
def shipped_runs() -> Iterator[ShippedRuns]:
    """Each shipped plan run once per test process, for the tests that only read the run (tests/shipped_runs.py)."""
    runs = ShippedRuns()
    yield runs
    runs.close()


@pytest.fixture
def data_dir() -> Path:
    return DATA


@pytest.fixture
def shared_models() -> Path:
    if not SHARED_MODELS.is_dir():
        pytest.skip("../shared/models is not present")
    return SHARED_MODELS


@pytest.fixture
def real_kitchen(tmp_path: Path, shared_models: Path) -> Iterator[BulletWorld]:
    """The bundled kitchen world with the real PR2 and the real IAI kitchen from ../shared/models in place of ours."""
    text = default_world().read_text()
    text = text.replace("file: robots/pr2/pr2.urdf", f"file: {shared_models / 'pr2' / 'pr2.urdf'}")
    text = text.replace("file: environments/kitchen/kitchen.urdf", f"file: {shared_models / 'kitchen' / 'kitchen.urdf'}")
    # the real counter top is 5 mm higher than ours (0.856 m): the things on it start 1 mm above it, as in ours
    text = text.replace(", 0.851]", ", 0.857]")
    path = tmp_path / "real_kitchen.yaml"
    path.write_text(text)
    world = load_world(path)
    yield world
    world.exit()
