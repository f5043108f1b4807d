"""Fixtures of the world tests."""
from __future__ import annotations

import pytest

from pycram_cli import Object


@pytest.fixture
def arm_scene(world, data_dir):
    """A world with the test arm (a slide and a shoulder, a hand link) and a cube 0.5 m in front of it."""
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0, 0.5])
    return world, arm, cube
