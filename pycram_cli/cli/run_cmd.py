"""`pycram run PLAN`: validate and run a plan, showing a live tree, and save its trace."""
from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

import click
from rich.live import Live
from rich.markup import escape

from .. import interrupts
from ..files import check_writable
from ..plan.trace import TraceNode, normalised, save
from ..scenario import prepare
from ..world.camera import default_camera, render, write_png
from . import console
from .options import Number, gui_option, json_option, wait_for_window
from .trace_cmd import PLAIN, build_tree, describe_node, find_node

EXIT_FAILED = 1


# -- progress views (observers of a run) ------------------------------------------------------------
class PlainView:
    """One line per finished node on stderr (not a terminal, e.g. CI logs)."""

    def started(self, node: TraceNode) -> None:
        pass

    def finished(self, node: TraceNode) -> None:
        data = node.to_dict(timing=True)
        data.pop("children", None)
        details = describe_node(data)
        console.err.print(f"{PLAIN.get(node.status, node.status):9} {node.path}" + (f"  {details}" if details else ""),
                          markup=False, highlight=False)

    def log(self, node: TraceNode, message: str) -> None:
        pass  # the finished line of the log step shows the message


class LiveView:
    """A live tree of the plan on a terminal: each node with its status, finished subtrees folded."""

    def __init__(self) -> None:
        self.root: TraceNode | None = None
        self._last: Any = ""
        self.live = Live(console=console.err, get_renderable=self.render, refresh_per_second=8, transient=False,
                         auto_refresh=True, vertical_overflow="crop")

    def render(self) -> Any:
        if self.root is None:
            return ""
        try:
            self._last = build_tree(self.root.to_dict(timing=True), collapse=True)
        except RuntimeError:  # the tree changed while it was read: show the previous picture
            pass
        return self._last

    def __enter__(self) -> "LiveView":
        self.live.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.live.refresh()
        self.live.__exit__(*exc)

    def started(self, node: TraceNode) -> None:
        if self.root is None and "/" not in node.path:
            self.root = node

    def finished(self, node: TraceNode) -> None:
        pass

    def log(self, node: TraceNode, message: str) -> None:
        self.live.console.print(f"[cyan]log[/] [dim]{escape(node.path)}[/]: {escape(message)}")


class Paced:
    """Wraps a view: pauses after each motion designator so that a person can follow it in the window."""

    def __init__(self, view: Any, seconds: float) -> None:
        self.view, self.seconds = view, seconds

    def started(self, node: TraceNode) -> None:
        self.view.started(node)

    def finished(self, node: TraceNode) -> None:
        self.view.finished(node)
        if "designator" in node.info:
            interrupts.pause(self.seconds)  # wakes at once on Ctrl-C

    def log(self, node: TraceNode, message: str) -> None:
        self.view.log(node, message)

    def __enter__(self) -> "Paced":
        self.view.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.view.__exit__(*exc)


class QuietView:
    def started(self, node: TraceNode) -> None:
        pass

    def finished(self, node: TraceNode) -> None:
        pass

    def log(self, node: TraceNode, message: str) -> None:
        pass


# -- the command -----------------------------------------------------------------------------------------
@click.command("run")
@click.argument("plan_file", metavar="PLAN")
@click.option("--world", "world_file", metavar="WORLD",
              help="World file or bundled world name (default: the plan's `world:`, else the kitchen).")
@click.option("-p", "--param", "params", multiple=True, metavar="NAME=VALUE",
              help="Set a plan parameter (VALUE is read as YAML: 0.3, [1, 0, 0], milk). Repeatable.")
@click.option("--trace", "trace_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write the run's trace (JSON) to this file.")
@click.option("--render", "render_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write a PNG of the final scene (headless).")
@click.option("--pace", type=Number(0.0, 60.0), default=None, metavar="SECONDS",
              help="Pause after each motion so it can be watched (default: 0.5 with --gui, else 0).")
@json_option
@gui_option
@click.pass_context
def run(ctx: click.Context, plan_file: str, world_file: str | None, params: tuple[str, ...], trace_file: Path | None,
        render_file: Path | None, pace: float | None, as_json: bool, gui: bool) -> None:
    """Validate and run PLAN (a plan file, or the name of a bundled plan).

    Shows the plan as a live tree while it runs and a summary at the end. Exit code 0 when
    the plan succeeded, 1 when it failed, 2 for invalid input.
    """
    for output, key in ((trace_file, "trace"), (render_file, "render")):
        if output is not None:
            check_writable(output, key)  # before anything runs
    scenario = prepare(plan_file, world_file, assignments=params)
    plan, world_path, values = scenario.plan, scenario.world_path, scenario.params
    world = scenario.load_world(mode="gui" if gui else "direct")
    try:
        view: Any
        if as_json:
            view = QuietView()
        elif console.err.is_terminal:
            view = LiveView()
        else:
            view = PlainView()
        if not as_json:
            console.info(f"running {plan.path} on {world_path}"
                         + (f" with {', '.join(f'{k}={json.dumps(v)}' for k, v in values.items())}" if values else ""))
        started = time.perf_counter()
        pace = pace if pace is not None else (0.5 if gui else 0.0)
        if pace > 0:
            view = Paced(view, pace)
        if isinstance(view.view if isinstance(view, Paced) else view, LiveView):
            with view:
                result = scenario.run(world, view)
        else:
            result = scenario.run(world, view)
        duration = time.perf_counter() - started
        interrupted = result.status == "interrupted"
        if trace_file is not None:
            save(result.trace, trace_file)
        if render_file is not None and not interrupted:
            write_png(render_file, render(world, default_camera(world), 960, 720), key="render")
        if as_json:
            console.emit_json(normalised({"status": result.status, "failure": result.failure,
                                          "duration": round(duration, 3), "trace": result.trace}))
        else:
            _summary(plan, result, duration, trace_file)
        if gui and not interrupted:
            wait_for_window(world)
    finally:
        world.exit()
    if result.status == "interrupted":
        ctx.exit(interrupts.exit_code() or 130)
    if not result.succeeded:
        ctx.exit(EXIT_FAILED)


def _summary(plan: Any, result: Any, duration: float, trace_file: Path | None) -> None:
    name = plan.path.name
    if result.succeeded:
        console.success(f"plan {name} succeeded in {duration:.2f} s ({result.steps} steps)")
    elif result.status == "interrupted":
        console.error(f"plan {name} {(result.failure or {}).get('message', 'interrupted')} after {duration:.2f} s"
                      + (" (the trace records where)" if trace_file is not None else ""))
    else:
        failure = result.failure or {}
        node = find_node(result.trace["root"], failure.get("path", ""))
        where = f" ({plan.path}:{node['source']})" if node and node.get("source") else ""
        message = (f"plan {name} {result.status} after {duration:.2f} s: {failure.get('type')} at "
                   f"{failure.get('path')}{where}: {failure.get('message')}")
        for nested in failure.get("failures") or []:
            message += f"\n  - {nested.get('type')} at {nested.get('path')}: {nested.get('message')}"
        if console.out.is_terminal:
            console.out.print(f"[bold red]✗[/] {escape(message)}")
        else:
            console.plain(message)
    if trace_file is not None:
        console.info(f"trace written to {trace_file}")


COMMANDS = [run]
