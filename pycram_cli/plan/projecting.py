"""The `project` node: alternatives tried in prospection before the robot acts; the best one then runs for real.

    - project:
        alternatives:                  # named alternatives, each a list of steps
          left:  [{pick-up: {object: milk, arm: left}}]
          right: [{pick-up: {object: milk, arm: right}}]
        runs: 20                       # projected runs per alternative
        vary:                          # how each run's world differs from the world as it is now
          milk: {noise: [0.02, 0.02, 0], yaw: 0.17}   # the variation file's noise (m) and yaw (rad)
        choose: most-successful        # or first-success, fewest-steps, {max: rate - 0.01 * steps}
        at-least: 0.8                  # else fail with a ProjectionFailure carrying the table
        seed: 0
        timeout: 30                    # seconds a projected run may take (else recorded as a Timeout)
      as: choice                       # {name: the chosen alternative, table: its outcomes by alternative}

Why: `try_in_order` and `try_all` try alternatives for real, so a failed attempt leaves the world
changed (an object knocked over, a drawer half open) before the next starts. The design's point
of a fast BulletWorld is projection: simulate what would happen, then choose.

How: the world's state is saved; every projected run starts from it exactly
(`BulletWorld.reset_to`: the same state whatever ran before), the varied objects moved by draws
from the run's own seed (the same draws for every alternative, so that they are compared on
the same scenes; a draw that puts an object inside another or over nothing is drawn again, see
worldfile/starts.py), and runs the alternative's steps with bindings of their own, quietly (no
live view or replay sees them: `Runtime.projected`). Who runs the runs is the run's `Projector`
(runtime.py): by default this process, one after another; `pycram run` gives the sweep's local
workers (sweep/projection.py), which run them in forked copies of this process when that is
faster. Either way each run gives a row, and the rows are folded in order into one summary
entry per alternative (the trace stays small, and the same however they ran); the table of
outcomes goes into the node's `projection` record. Then the world is reset to the saved state
— bitwise the state before the node — and the chosen alternative runs for real, its steps
under `chosen NAME`. Choices are deterministic: `fewest-steps` counts steps, not seconds.
"""
from __future__ import annotations

import hashlib
import math
import random
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..errors import Location, did_you_mean
from ..failures import Failure, FailureRecord, ProjectionFailure
from ..limits import MAX_PROJECTED, MAX_PROJECTED_REPLAYS, MAX_SCENARIO_TIMEOUT
from ..schema import describe, is_number
from ..status import Status
from ..world.pose import quat_multiply, yaw_quaternion
from ..worldfile.starts import start_problems
from ..yamlsource import LList, LMap
from .composites import Seq
from .context import jsonable
from .runtime import Cancelled, LimitExceeded, Record, Row, Runtime
from .scoring import OUTCOMES, SENSES, Score, ScoreError, parse_score
from .syntax import Node, Parser, node_type

if TYPE_CHECKING:
    from ..world import BulletWorld, Object
    from .validate import Validator

CHOICES = ("most-successful", "first-success", "fewest-steps")
PROJECT_KEYS = ("alternatives", "runs", "vary", "choose", "at-least", "seed", "timeout", "as")
VARY_KEYS = ("noise", "yaw")
DEFAULT_RUNS = 10
#: draws of one run before it is given up as impossible (recorded as such, not counted)
REDRAWS = 20
#: the reason a projected run's token is cancelled with when it runs past the step's `timeout`
TIMED_OUT = "ran past the projection's timeout"
#: a row's key for what its trace entry ended with (status, failure): taken out when the run is folded
FOLD = "_ended"
#: a row's key for the run's replay (when the run's replay is recorded): handed to the replay record when folded
REPLAY = "_replay"


class InProcess:
    """The default `Projector`: the runs one after another, in this process."""

    def runs(self, count: int, one: Callable[[int], Row], lost: Callable[[int, str, str], Row],
             check: Callable[[], None], timeout: float | None) -> list[Row]:
        rows = []
        for index in range(count):
            check()
            rows.append(one(index))
        return rows


IN_PROCESS = InProcess()


def run_seed(seed: int, path: str, run: int, attempt: int = 0) -> int:
    """The seed of one projected run (of the node at `path`): the same on every machine and for every alternative."""
    text = f"pycram-project/{seed}/{path}/{run}/{attempt}"
    return int.from_bytes(hashlib.sha256(text.encode()).digest()[:4], "big")


@dataclass(frozen=True)
class Variation:
    """How one object varies in the projected runs: uniform noise per axis (m), a turn about z in ±yaw (rad)."""

    name: str
    where: Location
    noise: tuple[float, float, float]
    yaw: float


@node_type("project")
class Project(Node):
    KEYS = ()
    BINDS = True
    DOC = ("try named alternatives in prospection (several runs each, the world varied), then run the best for real; "
           "fails with a ProjectionFailure when none succeeds often enough")

    def __init__(self, head: str, where: Location, alternatives: list[tuple[str, Location, list[Node]]], runs: int,
                 variations: list[Variation], choose: str | Score, at_least: float, seed: int,
                 timeout: float | None = None) -> None:
        super().__init__(head, where)
        self.alternatives, self.runs, self.variations = alternatives, runs, variations
        self.choose, self.at_least, self.seed, self.timeout = choose, at_least, seed, timeout

    # -- reading ---------------------------------------------------------------------------------
    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        body = step[head]
        where = step.loc(head, True)
        if not isinstance(body, LMap):
            parser.error(f"expected a mapping with 'alternatives' (and runs, vary, choose, at-least, seed), got "
                         f"{describe(body)}", where, key=head,
                         suggestion="e.g. project: {alternatives: {left: [...], right: [...]}, runs: 20}")
            return None
        for key in parser.names_only(body):
            if key not in PROJECT_KEYS:
                parser.error(f"unknown key '{key}' in 'project'", body.loc(key), key=str(key),
                             suggestion=f"'project' takes: {', '.join(PROJECT_KEYS)}")
        alternatives: list[tuple[str, Location, list[Node]]] = []
        if "alternatives" not in body:
            parser.error("a 'project' step needs 'alternatives'", step.loc(head), key="alternatives")
        else:
            alternatives = parser.named_steps(
                body, "alternatives", "names to lists of steps",
                "e.g. alternatives: {left: [{pick-up: {object: milk, arm: left}}], right: [...]}")
        runs = _whole(parser, body, "runs", DEFAULT_RUNS, 1, MAX_PROJECTED)
        seed = _whole(parser, body, "seed", 0, 0, 2**32 - 1)
        choose = _choice(parser, body)
        at_least = body.get("at-least", 0.0)
        if isinstance(at_least, bool) or not is_number(at_least) or not 0.0 <= float(at_least) <= 1.0:
            parser.error(f"expected a success rate from 0 to 1, got {describe(at_least)}", body.loc("at-least", True),
                         key="at-least")
            at_least = 0.0
        variations = _variations(parser, body)
        timeout = body.get("timeout")
        if timeout is not None and (isinstance(timeout, bool) or not is_number(timeout)
                                    or not 0.0 < float(timeout) <= MAX_SCENARIO_TIMEOUT):
            parser.error(f"expected seconds above 0 and at most {MAX_SCENARIO_TIMEOUT:g}, got {describe(timeout)}",
                         body.loc("timeout", True), key="timeout")
            timeout = None
        node = cls(head, step.loc(head), alternatives, int(runs), variations, choose, float(at_least), int(seed),
                   None if timeout is None else float(timeout))
        if "as" in body:  # also written inside the mapping (an `as` beside `project` wins)
            node.bind = parser.identifier(body["as"], body.loc("as", True), "as")
            node.bind_where = body.loc("as", True)
        return node

    def parts(self) -> list[tuple[str, list[Node]]]:
        return [(name, steps) for name, _, steps in self.alternatives]

    def check(self, v: Validator) -> None:
        # each alternative sees what is bound before the node, and what it binds stays in it (as a branch's)
        v.check_branches([Seq("seq", where, steps) for _, where, steps in self.alternatives])
        if v.facts is not None:
            for variation in self.variations:
                if variation.name not in v.facts.objects:
                    v.error(f"unknown object '{variation.name}' in the world", variation.where, key=variation.name,
                            suggestion=did_you_mean(variation.name, v.facts.objects))

    # -- running -----------------------------------------------------------------------------------
    def execute(self, ex: Runtime, tn: Record) -> Any:
        world = ex.world
        runs = [(name, where, steps, run) for name, where, steps in self.alternatives for run in range(self.runs)]
        table: dict[str, dict[str, Any]] = {}
        # The world is held for the whole projection (other branches wait): every run starts from `state`,
        # and worker processes are made from this process as it is now (sweep/projection.py).
        with ex.world_action():
            state = world.save_state()
            try:
                with world.unwatched():  # not the real run: a replay shows none of it
                    rows = (ex.projector or IN_PROCESS).runs(
                        len(runs), lambda i: self._project(ex, tn, world, state, *runs[i]),
                        lambda i, status, message: _lost(runs[i][3], status, message), ex.token.check, self.timeout)
                for (name, where, _, _), row in zip(runs, rows):  # folded in order, however they were run
                    self._fold(ex, tn, name, where, row)
                for name, _, _ in self.alternatives:
                    table[name] = _row([row for (alternative, _, _, _), row in zip(runs, rows) if alternative == name])
                choice, why = self._choose(table)
                choose = self.choose.describe() if isinstance(self.choose, Score) else self.choose
                tn.info["projection"] = {"runs": self.runs, "seed": self.seed, "choose": choose,
                                         "at-least": self.at_least, "alternatives": table, "choice": choice, "why": why}
                if self.timeout is not None:
                    tn.info["projection"]["timeout"] = self.timeout
            finally:  # also when cancelled (no cancellation check): the trace's final state is the real world's
                world.reset_to(state)  # bitwise the state before the node, and the same whatever was projected
                world.release_state(state)
        if choice is None:
            raise ProjectionFailure(f"no alternative succeeded in at least {100 * self.at_least:.0f} % of "
                                    f"{self.runs} projected runs: {_table_text(table)}", table=table)
        steps = next(steps for name, _, steps in self.alternatives if name == choice)
        where = next(where for name, where, _ in self.alternatives if name == choice)
        value = ex.run_group(steps, tn.child(f"chosen {choice}", "chosen", where))
        if not self.bind:
            return value
        return {"name": choice, "value": value,
                "table": {name: {k: v for k, v in row.items() if k != "outcomes"} for name, row in table.items()}}

    def _project(self, ex: Runtime, tn: Record, world: BulletWorld, state: Any, name: str, where: Location,
                 steps: list[Node], run: int) -> dict[str, Any]:
        """One projected run of one alternative: reset, vary, run quietly in a frame of its own; its row (with
        what its trace entry ended with under FOLD, for `_fold`). The same here and in a worker process."""
        world.reset_to(state)
        redrawn = self._vary(world, world_state=state, path=tn.path, run=run)
        if redrawn is None:
            return {"run": run, "status": "impossible", "failure": None, "steps": 0}
        record = tn.detached(f"projected {name} {run}", "projection", where)
        row: dict[str, Any] = {"run": run, **({"redrawn": len(redrawn)} if redrawn else {})}
        token = ex.token.child()
        timer = None
        if self.timeout is not None:
            timer = threading.Timer(self.timeout, token.cancel, (TIMED_OUT,))
            timer.daemon = True
            timer.start()
        keep = world.recording_replay and run < MAX_PROJECTED_REPLAYS  # a report may open it (bounded)
        projected = ex.projected(token, record=keep)
        try:
            projected.run_group(steps, record)
            row.update(status="succeeded", failure=None)
        except Failure as exc:
            row.update(status="failed", failure=f"{exc.type_name}: {exc.message}")
        except Cancelled:
            if ex.token.cancelled or token.reason != TIMED_OUT:
                raise
            row.update(_lost(run, "timeout", f"ran past the {self.timeout:g} s timeout"))
            record.failure = _failure(row)
        except LimitExceeded as exc:  # in a projection, an outcome of the alternative like any other
            row.update(status="failed", failure=f"LimitExceeded: {exc.message}")
            record.failure = _failure(row)
        except Exception as exc:  # noqa: BLE001 - an internal error in one projection is recorded; the node goes on
            row.update(status="error", failure=f"{type(exc).__name__}: {exc}")
        finally:
            if timer is not None:
                timer.cancel()
            replay = projected.replay_record()
        if replay is not None:
            row[REPLAY] = {**replay, "root": record.to_dict(timing=True)}
        row["steps"] = _steps(record)
        row[FOLD] = {"status": str(Status.SUCCEEDED if row["status"] == "succeeded" else Status.FAILED),
                     "failure": record.failure}
        return row

    @staticmethod
    def _fold(ex: Runtime, tn: Record, name: str, where: Location, row: dict[str, Any]) -> None:
        """The run's entry in the trace, folded at once into `projected NAME` (the trace stays small)."""
        ended, replay = row.pop(FOLD, None), row.pop(REPLAY, None)
        if ended is None:  # a run that could not start has no entry
            return
        child = tn.child(f"projected {name} {row['run']}", "projection", where)
        failure = ended["failure"]  # a dict where a worker or a lost run made it
        child.status = Status(ended["status"])
        child.failure = FailureRecord(failure["type"], failure["message"]) if isinstance(failure, dict) else failure
        ex.fold(tn, child, f"projected {name}")
        if replay is not None:
            ex.keep_replay(tn, name, row["run"], replay)

    def _vary(self, world: BulletWorld, world_state: Any, path: str, run: int) -> list[str] | None:
        """Move the varied objects for run `run` (drawn again while they cannot start); the rejected draws' reasons,
        or None when no draw of 1 + REDRAWS could start."""
        if not self.variations:
            return []
        objects = [world.get_object_by_name(v.name) for v in self.variations]
        start = {v.name: obj.get_pose() for v, obj in zip(self.variations, objects) if obj is not None}
        reasons: list[str] = []
        for attempt in range(REDRAWS + 1):
            if attempt:
                world.reset_to(world_state)
            rng = random.Random(run_seed(self.seed, path, run, attempt))
            moved: list[Object] = []
            for variation, obj in zip(self.variations, objects):
                if obj is None:
                    continue
                (x, y, z), orientation = start[variation.name]
                dx, dy, dz = (rng.uniform(-n, n) if n else 0.0 for n in variation.noise)
                yaw = rng.uniform(-variation.yaw, variation.yaw) if variation.yaw else 0.0
                turned = quat_multiply(yaw_quaternion(yaw), orientation) if yaw else orientation
                obj.set_position_and_orientation((x + dx, y + dy, z + dz), turned)
                moved.append(obj)
            problems = start_problems(world, moved)
            if not problems:
                return reasons
            reasons.append("; ".join(problems))
        return None

    def _choose(self, table: dict[str, dict[str, Any]]) -> tuple[str | None, str]:
        """The chosen alternative (None: none is good enough) and why, in words."""
        good = [name for name, row in table.items() if row["rate"] is not None and row["rate"] >= self.at_least
                and row["succeeded"] > 0]
        if not good:
            return None, f"none succeeded in at least {100 * self.at_least:.0f} % of its runs"
        if isinstance(self.choose, Score):
            score = self.choose
            sign = 1.0 if score.sense == "max" else -1.0
            best = max(good, key=lambda name: (sign * score.of(table[name]), -list(table).index(name)))
            return best, f"the {'highest' if sign > 0 else 'lowest'} {score.text} ({score.of(table[best]):.4g})"
        if self.choose == "first-success":
            return good[0], "the first alternative that succeeded often enough"
        if self.choose == "fewest-steps":
            best = min(good, key=lambda name: (table[name]["steps"], -table[name]["rate"], list(table).index(name)))
            return best, f"the fewest steps when it succeeds ({table[best]['steps']:g} on average)"
        best = max(good, key=lambda name: (table[name]["rate"], -list(table).index(name)))
        return best, f"the most successful ({table[best]['succeeded']} of {table[best]['runs']} runs)"


# -- helpers --------------------------------------------------------------------------------------------
def _choice(parser: Parser, body: LMap) -> str | Score:
    """`choose`: one of CHOICES, or `{max: EXPR}` / `{min: EXPR}` over the outcomes (see scoring.py)."""
    choose = body.get("choose", CHOICES[0])
    where = body.loc("choose", True)
    if isinstance(choose, LMap):
        if len(choose) != 1 or next(iter(choose)) not in SENSES:
            parser.error(f"expected {{max: EXPRESSION}} or {{min: EXPRESSION}}, got {describe(choose)}", where,
                         key="choose", suggestion="e.g. choose: {max: rate - 0.01 * steps}")
            return CHOICES[0]
        sense = str(next(iter(choose)))
        text = choose[sense]
        if isinstance(text, bool) or not isinstance(text, (str, int, float)):
            parser.error(f"expected an arithmetic expression, got {describe(text)}", choose.loc(sense, True),
                         key=sense, suggestion="e.g. rate - 0.01 * steps")
            return CHOICES[0]
        try:
            return parse_score(sense, str(text))
        except ScoreError as exc:
            suggestion = did_you_mean(exc.name, list(OUTCOMES)) if exc.name else None
            parser.error(f"choose {sense}: {exc}", choose.loc(sense, True), key=sense,
                         suggestion=suggestion or f"the outcomes: {', '.join(OUTCOMES)}")
            return CHOICES[0]
    if choose not in CHOICES:
        parser.error(f"expected one of {', '.join(CHOICES)}, or {{max: EXPRESSION}} / {{min: EXPRESSION}}, got "
                     f"{describe(choose)}", where, key="choose", suggestion="e.g. choose: {max: rate - 0.01 * steps}")
        return CHOICES[0]
    return str(choose)


def _whole(parser: Parser, body: LMap, key: str, default: int, low: int, high: int) -> int:
    value = body.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        parser.error(f"expected a whole number from {low} to {high}, got {describe(value)}", body.loc(key, True),
                     key=key)
        return default
    return value


def _variations(parser: Parser, body: LMap) -> list[Variation]:
    """`vary: {object: {noise: [x, y, z] or a number (x and y), yaw: rad}}`, checked where it is written."""
    if "vary" not in body:
        return []
    given = body["vary"]
    if not isinstance(given, LMap):
        parser.error(f"expected a mapping of object names to {{noise, yaw}}, got {describe(given)}",
                     body.loc("vary", True), key="vary", suggestion="e.g. vary: {milk: {noise: [0.02, 0.02, 0]}}")
        return []
    found: list[Variation] = []
    for name in parser.names_only(given):
        spec = given[name]
        where = given.loc(name, True)
        if not isinstance(spec, LMap):
            parser.error(f"expected {{noise, yaw}}, got {describe(spec)}", where, key=str(name))
            continue
        for key in parser.names_only(spec):
            if key not in VARY_KEYS:
                parser.error(f"unknown key '{key}' in a varied object", spec.loc(key), key=str(key),
                             suggestion=f"a varied object takes: {', '.join(VARY_KEYS)}")
        noise = (0.0, 0.0, 0.0)
        if "noise" in spec:
            value = spec["noise"]
            if is_number(value) and not isinstance(value, bool) and math.isfinite(float(value)) and value >= 0:
                noise = (float(value), float(value), 0.0)
            elif (isinstance(value, LList) and len(value) == 3
                  and all(is_number(n) and not isinstance(n, bool) and math.isfinite(float(n)) and n >= 0
                          for n in value)):
                noise = tuple(float(n) for n in value)  # type: ignore[assignment]
            else:
                parser.error(f"expected a number (m, x and y) or [x, y, z], each 0 or more, got {describe(value)}",
                             spec.loc("noise", True), key="noise")
        yaw = spec.get("yaw", 0.0)
        if isinstance(yaw, bool) or not is_number(yaw) or not 0.0 <= float(yaw) <= math.pi:
            parser.error(f"expected a turn from 0 to pi (rad), got {describe(yaw)}", spec.loc("yaw", True), key="yaw")
            yaw = 0.0
        found.append(Variation(str(name), given.loc(name), noise, float(yaw)))
    return found


def _steps(record: Record) -> int:
    """How many steps ran under `record` (itself not counted)."""
    return sum(1 for node in record.walk() if node is not record and node.status not in (Status.PENDING, Status.SKIPPED))


def _row(rows: list[dict[str, Any]]) -> dict[str, Any]:
    """One alternative's outcomes: runs that could start, successes, rate, failures by type, mean steps of successes."""
    counted = [r for r in rows if r["status"] != "impossible"]
    succeeded = [r for r in counted if r["status"] == "succeeded"]
    failures: dict[str, int] = {}
    for r in counted:
        if r["failure"]:
            kind = r["failure"].split(":", 1)[0]
            failures[kind] = failures.get(kind, 0) + 1
    return {"runs": len(counted), "succeeded": len(succeeded),
            "rate": round(len(succeeded) / len(counted), 4) if counted else None,
            "steps": round(sum(r["steps"] for r in succeeded) / len(succeeded), 2) if succeeded else None,
            "failures": dict(sorted(failures.items())), "impossible": len(rows) - len(counted),
            "outcomes": jsonable(rows)}


def _lost(run: int, status: str, message: str) -> dict[str, Any]:
    """The row of a run that gave no answer: `timeout` or `error` (its worker process died)."""
    kind = "Timeout" if status == "timeout" else "InternalError"
    return {"run": run, "status": status, "failure": f"{kind}: {message}", "steps": 0,
            FOLD: {"status": str(Status.FAILED), "failure": {"type": kind, "message": message}}}


def _failure(row: dict[str, Any]) -> FailureRecord:
    kind, _, message = row["failure"].partition(": ")
    return FailureRecord(kind, message)


def _table_text(table: dict[str, dict[str, Any]]) -> str:
    parts = []
    for name, row in table.items():
        causes = ", ".join(f"{count} {kind}" for kind, count in row["failures"].items())
        parts.append(f"{name}: {row['succeeded']} of {row['runs']}" + (f" ({causes})" if causes else ""))
    return "; ".join(parts)

