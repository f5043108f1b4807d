"""Shared fixtures: fresh worlds, test data, and the real ROS models when they are present."""
from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Iterator

import pytest

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
