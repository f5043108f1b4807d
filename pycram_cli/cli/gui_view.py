"""`pycram run --gui`: the window's camera follows the robot and what it works on; captions name the step and failures.

`GuiView` wraps the run's view (live tree, plain lines, pauses): before passing each event on,
it points PyBullet's viewer at the robot and the objects and places of the step that just ran
(the resolved designator slots and query arguments: `object: bowl`, `target: [x, y, z]`), and
names that step in the top left corner of the window. Below it, a failed step's failure is shown in
red; once a later step succeeds, it stays, in orange, as the failure the plan recovered from; when the
plan ends, the last line says how (`plan failed: ...` in red, `plan succeeded` in green). With
`follow=False` the camera is placed once, on the robot and every object it may work on, and then left
alone. The window starts framed on the robot already (the world loader points it there before the
first picture).
"""
from __future__ import annotations

from typing import Any

from ..plan.observer import Observing
from ..plan.replay import focus_points
from ..plan.trace import TraceNode
from ..world import BulletWorld
from ..world.camera import frame_viewer_on_robot, movable_objects, robot_camera

FAILED = (0.8, 0.05, 0.05)
RECOVERED = (0.75, 0.4, 0.0)
SUCCEEDED = (0.05, 0.5, 0.1)
STEP_LINE, FAILURE_LINE = 0, 1
MAX_CHARS = 110  # a caption line, at most (PyBullet does not wrap text)


def caption(node: TraceNode) -> str:
    """`item 0 / 0:call move_object / 6:pick-up` — the end of the step's path, short enough for the window."""
    parts = node.path.split("/")
    return ("… / " if len(parts) > 3 else "") + " / ".join(parts[-3:])


def failure_text(node: TraceNode) -> str | None:
    """`Type: message` of the failure a node failed with itself (not one it passed on from below), else None."""
    failure = node.failure if node.status == "failed" else None
    if failure is None:
        return None
    return _clip(f"{failure.type}: {failure.message}")


def _clip(text: str) -> str:
    return text if len(text) <= MAX_CHARS else text[: MAX_CHARS - 1] + "…"


class GuiView(Observing):
    """Wraps a view of a run in a GUI world (see the module docstring).

    The window stops redrawing while steps execute (each PyBullet call would otherwise wait for a
    frame, which makes a run 50 times slower under a software renderer) and shows the world again
    after each step: motions are teleports, so nothing is missed.
    """

    def __init__(self, world: BulletWorld, view: Any, follow: bool = True) -> None:
        self.world, self.view, self.follow = world, view, follow
        self._failure: tuple[str, tuple[float, float, float]] | None = None  # the failure line: text, colour
        with world.lock:
            self._focus: list[Any] = [tuple((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(world)]
            self._camera = frame_viewer_on_robot(world)
            self.world.show_caption("starting", self._camera, STEP_LINE)
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
        leaf, root = not node.children, "/" not in node.path
        if leaf or root:
            with self.world.lock:
                if leaf and self.follow:
                    self._focus = focus_points(self.world, node.info) or self._focus  # nothing named: same focus
                    self._frame()
                self._note(node, leaf, root)
                if leaf:
                    self.world.show_caption(caption(node), self._camera, STEP_LINE)
                if self._failure is not None:
                    self.world.show_caption(self._failure[0], self._camera, FAILURE_LINE, self._failure[1])
                else:
                    self.world.clear_caption(FAILURE_LINE)
                self.world.set_rendering(True)
            self._drawing = True
        self.view.finished(node)

    def _note(self, node: TraceNode, leaf: bool, root: bool) -> None:
        """What the failure line says after `node` finished (see the module docstring)."""
        if root:
            failure = node.failure
            if node.status == "failed" and failure is not None:
                self._failure = (_clip(f"plan failed: {failure.type}: {failure.message}"), FAILED)
            elif node.status == "succeeded":
                self._failure = ("plan succeeded", SUCCEEDED)
            return
        own = failure_text(node)
        if own is not None:
            self._failure = (f"FAILED {own}", FAILED)
        elif leaf and node.status == "succeeded" and self._failure is not None and self._failure[1] == FAILED:
            self._failure = (_clip("recovered from " + self._failure[0].removeprefix("FAILED ")), RECOVERED)

    def log(self, node: TraceNode, message: str) -> None:
        self.view.log(node, message)

    def folded(self, summary: TraceNode, child: TraceNode) -> None:
        self.view.folded(summary, child)

    def close(self) -> None:
        """Make sure the window draws again (after the run, also when it failed or was interrupted)."""
        with self.world.lock:
            self.world.set_rendering(True)
        self._drawing = True
