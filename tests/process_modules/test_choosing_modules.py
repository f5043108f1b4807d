"""Process modules are chosen by name: the designator's default, unless the robot's description names another."""
from __future__ import annotations

import dataclasses

import pytest

from pycram_cli.errors import InputError
from pycram_cli.process_modules import PROCESS_MODULES, ProcessModule, choose, process_module
from pycram_cli.process_modules.navigation import Navigation
from pycram_cli.robots import bundled_descriptions


@pytest.fixture
def registry_snapshot():
    saved = dict(PROCESS_MODULES)
    yield
    PROCESS_MODULES.clear()
    PROCESS_MODULES.update(saved)


@pytest.fixture
def pr2():
    return next(d for d in bundled_descriptions() if d.name == "pr2")


def test_the_designators_default_module_serves_a_robot_that_names_none(pr2):
    assert isinstance(choose("moving", "navigation", pr2), Navigation)
    assert isinstance(choose("moving", "navigation", None), Navigation)


def test_a_robot_description_can_name_its_own_module_for_a_designator(registry_snapshot, pr2):
    @process_module("turtle-navigation")
    class TurtleNavigation(ProcessModule):
        def execute(self, robot, slots):  # type: ignore[no-untyped-def]
            return "rolled"

    turtle = dataclasses.replace(pr2, name="turtle", process_modules={"moving": "turtle-navigation"})
    assert isinstance(choose("moving", "navigation", turtle), TurtleNavigation)
    assert isinstance(choose("moving", "navigation", pr2), Navigation)


def test_a_module_name_nobody_registered_is_an_input_error_naming_the_description(pr2):
    flying = dataclasses.replace(pr2, process_modules={"moving": "navigaton"})
    with pytest.raises(InputError, match="no process module 'navigaton' for 'moving'") as caught:
        choose("moving", "navigation", flying)
    assert caught.value.suggestion == "did you mean 'navigation'?"
    assert caught.value.location.file == str(pr2.path)
