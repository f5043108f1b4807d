"""A small multicast event: `event += handler`, `event -= handler`, `event(*args)`."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any


class Event:
    """Calls every registered handler, in the order they were added."""

    def __init__(self, name: str = "event") -> None:
        self.name = name
        self._handlers: list[Callable[..., Any]] = []

    def __iadd__(self, handler: Callable[..., Any]) -> Event:
        if not callable(handler):
            raise TypeError(f"{self.name}: a handler must be callable, got {type(handler).__name__}")
        self._handlers.append(handler)
        return self

    def __isub__(self, handler: Callable[..., Any]) -> Event:
        try:
            self._handlers.remove(handler)
        except ValueError:
            raise ValueError(f"{self.name}: that handler was never added") from None
        return self

    def fire(self, *args: Any, **kwargs: Any) -> None:
        for handler in list(self._handlers):
            handler(*args, **kwargs)

    __call__ = fire

    def __len__(self) -> int:
        return len(self._handlers)

    def __repr__(self) -> str:
        return f"Event({self.name!r}, {len(self._handlers)} handlers)"
