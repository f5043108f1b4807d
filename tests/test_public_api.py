"""The Python API the README and the docs show keeps working after first use (issue 18).

Once `perform` had run, `from pycram_cli.designators import perform` used to give the submodule
`designators/perform.py` (importing a submodule sets the package attribute of the same name), so a
second call raised "'module' object is not callable". Here every name the README and the docs
import is imported, their examples are run twice, and every name must still be the same object;
and no public name of any package may be shadowed by a submodule, whatever gets imported.
"""
from __future__ import annotations

import ast
import importlib
import pkgutil
import re
import types
from pathlib import Path

import pytest

import pycram_cli

REPO = Path(__file__).resolve().parents[1]
DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]


def python_blocks() -> list[tuple[Path, str]]:
    blocks = []
    for path in DOCS:
        for match in re.finditer(r"```python\n(.*?)```", path.read_text(), re.S):
            blocks.append((path, match.group(1)))
    return blocks


def documented_names() -> list[tuple[str, str]]:
    """(module, name) for every `from pycram_cli... import name` in a Python block of the README or the docs."""
    found = []
    for _, block in python_blocks():
        for node in ast.walk(ast.parse(block)):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("pycram_cli"):
                found += [(node.module, alias.name) for alias in node.names]
    return sorted(set(found))


def resolve(module: str, name: str):
    namespace: dict = {}
    exec(f"from {module} import {name}", namespace)  # noqa: S102 - the statement the docs show
    return namespace[name]


def block_with(text: str) -> str:
    return next(block for _, block in python_blocks() if text in block)


def test_the_docs_import_the_names_this_test_covers():
    names = {name for _, name in documented_names()}
    assert {"perform", "load_world", "BulletWorld", "stable", "visible", "run_query", "load_plan", "run_plan",
            "process_module"} <= names


def test_every_documented_name_is_the_same_object_after_the_examples_ran_twice(tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    before = {(module, name): resolve(module, name) for module, name in documented_names()}
    for (module, name), value in before.items():
        assert not isinstance(value, types.ModuleType), f"{module}.{name} is a module, not the documented object"

    api = block_with("perform(world, \"moving\"")
    plans = block_with("load_plan(")
    queries = block_with("run_query(world")
    for _ in range(2):  # the examples, twice
        exec(api, {})  # noqa: S102 - the README's own example
        exec(plans, {})  # noqa: S102
        world = resolve("pycram_cli", "load_world")()
        try:
            exec(queries, {"world": world, "milk": world.get_object_by_name("milk"),  # noqa: S102
                           "bottle": world.get_object_by_name("bottle"), "pr2": world.robot})
        finally:
            world.exit()
        perform = resolve("pycram_cli.designators", "perform")
        assert callable(perform) and not isinstance(perform, types.ModuleType)

    for key, value in before.items():
        assert resolve(*key) is value, f"{key[0]}.{key[1]} changed after first use"


def _all_modules() -> list[str]:
    return [info.name for info in pkgutil.walk_packages(pycram_cli.__path__, "pycram_cli.")]


@pytest.mark.parametrize("package", ["pycram_cli", *(
    name for name in (info.name for info in pkgutil.walk_packages(pycram_cli.__path__, "pycram_cli."))
    if name.count(".") == 1 and (Path(pycram_cli.__path__[0]) / name.split(".")[1] / "__init__.py").exists())])
def test_no_public_name_is_shadowed_by_a_submodule(package):
    module = importlib.import_module(package)
    public = [name for name in getattr(module, "__all__", []) if not name.startswith("__")]
    before = {name: getattr(module, name) for name in public}
    for name in _all_modules():  # importing a submodule sets the package attribute of its name
        importlib.import_module(name)
    for name, value in before.items():
        now = getattr(module, name)
        assert now is value, f"{package}.{name} was replaced by {now!r} (a submodule of the same name?)"
        assert not isinstance(now, types.ModuleType), f"{package}.{name} is a module"
    # (reasoning's `stable`, `contact` and `supporting` share their submodules' names; that is safe only because
    # reasoning/__init__.py imports those submodules before it binds the functions, which this test checks)
