"""Where the bundled data lives, both in a source checkout and in an installed package."""
from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass
from pathlib import Path

from .errors import InputError, Location, did_you_mean
from .files import probe

_PACKAGE = Path(__file__).resolve().parent


def bundled(name: str) -> Path:
    """The bundled folder `name` (`resources`, `worlds` or `plans`).

    An installed package carries it as `pycram_cli/_bundled/<name>`; a source
    checkout (editable install, tests) has it at the top of the repository.
    """
    installed = _PACKAGE / "_bundled" / name
    if installed.is_dir():
        return installed
    return _PACKAGE.parent / name


def resources_dir() -> Path:
    return bundled("resources")


def worlds_dir() -> Path:
    return bundled("worlds")


def plans_dir() -> Path:
    return bundled("plans")


def default_world() -> Path:
    """The world every command uses when none is given."""
    return worlds_dir() / "kitchen.yaml"


def cache_dir() -> Path:
    """A per-user folder for generated files (URDFs made from meshes, patched URDFs)."""
    base = os.environ.get("PYCRAM_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME")
    root = Path(base) if base else Path.home() / ".cache"
    folder = (root / "pycram") if not os.environ.get("PYCRAM_CACHE_DIR") else root
    folder.mkdir(parents=True, exist_ok=True)
    return folder


@dataclass(frozen=True)
class Found:
    """A plan or world a name can mean: where it comes from (`local`: the working folder's `plans/` or
    `worlds/`; `bundled`: installed with pycram) and whether a local file of the same name hides it."""

    name: str
    path: Path
    source: str
    shadowed: bool = False

    @property
    def origin(self) -> str:
        """`local`, `bundled`, or `bundled (shadowed by the local one)`, with the path."""
        return self.source + (" (shadowed by the local one)" if self.shadowed else "") + f"  {self.path}"


def available(kind: str) -> list[Found]:
    """The plans or worlds (`kind`: `plans` or `worlds`) in the order names resolve: the working folder's
    `plans/` (`worlds/`) first, then the bundled ones (in a source checkout they are the same folder)."""
    local_folder, bundled_folder = Path.cwd() / kind, bundled(kind)
    local = [Found(name, Path(kind) / f"{name}.yaml", "local") for name in _names(local_folder)]
    if local_folder.is_dir() and local_folder.resolve() == bundled_folder.resolve():
        return local
    hidden = {item.name for item in local}
    return local + [Found(name, bundled_folder / f"{name}.yaml", "bundled", name in hidden)
                    for name in _names(bundled_folder)]


def _same_file(a: Path, b: Path) -> bool:
    try:
        return a.resolve() == b.resolve()
    except (OSError, RuntimeError):
        return False


def _not_a_folder(value: str, base: Path, what: str, where: Location, key: str | None = None) -> None:
    """A folder where a plan or world file was named: an input error that says so, with the files in it."""
    path = Path(value) if Path(value).is_absolute() else base / value
    try:
        if not path.is_dir():
            return
        inside = sorted(p.name for p in path.glob("*.yaml") if not p.name.endswith(".vary.yaml"))[:5]
    except (OSError, ValueError):
        return
    raise InputError(f"'{value}' is a folder, not a {what} file", where, key=key,
                     suggestion=f"name a file in it: {', '.join(inside)}" if inside else f"name a {what} file")


def _known_names(kind: str) -> list[str]:
    """The names a plan or world can be given by (`kind`: plans or worlds): the working folder's, then the bundled."""
    return list(dict.fromkeys(found.name for found in available(kind)))


def _names(folder: Path) -> list[str]:
    # variation files (`set_table.vary.yaml`) sit beside their plans but are no plans
    return sorted(p.stem for p in folder.glob("*.yaml") if not p.name.endswith(".vary.yaml")) if folder.is_dir() else []


def _find(value: str, base: Path, bundled_folder: Path, what: str, where: Location,
          key: str | None = None, naming: Path | None = None) -> Path | None:
    """The first regular file `value` names; None when nothing is there. Something there that cannot be
    read (a pipe, a device, a name too long) is an input error, not a reason to look further."""
    path = Path(value)
    if "~" in value:
        with contextlib.suppress(RuntimeError):  # no home folder to expand into
            path = path.expanduser()
    candidates = [path]
    if not path.is_absolute():
        names = [value] if value.endswith((".yaml", ".yml")) else [value, f"{value}.yaml"]
        local = Path.cwd() / bundled_folder.name  # the working folder's plans/ or worlds/ win over installed copies
        candidates = [base / n for n in names] + [local / n for n in names] + [bundled_folder / n for n in names]
    for candidate in candidates:
        problem = probe(candidate)
        if problem is None and naming is not None and _same_file(candidate, naming):
            continue  # the file that names it is not it
        if problem is None:
            return candidate
        if problem != "not found" and not problem.startswith("it is a folder"):
            raise InputError(f"cannot read {what}: {problem}", where, key=key)
    return None


def find_world(value: str | None, base: Path | None = None, where: Location | None = None,
               naming: Path | None = None) -> Path:
    """A world file: a path (relative to `base`, default the current folder) or a bundled world's name.

    None means the default world. Not found: an input error at `where` with a suggestion. `naming`: the
    file that names the world (a plan), never the world itself: `world: mine` in `plans/mine.yaml` is
    `worlds/mine.yaml`, not the plan.
    """
    if value is None:
        return default_world()
    found = _find(value, base if base is not None else Path.cwd(), worlds_dir(), "world file",
                  where or Location(value), "world" if where else None, naming)
    if found is not None:
        return found
    _not_a_folder(value, base if base is not None else Path.cwd(), "world", where or Location(value),
                  "world" if where else None)
    names = _known_names("worlds")
    raise InputError(f"world file not found: '{value}'", where or Location(value), key="world" if where else None,
                     suggestion=did_you_mean(value, names) or (f"worlds: {', '.join(names)}" if names else None))


def find_plan(value: str, base: Path | None = None) -> Path:
    """A plan file: a path (relative to `base`, default the current folder) or a bundled plan's name (`set_table`)."""
    found = _find(value, base if base is not None else Path.cwd(), plans_dir(), "plan file", Location(value))
    if found is not None:
        return found
    _not_a_folder(value, base if base is not None else Path.cwd(), "plan", Location(value))
    names = _known_names("plans")
    raise InputError("plan file not found", Location(value),
                     suggestion=did_you_mean(value, names) or (f"plans: {', '.join(names)}" if names else None))
