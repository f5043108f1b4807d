"""Process modules are chosen by designator type and robot: a robot's own module wins over the default."""
from __future__ import annotations

import pytest

from pycram_cli.process_modules import PROCESS_MODULES, ProcessModule, choose, process_module
from pycram_cli.process_modules.navigation import Navigation


@pytest.fixture
def registry_snapshot():
    saved = dict(PROCESS_MODULES)
    yield
    PROCESS_MODULES.clear()
    PROCESS_MODULES.update(saved)


def test_the_default_modules_serve_any_robot_with_a_description():
    assert isinstance(choose("moving", "pr2"), Navigation)
    assert isinstance(choose("moving", "some_other_robot"), Navigation)


def test_a_robot_specific_module_is_chosen_for_that_robot_only(registry_snapshot):
    @process_module("moving", robot="turtle")
    class TurtleNavigation(ProcessModule):
        resource = "base"

        def execute(self, robot, slots):  # type: ignore[no-untyped-def]
            return "rolled"

    assert isinstance(choose("moving", "turtle"), TurtleNavigation)
    assert isinstance(choose("moving", "pr2"), Navigation)


def test_an_unknown_designator_has_no_module():
    with pytest.raises(LookupError, match="no process module for 'flying'"):
        choose("flying", "pr2")
