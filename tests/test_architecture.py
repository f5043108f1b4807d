"""Architecture: PyBullet belongs to the world package; every other layer goes through the world's methods."""
from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "pycram_cli"
WORLD = PACKAGE / "world"


def is_pybullet(module: str) -> bool:
    """pybullet itself and its companion packages (pybullet_data, pybullet_utils, ...)."""
    top = module.split(".")[0]
    return top == "pybullet" or top.startswith("pybullet_")


def pybullet_imports(path: Path) -> list[str]:
    """Every import of PyBullet anywhere in a file (module level, functions, classes, conditionals)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found: list[str] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            modules = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            modules = [node.module]
        elif (isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant)
              and isinstance(node.args[0].value, str)
              and ((isinstance(node.func, ast.Name) and node.func.id == "__import__")
                   or (isinstance(node.func, ast.Attribute) and node.func.attr == "import_module"))):
            modules = [node.args[0].value]
        else:
            continue
        found += [f"{path}:{node.lineno}: {module}" for module in modules if is_pybullet(module)]
    return found


def modules_outside_world() -> list[Path]:
    return [path for path in sorted(PACKAGE.rglob("*.py")) if WORLD not in path.parents]


def test_no_module_outside_the_world_package_imports_pybullet():
    modules = modules_outside_world()
    assert len(modules) > 40  # the walk really covers the package
    offenders = [hit for path in modules for hit in pybullet_imports(path)]
    assert offenders == [], "PyBullet imported outside pycram_cli/world/:\n" + "\n".join(offenders)


def test_the_world_package_is_where_pybullet_is_imported():
    importers = {path.name for path in WORLD.rglob("*.py") if pybullet_imports(path)}
    assert {"bullet_world.py", "object.py"} <= importers


def test_the_check_finds_imports_anywhere_in_a_file(tmp_path):
    source = tmp_path / "sneaky.py"
    source.write_text(
        "import os, pybullet as p\n"
        "from pybullet import getClosestPoints\n"
        "def helper():\n"
        "    import pybullet_data\n"
        "    return __import__('pybullet')\n"
        "class Thing:\n"
        "    if True:\n"
        "        import importlib\n"
        "        bullet = importlib.import_module('pybullet.foo')\n"
        "import pybulletish_but_not_it  # not PyBullet\n"
        "from . import pybullet_helpers  # a relative module of ours, not PyBullet\n"
    )
    lines = sorted(int(hit.split(":")[-2]) for hit in pybullet_imports(source))
    assert lines == [1, 2, 4, 5, 9]
