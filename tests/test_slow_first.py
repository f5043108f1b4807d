"""tests/slow_first.py: the suite hands out its longest tests first, and its list of them names tests that exist."""
from __future__ import annotations

import ast
import re
from dataclasses import dataclass, field
from pathlib import Path

import slow_first

TESTS = Path(__file__).resolve().parent


@dataclass
class Definition:
    scope: str


@dataclass
class Info:
    name2fixturedefs: dict = field(default_factory=dict)


@dataclass
class Item:
    nodeid: str
    shared: bool = False

    @property
    def _fixtureinfo(self) -> Info:
        return Info({"kitchen": [Definition("module" if self.shared else "function")]})


def ids(items: list[Item]) -> list[str]:
    return [item.nodeid for item in items]


def test_listed_tests_go_first_longest_first_and_the_others_keep_their_order():
    items = [Item("a.py::one"), Item("a.py::two"), Item("b.py::three"), Item("c.py::four")]
    slow_first.order(items, {"c.py::four": 30.0, "a.py::two": 50.0})
    assert ids(items) == ["a.py::two", "c.py::four", "a.py::one", "b.py::three"]


def test_a_listed_test_on_a_module_fixture_moves_its_whole_module_in_its_own_order():
    items = [Item("a.py::one"), Item("m.py::x", shared=True), Item("m.py::y", shared=True),
             Item("m.py::z", shared=True), Item("b.py::long")]
    slow_first.order(items, {"m.py::z": 20.0, "b.py::long": 40.0})
    assert ids(items) == ["b.py::long", "m.py::x", "m.py::y", "m.py::z", "a.py::one"]


def test_a_test_in_an_xdist_group_is_found_by_its_id_without_the_group_suffix():
    """`--dist loadgroup` appends `@group` to a grouped test's id; the list names it as `--durations` does."""
    items = [Item("a.py::one"), Item("w.py::window@gui"), Item("p.py::golden[x]@shipped-x")]
    slow_first.order(items, {"w.py::window": 60.0, "p.py::golden[x]": 30.0})
    assert ids(items) == ["w.py::window@gui", "p.py::golden[x]@shipped-x", "a.py::one"]


def test_the_list_is_read_from_a_durations_report(tmp_path: Path):
    report = ["============ slowest durations ============",
              "61.20s call     tests/plan/test_x.py::test_long[3]",
              "1.50s setup    tests/plan/test_x.py::test_long[3]",
              "0.01s teardown tests/plan/test_x.py::test_long[3]",
              "2.00s call     tests/cli/test_y.py::test_short",
              "9.00s call     tests/world/test_w.py::test_window@gui"]
    assert slow_first.totals(report) == {"tests/plan/test_x.py::test_long[3]": 62.71,
                                         "tests/cli/test_y.py::test_short": 2.0,
                                         "tests/world/test_w.py::test_window": 9.0}
    listed = tmp_path / "durations.txt"
    listed.write_text("# a comment\n   62.71  tests/plan/test_x.py::test_long[3]\n\n")
    assert slow_first.read(listed) == {"tests/plan/test_x.py::test_long[3]": 62.71}


def test_every_listed_test_is_a_test_of_the_suite():
    """The list follows renames: each entry names a test function of an existing module (parameters aside)."""
    listed = slow_first.read()
    assert listed, "tests/durations.txt lists no test"
    missing = []
    for nodeid in listed:
        path, _, name = nodeid.partition("::")
        module = TESTS.parent / path
        function = re.sub(r"\[.*\]$", "", name).split("::")[-1]
        if not module.is_file():
            missing.append(nodeid)
            continue
        names = {node.name for node in ast.walk(ast.parse(module.read_text()))
                 if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))}
        if function not in names:
            missing.append(nodeid)
    assert not missing, f"tests/durations.txt names tests that no longer exist: {missing}"
