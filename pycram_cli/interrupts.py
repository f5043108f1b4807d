"""Ctrl-C (SIGINT) and SIGTERM end a command quickly and cleanly, from anywhere.

`install()` (the command line does it first thing, before the heavy imports) puts in a
handler that never takes a lock (a signal can arrive while the main thread holds any of
them): it only notes the signal and writes one byte to a pipe. A watcher thread reads it
and does the work in ordinary thread context:

- while a plan runs, it asks the run to stop (`on_signal` registers the run's interrupt):
  every branch is cancelled, `wait` wakes at once, the run ends with status `interrupted`
  and its trace is written whole;
- otherwise (loading a world, writing files) the handler raises `Interrupted` in the main
  thread, which ends the command without a traceback; while the command's modules are
  imported (`deferred`) it raises as soon as they are.

The exit code is 128 + the signal's number: 130 for SIGINT, 143 for SIGTERM. A second
signal ends the process at once, and so does the watcher when the command has not ended
`DEADLINE` seconds after the first (a step that cannot be interrupted is running); it then says
so on stderr, naming the output files the command still owed (`owe`/`paid`), which are not written.
"""
from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from collections.abc import Callable, Iterator

#: seconds after the first signal at which the process ends whatever it is doing
DEADLINE = 3.0
SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(KeyboardInterrupt):
    """The command was interrupted by a signal (raised in the main thread when no run can be stopped)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum

    @property
    def exit_code(self) -> int:
        return 128 + self.signum


_received: int | None = None
_stoppers: list[Callable[[str], None]] = []
_event = threading.Event()  # set (by the watcher) once a signal has been received
_pipe: int | None = None
_deferring = 0  # inside `deferred()`: note the signal, raise when the block ends
_owed: list[str] = []  # output files the command has still to write (named if the watcher must end it)


def exit_code() -> int | None:
    """128 + the first signal's number (130, 143), or None when no signal was received."""
    return None if _received is None else 128 + _received


def signal_name() -> str | None:
    return None if _received is None else signal.Signals(_received).name


def install() -> None:
    """Handle SIGINT and SIGTERM as described above (main thread only; installing twice changes nothing)."""
    global _pipe
    if _pipe is not None or threading.current_thread() is not threading.main_thread():
        return
    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)
    _pipe = write_end
    threading.Thread(target=_watch, args=(read_end,), name="pycram signals", daemon=True).start()
    for signum in SIGNALS:
        if signal.getsignal(signum) is not signal.SIG_IGN:  # ignored by our parent (a background job): keep it so
            signal.signal(signum, _handler)


def _handler(signum: int, frame: object) -> None:
    global _received
    if _received is not None:  # a second signal: the user insists
        os._exit(128 + _received)
    _received = signum
    if _pipe is not None:
        with contextlib.suppress(OSError):
            os.write(_pipe, bytes([signum]))
    if not _stoppers and not _deferring:
        raise Interrupted(signum)


def _watch(read_end: int) -> None:
    data = os.read(read_end, 1)
    if not data:
        return
    signum = data[0]
    _event.set()
    for stop in list(_stoppers):
        with contextlib.suppress(Exception):
            stop(signal.Signals(signum).name)
    time.sleep(DEADLINE)
    name = signal.Signals(signum).name
    unwritten = f"; not written: {', '.join(_owed)}" if _owed else ""
    with contextlib.suppress(OSError):
        os.write(2, f"error: interrupted by {name}, and the command did not end within {DEADLINE:g} s: "
                    f"exiting now{unwritten}\n".encode())
    os._exit(128 + signum)  # the command is still not done: leave anyway


def owe(description: str) -> None:
    """The command will write this output file (`the trace run.json`): named if the watcher must end it first."""
    _owed.append(description)


def paid(description: str) -> None:
    """The output file `owe` named is written (or will not be)."""
    with contextlib.suppress(ValueError):
        _owed.remove(description)


@contextlib.contextmanager
def on_signal(stop: Callable[[str], None]) -> Iterator[None]:
    """While inside, a signal calls `stop(signal name)` (from the watcher thread) instead of raising."""
    _stoppers.append(stop)
    try:
        if _event.is_set():  # a signal came just before
            stop(signal_name() or "SIGINT")
        yield
    finally:
        _stoppers.remove(stop)


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """A signal inside does not raise at once (imports would turn it into other errors); it raises
    `Interrupted` when the block ends. The watcher's deadline still applies."""
    global _deferring
    _deferring += 1
    try:
        yield
    finally:
        _deferring -= 1
    if _received is not None and not _stoppers:
        raise Interrupted(_received)


def pause(seconds: float) -> None:
    """Sleep, but wake at once when a signal has been received."""
    _event.wait(max(0.0, seconds))

