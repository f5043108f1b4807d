"""Fixtures for the reasoning tests: the module's kitchen world (tests/conftest.py), put back exactly after every test."""
from __future__ import annotations

from typing import Any, Iterator

import pytest
from scenes import wake


@pytest.fixture
def scene(kitchen: Any) -> Iterator[Any]:
    """The module's kitchen world; whatever the test moves is undone afterwards."""
    state = kitchen.save_state()
    yield kitchen
    kitchen.restore_state(state)
    kitchen.release_state(state)
    wake(kitchen)
