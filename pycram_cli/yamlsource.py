"""YAML that remembers where each value came from (file, line, column).

Mappings load as `LMap` and sequences as `LList`; both keep the marks of their keys
and items so that any problem found later can be reported at its exact place.
Duplicate keys are an error (plain YAML silently keeps the last one).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from .errors import InputError, Location


class LMap(dict):
    """A mapping with `where` (its own place), `key_where[k]` and `value_where[k]`."""

    where: Location
    key_where: dict[Any, Location]
    value_where: dict[Any, Location]

    def loc(self, key: Any | None = None, value: bool = False) -> Location:
        if key is None:
            return self.where
        table = self.value_where if value else self.key_where
        return table.get(key, self.where)


class LList(list):
    """A sequence with `where` and `item_where[i]`."""

    where: Location
    item_where: list[Location]

    def loc(self, index: int | None = None) -> Location:
        if index is None or index >= len(self.item_where):
            return self.where
        return self.item_where[index]


def where_of(value: Any, fallback: Location) -> Location:
    return getattr(value, "where", fallback)


def _make_loader(filename: str) -> type[yaml.SafeLoader]:
    def location(mark: yaml.Mark) -> Location:
        return Location(filename, mark.line + 1, mark.column + 1)

    class Loader(yaml.SafeLoader):
        pass

    def construct_mapping(loader: yaml.SafeLoader, node: yaml.MappingNode) -> LMap:
        loader.flatten_mapping(node)
        result = LMap()
        result.where = location(node.start_mark)
        result.key_where, result.value_where = {}, {}
        for key_node, value_node in node.value:
            key = loader.construct_object(key_node, deep=True)
            if isinstance(key, (list, dict)):
                raise InputError("a mapping key must be a plain value", location(key_node.start_mark))
            if key in result:
                raise InputError(
                    f"duplicate key '{key}' (first given at line {result.key_where[key].line})",
                    location(key_node.start_mark), key=str(key),
                )
            result[key] = loader.construct_object(value_node, deep=True)
            result.key_where[key] = location(key_node.start_mark)
            result.value_where[key] = location(value_node.start_mark)
        return result

    def construct_sequence(loader: yaml.SafeLoader, node: yaml.SequenceNode) -> LList:
        result = LList(loader.construct_object(child, deep=True) for child in node.value)
        result.where = location(node.start_mark)
        result.item_where = [location(child.start_mark) for child in node.value]
        return result

    Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, construct_mapping)
    Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_SEQUENCE_TAG, construct_sequence)
    return Loader


def load_yaml_text(text: str, filename: str) -> Any:
    try:
        return yaml.load(text, Loader=_make_loader(filename))  # noqa: S506 - SafeLoader subclass
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = Location(filename, mark.line + 1, mark.column + 1) if mark else Location(filename)
        problem = exc.problem or "malformed YAML"
        context = f" {exc.context}" if exc.context else ""
        raise InputError(f"malformed YAML: {problem}{context}", where) from None
    except yaml.YAMLError as exc:
        raise InputError(f"malformed YAML: {exc}", Location(filename)) from None


def load_yaml(path: Path) -> Any:
    """Parse a YAML file, turning every problem into an InputError that names the place."""
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise InputError("file not found", Location(str(path))) from None
    except (IsADirectoryError, PermissionError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read file: {exc.__class__.__name__}", Location(str(path))) from None
    return load_yaml_text(text, str(path))
