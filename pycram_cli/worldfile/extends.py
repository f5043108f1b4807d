"""`extends:` in a world file: a world made from another one, with objects added or changed.

    extends: kitchen                  # a world's name (pycram worlds) or a file relative to this one
    objects:
      - name: mug                     # a name the base world does not have: a new object (name, type, file)
        type: mug
        file: objects/mug.obj
        position: [1.3, 1.2, 0.851]
      - name: milk                    # a name it has: the keys given here replace the base's, the rest stay
        position: [1.3, 1.1, 0.851]

The base world's objects come first, in its order (a changed one in its place), then the new ones; its
`gravity` and `description` hold unless this file gives its own. A base may extend another world in
turn. Each object's `file:` is found relative to the file that names it. A name that means this very
file (`worlds/kitchen.yaml` extending `kitchen`) means the bundled world of that name.

Only YAML is read here (no models), so completion can list an extended world's objects cheaply.
"""
from __future__ import annotations

from pathlib import Path

from ..errors import InputError, Location, did_you_mean
from ..paths import find_world, worlds_dir
from ..yamlsource import LList, LMap, load_yaml

EXTENDS = "extends"
#: worlds extending worlds, at most this deep
MAX_DEPTH = 16


def folder_of(item: LMap, default: Path) -> Path:
    """The folder an object's `file:` is relative to: that of the file that gave it."""
    folder = getattr(item, "folder", None)
    return folder if isinstance(folder, Path) else default


def merged(data: LMap, path: Path, errors: list[InputError], chain: tuple[Path, ...] = ()) -> LMap:
    """`data` (the top-level mapping of the world file `path`) with its `extends:` applied: the base world's
    objects changed and added to, its gravity and description inherited. Without `extends:` it is `data`."""
    if EXTENDS not in data:
        return data
    where = data.loc(EXTENDS, True)
    base_path = _base(data[EXTENDS], path, where, chain, errors)
    if base_path is None:
        return data  # its own objects alone are still checked
    base = load_yaml(base_path)
    if not isinstance(base, LMap):
        errors.append(InputError("the world it extends is not a world file (a mapping with 'objects')", where,
                                 key=EXTENDS))
        return data
    base = merged(base, base_path, errors, (*chain, path.resolve()))
    result = _copy(data)
    for key in ("gravity", "description"):
        if key not in data and key in base:
            _put(result, key, base[key], base.loc(key), base.loc(key, True))
    objects = data.get("objects", [])
    base_objects = base.get("objects", [])
    if isinstance(objects, LList) and isinstance(base_objects, LList):
        _put(result, "objects", _objects(base_objects, base_path.parent, objects, path.parent, errors),
             data.loc("objects") if "objects" in data else data.where, data.loc("objects", True))
    elif isinstance(base_objects, LList) and "objects" not in data:
        _put(result, "objects", _objects(base_objects, base_path.parent, _empty_list(data.where), path.parent, errors),
             data.where, data.where)
    return result


def _base(value: object, path: Path, where: Location, chain: tuple[Path, ...], errors: list[InputError]) -> Path | None:
    """The file `extends:` names; None (and an error) when it names none, or when worlds extend in a circle."""
    if not isinstance(value, str) or not value.strip():
        errors.append(InputError("expected the name or file of the world this one extends", where, key=EXTENDS,
                                 suggestion="e.g. extends: kitchen"))
        return None
    try:
        found = find_world(value, path.parent, where)
    except InputError as exc:
        errors.append(exc)
        return None
    if found.resolve() == path.resolve():  # `worlds/kitchen.yaml` extending `kitchen`: the bundled one
        bundled = worlds_dir() / (value if value.endswith((".yaml", ".yml")) else f"{value}.yaml")
        if not bundled.is_file() or bundled.resolve() == path.resolve():
            errors.append(InputError(f"a world cannot extend itself ('{value}' is this file)", where, key=EXTENDS))
            return None
        found = bundled
    if found.resolve() in chain or len(chain) >= MAX_DEPTH:
        errors.append(InputError(f"worlds extend each other in a circle ('{value}' extends this world in turn)"
                                 if found.resolve() in chain else f"worlds extend worlds more than {MAX_DEPTH} deep",
                                 where, key=EXTENDS))
        return None
    return found


def _objects(base: LList, base_folder: Path, own: LList, folder: Path, errors: list[InputError]) -> LList:
    """The base's objects with this file's changes applied in place, then this file's new objects."""
    items: list[LMap] = []
    by_name: dict[str, int] = {}
    for item in base:
        if isinstance(item, LMap):
            copy = _copy(item)
            copy.folder = folder_of(item, base_folder)  # type: ignore[attr-defined]  # LMap: its folder rides as an attribute
            if isinstance(item.get("name"), str):
                by_name.setdefault(item["name"], len(items))
            items.append(copy)
    result = _empty_list(own.where)
    added: list[tuple[LMap, Location]] = []
    for index, item in enumerate(own):
        name = item.get("name") if isinstance(item, LMap) else None
        if isinstance(name, str) and name in by_name:
            items[by_name[name]] = _changed(items[by_name[name]], item, folder)
            continue
        if isinstance(item, LMap):
            item.folder = folder  # type: ignore[attr-defined]  # LMap: its folder rides as an attribute
            missing = [key for key in ("type", "file") if key not in item]
            close = did_you_mean(name, list(by_name)) if isinstance(name, str) else None
            if missing and close:
                errors.append(InputError(f"the world it extends has no object '{name}' to change, and a new object "
                                         f"needs {' and '.join(missing)}", item.loc("name", True), key="name",
                                         suggestion=close))
                continue
        added.append((item, own.loc(index)))
    for item in items:
        result.append(item)
        result.item_where.append(item.where)
    for item, at in added:
        result.append(item)
        result.item_where.append(at)
    return result


def _changed(base: LMap, change: LMap, folder: Path) -> LMap:
    """An object of the base world with the keys `change` gives replaced (placed where the change is)."""
    result = _copy(base)
    result.where = change.where
    for key, value in change.items():
        _put(result, key, value, change.loc(key), change.loc(key, True))
    result.folder = folder if "file" in change else folder_of(base, folder)  # type: ignore[attr-defined]  # LMap: its folder rides as an attribute
    return result


def _copy(data: LMap) -> LMap:
    result = LMap(data)
    result.where, result.key_where, result.value_where = data.where, dict(data.key_where), dict(data.value_where)
    return result


def _put(data: LMap, key: str, value: object, key_where: Location, value_where: Location) -> None:
    data[key] = value
    data.key_where[key], data.value_where[key] = key_where, value_where


def _empty_list(where: Location) -> LList:
    result = LList()
    result.where, result.item_where = where, []
    return result

