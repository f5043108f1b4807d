"""`pycram run --gui`: the window's camera follows the robot and what it works on; a caption names the step.

`GuiView` wraps the run's view (live tree, plain lines, pauses): before passing each event on,
it points PyBullet's viewer at the robot and the objects and places of the step that just ran
(the resolved designator slots and query arguments: `object: bowl`, `target: [x, y, z]`), and
names that step in the top left corner of the window. With `follow=False` the
camera is placed once, on the robot and every object it may work on, and then left alone.
"""
from __future__ import annotations

from typing import Any

from ..plan.replay import focus_points
from ..plan.trace import TraceNode
from ..world import BulletWorld
from ..world.camera import movable_objects, robot_camera


def caption(node: TraceNode) -> str:
    """`item 0 / 0:call move_object / 6:pick-up` — the end of the step's path, short enough for the window."""
    parts = node.path.split("/")
    return ("… / " if len(parts) > 3 else "") + " / ".join(parts[-3:])


class GuiView:
    """Wraps a view of a run in a GUI world (see the module docstring).

    The window stops redrawing while steps execute (each PyBullet call would otherwise wait for a
    frame, which makes a run 50 times slower under a software renderer) and shows the world again
    after each step: motions are teleports, so nothing is missed.
    """

    def __init__(self, world: BulletWorld, view: Any, follow: bool = True) -> None:
        self.world, self.view, self.follow = world, view, follow
        with world.lock:
            self._focus: list[Any] = [tuple((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(world)]
            self._camera = world.viewer_camera()
            self._frame()
            self.world.show_caption("starting", self._camera)
        self._drawing = True

    def _frame(self) -> None:
        if self._camera is None:
            return
        fov, aspect = self._camera.vertical_fov_deg, self.world.viewer_aspect()
        self._camera = robot_camera(self.world, self._focus, fov, aspect)
        self.world.set_viewer_camera(self._camera)

    def started(self, node: TraceNode) -> None:
        if self._drawing:
            with self.world.lock:
                self.world.set_rendering(False)
            self._drawing = False
        self.view.started(node)

    def finished(self, node: TraceNode) -> None:
        if not node.children:
            with self.world.lock:
                if self.follow:
                    self._focus = focus_points(self.world, node.info) or self._focus  # nothing named: same focus
                    self._frame()
                self.world.show_caption(caption(node), self._camera)
                self.world.set_rendering(True)
            self._drawing = True
        self.view.finished(node)

    def log(self, node: TraceNode, message: str) -> None:
        self.view.log(node, message)

    def close(self) -> None:
        """Make sure the window draws again (after the run, also when it failed or was interrupted)."""
        with self.world.lock:
            self.world.set_rendering(True)
        self._drawing = True
