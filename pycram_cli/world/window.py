"""What a world does with its GUI window: the viewer's camera, pausing its redraws, captions at its top left.

`BulletWorld` takes these methods from `GuiWindow`; each does nothing (or answers a default) for a world without a
window (`mode` other than gui, or disconnected), so callers never ask which kind of world they have. Apart from
`bullet_world.py` because the window is a concern of its own: only `--gui` runs and the viewer module use it.
"""
from __future__ import annotations

import contextlib
import math
import time
from collections.abc import Callable, Iterator

import numpy as np
import pybullet as p

from ..quiet import held_back, is_verbose, silenced
from .camera import Camera
from .pose import matrix_to_quat

#: the window's thread prints its OpenGL driver's names last of its start-up (lines 'ven = ...', MARK); what it prints
#: is held back until MARK came and then nothing for CHATTER_QUIET s, or nothing at all for CHATTER_SILENT s (a build
#: that prints no such line), at most CHATTER_WAIT s after the window opened (s)
MARK = b"ven = "
CHATTER_QUIET = 0.15
CHATTER_SILENT = 1.0
CHATTER_WAIT = 5.0


def open_window() -> int:
    """Connect a PyBullet GUI client (its id, negative when none opened) with its side panel and shadows off, once its
    window shows the scene, its driver chatter kept off the terminal (`held_back`: the window prints it from its own
    thread, which on a loaded machine came after a fixed wait and reached the terminal)."""
    with held_back() as said:
        client = p.connect(p.GUI)
        if client < 0:
            return client
        p.configureDebugVisualizer(p.COV_ENABLE_GUI, 0, physicsClientId=client)
        p.configureDebugVisualizer(p.COV_ENABLE_SHADOWS, 0, physicsClientId=client)
        deadline = time.monotonic() + CHATTER_WAIT
        while p.getDebugVisualizerCamera(physicsClientId=client)[0] <= 0 and time.monotonic() < deadline:
            time.sleep(0.02)
        if not is_verbose():
            _until_said(said, deadline)
    return client


def _until_said(said: Callable[[], bytes], deadline: float) -> None:
    """Wait until the window's start-up chatter is over (see MARK) or the deadline."""
    size, changed = -1, time.monotonic()
    while time.monotonic() < deadline:
        text = said()
        now = time.monotonic()
        if len(text) != size:
            size, changed = len(text), now
        if now - changed >= (CHATTER_QUIET if MARK in text else CHATTER_SILENT):
            return
        time.sleep(0.02)


class GuiWindow:
    """The GUI window's side of a `BulletWorld` (a base class: it reads the world's client, mode and captions)."""

    mode: str
    client_id: int
    _captions: dict[int, int]

    def is_connected(self) -> bool:
        raise NotImplementedError

    @contextlib.contextmanager
    def rendering_paused(self) -> Iterator[None]:
        """`with world.rendering_paused():` — the GUI window does not redraw inside (loading many bodies
        is then about 30 times faster under a software renderer); nothing without a window."""
        self.set_rendering(False)
        try:
            yield
        finally:
            self.set_rendering(True)

    def set_rendering(self, on: bool) -> None:
        """Let the GUI window redraw (on) or keep showing its last picture (off), nothing without a window.

        While a window redraws, every PyBullet call waits for a frame (about 10 ms under a software
        renderer), so runs switch it off while a step executes and on again to show its result.
        """
        if self.mode == "gui" and self.is_connected():
            p.configureDebugVisualizer(p.COV_ENABLE_RENDERING, 1 if on else 0, physicsClientId=self.client_id)

    def viewer_camera(self) -> Camera | None:
        """Where the GUI window's camera is now (with the window's field of view); None without a window."""
        if self.mode != "gui" or not self.is_connected():
            return None
        info = p.getDebugVisualizerCamera(physicsClientId=self.client_id)
        view, projection = info[2], info[3]
        rotation = np.array(view, dtype=float).reshape(4, 4, order="F")
        eye = -rotation[:3, :3].T @ rotation[:3, 3]
        target = tuple(float(v) for v in info[11])
        fov = math.degrees(2.0 * math.atan(1.0 / projection[5])) if projection[5] else 60.0
        return Camera(tuple(float(v) for v in eye), target, vertical_fov_deg=fov)  # type: ignore[arg-type]

    def viewer_aspect(self) -> float:
        """Width over height of the GUI window (4/3 without a window)."""
        if self.mode != "gui" or not self.is_connected():
            return 4 / 3
        info = p.getDebugVisualizerCamera(physicsClientId=self.client_id)
        return info[0] / info[1] if info[1] else 4 / 3

    def set_viewer_camera(self, camera: Camera) -> None:
        """Point the GUI window's camera from `camera.eye` at `camera.target` (nothing without a window).

        The window keeps its own field of view (see `viewer_camera`)."""
        if self.mode != "gui" or not self.is_connected():
            return
        offset = np.asarray(camera.target, dtype=float) - np.asarray(camera.eye, dtype=float)
        distance = float(np.linalg.norm(offset))
        if distance < 1e-6:
            return
        forward = offset / distance
        pitch = math.degrees(math.asin(max(-1.0, min(1.0, float(forward[2])))))
        yaw = math.degrees(math.atan2(-float(forward[0]), float(forward[1])))
        p.resetDebugVisualizerCamera(distance, yaw, pitch, list(camera.target), physicsClientId=self.client_id)

    def show_caption(self, text: str, camera: Camera | None = None, line: int = 0,
                     color: tuple[float, float, float] = (0.05, 0.05, 0.3)) -> None:
        """Show `text` at the top left of the GUI window, on line `line` (0: the top), in `color` (replacing what that
        line showed; nothing without a window).

        PyBullet draws text at a point in the world, so it is placed just in front of the viewer's camera:
        `camera` when the caller has just set it (the window reports a new camera only once it has drawn it).
        """
        if self.mode != "gui" or not self.is_connected():
            return
        camera = camera or self.viewer_camera()
        if camera is None:
            return
        eye = np.asarray(camera.eye, dtype=float)
        forward = np.asarray(camera.target, dtype=float) - eye
        forward /= np.linalg.norm(forward) or 1.0
        right = np.cross(forward, (0.0, 0.0, 1.0))
        right /= np.linalg.norm(right) or 1.0
        up = np.cross(right, forward)
        depth = 1.0
        half_v = math.tan(math.radians(camera.vertical_fov_deg) / 2.0) * depth
        half_h = half_v * self.viewer_aspect()
        where = eye + forward * depth + up * half_v * (0.9 - 0.09 * line) - right * half_h * 0.96
        # turned to face this camera: PyBullet would turn it to the camera the window still shows
        facing = matrix_to_quat(np.column_stack([right, up, -forward]))
        previous = self._captions.get(line, -1)
        options = {"replaceItemUniqueId": previous} if previous >= 0 else {}
        with silenced():
            self._captions[line] = p.addUserDebugText(text, where.tolist(), textColorRGB=list(color),
                                                      textSize=0.06 * half_v, textOrientation=list(facing),
                                                      physicsClientId=self.client_id, **options)

    def clear_caption(self, line: int) -> None:
        """Take line `line` of the caption away (nothing when it shows nothing, or without a window)."""
        item = self._captions.pop(line, -1)
        if item >= 0 and self.mode == "gui" and self.is_connected():
            with silenced():
                p.removeUserDebugItem(item, physicsClientId=self.client_id)
