"""Recording a run so that it can be replayed: the world's state after every step.

A `Recorder` is an observer of a run (it passes every event on to the observer it wraps).
It reads the state of the world when the run starts (every object's pose and movable joint
values) and again whenever a leaf step has finished, and keeps what changed:

    {"world_file": "/.../kitchen.yaml",
     "initial": {"pr2": {"position": [...], "orientation": [...], "joints": {...}}, ...},
     "steps": [{"path": "body/0:for_each/item 0/0:world-state-detecting", "status": "succeeded",
                "changed": {"pr2": {"joints": {"torso_lift_joint": 0.3}}, "milk": {"position": [...]}}}, ...,
               {"path": ".../0:place", "status": "succeeded", "changed": {...},
                "physics": [{"t": 0.05, "changed": {"milk": {"position": [...], "orientation": [...]}}}, ...]}]}

Physics inside a step (place lets the object go and settles it) is kept too, so that a replay shows the
motion and not only where it ended: every PHYSICS_EVERY simulation steps (20 per simulated second) the
step's `physics` list gets a frame of what moved since the previous one — the free objects' poses; the
robots' and environments' joints only in a step's first frame, as physics holds them still (the arm let go
and drew back before the object settles). At most MAX_PHYSICS_FRAMES frames a step: a step that simulates
longer keeps every second frame (then every fourth, ...), each kept frame taking what the dropped one moved.
`t` is the simulated time since the step began (seconds, 4 decimals).

A step whose query simulated what would happen on the world's prospection copy (`stable`: does the object stay
put?) has `prospection`: the same frames of what that simulation did to the objects the step names (the
world itself never moved).

A `locate` step's entry also has `candidates`: its floor map (locations/plot.py `candidate_map`: every candidate
position with the test that ruled it out, the poses found, the target), which the step gives only while a replay
is recorded and which stays out of the trace's tree.

Bounded like the trace tree: when a `retry` folds an attempt into its `folded attempts` node, the
steps recorded for that attempt are folded too, into one entry at the place of the last of them
that stands for all of them: `{"path": ".../folded attempts", "status": "failed", "folded": N,
"changed": ...}`, whose `changed` holds, for everything the folded steps changed, the value it had
after the last of them. So the states after it are exact, and a replayed run shows the folded
attempts as one step.

A `project` step's projected runs are not steps of the run (the world is put back after them),
so none of them is among `steps`; the first MAX_PROJECTED_REPLAYS runs of each alternative are
recorded where they run, each as a record of its own, `{"initial", "steps", "root"}` (`root`: the
run's own trace tree, which the run's trace folds away), under `projections`: step path ->
alternative -> run number. A report opens them from the step's table.

The trace keeps this under its `replay` key, which `trace.comparable()` leaves out: golden traces
and `trace diff` compare behaviour, not the replay. The record is still deterministic: a leaf's
`finished` event comes while its thread holds the scheduler's turn (see scheduler.py), so the
steps are recorded in the same order, with the same states, however the threads interleave.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..limits import MAX_PHYSICS_FRAMES
from ..locations.plot import MAP_KEY
from ..status import Status
from ..world.bullet_world import STEP_HZ
from .observer import Observing
from .trace import DIGITS, TraceNode, canonical_quaternion

if TYPE_CHECKING:
    from ..world import BulletWorld
    from .executor import Observer

State = dict[str, dict[str, Any]]

#: simulation steps (1/240 s) between two physics frames of a step: 20 frames per simulated second
PHYSICS_EVERY = 12
#: what a free object must move (m, or a quaternion coordinate) to be in a physics frame: 0.1 mm
PHYSICS_TOLERANCE = 1e-4

Point = tuple[float, float, float]

#: slot and argument names whose values are places (objects are recognised by their names)
PLACES = ("target", "look", "position")
#: object types that are scenery, never what a step works on
SCENERY = ("robot", "environment")


def world_state(world: BulletWorld, free_only: bool = False) -> State:
    """Every object's pose and movable joint values, rounded as traces are (6 decimals); `free_only`: only the
    objects physics moves (neither robots nor environments), and their poses only."""
    state: State = {}
    with world.lock:
        for obj in world.objects:
            if free_only and obj.fixed:
                continue
            position, orientation = obj.get_pose()
            entry: dict[str, Any] = {"position": [round(float(v), DIGITS) + 0.0 for v in position],
                                     "orientation": [round(v, DIGITS) + 0.0 for v in canonical_quaternion(orientation)]}
            joints = {} if free_only else obj.get_joint_positions()
            if joints:
                entry["joints"] = {name: round(value, DIGITS) + 0.0 for name, value in joints.items()}
            state[obj.name] = entry
    return state


def changes(before: State, after: State) -> State:
    """What differs from `before` in `after`: per object, the pose (position and orientation together) and
    the joints whose values changed."""
    found: State = {}
    for name, entry in after.items():
        old = before.get(name, {})
        delta: dict[str, Any] = {}
        if entry["position"] != old.get("position") or entry["orientation"] != old.get("orientation"):
            delta["position"], delta["orientation"] = entry["position"], entry["orientation"]
        old_joints = old.get("joints", {})
        moved = {k: v for k, v in entry.get("joints", {}).items() if old_joints.get(k) != v}
        if moved:
            delta["joints"] = moved
        if delta:
            found[name] = delta
    return found


class Recorder(Observing):
    """Observes a run, passing every event on to `inner`, and records the world after each leaf step."""

    def __init__(self, world: BulletWorld, inner: Observer | None = None,
                 world_file: Path | str | None = None) -> None:
        self.world = world
        self.inner = inner
        self.world_file = str(world_file) if world_file is not None else None
        self.initial = world_state(world)
        self._last = self.initial
        self.steps: list[dict[str, Any]] = []
        self._physics = PhysicsFrames(world, self.initial)
        self._whatif = PhysicsFrames(world, self.initial, free_only=True)
        self._unwatch = [world.watch_steps(self._physics.stepped),
                         world.watch_steps(self._whatif.stepped, prospection=True)]
        self._was_recording = world.recording_replay
        world.recording_replay = True
        #: the replays of projected runs (a `project` step's, see `projected`): step path -> alternative -> run
        self.projections: dict[str, dict[str, dict[str, Any]]] = {}

    def close(self) -> None:
        """Stop watching the world's physics (the run is over)."""
        for unwatch in self._unwatch:
            unwatch()
        self.world.recording_replay = self._was_recording  # a projected run's recorder: the run's goes on

    def started(self, node: TraceNode) -> None:
        if self.inner is not None:
            self.inner.started(node)

    def finished(self, node: TraceNode) -> None:
        if not node.children:  # a leaf step (or an empty composite: recorded as a step that changed nothing)
            state = world_state(self.world)
            entry: dict[str, Any] = {"path": node.path, "status": str(node.status), "changed": changes(self._last, state)}
            physics = self._physics.take(state)
            if physics:
                entry["physics"] = physics
            named = {v for v in _named(node.info) if isinstance(v, str)}
            whatif = [frame for frame in ({"t": f["t"], "changed": {k: v for k, v in f["changed"].items() if k in named}}
                                          for f in self._whatif.take(state)) if frame["changed"]]
            if whatif:  # what a query (stable) simulated on the prospection copy: the objects the step names
                entry["prospection"] = whatif
            location = node.info.get("location")
            if isinstance(location, dict) and MAP_KEY in location:  # the replay's, not the trace's
                entry["candidates"] = location.pop(MAP_KEY)
            self.steps.append(entry)
            self._last = state
        if self.inner is not None:
            self.inner.finished(node)

    def log(self, node: TraceNode, message: str) -> None:
        if self.inner is not None:
            self.inner.log(node, message)

    def folded(self, summary: TraceNode, child: TraceNode) -> None:
        """`child` (an attempt of a retry, with its subtree) was folded into `summary`: fold its steps here too."""
        fold_steps(self.steps, self.initial, summary.path, child.path, _earlier_attempts(summary.path, child.path))
        if self.inner is not None:
            self.inner.folded(summary, child)

    def projected(self, node: TraceNode, name: str, run: int, replay: dict[str, Any]) -> None:
        """The replay of run `run` of alternative `name` of the `project` step `node` (recorded where it ran)."""
        self.projections.setdefault(node.path, {}).setdefault(name, {})[str(run)] = replay
        inner = getattr(self.inner, "projected", None)
        if inner is not None:
            inner(node, name, run, replay)

    def record(self) -> dict[str, Any]:
        """The replay record (see the module docstring), ready for the trace's `replay` key."""
        record = {"world_file": self.world_file, "initial": self.initial, "steps": list(self.steps)}
        if self.projections:
            record["projections"] = self.projections
        return record


class PhysicsFrames:
    """The physics frames of the step running now (see the module docstring): `stepped` after every simulation
    step, `take` when the step has finished."""

    def __init__(self, world: BulletWorld, state: State, free_only: bool = False) -> None:
        self.world = world
        self.free_only = free_only  # only the free objects' poses, also in the first frame (a prospection copy's)
        self._last = state  # the state the next frame's changes are counted from
        self._frames: list[dict[str, Any]] = []
        self._pending: State = {}  # what a dropped frame moved, for the next kept one
        self._steps = 0  # simulation steps since the step began
        self._every = PHYSICS_EVERY

    def stepped(self, world: BulletWorld) -> None:
        self._steps += 1
        if self._steps % self._every:
            return
        first = not self._frames and not self._pending and not self.free_only
        now = world_state(world, free_only=not first)
        moved = changes(self._last, now) if first else {
            name: entry for name, entry in now.items() if _moved(self._last.get(name), entry)}
        self._last = now if first else {**self._last, **moved}
        if self._pending:
            moved = _merged(self._pending, moved)  # the dropped frame's changes: already counted in _last
            self._pending = {}
        self._frames.append({"t": round(self._steps / STEP_HZ, 4) + 0.0, "changed": moved})
        if len(self._frames) > MAX_PHYSICS_FRAMES:
            self._thin()

    def _thin(self) -> None:
        """Keep every second frame (each taking what the one before it moved); an odd last one waits for the next."""
        kept: list[dict[str, Any]] = []
        frames = self._frames
        for index in range(1, len(frames), 2):
            kept.append({"t": frames[index]["t"], "changed": _merged(frames[index - 1]["changed"],
                                                                       frames[index]["changed"])})
        self._pending = frames[-1]["changed"] if len(frames) % 2 else {}
        self._frames = kept
        self._every *= 2

    def take(self, state: State) -> list[dict[str, Any]]:
        """The frames of the step that has just finished (in the world `state`); the next step starts afresh."""
        frames, self._frames, self._pending = self._frames, [], {}
        self._last, self._steps, self._every = state, 0, PHYSICS_EVERY
        return [frame for frame in frames if frame["changed"]]


def _named(info: dict[str, Any]) -> Iterable[Any]:
    """The values a step's record names: its designator's slots, its query's arguments and its condition's."""
    for key in ("designator",):
        if isinstance(info.get(key), dict):
            yield from (info[key].get("resolved") or info[key].get("slots") or {}).values()
    if isinstance(info.get("query"), dict):
        yield from (info["query"].get("args") or {}).values()
    condition = info.get("condition")
    while isinstance(condition, dict):
        if isinstance(condition.get("query"), dict):
            yield from (condition["query"].get("args") or {}).values()
        condition = condition.get("not")


def _moved(before: dict[str, Any] | None, after: dict[str, Any]) -> bool:
    """Whether a free object's pose changed by more than PHYSICS_TOLERANCE (in a coordinate of its position or
    quaternion) since its last physics frame: what rests keeps out of the frames, a slow drift still shows."""
    if before is None:
        return True
    return any(abs(a - b) > PHYSICS_TOLERANCE for key in ("position", "orientation")
               for a, b in zip(before[key], after[key]))


def apply_changes(state: State, changed: State) -> None:
    """Bring `state` (by object name) up to date with a frame's `changed` entries: their values replace those of
    `state`, a joint at a time (a change names only the joints that moved)."""
    for name, entry in changed.items():
        into = state.setdefault(name, {})
        joints = {**into.get("joints", {}), **entry.get("joints", {})}
        into.update(entry)
        if joints:
            into["joints"] = joints


def _merged(earlier: State, later: State) -> State:
    """Two frames' changes as one: the later one's values where both changed something."""
    merged: State = {name: dict(entry) for name, entry in earlier.items()}
    apply_changes(merged, later)
    return merged


def _earlier_attempts(summary_path: str, child_path: str) -> Callable[[str], bool]:
    """Whether a step's path is in an attempt (or its recovery) of the same retry before the folded one:
    the steps of the folded attempt all come after such a step (a retry's attempts run one after another)."""
    parent, _, label = child_path.rpartition("/")
    kind, _, number = label.partition(" ")
    if not number.isdigit():
        return lambda path: False
    before = int(number)

    def earlier(path: str) -> bool:
        if not path.startswith(parent + "/"):
            return False
        head = path[len(parent) + 1:].split("/", 1)[0]
        group, _, index = head.partition(" ")
        return group in ("attempt", "recover") and index.isdigit() and int(index) < before

    return earlier


def _keys(changed: State) -> set[tuple[str, str | None]]:
    """What a step's changes touch: (object, None) for its pose, (object, joint) for each joint."""
    keys: set[tuple[str, str | None]] = set()
    for name, delta in changed.items():
        if "position" in delta:
            keys.add((name, None))
        keys.update((name, joint) for joint in delta.get("joints", {}))
    return keys


def fold_steps(steps: list[dict[str, Any]], initial: State, summary_path: str, child_path: str,
               earlier: Callable[[str], bool] = lambda path: False) -> None:
    """Fold the recorded steps under `child_path` (and the summary entry `summary_path`, if there is one)
    into one summary entry, in place, at the place of the last of them (see the module docstring).

    `earlier(path)`: a step that surely comes before every step to fold (the search stops there)."""
    prefix = child_path + "/"
    found: list[int] = []
    for index in range(len(steps) - 1, -1, -1):
        path = steps[index]["path"]
        if path in (summary_path, child_path) or path.startswith(prefix):
            found.append(index)
            if path == summary_path:
                break  # an earlier summary comes before everything folded since
        elif earlier(path):
            break
    if not found:
        return
    last = found[0]
    wanted: set[tuple[str, str | None]] = set()
    count = 0
    for index in found:
        wanted |= _keys(steps[index]["changed"])
        count += steps[index].get("folded", 1)
    changed: State = {}
    missing = set(wanted)
    for index in range(last, -1, -1):  # the value each had after the last folded step: the latest change to it
        if not missing:
            break
        for key in _keys(steps[index]["changed"]) & missing:
            _put(changed, key, steps[index]["changed"][key[0]])
            missing.discard(key)
    for key in missing:  # changed back to where it started
        _put(changed, key, initial.get(key[0], {}))
    entry = {"path": summary_path, "status": Status.FAILED.value, "folded": count, "changed": changed}
    for index in found:  # from the last: indices before it stay valid
        del steps[index]
    steps.insert(last - (len(found) - 1), entry)


def _put(changed: State, key: tuple[str, str | None], source: dict[str, Any]) -> None:
    name, joint = key
    entry = changed.setdefault(name, {})
    if joint is None:
        if "position" in source and "orientation" in source:
            entry["position"], entry["orientation"] = source["position"], source["orientation"]
    elif joint in source.get("joints", {}):
        entry.setdefault("joints", {})[joint] = source["joints"][joint]
    if not entry:
        del changed[name]


# -- what a step works on -------------------------------------------------------------------------
def focus_points(world: BulletWorld, info: dict[str, Any]) -> list[Point]:
    """The objects (their bounding boxes' centres) and places a step names in its resolved designator
    slots or query arguments (`object: bowl`, `target: [x, y, z]`): what a camera should show with the robot."""
    values: dict[str, Any] = {}
    if isinstance(info.get("designator"), dict):
        values.update(info["designator"].get("resolved") or info["designator"].get("slots") or {})
    if isinstance(info.get("query"), dict):
        values.update(info["query"].get("args") or {})
    points: list[Point] = []
    for key, value in values.items():
        points.extend(_points(world, key, value))
    return points


def _points(world: BulletWorld, key: str, value: Any) -> Iterable[Point]:
    if isinstance(value, str):
        obj = world.get_object_by_name(value)
        if obj is not None and obj.type not in SCENERY:
            lo, hi = obj.get_aabb()
            yield ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2)
    elif (key in PLACES and isinstance(value, (list, tuple)) and len(value) == 3
          and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        yield (float(value[0]), float(value[1]), float(value[2]))
    elif isinstance(value, (list, tuple)):
        for item in value:
            if isinstance(item, str):
                yield from _points(world, key, item)
