"""`pycram run PLAN`: validate and run a plan, showing a live tree, and save its trace."""
from __future__ import annotations

import contextlib
import time
from pathlib import Path
from typing import Any

import click
from rich.live import Live
from rich.text import Text

from .. import interrupts
from ..errors import InputError, Location
from ..failures import FailureRecord, InternalError
from ..files import check_writable
from ..limits import MAX_PROJECTED, MAX_WORKERS
from ..plan.observer import Observing
from ..plan.trace import TraceNode, dumps, normalised
from ..report.failures import failure_camera
from ..scenario import prepare
from ..scenario.starts import ImpossibleStart, possible_variant
from ..scenario.variation_files import read_variations, variation_file
from ..sweep.projection import LocalProjector, Projection, project
from ..world.camera import IMAGE_FORMATS, encode_image, image_format, moved_since, poses, render
from . import console
from .complete import plan_names, world_names
from .files import MCAP_FORMATS, REPORT_FORMATS, check_outputs, distinct_outputs, write_mcap, write_output, write_report
from .gui_view import GuiView
from .options import (
    Number,
    camera_option,
    gui_option,
    image_camera,
    json_option,
    parse_size,
    parse_view,
    size_option,
    wait_for_window,
)
from .run_log import WIDTH, RunLog, clip
from .trace_cmd import build_tree, find_node, short

EXIT_FAILED = 1


# -- progress views (observers of a run) ------------------------------------------------------------
class LiveView(Observing):
    """A live tree of the plan on a terminal: each node with its status, finished subtrees folded."""

    def __init__(self) -> None:
        self.root: TraceNode | None = None
        self._last: Any = ""
        self.live = Live(console=console.err, get_renderable=self.render, refresh_per_second=8, transient=False,
                         auto_refresh=True, vertical_overflow="crop")

    def render(self) -> Any:
        if self.root is None:
            return ""
        with contextlib.suppress(RuntimeError):  # the tree changed while it was read: show the previous picture
            self._last = build_tree(self.root.to_dict(timing=True), collapse=True)
        return self._last

    def __enter__(self) -> LiveView:
        self.live.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.live.refresh()
        self.live.__exit__(*exc)

    def started(self, node: TraceNode) -> None:
        if self.root is None and "/" not in node.path:
            self.root = node

    def log(self, node: TraceNode, message: str) -> None:
        self.live.console.print(Text.assemble(("log", "cyan"), " ", (node.path, "dim"), ": ", message))


class Paced(Observing):
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

    def folded(self, summary: TraceNode, child: TraceNode) -> None:
        self.view.folded(summary, child)

    def __enter__(self) -> Paced:
        self.view.__enter__()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.view.__exit__(*exc)


class QuietView(Observing):
    """Shows nothing (`--quiet`, `--json`)."""


# -- the command -----------------------------------------------------------------------------------------
# long: one click command: each of its flags handed on in the order a run needs them (the work is in scenario/)
@click.command("run")
@click.argument("plan_file", metavar="PLAN", shell_complete=plan_names)
@click.option("--world", "world_file", metavar="WORLD", shell_complete=world_names,
              help="World file or bundled world name (default: the plan's `world:`, else the kitchen).")
@click.option("-p", "--param", "params", multiple=True, metavar="NAME=VALUE",
              help="Set a plan parameter (VALUE is read as YAML: 0.3, [1, 0, 0], milk). Repeatable.")
@click.option("--trace", "trace_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write the run's trace (JSON) to this file.")
@click.option("--render", "render_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write an image of the final scene (headless); its extension sets the format (.png, .jpg, ...).")
@camera_option
@size_option
@click.option("--report", "report_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write a replay report: one HTML file with a 3D replay, the plan tree and a timeline.")
@click.option("--mcap", "mcap_file", type=click.Path(dir_okay=False, path_type=Path),
              help="Write the replay as an MCAP file (.mcap) that Foxglove opens: the bodies, their frames, "
                   "the steps as a log, the robot camera's images.")
@click.option("--pace", type=Number(0.0, 60.0), default=None, metavar="SECONDS",
              help="Pause after each motion so it can be watched (default: 0.5 with --gui, else 0).")
@click.option("--scenario", "scenario_seed", type=int, default=None, metavar="SEED",
              help="Run one scenario of a sweep: the world and parameters drawn from SEED (see `pycram sweep`).")
@click.option("--vary", "vary_file", metavar="VARY.yaml",
              help="The variation file --scenario draws from (default: PLAN.vary.yaml beside the plan).")
@click.option("--project", "project_runs", type=click.IntRange(1, MAX_PROJECTED), default=None, metavar="N",
              help="Before acting, run the plan N times in prospection on scenarios drawn from the variation file "
                   "(--vary) and print the success rate and the failures by cause.")
@click.option("--require", type=Number(0.0, 1.0), default=None, metavar="P",
              help="With --project: do not run (exit 1) when the projected success rate is below P (0-1).")
@click.option("--workers", type=click.IntRange(1, MAX_WORKERS), default=None, metavar="K",
              help="Worker processes for projections (--project, and `project` steps when that is faster): at most "
                   "K (default: the cores other work leaves idle).")
@click.option("--follow/--no-follow", default=True, show_default=True,
              help="With --gui: the window's camera follows the robot (else it stays where it was put at the start).")
@json_option
@gui_option
@click.pass_context
def run(ctx: click.Context, plan_file: str, world_file: str | None, params: tuple[str, ...], trace_file: Path | None,
        render_file: Path | None, camera: str | None, size: str, report_file: Path | None, mcap_file: Path | None,
        pace: float | None, scenario_seed: int | None, vary_file: str | None, project_runs: int | None,
        require: float | None, workers: int | None, follow: bool, as_json: bool, gui: bool) -> None:
    """Validate and run PLAN (a plan file, or the name of a bundled plan).

    Shows the plan as a live tree while it runs and a summary at the end. Exit code 0 when
    the plan succeeded, 1 when it failed, 2 for invalid input.
    """
    image_size, view_name = parse_size(size), parse_view(camera)
    if camera is not None and render_file is None:
        raise InputError("sets the camera of the --render image, but no --render FILE is given",
                         Location("--camera"))
    if not follow and not gui:
        raise InputError("keeps the first view of the --gui window, but no --gui is given", Location("--no-follow"),
                         suggestion="add --gui, or leave --no-follow out")
    check_outputs([(trace_file, None, "trace"), (render_file, IMAGE_FORMATS, "image"),
                   (report_file, REPORT_FORMATS, "report"), (mcap_file, MCAP_FORMATS, "MCAP file")])
    distinct_outputs([(trace_file, "trace"), (render_file, "image"), (report_file, "report"), (mcap_file, "MCAP file")])
    for output, key in ((trace_file, "trace"), (render_file, "render"), (report_file, "report"), (mcap_file, "mcap")):
        if output is not None:
            check_writable(output, key)  # a pipe, a device, no permission: before anything runs
    if require is not None and project_runs is None:
        raise InputError("sets the success rate --project must reach, but no --project N is given",
                         Location("--require"), suggestion="add --project 20 (or leave --require out)")
    if project_runs is not None and scenario_seed is not None:
        raise InputError("projects the plan over scenarios, and --scenario runs one of them: give one of them",
                         Location("--project"))
    scenario = prepare(plan_file, world_file, assignments=params)
    if vary_file is not None and scenario_seed is None and project_runs is None:
        raise InputError("--vary draws a scenario only with --scenario SEED (or projections with --project N)",
                         Location("--vary"))
    if project_runs is not None:
        given = {name for name in (a.partition("=")[0].strip() for a in params)}
        projection = Projection(str(scenario.plan.path), vary_file, str(scenario.world_path),
                                {k: v for k, v in scenario.params.items() if k in given}, project_runs,
                                workers=workers)
        try:
            summary = project(projection)
        except KeyboardInterrupt:
            console.error("interrupted while projecting: nothing was run")
            ctx.exit(interrupts.exit_code() or 130)
        refused = require is not None and (summary["rate"] or 0.0) < require
        if as_json and refused:
            console.emit_json({"status": "not run", "projection": summary})
        elif not as_json:
            _projected(summary, scenario.plan.path, vary_file, require)
        if refused and require is not None:  # (refused says it is not None; the type checker wants it said)
            console.error(f"not running {scenario.plan.path.name}: the projected success rate "
                          f"{_percent(summary['rate'])} is below the required {100 * require:.1f} %")
            ctx.exit(EXIT_FAILED)
    if scenario_seed is not None:
        vary = variation_file(scenario.plan.path, vary_file, "--scenario", "running one scenario")
        variations = read_variations(vary, scenario.world, scenario.plan)
        base = scenario
        try:  # the sweep's draw: redrawn while its objects cannot start (scenario/starts.py)
            variant, world = possible_variant(variations, scenario_seed, None,
                                              lambda v: base.varied(v).load_world(mode="gui" if gui else "direct"),
                                              release=lambda w: w.exit())
        except ImpossibleStart as exc:
            raise InputError(f"{exc} (the variation file draws starts that cannot be)", Location("--scenario"),
                             suggestion=f"check the poses and `separation` of {vary}") from None
        given = {name for name in (a.partition("=")[0].strip() for a in params)}
        before = scenario.params
        scenario = scenario.varied(variant).with_params({k: v for k, v in before.items() if k in given})
    else:
        world = scenario.load_world(mode="gui" if gui else "direct")
    plan, world_path, values = scenario.plan, scenario.world_path, scenario.params
    try:
        before = poses(world)
        view: Any
        if as_json or console.is_quiet():
            view = QuietView()
        elif console.err.is_terminal:
            view = LiveView()
        else:
            view = RunLog()  # an indented log, one line per step (CI logs)
        if not as_json:
            for line in _running(plan.path, world_path, values):
                console.info(line)
        started = time.perf_counter()
        progress = view
        pace = pace if pace is not None else (0.5 if gui else 0.0)
        if pace > 0:
            view = Paced(view, pace)
        observer = GuiView(world, view, follow) if gui else view
        replay = trace_file is not None or report_file is not None or mcap_file is not None
        for output in (trace_file, render_file, report_file, mcap_file):
            if output is not None:
                interrupts.owe(str(output))  # said on stderr if a signal's deadline ends the run before it is written
        projector = None if gui else LocalProjector(workers)  # `project` steps' runs on local workers (not under a window)
        internal: InternalError | None = None
        try:
            try:
                if isinstance(progress, LiveView):
                    with view:
                        result = scenario.run(world, observer, replay=replay, projector=projector)
                else:
                    result = scenario.run(world, observer, replay=replay, projector=projector)
            except InternalError as exc:  # a bug stopped the run: its trace is still written, then main says it
                if exc.result is None:
                    raise
                internal, result = exc, exc.result
        finally:
            if isinstance(observer, GuiView):
                observer.close()
            if isinstance(progress, RunLog):
                progress.close()  # the rest of the log, also when the run was interrupted
        duration = time.perf_counter() - started
        interrupted = result.status == "interrupted"
        if trace_file is not None:
            write_output(trace_file, dumps(result.trace), "trace")
        if internal is not None:
            raise internal  # the one-line message and exit 3 (cli/main.py), the traceback under --verbose
        if render_file is not None and not interrupted:
            cam = None
            if not result.succeeded and (camera is None or view_name == "target"):  # a failure: what failed, where
                cam = failure_camera(world, result.trace, image_size[0] / image_size[1])
            cam = cam or image_camera(world, view_name, image_size, moved_since(world, before) or None)
            write_output(render_file, encode_image(render(world, cam, *image_size), render_file.suffix),
                         f"{image_size[0]}x{image_size[1]} {image_format(render_file.suffix)}")
        if report_file is not None and not interrupted:
            write_report(report_file, result.trace, scenario.world_path)
        if mcap_file is not None and not interrupted:
            write_mcap(mcap_file, result.trace, scenario.world_path)
        if as_json:
            failure = result.failure.to_json() if result.failure is not None else None
            console.emit_json(normalised({"status": result.status, "failure": failure,
                                          "duration": round(duration, 3), "trace": result.trace,
                                          **({"projection": summary} if project_runs is not None else {})}))
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


def _percent(rate: float | None) -> str:
    return "-" if rate is None else f"{100.0 * rate:.1f} %"


def _projected(summary: dict[str, Any], plan_path: Path, vary_file: str | None, require: float | None) -> None:
    """The projection's success rate and its failures by cause, each with the command that replays an example."""
    lo, hi = summary["interval"]
    console.info(f"projected {plan_path.name} {summary['scenarios']} times on scenarios of "
                 f"{Path(summary['vary']).name}: succeeded {summary['succeeded']} of {summary['runs']}, "
                 f"{_percent(summary['rate'])} (95 % interval {100 * lo:.1f}-{100 * hi:.1f} %)"
                 + (f"; required {100 * require:.1f} %" if require is not None else ""))
    starts = summary["starts"]
    if starts["invalid"]:
        console.info(f"  {starts['invalid']} scenarios could not start (not counted): {starts['invalid_example']}")
    for failure in summary["failures"]:
        example = failure["example"]
        replay = f"pycram run {plan_path} --scenario {example['seed']}" + (f" --vary {vary_file}" if vary_file else "")
        console.info(f"  {failure['count']:>4}  {failure['type']} at {failure['path'] or '-'}")
        console.info(f"        e.g. {example['message']}")
        console.info(f"        replay: {replay}")


def _running(plan_path: Path, world_path: Path, values: dict[str, Any]) -> list[str]:
    """`running PLAN on WORLD` (the files in full: which ones ran), then the parameters, shortened to one line."""
    lines = [f"running {plan_path} on {world_path}"]
    if values:
        lines.append(clip("with " + ", ".join(f"{k}={short(v, 40)}" for k, v in values.items()), WIDTH - 6))
    return lines


def _summary(plan: Any, result: Any, duration: float, trace_file: Path | None = None) -> None:
    name = plan.path.name
    if result.succeeded:
        console.success(f"plan {name} succeeded in {duration:.2f} s ({result.steps} steps)")
    elif result.status == "interrupted":
        console.error(f"plan {name} {result.failure.message if result.failure else 'interrupted'} after {duration:.2f} s"
                      + (" (the trace records where)" if trace_file is not None else ""))
    else:
        failure = result.failure or FailureRecord("Failure", "", None)
        node = find_node(result.trace["root"], failure.path or "")
        where = f" ({plan.path}:{node['source']})" if node and node.get("source") else ""
        message = (f"plan {name} {result.status} after {duration:.2f} s: {failure.type} at "
                   f"{failure.path}{where}: {failure.message}")
        for nested in failure.failures:
            message += f"\n  - {nested.type} at {nested.path}: {nested.message}"
        if console.out.is_terminal:
            console.out.print(Text.assemble(("✗", "bold red"), " ", message))
        else:
            console.plain(message)
