"""Long tests first: the suite's two pytest-xdist workers finish together instead of one waiting on a long test
that started last.

`--dist loadgroup` hands tests out in collection order, a few at a time, to whichever worker asks. A test that
takes a minute and is handed out near the end keeps one worker busy for that minute after the other has run
out of work. `tests/durations.txt` lists the tests that took longest in a measured run of the whole suite
(seconds, setup + call + teardown, and the test's id); `order` moves them to the front, longest first, and
leaves every other test where collection put it. A listed test that no longer exists is reported by
tests/test_slow_first.py, so that the list follows renames.

Regenerate the list after a measured run: `pytest -q --durations=0 > run.txt` and
`python tests/slow_first.py run.txt > tests/durations.txt`.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path
from typing import Iterable, Sequence

LIST = Path(__file__).resolve().parent / "durations.txt"
#: tests shorter than this stay in collection order: moving them gains nothing, and module fixtures stay shared
THRESHOLD = 4.0
#: how many of the longest tests the list keeps
KEEP = 120


def read(path: Path = LIST) -> dict[str, float]:
    """The listed tests' measured seconds by test id (comments and blank lines ignored)."""
    seconds: dict[str, float] = {}
    if not path.is_file():
        return seconds
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            value, nodeid = line.split(None, 1)
            seconds[nodeid] = float(value)
    return seconds


def _shares_a_fixture(item) -> bool:
    """Whether the test uses a fixture set up once for several tests (module scope or wider, but a session's):
    such a test stays beside its module's others, so that the fixture is still set up once per worker."""
    info = getattr(item, "_fixtureinfo", None)
    if info is None:
        return False
    return any(getattr(definitions[-1], "scope", "function") in ("class", "module", "package")
               for definitions in info.name2fixturedefs.values() if definitions)


def order(items: list, seconds: dict[str, float]) -> None:
    """Sort pytest items in place, longest listed first. A listed test on function-scoped fixtures moves alone; one
    on a module's shared fixture moves its whole module, in the module's own order; every other test keeps its
    place after them."""
    weight: dict[int, float] = {}  # id(item) -> the seconds of the block it moves with (0: it stays)
    modules: dict[str, float] = {}
    for item in items:
        took = seconds.get(listed_id(item.nodeid), 0.0)
        if took and _shares_a_fixture(item):
            module = item.nodeid.split("::", 1)[0]
            modules[module] = max(modules.get(module, 0.0), took)
        elif took:
            weight[id(item)] = took
    for item in items:
        module = item.nodeid.split("::", 1)[0]
        if id(item) not in weight and module in modules:
            weight[id(item)] = modules[module]
    position = {id(item): index for index, item in enumerate(items)}
    start: dict[str, int] = {}
    for index, item in enumerate(items):
        start.setdefault(item.nodeid.split("::", 1)[0], index)

    def key(item) -> tuple[float, int, int]:
        module = item.nodeid.split("::", 1)[0]
        block = start[module] if module in modules else position[id(item)]
        return -weight.get(id(item), 0.0), block, position[id(item)]

    items.sort(key=key)


_DURATION = re.compile(r"^\s*([0-9.]+)s (setup|call|teardown)\s+(\S.*?)\s*$")
#: the `@group` a pytest-xdist worker's report appends to a grouped test's id (a test's name and its parameters,
#: which end in `]`, hold no `@` of their own at the end)
_GROUP = re.compile(r"@[^\[\]:/]+$")


def listed_id(nodeid: str) -> str:
    """A test's id as the list names it: without the `@group` that `--dist loadgroup` appends to the id of a test
    marked `xdist_group` (the window tests, the readers of a shipped run), else such a test would never match."""
    return _GROUP.sub("", nodeid)


def totals(lines: Iterable[str]) -> dict[str, float]:
    """Each test's setup + call + teardown seconds from pytest's `--durations=0` report."""
    found: dict[str, float] = {}
    for line in lines:
        match = _DURATION.match(line)
        if match:
            nodeid = listed_id(match.group(3))
            found[nodeid] = found.get(nodeid, 0.0) + float(match.group(1))
    return found


def main(argv: Sequence[str]) -> int:
    """Print the durations list from a `--durations=0` report (the report file is the one argument)."""
    found = totals(Path(argv[0]).read_text().splitlines())
    longest = sorted(((s, n) for n, s in found.items() if s >= THRESHOLD), key=lambda pair: (-pair[0], pair[1]))
    print("# seconds  test (setup + call + teardown, measured by `pytest -q --durations=0`; see tests/slow_first.py)")
    for value, nodeid in longest[:KEEP]:
        print(f"{value:8.2f}  {nodeid}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
