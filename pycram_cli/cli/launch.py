"""The `pycram` command's entry point: signals are handled before anything heavy is imported.

Importing the commands pulls in PyBullet, NumPy and the rest (a noticeable part of a
second); a Ctrl-C meanwhile must end the command quietly with exit 130 (143 for SIGTERM),
not with a KeyboardInterrupt traceback. So this module imports nothing of pycram but the
signal handling, installs it, and only then loads the commands (see `interrupts.py`).
"""
from __future__ import annotations

import contextlib
import os
import sys

from .. import interrupts


def main() -> None:
    interrupts.install()
    try:
        with interrupts.deferred():  # a signal during the imports ends the command right after them
            from .main import cli  # why: the heavy import happens after the signal handlers are in place
        cli(prog_name="pycram")
    except KeyboardInterrupt:
        code = interrupts.exit_code() or 130
        _say_interrupted()
        sys.exit(code)
    except SystemExit:
        signalled = interrupts.exit_code()
        if signalled is not None:  # whatever the command ended with, a signal decides the exit code
            sys.exit(signalled)
        raise
    except BaseException:
        if interrupts.exit_code() is None:
            raise
        _say_interrupted()  # an interrupted import or call can surface as another error: it was the signal
        sys.exit(interrupts.exit_code())


def _say_interrupted() -> None:
    with contextlib.suppress(OSError):
        os.write(2, b"error: interrupted\n")


if __name__ == "__main__":  # pragma: no cover
    main()
