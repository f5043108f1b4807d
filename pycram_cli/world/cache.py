"""One cache per world: what the layers above work out about a world and its objects (kinematic chains, tool axes,
hands, drawn boxes, floor maps, IK answers, motion checks) is kept here, in named tables the world owns.

Why one cache owned by the world rather than a table per module: the answers live and go with the world (and an
object's with the object: every table is keyed weakly by its owner), two worlds never share an answer, and one call
forgets them (`forget`, `forget_everywhere` for a benchmark of first questions). The world layer is the lowest: the
cache stores what it is given without knowing what it is.

Three shapes of table, each by name and owner (the world itself or one of its objects):
- `table(name, owner)`: a plain dict (what the owner's answers are, by question);
- `memo(name, owner, size)`: a `Memo`, the latest `size` answers (the oldest used forgotten first);
- `kept(name, owner, stamp, build)`: one value, built again whenever the stamp (a version, a signature of the world's
  state) is not the one it was built for: a changed world never gets a stale answer.
"""
from __future__ import annotations

import threading
import weakref
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any, TypeVar

T = TypeVar("T")

#: every live world's cache, for `forget_everywhere`
_CACHES: weakref.WeakSet[WorldCache] = weakref.WeakSet()
_CACHES_LOCK = threading.Lock()


class Memo:
    """The latest `size` answers by question: an answer recalled counts as used, the oldest used goes first."""

    def __init__(self, size: int) -> None:
        self.size = size
        self._answers: OrderedDict[Hashable, Any] = OrderedDict()

    def recall(self, key: Hashable) -> Any:
        """The answer kept for `key`, or None."""
        found = self._answers.get(key)
        if found is not None:
            self._answers.move_to_end(key)
        return found

    def remember(self, key: Hashable, answer: Any) -> None:
        self._answers[key] = answer  # a key asked again keeps its place: it was recalled just before
        while len(self._answers) > self.size:
            self._answers.popitem(last=False)

    def __len__(self) -> int:
        return len(self._answers)


class _Stamped:
    """A `kept` value and the stamp it was built for."""

    __slots__ = ("stamp", "value")

    def __init__(self, stamp: Any, value: Any) -> None:
        self.stamp, self.value = stamp, value


class WorldCache:
    """The named tables of one world (`world.cache`); each table holds one entry per owner, weakly keyed."""

    def __init__(self) -> None:
        self._tables: dict[str, weakref.WeakKeyDictionary[Any, Any]] = {}
        self._lock = threading.Lock()  # worlds may be asked from threads of their own (locations, ray workers)
        with _CACHES_LOCK:
            _CACHES.add(self)

    def _entry(self, name: str, owner: Any, make: Callable[[], T]) -> T:
        with self._lock:
            owners = self._tables.get(name)
            if owners is None:
                owners = self._tables[name] = weakref.WeakKeyDictionary()
            found = owners.get(owner)
            if found is None:
                found = owners[owner] = make()
            return found

    def table(self, name: str, owner: Any) -> dict[Any, Any]:
        """Table `name`'s dict for `owner` (the world or one of its objects): empty the first time, gone with the
        owner or when forgotten."""
        found: dict[Any, Any] = self._entry(name, owner, dict)
        assert isinstance(found, dict), f"world cache table {name!r} is not a plain table"
        return found

    def memo(self, name: str, owner: Any, size: int) -> Memo:
        """Table `name`'s `Memo` of the latest `size` answers for `owner`."""
        found = self._entry(name, owner, lambda: Memo(size))
        assert isinstance(found, Memo), f"world cache table {name!r} is not a memo"
        return found

    def kept(self, name: str, owner: Any, stamp: Any, build: Callable[[], T]) -> T:
        """The value of table `name` for `owner` if it was built for `stamp` (compared with ==), else `build()`'s,
        kept for `stamp` (built outside the cache's lock: building may ask the cache again)."""
        with self._lock:
            owners = self._tables.get(name)
            found = owners.get(owner) if owners is not None else None
        if isinstance(found, _Stamped) and found.stamp == stamp:
            return found.value
        value = build()
        with self._lock:
            self._tables.setdefault(name, weakref.WeakKeyDictionary())[owner] = _Stamped(stamp, value)
        return value

    def forget(self, *names: str, owner: Any = None) -> None:
        """Forget tables `names` (none named: every table), for `owner` only when given."""
        with self._lock:
            for name in names or list(self._tables):
                owners = self._tables.get(name)
                if owners is None:
                    continue
                if owner is None:
                    owners.clear()
                else:
                    owners.pop(owner, None)

    def names(self) -> list[str]:
        """The names of the tables that hold something, sorted."""
        with self._lock:
            return sorted(name for name, owners in self._tables.items() if len(owners))


def forget_everywhere(*names: str) -> None:
    """`forget(*names)` in every live world's cache: what a benchmark of first questions needs."""
    with _CACHES_LOCK:
        caches = list(_CACHES)
    for cache in caches:
        cache.forget(*names)
