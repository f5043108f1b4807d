"""Architecture rules, checked on the source with `ast` (nothing is imported).

Data flows one way: a package imports only packages below it in LAYERS (and the shared
modules at the bottom import no layer at all); imports only needed for type annotations
(under `if TYPE_CHECKING:`) do not count.

Only the world package imports PyBullet; every other layer goes through the world's methods.

pycram_cli/plan has two floors: the language floor (what a plan is and means) never
imports the running floor (executor, scheduler, trace); no module of the package imports
another in a cycle; and imports sit at module top, not inside functions.
"""
from __future__ import annotations

import ast
from pathlib import Path

PLAN_DIR = Path(__file__).resolve().parents[1] / "pycram_cli" / "plan"
PLAN_PACKAGE = "pycram_cli.plan"

PLAN_LANGUAGE_FLOOR = {"context", "runtime", "syntax", "resources", "composites", "leaves", "decorators",
                       "actions", "projecting", "scoring", "params", "validate", "language"}
PLAN_RUNNING_FLOOR = {"scheduler", "trace", "trace_schema", "executor", "replay", "observer"}
PLAN_ON_TOP = {"__init__"}  # tools and the package's own exports, above both floors
PLAN_NODE_MODULES = {"composites", "decorators", "leaves", "actions", "projecting"}


def _plan_modules() -> dict[str, Path]:
    return {path.stem: path for path in sorted(PLAN_DIR.glob("*.py"))}


def _is_type_checking(test: ast.expr) -> bool:
    return ((isinstance(test, ast.Name) and test.id == "TYPE_CHECKING")
            or (isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"))


def _imports(tree: ast.AST, type_checking: bool) -> list[ast.Import | ast.ImportFrom]:
    """Every import statement anywhere in the tree; those under `if TYPE_CHECKING:` only when asked."""
    found: list[ast.Import | ast.ImportFrom] = []

    def visit(node: ast.AST) -> None:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append(node)
        if isinstance(node, ast.If) and _is_type_checking(node.test) and not type_checking:
            for child in node.orelse:
                visit(child)
            return
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(tree)
    return found


def _plan_targets(statement: ast.Import | ast.ImportFrom, modules: set[str]) -> set[str]:
    """The modules of plan/ an import statement (in a module of plan/) imports."""
    if isinstance(statement, ast.Import):
        names = [alias.name for alias in statement.names]
        froms: list[str] = []
    else:
        if statement.level:
            base = PLAN_PACKAGE.split(".")[: len(PLAN_PACKAGE.split(".")) - (statement.level - 1)]
            base_name = ".".join(base + ([statement.module] if statement.module else []))
        else:
            base_name = statement.module or ""
        names = [base_name]
        froms = [alias.name for alias in statement.names] if base_name == PLAN_PACKAGE else []
    targets: set[str] = set()
    for name in names:
        if name == PLAN_PACKAGE:
            # `from . import trace` imports the submodule; `from . import run_plan` the package itself
            targets |= {f if f in modules else "__init__" for f in froms} or {"__init__"}
        elif name.startswith(PLAN_PACKAGE + "."):
            targets.add(name[len(PLAN_PACKAGE) + 1:].split(".")[0])
    return targets


def plan_import_graph(type_checking: bool = False) -> dict[str, set[str]]:
    """Module -> the modules of plan/ it imports (relative imports resolved)."""
    modules = _plan_modules()
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(), str(path))
        graph[name] = set()
        for statement in _imports(tree, type_checking):
            graph[name] |= _plan_targets(statement, set(modules))
        graph[name].discard(name)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of the graph as a path that ends where it starts, or None."""
    state: dict[str, str] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = "open"
        stack.append(node)
        for target in sorted(graph.get(node, ())):
            if state.get(target) == "open":
                return stack[stack.index(target):] + [target]
            if target not in state:
                cycle = visit(target)
                if cycle:
                    return cycle
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            cycle = visit(node)
            if cycle:
                return cycle
    return None


def test_find_cycle_reports_a_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_plan_import_graph_resolves_relative_imports():
    graph = plan_import_graph()
    assert "syntax" in graph["validate"]
    assert "trace" in graph["executor"]
    assert {"executor", "language", "params", "validate"} <= graph["__init__"]


def test_plan_has_no_import_cycle():
    cycle = find_cycle(plan_import_graph())
    assert cycle is None, "import cycle in pycram_cli/plan: " + " -> ".join(cycle or [])


def test_plan_modules_each_belong_to_a_floor():
    modules = set(_plan_modules())
    floors = [PLAN_LANGUAGE_FLOOR, PLAN_RUNNING_FLOOR, PLAN_ON_TOP]
    unplaced = modules - set().union(*floors)
    assert not unplaced, f"modules of plan/ on no floor (add them to tests/test_architecture.py): {sorted(unplaced)}"
    assert not (PLAN_LANGUAGE_FLOOR & PLAN_RUNNING_FLOOR)


def test_plan_language_floor_does_not_import_the_running_floor():
    """Not even for type checking: nodes reach the runtime through the protocols in runtime.py."""
    graph = plan_import_graph(type_checking=True)
    for module in sorted(PLAN_LANGUAGE_FLOOR):
        assert not graph[module] & {"executor", "scheduler", "trace"}, \
            f"plan/{module}.py (language floor) imports {sorted(graph[module] & PLAN_RUNNING_FLOOR)}"
        above = graph[module] - PLAN_LANGUAGE_FLOOR
        assert not above, f"plan/{module}.py (language floor) imports modules above it: {sorted(above)}"


def test_plan_syntax_validate_and_resources_know_no_node_module():
    """The node registry is filled by language.py; validation and resource analysis ask the nodes."""
    graph = plan_import_graph(type_checking=True)
    for module in ("syntax", "validate", "resources"):
        known = graph[module] & (PLAN_NODE_MODULES | {"language"})
        assert not known, f"plan/{module}.py imports {sorted(known)}"
    assert PLAN_NODE_MODULES <= graph["language"]


def test_plan_has_no_import_inside_a_function():
    """Imports sit at module top; one inside a function needs a comment saying `why:` (on it or the line before)."""
    found: set[str] = set()
    for name, path in _plan_modules().items():
        lines = path.read_text().splitlines()
        tree = ast.parse("\n".join(lines), str(path))
        for function in ast.walk(tree):
            if not isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for statement in ast.walk(function):
                if not isinstance(statement, (ast.Import, ast.ImportFrom)):
                    continue
                here = lines[statement.lineno - 1]
                before = lines[statement.lineno - 2] if statement.lineno > 1 else ""
                if "why:" not in here and "why:" not in before:
                    found.add(f"plan/{name}.py:{statement.lineno}: {here.strip()}")
    assert not found, "imports inside functions (move them to the top, or say why:):\n" + "\n".join(sorted(found))


# -- the layers of the whole package ----------------------------------------------------------------------

PACKAGE_DIR = Path(__file__).resolve().parents[1] / "pycram_cli"
#: bottom to top; a module may import its own layer and the layers below it
LAYERS = ["world", "robots", "worldfile", "reasoning", "planning", "process_modules", "locations", "designators",
          "design", "plan", "scenario", "sweep", "report", "cli"]
#: modules at the package's top level shared by every layer; they import only each other
SHARED = {"errors", "failures", "kinds", "schema", "yamlsource", "jsonable", "paths", "quiet", "limits", "files",
          "interrupts", "signature", "status", "drawing"}


def _layer_of(module: str) -> str | None:
    """`pycram_cli.plan.leaves` -> `plan`; shared modules -> `shared`; the package facade -> None."""
    parts = module.split(".")
    if parts[0] != "pycram_cli" or len(parts) < 2:
        return None
    if parts[1] in SHARED:
        return "shared"
    return parts[1] if parts[1] in LAYERS else None


def _module_name(path: Path) -> str:
    relative = path.relative_to(PACKAGE_DIR.parent).with_suffix("")
    parts = list(relative.parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _absolute(statement: ast.ImportFrom, module: str, is_package: bool) -> str:
    base = module.split(".") if is_package else module.split(".")[:-1]
    if statement.level > 1:
        base = base[: len(base) - (statement.level - 1)]
    return ".".join(base + ([statement.module] if statement.module else []))


def _imported(path: Path) -> set[str]:
    """The pycram_cli modules a file imports (`from . import x` counts as importing `x`), TYPE_CHECKING excluded."""
    module = _module_name(path)
    found: set[str] = set()
    for statement in _imports(ast.parse(path.read_text()), type_checking=False):
        if isinstance(statement, ast.Import):
            found |= {alias.name for alias in statement.names}
            continue
        target = _absolute(statement, module, path.name == "__init__.py") if statement.level else (statement.module or "")
        found.add(target)
        found |= {f"{target}.{alias.name}" for alias in statement.names}
    return {name for name in found if name.startswith("pycram_cli")}


def test_nothing_imports_upward():
    rank = {layer: index for index, layer in enumerate(LAYERS)}
    upward = []
    for path in sorted(PACKAGE_DIR.rglob("*.py")):
        layer = _layer_of(_module_name(path))
        if layer is None:
            continue
        for target in _imported(path):
            other = _layer_of(target)
            if other is None or other == "shared" or other == layer:
                if layer == "shared" and other not in (None, "shared"):
                    upward.append(f"{_module_name(path)} (shared) imports {target}")
                continue
            if layer == "shared" or rank[other] > rank[layer]:
                upward.append(f"{_module_name(path)} ({layer}) imports {target} ({other})")
    assert not upward, "imports against the flow " + " > ".join(reversed(LAYERS)) + ":\n" + "\n".join(upward)


def test_every_package_is_placed_in_a_layer():
    packages = {p.name for p in PACKAGE_DIR.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    modules = {p.stem for p in PACKAGE_DIR.glob("*.py")} - {"__init__", "__main__"}
    assert packages <= set(LAYERS), f"packages without a layer: {packages - set(LAYERS)}"
    assert modules <= SHARED, f"top-level modules without a place: {modules - SHARED}"


def test_the_process_modules_are_executors_only():
    """Motion planning lives in planning/: a process module carries out what planning/ plans, so its modules define
    executors (and private helpers), the registry its lookup; nothing public besides."""
    found = []
    for path in sorted((PACKAGE_DIR / "process_modules").glob("*.py")):
        if path.stem in ("__init__", "registry"):
            continue
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not node.name.startswith("_"):
                found.append(f"process_modules/{path.name}:{node.lineno}: def {node.name} (planning goes in planning/)")
    assert not found, "\n".join(found)


def test_only_performing_reaches_the_executors():
    """Locations and designators ask planning/ what would work; only performing a designator chooses its executor."""
    importers = sorted(_module_name(path) for path in PACKAGE_DIR.rglob("*.py")
                       if _layer_of(_module_name(path)) not in (None, "process_modules")
                       and any(_layer_of(t) == "process_modules" for t in _imported(path)))
    assert importers == ["pycram_cli.designators.performing"]


def test_the_layer_check_sees_an_upward_import(tmp_path):
    statement = ast.parse("from ..plan import run_plan").body[0]
    assert isinstance(statement, ast.ImportFrom)
    assert _absolute(statement, "pycram_cli.world.object", False) == "pycram_cli.plan"
    assert _layer_of("pycram_cli.plan") == "plan" and _layer_of("pycram_cli.errors") == "shared"


# -- PyBullet belongs to the world package ---------------------------------------------------------------

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


# -- sizes ---------------------------------------------------------------------------------------------------

#: a module longer than this does several jobs: split it by job
MODULE_LINES = 600
#: a function longer than this says why, in a `# long: ...` comment on the line above its `def` (or its decorators)
FUNCTION_LINES = 60


def long_functions(path: Path, limit: int = FUNCTION_LINES) -> list[str]:
    """`name (n lines)` of every function of the file longer than `limit` lines without a `# long:` comment."""
    lines = path.read_text().splitlines()
    found = []
    for node in ast.walk(ast.parse("\n".join(lines))):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        length = (node.end_lineno or node.lineno) - node.lineno + 1
        first = min([node.lineno] + [d.lineno for d in node.decorator_list])
        if length > limit and not (first > 1 and lines[first - 2].strip().startswith("# long:")):
            found.append(f"{node.name} ({length} lines)")
    return found


def test_no_module_is_over_600_lines():
    long = [f"{path.relative_to(PACKAGE_DIR)}: {n}" for path in sorted(PACKAGE_DIR.rglob("*.py"))
            if (n := len(path.read_text().splitlines())) > MODULE_LINES]
    assert not long, f"modules over {MODULE_LINES} lines (split them by job):\n" + "\n".join(long)


def test_every_long_function_says_why():
    found = []
    for path in sorted(PACKAGE_DIR.rglob("*.py")):
        where = path.relative_to(PACKAGE_DIR).as_posix()
        found += [f"{where}:{text}" for text in long_functions(path)]
    assert not found, (f"functions over {FUNCTION_LINES} lines without a `# long: why` comment above them:\n"
                       + "\n".join(found))


def test_the_length_check_sees_a_long_function_and_its_comment(tmp_path):
    body = "\n".join(f"    x{k} = {k}" for k in range(70))
    bare = tmp_path / "bare.py"
    bare.write_text(f"def f():\n{body}\n")
    said = tmp_path / "said.py"
    said.write_text(f"# long: seventy steps in a row\ndef f():\n{body}\n")
    assert long_functions(bare) == ["f (71 lines)"] and long_functions(said) == []
