"""The actor: what an action's `run` performs its expansion through, each part recorded as a child.

An action never calls process modules or queries itself; it asks its actor to

* `motion(designator, slots)`: perform a motion designator (a child named after it);
* `query(name, args)`: ask a reasoning query (a child named after it);
* `locate(finder)`: the next pose of a location designator (a child `locate`);
* `action(name, slots)`: perform another action (a child `action NAME`, with its own children);
* `attempt(number, steps)`: try one choice (a child `attempt N` holding what it did), so that a
  failed choice shows in the trace and the action goes on with the next candidate.

Two actors exist: `DirectActor` (here) performs at once and records a nested dict, for Python
(`perform_action`); the plan runs actions with an actor of its own that makes every child a
step of the plan's trace (`pycram_cli/plan/actions.py`), taking turns with concurrent branches
at every motion, query and location like any other leaf step.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from ...errors import PycramError
from ...failures import Failure, FailureRecord, LocationFailure, as_failure
from ...jsonable import jsonable
from ...locations import BasePoseResolution, LocationSpec, SpotResolution, parse_location, resolution
from ...locations.plot import MAP_KEY, candidate_map
from ...reasoning import QueryAnswer, run_query
from ...robots import Robot
from ...status import Status
from ...world import BulletWorld, Object
from ..performing import perform
from .declaration import ACTIONS

#: errors of values met while acting that are reported as failures (never tracebacks)
VALUE_ERRORS = (PycramError,)  # what a step turns into a failure: pycram's own errors (anything else is a bug)


class Finder:
    """A location designator being resolved for an action: the mapping (or spec), and its lazy resolution."""

    def __init__(self, location: Any, for_object: Object | None = None, here: bool = False) -> None:
        self.location = location
        self.for_object = for_object
        self.here = here
        self.resolution: BasePoseResolution | SpotResolution | None = None

    def next(self, world: BulletWorld) -> Any:
        if self.resolution is None:
            spec = self.location if isinstance(self.location, LocationSpec) else parse_location(
                world, self.location, self.for_object)
            self.resolution = resolution(Robot.of(world), spec)
            if isinstance(self.resolution, BasePoseResolution):
                self.resolution.here = self.here
        return self.resolution.next()

    def record(self) -> dict[str, Any]:
        """What the trace says of the resolution so far: the location, candidates, how many were tried and why not."""
        res = self.resolution
        if res is None:
            return {"spec": jsonable(self.location)}
        counts = res.candidates.counts() if res.prepared else {}
        record = {"spec": jsonable(res.spec.to_json()), "candidates": len(res.candidates) if res.prepared else 0,
                  "tried": res.cursor, "ruled_out": dict(sorted(counts.items()))}
        if res.prepared and res.robot.world.recording_replay:  # the replay takes it (plan/replay.py), the trace not
            record[MAP_KEY] = candidate_map(res)
        return record


class Actor:
    """Performs the parts of an action and records them; subclasses decide how (at once, or as plan steps)."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world

    @property
    def robot(self) -> Robot:
        return Robot.of(self.world)

    # -- what subclasses provide -----------------------------------------------------------------------
    def leaf(self, label: str, type: str, run: Callable[[dict[str, Any]], Any]) -> Any:
        """Run one step that touches the world; `run(info)` records what the trace should say in `info`."""
        raise NotImplementedError

    def group(self, label: str, type: str, run: Callable[[Actor], Any], info: dict[str, Any] | None = None) -> Any:
        """Run steps under a child of their own; `run(actor)` performs them through the child's actor."""
        raise NotImplementedError

    # -- what actions use ----------------------------------------------------------------------------------
    def motion(self, designator: str, slots: Mapping[str, Any]) -> Any:
        slots = {k: v for k, v in slots.items() if v is not None}  # slots left open are inferred

        def run(info: dict[str, Any]) -> Any:
            info["designator"] = {"slots": jsonable(dict(slots))}
            try:
                performed = perform(self.world, designator, slots)
            except Failure:
                raise
            except VALUE_ERRORS as exc:
                raise as_failure(exc, designator) from exc
            info["designator"]["resolved"] = jsonable(performed.resolved)
            return performed.result

        return self.leaf(designator, designator, run)

    def query(self, name: str, args: Mapping[str, Any]) -> QueryAnswer:
        def run(info: dict[str, Any]) -> QueryAnswer:
            try:
                answer = run_query(self.world, name, args)
            except VALUE_ERRORS as exc:
                raise as_failure(exc, name) from exc
            info["query"] = {"args": jsonable(answer.args), "result": jsonable(answer.result),
                             "details": jsonable(answer.details)}
            return answer

        return self.leaf(name, name, run)

    def locate(self, finder: Finder) -> Any:
        def run(info: dict[str, Any]) -> Any:
            try:
                found = finder.next(self.world)
            except LocationFailure:
                info["location"] = finder.record()
                raise
            except VALUE_ERRORS as exc:
                info["location"] = finder.record()
                raise as_failure(exc, "location") from exc
            info["location"] = {**finder.record(), "found": jsonable(found.to_json())}
            return found

        return self.leaf("locate", "locate", run)

    def action(self, name: str, slots: Mapping[str, Any]) -> Any:
        spec = ACTIONS[name]
        given = {k: v for k, v in slots.items() if v is not None}
        return self.group(f"action {name}", "action", lambda actor: spec.perform(actor, given),
                          {"action": {"type": name, "slots": jsonable(given)}})

    def attempt(self, number: int, run: Callable[[Actor], Any]) -> Any:
        return self.group(f"attempt {number}", "attempt", run)


class DirectActor(Actor):
    """Performs everything at once; `record` is the expansion as nested dicts (type, status, info, children)."""

    def __init__(self, world: BulletWorld, record: dict[str, Any] | None = None) -> None:
        super().__init__(world)
        self.record = record if record is not None else {"children": []}
        self.record.setdefault("children", [])

    def _child(self, label: str, type: str) -> dict[str, Any]:
        child = {"label": f"{len(self.record['children'])}:{label}", "type": type, "status": Status.RUNNING.value}
        self.record["children"].append(child)
        return child

    def leaf(self, label: str, type: str, run: Callable[[dict[str, Any]], Any]) -> Any:
        child = self._child(label, type)
        info: dict[str, Any] = {}
        try:
            with self.world.lock:
                value = run(info)
            child["status"] = Status.SUCCEEDED.value
            return value
        except Failure as exc:
            child["status"], child["failure"] = Status.FAILED.value, FailureRecord(exc.type_name, exc.message).to_json()
            raise
        finally:
            child.update(info)

    def group(self, label: str, type: str, run: Callable[[Actor], Any], info: dict[str, Any] | None = None) -> Any:
        child = self._child(label, type)
        child.update(info or {})
        try:
            value = run(DirectActor(self.world, child))
            child["status"] = Status.SUCCEEDED.value
            return value
        except Failure as exc:
            child["status"], child["failure"] = Status.FAILED.value, FailureRecord(exc.type_name, exc.message).to_json()
            raise
