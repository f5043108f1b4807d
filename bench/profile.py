#!/usr/bin/env python3
"""Where a plan's time goes: the plan run in-process under cProfile, its time grouped by phase.

    python bench/profile.py fetch_milk                       # the plan on its own world
    python bench/profile.py set_table_actions --world kitchen_fetch
    python bench/profile.py set_table --top 30 --no-cprofile # phases only, at full speed
    python bench/profile.py fetch_milk --json                # the numbers, for scripts

How time is attributed to phases. Each phase has entry points, functions of the package named in
`PHASES` (IK: `reasoning.ik.solve`, ...; path checks: `motion.Motion._follow`, ...). They are wrapped
(every reference to them in the package's loaded modules, and the methods on their classes) by a
timer that keeps a stack of the phases entered: every moment of the run is charged to the
*innermost* phase on the stack when it happens — IK inside a location search counts as IK, the
closest-point queries inside IK's collision test as path checks — so the phases' `self` times add
up to the plan's time exactly. `incl.` is the time spent with the phase anywhere on the stack (what
the phase costs with everything it calls; these overlap). Time inside the plan run that no phase
entry point claims is `bookkeeping` (the executor, the trace, events: `run_plan` is its entry point);
time in a process module or designator that no deeper phase claims is `other` (designator
resolution, driving the base, the glue between phases). Loading the world is reported apart, as
`pycram run` reports plan time without it.

cProfile slows pure Python far more than calls into PyBullet, so under it the Python-heavy phases
look dearer than they are: `--no-cprofile` measures the phases alone (only the wrappers' few
microseconds per entry added), at nearly full speed. The top functions come from cProfile (own time, and time with
callees). `--unit` also measures the machine unit (one second of simulated physics of the bundled
kitchen, 240 steps, in the same process) and states plan time in it, so that runs on a loaded
machine compare.
"""
from __future__ import annotations

import sys
from pathlib import Path

# this file is named like the standard library's `profile`, which cProfile imports: its folder must not shadow it
sys.path[:] = [entry for entry in sys.path if Path(entry or ".").resolve() != Path(__file__).resolve().parent]

import argparse  # noqa: E402
import cProfile  # noqa: E402
import functools  # noqa: E402
import importlib  # noqa: E402
import json  # noqa: E402
import pkgutil  # noqa: E402
import pstats  # noqa: E402
import statistics  # noqa: E402
import time  # noqa: E402
from typing import Any, Callable  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

import pycram_cli  # noqa: E402

#: phase -> its entry points ("module:function" or "module:Class.method"), in the order they are reported
PHASES: dict[str, tuple[str, ...]] = {
    # (`ik.solutions` and `link_solutions` are iterators, run as their callers ask: their work is timed inside)
    "IK": ("pycram_cli.reasoning.ik:solve", "pycram_cli.reasoning.ik:solve_link",
           "pycram_cli.reasoning.ik:_Batch.__init__", "pycram_cli.reasoning.ik_search:_GroupSearch.measure",
           "pycram_cli.reasoning.ik_search:_GroupSearch.finished", "pycram_cli.reasoning.ik_search:_GroupSearch.step",
           "pycram_cli.reasoning.ik:forward_pose"),
    "path checks / collision": (
        "pycram_cli.planning.motion:Motion.__init__", "pycram_cli.planning.motion:Motion.walk",
        "pycram_cli.planning.motion:Motion._follow", "pycram_cli.planning.motion:Motion.scan",
        "pycram_cli.planning.motion:Motion.allow_current", "pycram_cli.planning.paths:search_path",
        "pycram_cli.planning.motion:hits_at", "pycram_cli.planning.motion:hits_at_goal",
        "pycram_cli.planning.contacts:collisions",
        "pycram_cli.world.bullet_world:BulletWorld.closest_points",
        "pycram_cli.world.bullet_world:BulletWorld.distance",
        "pycram_cli.world.bullet_world:BulletWorld.clear_fraction",
        "pycram_cli.world.bullet_world:BulletWorld.cast_rays"),
    "grasp planning": ("pycram_cli.planning.grasps:grasps",
                       "pycram_cli.planning.grasps:holdable_grasps",
                       "pycram_cli.planning.grasps:holdable",
                       "pycram_cli.designators.manipulation:take_with"),
    "physics": ("pycram_cli.world.bullet_world:BulletWorld.simulate", "pycram_cli.world.bullet_world:BulletWorld.step",
                "pycram_cli.reasoning.stable:stable", "pycram_cli.world.prospection:Prospection.sync"),
    "perception (rendering)": ("pycram_cli.reasoning.visibility:visible", "pycram_cli.reasoning.visibility:occluding",
                               "pycram_cli.world.bullet_world:BulletWorld.segmentation",
                               "pycram_cli.world.bullet_world:BulletWorld.segmentation_alone",
                               "pycram_cli.world.bullet_world:BulletWorld.segmentation_of",
                               "pycram_cli.world.bullet_world:BulletWorld.picture_of"),
    "locations": ("pycram_cli.locations:resolution", "pycram_cli.locations.base_poses:take_from_here",
                  "pycram_cli.locations.ranked:Resolution.prepare", "pycram_cli.locations.floor:floor_map",
                  "pycram_cli.locations.base_poses:BasePoseResolution.next",
                  "pycram_cli.locations.spots:SpotResolution.next",
                  "pycram_cli.designators.actions.actor:Finder.next"),
    "other (process modules, designators)": ("pycram_cli.designators.performing:perform",
                                             "pycram_cli.plan.actions:ActionStep.execute"),
    "bookkeeping / trace": ("pycram_cli.plan.executor:run_plan",),
}
LOADING = "world loading"
ENTRY_LOADING = ("pycram_cli.scenario:Scenario.load_world",)
BOOKKEEPING = "bookkeeping / trace"


class PhaseClock:
    """Charges every moment to the innermost phase entered (`self`), and keeps each phase's inclusive time."""

    def __init__(self) -> None:
        self.stack: list[str] = []
        self.own: dict[str, float] = {}
        self.inclusive: dict[str, float] = {}
        self.calls: dict[str, int] = {}
        self._depth: dict[str, int] = {}
        self._since: dict[str, float] = {}
        self._last = time.perf_counter()

    def _charge(self, now: float) -> None:
        if self.stack:
            top = self.stack[-1]
            self.own[top] = self.own.get(top, 0.0) + now - self._last
        self._last = now

    def enter(self, phase: str) -> None:
        now = time.perf_counter()
        self._charge(now)
        self.stack.append(phase)
        self.calls[phase] = self.calls.get(phase, 0) + 1
        depth = self._depth.get(phase, 0)
        if depth == 0:
            self._since[phase] = now
        self._depth[phase] = depth + 1

    def leave(self, phase: str) -> None:
        now = time.perf_counter()
        self._charge(now)
        self.stack.pop()
        depth = self._depth[phase] - 1
        self._depth[phase] = depth
        if depth == 0:
            self.inclusive[phase] = self.inclusive.get(phase, 0.0) + now - self._since[phase]


def _wrap(function: Callable[..., Any], phase: str, clock: PhaseClock) -> Callable[..., Any]:
    @functools.wraps(function)
    def timed(*args: Any, **kwargs: Any) -> Any:
        clock.enter(phase)
        try:
            return function(*args, **kwargs)
        finally:
            clock.leave(phase)

    timed.__profiled__ = True  # type: ignore[attr-defined]
    return timed


def _import_everything() -> list[Any]:
    """Every module of the package (so that every reference to an entry point can be found and wrapped)."""
    modules = []
    for info in pkgutil.walk_packages(pycram_cli.__path__, "pycram_cli."):
        if info.name.rsplit(".", 1)[-1] == "__main__":
            continue  # a package's command line: importing it runs it
        try:
            modules.append(importlib.import_module(info.name))
        except Exception:  # noqa: BLE001 - an optional extra (ray, a GUI) that is not installed
            continue
    return modules


def instrument(clock: PhaseClock, phases: dict[str, tuple[str, ...]]) -> list[str]:
    """Wrap every entry point of every phase; the entry points that do not exist (names to fix here)."""
    modules = _import_everything()
    missing = []
    for phase, entries in phases.items():
        for entry in entries:
            module_name, _, qualname = entry.partition(":")
            owner: Any = importlib.import_module(module_name)
            *path, name = qualname.split(".")
            for part in path:
                owner = getattr(owner, part, None)
            original = getattr(owner, name, None) if owner is not None else None
            if original is None or getattr(original, "__profiled__", False):
                if original is None:
                    missing.append(entry)
                continue
            wrapped = _wrap(original, phase, clock)
            setattr(owner, name, wrapped)
            if not path:  # a module's function: every module that imported it by name gets the wrapper too
                for module in modules:
                    for key, value in list(vars(module).items()):
                        if value is original:
                            setattr(module, key, wrapped)
    return missing


def machine_unit() -> float:
    """Seconds of one second of simulated physics (240 steps) of the bundled kitchen, median of three."""
    from pycram_cli.scenario import prepare
    from pycram_cli.worldfile.loader import load_spec

    spec = prepare(REPO / "plans" / "set_table.yaml").world
    world = load_spec(spec)
    try:
        times = []
        for _ in range(3):
            start = time.perf_counter()
            world.simulate(1.0)
            times.append(time.perf_counter() - start)
        return statistics.median(times)
    finally:
        world.exit()


def _short(func: tuple[str, int, str]) -> str:
    filename, line, name = func
    if filename == "~":
        return name
    path = Path(filename)
    for anchor in (REPO, Path(pycram_cli.__file__).resolve().parents[1]):
        try:
            return f"{path.resolve().relative_to(anchor)}:{line}({name})"
        except ValueError:
            continue
    return f"{'/'.join(path.parts[-2:])}:{line}({name})"


def top_functions(profile: cProfile.Profile, count: int) -> dict[str, list[dict[str, Any]]]:
    stats = pstats.Stats(profile)
    rows = [(func, nc, tt, ct) for func, (cc, nc, tt, ct, callers) in stats.stats.items()]  # type: ignore[attr-defined]
    own = sorted(rows, key=lambda r: -r[2])[:count]
    cumulative = sorted((r for r in rows if "pycram_cli" in r[0][0] and "bench/profile.py" not in r[0][0]),
                        key=lambda r: -r[3])[:count]
    as_dict = lambda r: {"function": _short(r[0]), "calls": r[1], "own": round(r[2], 4), "cumulative": round(r[3], 4)}
    return {"own": [as_dict(r) for r in own], "cumulative": [as_dict(r) for r in cumulative]}


def profile(plan: str, world: str | None, assignments: list[str], use_cprofile: bool, top: int,
            unit: bool) -> dict[str, Any]:
    from pycram_cli.scenario import prepare

    clock = PhaseClock()
    missing = instrument(clock, {**PHASES, LOADING: ENTRY_LOADING})
    scenario = prepare(plan, world=world, assignments=assignments)
    profiler = cProfile.Profile() if use_cprofile else None
    if profiler is not None:
        profiler.enable()
    start = time.perf_counter()
    result = scenario.run()
    total = time.perf_counter() - start
    if profiler is not None:
        profiler.disable()
    loading = clock.own.get(LOADING, 0.0)
    plan_time = clock.inclusive.get(BOOKKEEPING, 0.0)
    phases = {name: {"self": round(clock.own.get(name, 0.0), 4), "incl": round(clock.inclusive.get(name, 0.0), 4),
                     "calls": clock.calls.get(name, 0)} for name in PHASES}
    report: dict[str, Any] = {
        "plan": scenario.plan.path.stem, "world": scenario.world_path.stem, "status": result.status,
        "cprofile": use_cprofile, "plan_time": round(plan_time, 4), "world_loading": round(loading, 4),
        "total": round(total, 4), "phases": phases, "missing_entry_points": missing,
        "trace_duration": result.trace.get("timing", {}).get("duration"),
    }
    if unit:
        report["machine_unit"] = round(machine_unit(), 4)
        report["plan_time_units"] = round(plan_time / report["machine_unit"], 2)
    if profiler is not None:
        report["top"] = top_functions(profiler, top)
    return report


def show(report: dict[str, Any]) -> None:
    plan_time = report["plan_time"] or 1e-9
    mode = "under cProfile" if report["cprofile"] else "without cProfile"
    print(f"{report['plan']} on {report['world']}: {report['status']}, plan time {report['plan_time']:.3f} s {mode}"
          f" (world loading {report['world_loading']:.3f} s, not counted)")
    if "machine_unit" in report:
        print(f"machine unit (240 physics steps of the kitchen): {report['machine_unit']:.3f} s; "
              f"plan time = {report['plan_time_units']:.2f} units")
    print(f"\n{'phase':40s} {'self s':>8s} {'self %':>7s} {'incl. s':>8s} {'entries':>8s}")
    for name, row in sorted(report["phases"].items(), key=lambda kv: -kv[1]["self"]):
        print(f"{name:40s} {row['self']:8.3f} {100 * row['self'] / plan_time:6.1f}% {row['incl']:8.3f} {row['calls']:8d}")
    total = sum(row["self"] for row in report["phases"].values())
    print(f"{'(sum)':40s} {total:8.3f} {100 * total / plan_time:6.1f}%")
    if report["missing_entry_points"]:
        print("entry points not found (fix PHASES):", ", ".join(report["missing_entry_points"]))
    for key, title in (("own", "own time"), ("cumulative", "time with callees, the package's functions")):
        rows = report.get("top", {}).get(key)
        if rows:
            print(f"\ntop functions by {title}:")
            print(f"{'own s':>8s} {'cum. s':>8s} {'calls':>8s}  function")
            for row in rows:
                print(f"{row['own']:8.3f} {row['cumulative']:8.3f} {row['calls']:8d}  {row['function']}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("plan", help="a plan file or a bundled plan's name")
    parser.add_argument("--world", default=None, help="a world file or a bundled world's name (default: the plan's)")
    parser.add_argument("-p", dest="assignments", action="append", default=[], metavar="K=V", help="a parameter")
    parser.add_argument("--top", type=int, default=20, help="how many top functions to show (default 20)")
    parser.add_argument("--no-cprofile", dest="cprofile", action="store_false",
                        help="phases only, without cProfile's overhead")
    parser.add_argument("--unit", action="store_true", help="also measure the machine unit (240 physics steps)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    args = parser.parse_args(argv)
    report = profile(args.plan, args.world, args.assignments, args.cprofile, args.top, args.unit)
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        show(report)
    return 0 if report["status"] == "succeeded" else 1


if __name__ == "__main__":
    sys.exit(main())
