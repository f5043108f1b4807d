"""GUI mode opens PyBullet's window (under Xvfb when xvfb-run is available; skipped otherwise)."""
from __future__ import annotations

import shutil
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent("""
    import pybullet as p
    from pycram_cli import BulletWorld, Object
    from pycram_cli.world import WorldError
    gui = BulletWorld(mode="gui")
    assert p.getConnectionInfo(gui.client_id)["connectionMethod"] == p.GUI
    arm = Object("arm", "robot", {arm!r}, world=gui)
    try:
        BulletWorld(mode="gui")
        raise SystemExit("a second GUI world was allowed")
    except WorldError as exc:
        print("refused:", exc)
    direct = BulletWorld()
    gui.simulate(0.1)
    gui.exit()
    again = BulletWorld(mode="gui")   # the window may be opened again once the first has exited
    again.exit()
    direct.exit()
    print("ok")
""")


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="xvfb-run is not installed")
def test_gui_world_opens_a_window_and_a_second_one_is_refused(data_dir):
    done = subprocess.run(["xvfb-run", "-a", sys.executable, "-c", SCRIPT.format(arm=str(data_dir / "arm.urdf"))],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "refused: a GUI world is already open" in done.stdout
    assert done.stdout.strip().endswith("ok")
    assert "ven = " not in done.stdout + done.stderr  # the OpenGL driver chatter stays off the terminal
