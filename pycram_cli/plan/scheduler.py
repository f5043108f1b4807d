"""Cancellation tokens and the deterministic turn scheduler behind `par`, `pursue` and `try_all`.

Every branch of a concurrent node runs in its own thread. The threads share one world
(one PyBullet client), so world actions cannot truly overlap; what must not happen is
that the *order* in which branches act depends on how the operating system schedules
threads, because then the same plan on the same world could end differently.

So plan code runs under a *turn*: at any moment at most one thread of a run executes
plan steps. A thread keeps the turn until it has finished a leaf step (a designator, a
query, a log, ...) and is about to start another one; then it passes the turn on
round-robin (a branch whose leaf ended it reports its outcome first, so a deciding
success or failure cancels its siblings before they take another step), in the order of the branches' keys
(their index paths in the plan tree). A thread gives the turn up while it waits for its
branches to end, while it sleeps in `wait`, and before it starts when it must wait for
an earlier sibling that uses the same resource (arm, base, head) to finish. Sleeping is
the only thing whose wake-up time depends on the clock; every other hand-over is a
function of the plan alone, so traces are identical however threads interleave.
"""
from __future__ import annotations

import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

from .runtime import Cancelled

__all__ = ["Cancelled", "CancelToken", "Key", "Scheduler"]  # Cancelled lives in runtime; re-exported here

Key = tuple[int, ...]
POLL = 0.05  # seconds between checks of a cancellation while waiting (wake-ups are also notified)


class CancelToken:
    """Cancelled when it or any ancestor is cancelled. Checked before every step."""

    _notify: Callable[[], None] | None  # told when it is cancelled (the scheduler's wake-up), the parent's by default

    def __init__(self, parent: CancelToken | None = None, notify: Callable[[], None] | None = None) -> None:
        self._event = threading.Event()
        self._lock = threading.Lock()
        self._children: list[CancelToken] = []
        if notify is None and parent is not None:
            notify = parent._notify
        self._notify = notify
        self.reason = ""
        if parent is not None:
            parent._adopt(self)

    def _adopt(self, child: CancelToken) -> None:
        with self._lock:
            self._children.append(child)
            cancelled = self._event.is_set()
        if cancelled:
            child.cancel(self.reason)

    def child(self) -> CancelToken:
        return CancelToken(self)

    def cancel(self, reason: str = "") -> None:
        with self._lock:
            if self._event.is_set():
                return
            self.reason = reason
            self._event.set()
            children = list(self._children)
        for child in children:
            child.cancel(reason)
        if self._notify is not None:
            self._notify()

    @property
    def cancelled(self) -> bool:
        return self._event.is_set()

    def check(self) -> None:
        if self._event.is_set():
            raise Cancelled(self.reason)

    def sleep(self, seconds: float) -> None:
        """Sleep, waking at once (with Cancelled) if cancelled meanwhile."""
        if self._event.wait(max(0.0, seconds)):
            raise Cancelled(self.reason)


READY, JOINING, WAITING, SLEEPING, QUEUED = "ready", "joining", "waiting", "sleeping", "queued"


@dataclass
class _Entry:
    state: str = READY
    waits_for: set[Key] = field(default_factory=set)
    live_children: int = 0


class Scheduler:
    """Hands the turn from thread to thread in a deterministic order (see the module docstring)."""

    def __init__(self) -> None:
        self._cond = threading.Condition()
        self._entries: dict[Key, _Entry] = {(): _Entry()}
        self._holder: Key | None = ()
        self._pointer: Key = ()
        self._due: set[Key] = set()
        self._queued: dict[Key, list[Key]] = {}  # per parent: branches not started yet, in order
        self._stale = True  # whether `_next` must search again (set whenever a state or the pointer changes)
        self._cached: Key | None = None

    def wake(self) -> None:
        with self._cond:
            self._cond.notify_all()

    # -- choosing the next thread ---------------------------------------------------
    def _next(self) -> Key | None:
        """The next ready key after the pointer (round-robin); remembered until the entries or the pointer change,
        so that many waiting threads woken at once do not each search again."""
        if not self._stale:
            return self._cached
        first: Key | None = None
        after: Key | None = None
        for key, entry in self._entries.items():
            if entry.state != READY:
                continue
            if first is None or key < first:
                first = key
            if key > self._pointer and (after is None or key < after):
                after = key
        self._cached = after if after is not None else first
        self._stale = False
        return self._cached

    def _hand_over(self, key: Key) -> None:
        if self._holder == key:
            self._holder = None
            self._pointer = key
        self._stale = True
        self._cond.notify_all()

    # -- the turn -----------------------------------------------------------------------
    def acquire(self, key: Key, token: CancelToken) -> None:
        """Wait until it is `key`'s turn; raises Cancelled (without the turn) if cancelled first."""
        with self._cond:
            while True:
                if token.cancelled:
                    raise Cancelled(token.reason)
                if self._holder == key:
                    return
                if self._holder is None and self._next() == key:
                    self._holder = key
                    return
                self._cond.wait(POLL)

    def leaf_done(self, key: Key) -> None:
        """`key` finished a leaf step: it passes the turn before its next one."""
        with self._cond:
            self._due.add(key)

    def before_leaf(self, key: Key, token: CancelToken) -> None:
        """`key` is about to start a leaf step: if it has had its go, let the others have theirs first."""
        with self._cond:
            if key not in self._due:
                return
            self._due.discard(key)
        self.pass_turn(key, token)

    def pass_turn(self, key: Key, token: CancelToken) -> None:
        """After a leaf step: let the next thread have a turn, then wait for ours again."""
        with self._cond:
            if self._holder != key:
                return
            others = any(e.state == READY for k, e in self._entries.items() if k != key)
            if not others:
                self._pointer = key
                self._stale = True
                return
            self._hand_over(key)
        self.acquire(key, token)

    def sleep(self, key: Key, token: CancelToken, seconds: float) -> None:
        """Give the turn up while sleeping; the only hand-over that depends on the clock."""
        with self._cond:
            self._entries[key].state = SLEEPING
            self._stale = True
            self._hand_over(key)
        try:
            token.sleep(seconds)
        finally:
            with self._cond:
                self._entries[key].state = READY
                self._stale = True
                self._cond.notify_all()
        self.acquire(key, token)

    # -- branches -------------------------------------------------------------------------
    def spawn(self, parent: Key, count: int, waits_for: Mapping[int, Iterable[int]],
              running: int | None = None) -> list[Key]:
        """Register `count` branches of `parent` (which gives its turn up until they have all finished).

        Branch j does not become ready before every branch in `waits_for[j]` has finished. With
        `running`, only the first `running` branches start; the others are queued, and each time a
        branch of `parent` finishes the next queued one is let in (the caller starts its thread).
        """
        keys = [parent + (i,) for i in range(count)]
        active = count if running is None else min(count, running)
        with self._cond:
            for i, key in enumerate(keys):
                waits = {parent + (j,) for j in waits_for.get(i, ())}
                state = QUEUED if i >= active else WAITING if waits else READY
                self._entries[key] = _Entry(state=state, waits_for=waits)
            if active < count:
                self._queued[parent] = keys[active:]
            self._stale = True
            entry = self._entries[parent]
            entry.live_children = count
            if count:
                entry.state = JOINING
                if self._holder == parent:
                    self._holder = None
                self._pointer = parent
            self._cond.notify_all()
        return keys

    def finish(self, key: Key) -> None:
        """A branch has ended (however); its turn, if held, passes on."""
        with self._cond:
            self._hand_over(key)
            self._due.discard(key)
            self._entries.pop(key, None)
            for entry in self._entries.values():
                if key in entry.waits_for:
                    entry.waits_for.discard(key)
                    if not entry.waits_for and entry.state == WAITING:
                        entry.state = READY
            parent = self._entries.get(key[:-1])
            if parent is not None:
                parent.live_children -= 1
                if parent.live_children <= 0 and parent.state == JOINING:
                    parent.state = READY
            queue = self._queued.get(key[:-1])
            if queue:
                released = self._entries.get(queue.pop(0))
                if released is not None and released.state == QUEUED:
                    released.state = WAITING if released.waits_for else READY
            if queue is not None and not queue:
                del self._queued[key[:-1]]
            self._stale = True
            self._cond.notify_all()
