"""What a run tells the views that watch it (the live tree, the log, the window, the replay recorder).

`Observer` is what the executor calls, for every step, from the plan's threads (one call at a time: the run
holds a lock around them); `Observing` does nothing at each, so that a view derives from it and overrides only
what it shows. A view that wraps another passes every call on, `folded` too.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

if TYPE_CHECKING:
    from .trace import TraceNode


class Observer(Protocol):
    """Told about every step as it starts and ends, the messages of `log` steps, and folded attempts."""

    def started(self, node: TraceNode) -> None: ...

    def finished(self, node: TraceNode) -> None: ...

    def log(self, node: TraceNode, message: str) -> None: ...

    def folded(self, summary: TraceNode, child: TraceNode) -> None:
        """`child` (a repeated attempt, with its subtree) was folded into the summary node `summary`."""
        ...


class Observing:
    """The observer that does nothing: views derive from it and override what they show."""

    def started(self, node: TraceNode) -> None:
        pass

    def finished(self, node: TraceNode) -> None:
        pass

    def log(self, node: TraceNode, message: str) -> None:
        pass

    def folded(self, summary: TraceNode, child: TraceNode) -> None:
        pass
