"""Replay reports: one self-contained HTML file that shows what a run did.

`build_report(trace, world_path)` returns the page: a 3D replay of the run (three.js), the plan
tree with every node's status, duration, failure and reasoning answers, and a timeline. It
needs the trace's replay record (`Scenario.run(replay=True)`, `pycram run --trace/--report`)
to move anything; without one the 3D view shows the world as loaded. `build_mcap(trace, world_path)`
returns the same replay as an MCAP file for Foxglove (see foxglove.py); `build_comparison` puts two
runs' reports side by side, moved together, their first divergence marked (see compare.py).
"""
from .compare import build_comparison, step_differences
from .foxglove import MCAP_FORMATS, build_mcap
from .page import REPORT_FORMATS, build_report, report_data, report_world

__all__ = ["MCAP_FORMATS", "REPORT_FORMATS", "build_comparison", "build_mcap", "build_report", "report_data", "report_world",
           "step_differences"]
