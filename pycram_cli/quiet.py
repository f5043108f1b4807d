"""Keep PyBullet's C-level console output (build banner, URDF warnings) off the terminal.

PyBullet prints from C with printf, which Python's sys.stdout redirection cannot
catch, so the file descriptors 1 and 2 themselves are pointed at /dev/null for
the duration of a noisy call. `set_verbose(True)` (the CLI's `--verbose`) lets
everything through.
"""
from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Iterator

_verbose = False
_lock = threading.RLock()
_depth = 0
_saved: tuple[int, int] | None = None


def set_verbose(value: bool) -> None:
    global _verbose
    _verbose = value


def is_verbose() -> bool:
    return _verbose


@contextlib.contextmanager
def silenced() -> Iterator[None]:
    """Silence fd 1 and 2 (re-entrant, thread-safe) unless verbose."""
    global _depth, _saved
    if _verbose:
        yield
        return
    with _lock:
        if _depth == 0:
            try:
                sys.stdout.flush()
                sys.stderr.flush()
            except (ValueError, OSError):
                pass
            devnull = os.open(os.devnull, os.O_WRONLY)
            _saved = (os.dup(1), os.dup(2))
            os.dup2(devnull, 1)
            os.dup2(devnull, 2)
            os.close(devnull)
        _depth += 1
        try:
            yield
        finally:
            _depth -= 1
            if _depth == 0 and _saved is not None:
                out, err = _saved
                os.dup2(out, 1)
                os.dup2(err, 2)
                os.close(out)
                os.close(err)
                _saved = None
