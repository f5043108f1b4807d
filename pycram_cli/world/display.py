"""Whether a window can be opened: asked before PyBullet is, because PyBullet cannot say.

On Linux, PyBullet's GUI client opens the X display from its own thread and, when that
fails, prints "cannot connect to X server" and ends the whole process with exit code 1
(the code the CLI uses for "the plan failed"); when the display has no OpenGL (GLX), it
prints "Error in gladLoadGLX" and ends it with exit code 0, as if all went well. Both
messages go to a terminal that is silenced at that moment. So the display is opened once
here, with libX11 through ctypes (the same library PyBullet loads), its GLX version is
asked through libGL as PyBullet's loader asks it, and a `NoDisplayError` says what to do
instead. Other platforms have a window system of their own: nothing to ask.
"""
from __future__ import annotations

import ctypes
import ctypes.util
import os
import sys
import time

from ..errors import PycramError, setting

ADVICE = f"run under xvfb-run or without {setting('gui')}"


class NoDisplayError(RuntimeError, PycramError):
    """No window can be opened (no X display); the CLI reports it as invalid input (exit 2)."""


def _library(name: str, usual: str) -> ctypes.CDLL | None:
    """The shared library `name` (found by the system's rules, else by its `usual` file name), or None."""
    try:
        return ctypes.CDLL(ctypes.util.find_library(name) or usual)
    except OSError:
        return None


def display_problem() -> str | None:
    """Why a window cannot be opened here, or None when it can (always None outside Linux)."""
    if not sys.platform.startswith("linux"):
        return None
    name = os.environ.get("DISPLAY", "")
    if not name:
        return "no display (DISPLAY is not set)"
    x11 = _library("X11", "libX11.so.6")
    if x11 is None:
        return f"no X11 library to open display {name!r} with (install libx11)"
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    handle = None
    for attempt in range(5):  # a display server that is still starting (xvfb-run on a busy machine) gets a moment
        handle = x11.XOpenDisplay(name.encode())
        if handle:
            break
        time.sleep(0.2 * (attempt + 1))
    if not handle:
        return f"no display (cannot open DISPLAY={name!r})"
    try:
        return _opengl_problem(handle, name)
    finally:
        x11.XCloseDisplay(handle)


def _opengl_problem(handle: int, name: str) -> str | None:
    """Why PyBullet's window could not draw on the open display `handle`, or None: the window needs libGL and the
    display's GLX extension (asked for its version, as PyBullet's GL loader does before it gives up)."""
    gl = _library("GL", "libGL.so.1")
    if gl is None:
        return f"no OpenGL library to draw on display {name!r} with (install libgl1)"
    gl.glXQueryVersion.restype = ctypes.c_int
    gl.glXQueryVersion.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ctypes.c_int)]
    major, minor = ctypes.c_int(0), ctypes.c_int(0)
    if not gl.glXQueryVersion(handle, ctypes.byref(major), ctypes.byref(minor)):
        return f"display {name!r} has no OpenGL (its X server lacks the GLX extension)"
    return None


def check_display() -> None:
    """Raise NoDisplayError with a message a person can act on when no window can be opened."""
    problem = display_problem()
    if problem is not None:
        raise NoDisplayError(f"cannot open a window: {problem}; {ADVICE}")
