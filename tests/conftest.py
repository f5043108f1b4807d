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

from pycram_cli import BulletWorld  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
DATA = Path(__file__).resolve().parent / "data"
SHARED_MODELS = REPO.parent / "shared" / "models"


@pytest.fixture
def world() -> Iterator[BulletWorld]:
    w = BulletWorld()
    yield w
    w.exit()


@pytest.fixture
def data_dir() -> Path:
    return DATA


@pytest.fixture
def shared_models() -> Path:
    if not SHARED_MODELS.is_dir():
        pytest.skip("../shared/models is not present")
    return SHARED_MODELS
