"""Fixtures for plan tests (helpers live in plan_helpers.py)."""
from __future__ import annotations

import pytest

from plan_helpers import Runner


@pytest.fixture
def plans(tmp_path) -> Runner:
    return Runner(tmp_path)
