"""Every limit pycram puts on what it reads and runs, in one place (the README lists them).

Inputs beyond a limit are refused before anything runs (exit 2, with the place and the
limit); a run that goes beyond a run-time limit stops with a `LimitExceeded` failure that no
plan handler catches (exit 1), naming the step where it happened.
"""
from __future__ import annotations

#: world and plan files (YAML), and `-p` values, at most this many bytes
MAX_YAML_BYTES = 1024 * 1024
#: trace files read by `trace show` and `trace diff`
MAX_TRACE_BYTES = 64 * 1024 * 1024
#: model files (URDF) read to validate a world
MAX_MODEL_BYTES = 256 * 1024 * 1024
#: nesting of YAML and JSON collections (lists and mappings inside each other)
MAX_NESTING = 100
#: values a YAML document may stand for once its aliases (`*a`) and merge keys (`<<: *a`) are expanded
MAX_YAML_NODES = 100_000

#: steps nested inside each other in a plan file (a `par` in a `retry` in an `if` ... counts each)
MAX_PLAN_DEPTH = 40
#: branches of one `par`, `pursue` or `try_all`
MAX_BRANCHES = 256
#: branches of one concurrent step running at once (the others start, in order, as these end)
MAX_RUNNING_BRANCHES = 32
#: subplan calls nested inside each other at run time (recursion)
MAX_CALL_DEPTH = 64
#: steps nested inside each other at run time (calls included): the depth of the trace tree
MAX_STEP_DEPTH = 100
#: steps a run records (summarised retry attempts do not count)
MAX_TRACE_NODES = 50_000
#: physics frames a replayed step keeps at most (plan/replay.py: a longer simulation keeps fewer per second)
MAX_PHYSICS_FRAMES = 48
#: branch threads one run may have alive at once
MAX_THREADS = 256
#: items (list elements, mapping entries and single values, a shared part counted each time it appears) in one
#: value a step computes at run time (all the values of one `set` together)
MAX_VALUE_ITEMS = 100_000
#: characters of text (strings and mapping keys) in one value a step computes at run time
MAX_VALUE_CHARS = 1_000_000
#: lists and mappings nested inside each other in one value a step computes at run time
MAX_VALUE_NESTING = MAX_NESTING
#: attempts of a `retry` kept in the trace in full, at the start and at the end; those between are summarised
RETRY_KEPT = 3

#: every number a user gives (coordinates in metres, masses in kg, angles, distances): at most this large
MAX_MAGNITUDE = 1_000_000.0
#: `wait:` at most this many seconds (one day)
MAX_WAIT = 86_400.0
#: `retry: N` at most this many more attempts
MAX_RETRIES = 1_000_000_000

#: runs of one sweep: `-n` scenarios, times the `--compare` alternatives
MAX_SWEEP_RUNS = 100_000
#: a sweep's results.jsonl read back by `sweep --resume`, at most this many bytes (sweep.json: MAX_SWEEP_META_BYTES)
MAX_SWEEP_RESULTS_BYTES = 256 * 1024 * 1024
MAX_SWEEP_META_BYTES = 16 * 1024 * 1024
#: `sweep --timeout` at most this many seconds per scenario (one day)
MAX_SCENARIO_TIMEOUT = 86_400.0
#: `sweep --workers` at most this many worker processes or Ray actors
MAX_WORKERS = 256
#: the most runs `pycram run --project N` projects before acting
MAX_PROJECTED = 10_000
#: the projected runs of each alternative of a `project` step whose replay a recorded run keeps (the first ones)
MAX_PROJECTED_REPLAYS = 10


def size_text(count: int) -> str:
    """1048576 -> '1 MiB'."""
    for unit, factor in (("GiB", 1 << 30), ("MiB", 1 << 20), ("KiB", 1 << 10)):
        if count >= factor:
            value = count / factor
            return f"{value:.0f} {unit}" if value == int(value) else f"{value:.1f} {unit}"
    return f"{count} bytes"
