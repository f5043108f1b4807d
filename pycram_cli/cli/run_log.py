"""`pycram run`'s progress when stderr is not a terminal (CI logs): the plan tree as an indented log.

Steps are printed in the plan's order (pre-order; the branches of `par` one after another, never
interleaved however their threads ran), indented two spaces per level, under their own label
(`1:detecting`, not the whole path):

- a step with children as a header line (its label and what is known when it starts: the call's
  arguments, the condition, the item) once its first child has started;
- a step without children when it ends: its status (`ok`, `FAILED`, `recovered`, `skipped`,
  `cancelled`), its slots or answer and its duration;
- a step whose own failure arose at it after its children (`try_all`: every alternative failed)
  gets a closing line with that failure.

A failure is marked as `trace show` and the live view mark it (`trace_cmd.shown_status`):
`recovered` when something above it succeeded (a retry, a catch, another alternative), `FAILED`
when nothing did. A failed step is printed only once that is known, so the lines after it wait until
then (they are never buffered: the run's trace tree is what is read, from a cursor). Every line is
cut to WIDTH characters.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..plan.observer import Observing
from ..plan.trace import TraceNode
from . import console
from .trace_cmd import PLAIN, describe_node, saves_children, shown_status

WIDTH = 120  # characters per line at most (a longer one ends in "…")
INDENT = "  "
STATUS_WIDTH = max(len(word) for word in PLAIN.values())
UNFINISHED = ("pending", "running")
#: what a header line leaves out: it is printed when the step starts, before these are known
LATER = ("bound", "retries", "failure", "folded", "timing")


@dataclass
class _Frame:
    """A step whose header is printed and whose children are being printed."""

    node: TraceNode
    next: int = 0                  # the index in node.children of the next child to print
    last: TraceNode | None = None  # the child printed last (to find the place again if the list changed)


def _record(node: TraceNode, timing: bool = True) -> dict[str, Any]:
    """The node alone as a trace record (no children): what `describe_node` reads."""
    data: dict[str, Any] = {"path": node.path, "type": node.type, "status": node.status}
    data.update(node.info)
    if node.failure is not None:
        data["failure"] = node.failure.to_json()
    if timing and node.duration is not None:
        data["timing"] = {"started": node.started, "duration": node.duration}
    return data


def clip(line: str, width: int = WIDTH) -> str:
    """One line of at most `width` characters (newlines inside become spaces)."""
    line = line.replace("\r", " ").replace("\n", " ")
    return line if len(line) <= width else line[: width - 1] + "…"


class RunLog(Observing):
    """An observer of a run (see plan/observer.py) that prints the indented log described above."""

    def __init__(self, write: Callable[[str], None] | None = None, width: int = WIDTH) -> None:
        self.write = write or (lambda line: console.err.print(line, markup=False, highlight=False))
        self.width = width
        self.root: TraceNode | None = None
        self.stack: list[_Frame] = []
        self.done = False

    # -- observer --------------------------------------------------------------------------------
    def started(self, node: TraceNode) -> None:
        if self.root is None and "/" not in node.path:
            self.root = node
        self.flush()

    def finished(self, node: TraceNode) -> None:
        self.flush()

    # log: the log step's own line shows the message (Observing's does nothing)

    def close(self) -> None:
        """The run is over: print whatever is left, as it stands (also after an interrupt or an error)."""
        self.flush(final=True)

    # -- the cursor ----------------------------------------------------------------------------------
    def flush(self, final: bool = False) -> None:
        """Print every line that is ready, in order, from where the last flush stopped."""
        root = self.root
        if root is None or self.done:
            return
        final = final or root.status not in UNFINISHED  # the run is over: every failure's fate is known
        if not self.stack:
            if not self._visit(root, final):
                return
            if not self.stack:  # the root had no children
                self.done = True
                return
        while self.stack:
            frame = self.stack[-1]
            children = list(frame.node.children)
            index = self._place(frame, children)
            if index < len(children):
                if not self._visit(children[index], final):
                    return
                frame.next, frame.last = index + 1, children[index]
                continue
            if frame.node.status in UNFINISHED and not final:
                return  # more children may come
            self.stack.pop()
            if not self._close(frame.node, final):
                self.stack.append(frame)
                return
        self.done = True

    @staticmethod
    def _place(frame: _Frame, children: list[TraceNode]) -> int:
        """Where the next child to print is (a retry folds old attempts: the list may have changed)."""
        if frame.last is None:
            return 0
        if 0 < frame.next <= len(children) and children[frame.next - 1] is frame.last:
            return frame.next
        for index, child in enumerate(children):
            if child is frame.last:
                return index + 1
        return min(max(frame.next - 1, 0), len(children))  # folded away: its summary took its place

    def _saved(self) -> bool:
        """Whether a failure at the cursor was recovered from: a step above it succeeded."""
        saved = False
        for frame in self.stack:
            saved = saves_children({"status": frame.node.status}, saved)
        return saved

    def _visit(self, node: TraceNode, final: bool) -> bool:
        """Print the node's line if it is ready (True; a header is pushed to print its children under it)."""
        children = list(node.children)
        depth = len(self.stack)
        if children and (final or node.status not in UNFINISHED or any(c.status != "pending" for c in children)):
            details = describe_node({k: v for k, v in _record(node, timing=False).items() if k not in LATER},
                                    timing=False)
            self._print(INDENT * depth + node.label + (f"  {details}" if details else ""))
            self.stack.append(_Frame(node))
            return True
        if node.status in UNFINISHED and not final:
            return False
        return self._line(node, depth, final)

    def _close(self, node: TraceNode, final: bool) -> bool:
        """After a step's children (its frame popped): its own failure, if it arose there and not in a child."""
        if node.status != "failed" or node.failure is None or node.failure.path != node.path:
            return True
        return self._line(node, len(self.stack), final)

    def _line(self, node: TraceNode, depth: int, final: bool) -> bool:
        saved = self._saved()
        if node.status == "failed" and not (saved or final):
            return False  # recovered or fatal: not known yet
        data = _record(node)
        status = PLAIN.get(shown_status(data, saved), node.status)
        details = describe_node(data)
        self._print(f"{INDENT * depth}{status:{STATUS_WIDTH}} {node.label}" + (f"  {details}" if details else ""))
        return True

    def _print(self, line: str) -> None:
        self.write(clip(line, self.width))
