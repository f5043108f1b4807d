"""Keeping a C library's console output off the terminal: what PyBullet prints with printf, from any thread, while
pycram silences it, never reaches the user's terminal or pipe, not even later."""
from __future__ import annotations

import subprocess
import sys
import textwrap

PRINTF = textwrap.dedent("""
    import ctypes, os, sys, threading, time
    from pycram_cli.quiet import held_back, silenced
    libc = ctypes.CDLL(None)
    {body}
    print("end", flush=True)
""")


def run(body: str) -> str:
    done = subprocess.run([sys.executable, "-c", PRINTF.format(body=textwrap.indent(textwrap.dedent(body), "").strip())],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout + done.stderr


def test_what_c_printed_while_silenced_does_not_come_out_at_exit():
    """To a pipe, C's printf is buffered: unflushed, the chatter came out when the process ended."""
    out = run("""
    with silenced():
        libc.printf(b"chatter from C\\n")
    libc.printf(b"after\\n")
    """)
    assert "chatter" not in out and "after" in out and "end" in out


def test_held_back_output_is_offered_to_the_caller_and_kept_off_the_terminal():
    """A thread that prints late (PyBullet's window names its OpenGL driver from its own thread) is waited for."""
    out = run("""
    def late():
        time.sleep(0.3)
        libc.printf(b"ven = late driver\\n")
        libc.fflush(None)
    with held_back() as said:
        thread = threading.Thread(target=late)
        thread.start()
        while b"ven = " not in said():
            time.sleep(0.02)
        thread.join()
    print("said it", flush=True)
    """)
    assert "ven = " not in out and "said it" in out
