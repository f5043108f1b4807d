"""`pycram sweep ... --report sweep.html`: the sweep's page, and the replays of some scenarios written beside it.

The replays go to the folder `STEM-replays/` beside the page (made when missing: it belongs to the page),
one report per scenario (`scenario-INDEX.html`, `scenario-INDEX-ALT.html` for the --compare value ALT),
which the page links to by relative paths, so the page and its folder can be moved together.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

from ..errors import InputError, Location
from ..files import check_writable
from ..report import REPORT_FORMATS, build_report
from ..report.sweep_page import build_sweep_page, key_of
from ..sweep import PreparedSweep, replay_command
from ..sweep.plot import OutcomeMap, outcome_map
from ..sweep.replays import chosen, rerun
from . import console
from .files import check_output, write_output

#: `--replays N`: at most this many scenarios are run again for the page (N at most MAX_REPLAYS)
DEFAULT_REPLAYS = 10
MAX_REPLAYS = 100


def replays_folder(report: Path) -> Path:
    return report.parent / f"{report.stem}-replays"


def check_sweep_report(report: Path | None) -> None:
    """Before the sweep: the page can be written, and its replays' folder is a folder (or can be made)."""
    if report is None:
        return
    check_output(report, REPORT_FORMATS, "report")
    check_writable(report, "report")
    folder = replays_folder(report)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"the sweep report's replays go to '{folder}', which is not a folder", Location(str(report)),
                         suggestion="give the report another name, or move that file away")


def _file_name(record: dict[str, Any]) -> str:
    alternative = record.get("alt")
    return f"scenario-{record['index']}" + (f"-{alternative}" if alternative is not None else "") + ".html"


def write_sweep_report(prepared: PreparedSweep, summary: dict[str, Any], records: list[dict[str, Any]], report: Path,
                       replays: int) -> None:
    """Run the chosen scenarios again with their replays, write their reports and then the page."""
    alternatives = prepared.alternatives or []
    for record in records:  # which --compare value: its place in the list names its replay's file
        if record.get("alternative") is not None and record["alternative"] in alternatives:
            record["alt"] = alternatives.index(record["alternative"])
    picked = chosen(records, replays)
    links: dict[tuple[int, str], str] = {}
    if picked:
        folder = replays_folder(report)
        folder.mkdir(exist_ok=True)
        console.info(f"running {len(picked)} scenario{'s' if len(picked) != 1 else ''} again to record "
                     f"{'their replays' if len(picked) != 1 else 'its replay'} (--replays {replays})")
        for record, trace, same in rerun(prepared, picked):
            if not same:
                console.warning(f"scenario {record['index']} did not run again as it ran in the sweep "
                                "(its trace differs): its replay shows the second run")
            name = _file_name(record)
            write_output(folder / name, build_report(trace, prepared.scenario.world_path),
                         f"replay of scenario {record['index']}: {trace.get('status')}")
            links[key_of(record)] = f"{folder.name}/{name}"
    the_map: OutcomeMap | None
    try:
        the_map = outcome_map(prepared, records)
    except InputError:  # nothing varied has a position: the page lists the scenarios without a map
        the_map = None
    page = build_sweep_page(summary, records, the_map, links,
                            lambda record: replay_command(prepared, record["seed"], record.get("alternative")))
    write_output(report, page, f"sweep report, {len(page.encode()) // 1000} kB")
