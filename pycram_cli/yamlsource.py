"""YAML that remembers where each value came from (file, line, column).

Mappings load as `LMap` and sequences as `LList`; both keep the marks of their keys
and items so that any problem found later can be reported at its exact place.
Duplicate keys are an error (plain YAML silently keeps the last one); merge keys
(`<<: *defaults`) work, the mapping's own keys overriding merged ones. Bounded for any
input: file size, nesting and alias expansion (see `limits.py`); numbers must be finite.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import yaml

from .errors import InputError, Location
from .files import read_text
from .limits import MAX_NESTING, MAX_YAML_BYTES, MAX_YAML_NODES, size_text

_WHOLE = object()


class LMap(dict):
    """A mapping with `where` (its own place), `key_where[k]` and `value_where[k]`."""

    where: Location
    key_where: dict[Any, Location]
    value_where: dict[Any, Location]

    def loc(self, key: Any = _WHOLE, value: bool = False) -> Location:
        """The place of `key` (or of its value); with no key, of the mapping itself (a null key is a key)."""
        if key is _WHOLE:
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


MERGE_TAG = "tag:yaml.org,2002:merge"


# long: the Loader class is defined inside, closing over the file name every location names
def _make_loader(filename: str) -> type[yaml.SafeLoader]:
    def location(mark: yaml.Mark) -> Location:
        return Location(filename, mark.line + 1, mark.column + 1)

    class Loader(yaml.SafeLoader):
        """SafeLoader with locations, merge keys, bounded nesting and alias expansion, finite numbers."""

        _depth = 0
        _nodes = 0

        def compose_node(self, parent: Any, index: Any) -> Any:
            self._depth += 1
            if not self.check_event(yaml.AliasEvent):
                self._nodes += 1  # the values written out (aliases are counted once expanded, by _measure)
                if self._nodes > MAX_YAML_NODES:
                    raise InputError(_too_many(), location(self.peek_event().start_mark))
            try:
                if self._depth > MAX_NESTING:
                    raise InputError(f"nested deeper than {MAX_NESTING} levels (the limit)",
                                     location(self.peek_event().start_mark))
                return super().compose_node(parent, index)
            finally:
                self._depth -= 1

        def get_single_data(self) -> Any:
            node = self.get_single_node()
            if node is None:
                return None
            _measure(node, location)
            return self.construct_document(node)

        def construct_object(self, node: yaml.Node, deep: bool = False) -> Any:
            try:
                return super().construct_object(node, deep)
            except (ValueError, OverflowError, TypeError) as exc:
                raise InputError(f"cannot read this value: {exc}", location(node.start_mark)) from None

    def construct_mapping(loader: yaml.SafeLoader, node: yaml.MappingNode) -> LMap:
        explicit = {id(key) for key, _ in node.value if key.tag != MERGE_TAG}
        loader.flatten_mapping(node)  # merged entries first, then the mapping's own (which override them)
        result = LMap()
        result.where = location(node.start_mark)
        result.key_where, result.value_where = {}, {}
        own: dict[Any, bool] = {}
        for key_node, value_node in node.value:
            key = loader.construct_object(key_node, deep=True)
            if isinstance(key, (list, dict, set)):
                raise InputError("a mapping key must be a plain value (a name), not a list or a mapping",
                                 location(key_node.start_mark))
            mine = id(key_node) in explicit
            if key in result and mine and own.get(key):
                raise InputError(
                    f"duplicate key '{key}' (first given at line {result.key_where[key].line})",
                    location(key_node.start_mark), key=str(key),
                )
            try:
                result[key] = loader.construct_object(value_node, deep=True)
            except InputError as exc:  # a bad value deep inside: name the innermost key it belongs to
                if exc.key is None:
                    exc.key = str(key)
                raise
            own[key] = mine
            result.key_where[key] = location(key_node.start_mark)
            result.value_where[key] = location(value_node.start_mark)
        return result

    def construct_sequence(loader: yaml.SafeLoader, node: yaml.SequenceNode) -> LList:
        result = LList(loader.construct_object(child, deep=True) for child in node.value)
        result.where = location(node.start_mark)
        result.item_where = [location(child.start_mark) for child in node.value]
        return result

    def construct_float(loader: yaml.SafeLoader, node: yaml.ScalarNode) -> float:
        value = yaml.SafeLoader.construct_yaml_float(loader, node)
        if not math.isfinite(value):
            what = "too large a number" if not math.isnan(value) and any(c.isdigit() for c in node.value) else \
                "not a finite number"
            raise InputError(f"{what}: '{node.value}' (numbers must be finite)", location(node.start_mark))
        return value

    def construct_int(loader: yaml.SafeLoader, node: yaml.ScalarNode) -> int:
        if len(node.value) > 40:
            raise InputError(f"too large a number: '{node.value[:20]}...' ({len(node.value)} digits)",
                             location(node.start_mark))
        return yaml.SafeLoader.construct_yaml_int(loader, node)

    Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, construct_mapping)
    Loader.add_constructor("tag:yaml.org,2002:int", construct_int)
    Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_SEQUENCE_TAG, construct_sequence)
    Loader.add_constructor("tag:yaml.org,2002:float", construct_float)
    return Loader


def _children(node: yaml.Node) -> list[yaml.Node]:
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    if isinstance(node, yaml.MappingNode):
        return [item for pair in node.value for item in pair]
    return []


def _measure(root: yaml.Node, location: Any) -> None:
    """Refuse documents whose aliases expand beyond the limits (size or nesting) or refer to themselves.

    Aliases share nodes, so a few lines can stand for billions of values (an alias bomb);
    sizes are counted per distinct node (memoised), without recursion.
    """
    size: dict[int, int] = {}
    depth: dict[int, int] = {}
    open_nodes: set[int] = set()
    stack: list[tuple[yaml.Node, bool]] = [(root, False)]
    while stack:
        node, done = stack.pop()
        key = id(node)
        if done:
            open_nodes.discard(key)
            children = _children(node)
            total = 1 + sum(size[id(c)] for c in children)
            deepest = 1 + max((depth[id(c)] for c in children), default=0)
            if total > MAX_YAML_NODES:
                raise InputError(f"this value stands for more than {MAX_YAML_NODES} values once its aliases are "
                                 "expanded (the limit)", location(node.start_mark))
            if deepest > MAX_NESTING:
                raise InputError(f"nested deeper than {MAX_NESTING} levels once its aliases are expanded (the limit)",
                                 location(node.start_mark))
            size[key], depth[key] = total, deepest
            continue
        if key in size:
            continue
        if key in open_nodes:
            raise InputError("an alias refers to a collection that contains it (a structure without end)",
                             location(node.start_mark))
        open_nodes.add(key)
        stack.append((node, True))
        for child in _children(node):
            if id(child) in open_nodes:
                raise InputError("an alias refers to a collection that contains it (a structure without end)",
                                 location(child.start_mark))
            if id(child) not in size:
                stack.append((child, False))


def _count_values(text: str, filename: str) -> None:
    """Refuse a document with more than MAX_YAML_NODES values of its own (aliases not expanded) at once, with
    libyaml's parser (a tenth of a second per megabyte; the pure-Python loader takes seconds to get there).
    Malformed YAML is left to the loader, which says where and what."""
    if not getattr(yaml, "__with_libyaml__", False):
        return  # the loader counts as it goes (compose_node)
    count = 0
    try:
        for event in yaml.parse(text, Loader=yaml.CSafeLoader):
            if isinstance(event, (yaml.ScalarEvent, yaml.SequenceStartEvent, yaml.MappingStartEvent)):
                count += 1
                if count > MAX_YAML_NODES:
                    mark = event.start_mark
                    line, column = (mark.line + 1, mark.column + 1) if mark is not None else (None, None)
                    raise InputError(_too_many(), Location(filename, line, column))
    except yaml.YAMLError:
        return


def _too_many() -> str:
    return (f"more than {MAX_YAML_NODES} values (lists, mappings and scalars) in one file, the limit: "
            "split it, e.g. move steps into subplans")


def load_yaml_text(text: str, filename: str) -> Any:
    """Parse YAML text, turning every problem into an InputError that names the place."""
    if len(text) > MAX_YAML_BYTES:
        raise InputError(f"too large: more than {size_text(MAX_YAML_BYTES)} of YAML", Location(filename))
    _count_values(text, filename)
    try:
        return yaml.load(text, Loader=_make_loader(filename))  # a SafeLoader subclass: safe
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = Location(filename, mark.line + 1, mark.column + 1) if mark else Location(filename)
        problem = exc.problem or "malformed YAML"
        context = f" {exc.context}" if exc.context else ""
        raise InputError(f"malformed YAML: {problem}{context}", where) from None
    except yaml.YAMLError as exc:
        raise InputError(f"malformed YAML: {exc}", Location(filename)) from None
    except RecursionError:  # a last guard; the limits above stop nesting long before
        raise InputError(f"nested deeper than {MAX_NESTING} levels (the limit)", Location(filename)) from None


def load_yaml(path: Path) -> Any:
    """Parse a YAML file, turning every problem into an InputError that names the place.

    The file must be a regular file of at most MAX_YAML_BYTES (no pipes, devices or folders).
    """
    return load_yaml_text(read_text(path, MAX_YAML_BYTES), str(path))
