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
from collections.abc import Callable, Iterator

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
    devnull = os.open(os.devnull, os.O_WRONLY) if not _verbose else -1
    try:
        with _pointed_at(devnull):
            yield
    finally:
        if devnull >= 0:
            os.close(devnull)


@contextlib.contextmanager
def held_back() -> Iterator[Callable[[], bytes]]:
    """Like `silenced`, but what fd 1 and 2 get meanwhile is kept (a pipe, read by a thread) and offered to the caller
    (`said()`: all of it so far), which can wait until another thread's start-up chatter is over before the terminal
    is given back (PyBullet's window prints its OpenGL driver's names from its own thread, late on a loaded machine);
    then dropped. Verbose: nothing is held back, and `said()` is empty."""
    if _verbose:
        yield lambda: b""
        return
    read, write = os.pipe()
    chunks: list[bytes] = []

    def drain() -> None:
        while True:
            chunk = os.read(read, 65536)
            if not chunk:
                return
            chunks.append(chunk)

    reader = threading.Thread(target=drain, name="pycram-held-back", daemon=True)
    reader.start()
    try:
        with _pointed_at(write):
            yield lambda: b"".join(chunks)
    finally:
        os.close(write)  # the reader ends at the pipe's end (fd 1 and 2 point back elsewhere already)
        reader.join(timeout=1.0)
        os.close(read)


@contextlib.contextmanager
def _pointed_at(fd: int) -> Iterator[None]:
    """fd 1 and 2 pointed at `fd` (re-entrant: nested, the outermost decides; -1: left alone)."""
    global _depth, _saved
    if fd < 0:
        yield
        return
    with _lock:
        if _depth == 0:
            try:
                sys.stdout.flush()
                sys.stderr.flush()
            except (ValueError, OSError):
                pass
            _saved = (os.dup(1), os.dup(2))
            os.dup2(fd, 1)
            os.dup2(fd, 2)
        _depth += 1
        try:
            yield
        finally:
            _depth -= 1
            if _depth == 0 and _saved is not None:
                with contextlib.suppress(ValueError, OSError):
                    sys.stdout.flush()
                    sys.stderr.flush()
                out, err = _saved
                os.dup2(out, 1)
                os.dup2(err, 2)
                os.close(out)
                os.close(err)
                _saved = None
