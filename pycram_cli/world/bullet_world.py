"""BulletWorld: one PyBullet client with its objects, gravity, events and state.

Every PyBullet call names this world's client, so any number of worlds can live side
by side without seeing each other's changes; at most one of them shows a GUI window.
"""
from __future__ import annotations

import contextlib
import itertools
import math
import threading
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pybullet as p

from ..quiet import silenced
from .cache import WorldCache
from .camera import segmentation
from .display import check_display
from .events import Event
from .pose import Vec3, check_position
from .state import StateCache, WorldState
from .view import ViewRenderer
from .window import GuiWindow, open_window

if TYPE_CHECKING:
    from .object import Object
    from .prospection import Prospection

STEP_HZ = 240
#: how many shapes along one ray `cast_rays` looks at (it sees through the ignored ones)
_RAY_HITS = 16


class WorldError(RuntimeError):
    """Misuse of a world (a second GUI, a world that has exited, ...)."""


@dataclass(frozen=True)
class ClosestPoint:
    """One pair of closest points between two objects' collision shapes (world frame).

    `link_a`/`link_b` are link indices (-1: the base); `normal_on_b` points from b towards a;
    `distance` is negative when the shapes interpenetrate.
    """

    link_a: int
    link_b: int
    position_on_a: Vec3
    position_on_b: Vec3
    normal_on_b: Vec3
    distance: float


@dataclass(frozen=True)
class RayHit:
    """Where a ray first meets a collision shape: the object and link (-1: the base) hit, how far along the ray
    (0 at its start, 1 at its end), the point and the surface normal there (world frame)."""

    object: Object | None
    link: int
    fraction: float
    position: Vec3
    normal: Vec3


class BulletWorld(GuiWindow):
    """A simulated world. `BulletWorld.current_world` is the newest one that has not exited (the design's name for it,
    `current_bullet_world`, is kept equal).

    `BulletWorld("DIRECT")`, `BulletWorld(type="GUI")`: the design's spelling of the mode is accepted too.
    """

    current_world: BulletWorld | None = None
    current_bullet_world: BulletWorld | None = None  # the design's name for current_world
    #: the design's scripts set `BulletWorld.robot = robot` and read it back; each world's own robot is `world.robot`
    robot: Object | None = None
    _live: list[BulletWorld] = []
    _gui_world: BulletWorld | None = None
    _registry_lock = threading.Lock()

    # long: connecting the client (direct or GUI) and setting up every table the world owns
    def __init__(self, mode: str = "direct", gravity: Sequence[float] = (0.0, 0.0, -9.81), _hidden: bool = False,
                 type: str | None = None) -> None:
        """`type`: the design's keyword for `mode` (`BulletWorld(type="DIRECT")`); case does not matter.
        `_hidden`: a world's private copy (see prospection.py), never the current world."""
        mode = type if type is not None else mode
        mode = mode.lower() if isinstance(mode, str) else mode
        if mode not in ("direct", "gui") or (_hidden and mode != "direct"):
            raise ValueError(f"mode must be 'direct' or 'gui', got {mode!r}")
        with BulletWorld._registry_lock:
            if mode == "gui" and BulletWorld._gui_world is not None:
                raise WorldError(
                    "a GUI world is already open (PyBullet allows one window per process); "
                    "exit it first or create this world with mode='direct'"
                )
            if mode == "gui":
                check_display()  # PyBullet would end the process (exit code 1) without a display
                client = open_window()
            else:
                with silenced():
                    client = p.connect(p.DIRECT)
            if client < 0:
                raise WorldError(f"could not start a PyBullet {mode} client (for the GUI, is a display available?)")
            self.client_id: int = client
            p.setPhysicsEngineParameter(deterministicOverlappingPairs=1, physicsClientId=client)
            self.mode = mode
            self._hidden = _hidden
            if mode == "gui":
                BulletWorld._gui_world = self
            if not _hidden:
                BulletWorld._live.append(self)
                BulletWorld.current_world = BulletWorld.current_bullet_world = self
        self.objects: list[Object] = []
        self._by_id: dict[int, Object] = {}
        self.robot: Object | None = None
        #: the robot object's description as robots/ reads it (robots/description.py `description_for`): (the robot
        #: object, its description or None), set once by the world loader or on the first ask, and forgotten with the
        #: robot object; the world keeps it (not a table beside the world), so it lives and goes with the world
        self.described_robot: tuple[Object, Any] | None = None
        self.attachment_event = Event("attachment")
        self.detachment_event = Event("detachment")
        self.manipulation_event = Event("manipulation")
        self.lock = threading.RLock()
        self.gravity: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.source: Path | None = None  # the world file it was loaded from, if any
        self._exited = False
        self._realtime = False
        self._exit_hooks: list[Callable[[], None]] = []
        self._step_watchers: list[Callable[[BulletWorld], None]] = []  # called after every step (watch_steps)
        self._copy_watchers: list[Callable[[BulletWorld], None]] = []  # the same, for the prospection copy's steps
        #: a replay of a run on this world is being recorded (plan/replay.py): steps may keep details for it
        self.recording_replay = False
        #: what the layers above work out about this world and its objects (cache.py): it goes with the world
        self.cache = WorldCache()
        self._view: ViewRenderer | None = None  # made on the first picture_of
        self._captions: dict[int, int] = {}  # the GUI's caption text items by line, once shown
        self._prospection: Prospection | None = None  # made on the first query that tries things out
        # change tracking (see `version`): every change takes a fresh number from the clock
        self._clock = itertools.count(1)
        self._version = next(self._clock)  # the newest change of anything
        self._stepped = 0  # the newest simulation step (it may have moved every object)
        self._steps_taken = 0  # physics steps ever taken (not put back by a restore, unlike versions)
        self._fresh_from: tuple[WorldState, int] | None = None  # reset_to's last state, and the steps taken then
        self._states = StateCache(self)
        p.setTimeStep(1.0 / STEP_HZ, physicsClientId=client)
        self.set_gravity(gravity)

    # -- life cycle -------------------------------------------------------------
    @classmethod
    def current(cls) -> BulletWorld | None:
        return cls.current_world

    @property
    def alive(self) -> bool:
        return not self._exited

    def is_connected(self) -> bool:
        """Whether the PyBullet client still runs: False once the world exited or its GUI window was closed."""
        return not self._exited and bool(p.isConnected(physicsClientId=self.client_id))

    def add_exit_hook(self, hook: Callable[[], None]) -> None:
        """Call `hook` when this world exits (e.g. to free helper clients made for it)."""
        self._exit_hooks.append(hook)

    def watch_steps(self, watcher: Callable[[BulletWorld], None], prospection: bool = False) -> Callable[[], None]:
        """Call `watcher(world)` after every physics step of this world (a replay recording the motion physics
        makes), or with `prospection` of its prospection copy, where queries like `stable` simulate what would
        happen (prospection.py; the copy is passed); returns the function that stops it."""
        watchers = self._copy_watchers if prospection else self._step_watchers
        watchers.append(watcher)

        def unwatch() -> None:
            if watcher in watchers:
                watchers.remove(watcher)

        return unwatch

    @contextlib.contextmanager
    def unwatched(self) -> Iterator[None]:
        """`with world.unwatched():` — steps inside (of the world and of its prospection copy) are seen by no
        watcher: what a `project` step tries out is not the run, and a replay must not show its physics."""
        saved = list(self._step_watchers), list(self._copy_watchers)
        self._step_watchers.clear()
        self._copy_watchers.clear()  # the same list as the copy's own (prospection.py)
        try:
            yield
        finally:
            self._step_watchers[:], self._copy_watchers[:] = saved

    def exit(self) -> None:
        """Disconnect the client; the current world becomes the newest live one (or None)."""
        if self._exited:
            return
        self._exited = True
        for hook in self._exit_hooks:
            with contextlib.suppress(Exception):
                hook()
        self._view = None
        self.cache.forget()
        if self._prospection is not None:
            with contextlib.suppress(Exception):
                self._prospection.close()
            self._prospection = None
        with BulletWorld._registry_lock:
            with contextlib.suppress(Exception), silenced():
                p.disconnect(physicsClientId=self.client_id)
            if self in BulletWorld._live:
                BulletWorld._live.remove(self)
            if BulletWorld._gui_world is self:
                BulletWorld._gui_world = None
            if not self._hidden:
                BulletWorld.current_world = BulletWorld._live[-1] if BulletWorld._live else None
                BulletWorld.current_bullet_world = BulletWorld.current_world

    def __enter__(self) -> BulletWorld:
        return self

    def __exit__(self, *exc: object) -> None:
        self.exit()

    def _check_alive(self) -> None:
        if self._exited:
            raise WorldError("this world has exited")

    # -- events (the design's getters) ---------------------------------------------
    def get_attachment_event(self) -> Event:
        """The event fired with (parent, child) when two objects are attached (also `attachment_event`)."""
        return self.attachment_event

    def get_detachment_event(self) -> Event:
        """The event fired with (parent, child) when two objects are detached (also `detachment_event`)."""
        return self.detachment_event

    def get_manipulation_event(self) -> Event:
        """The event fired with (object, joint, old, new) when a joint of the environment is moved."""
        return self.manipulation_event

    # -- physics ----------------------------------------------------------------
    def set_gravity(self, vector: Sequence[float]) -> None:
        self._check_alive()
        self.gravity = check_position(vector, "gravity")
        p.setGravity(*self.gravity, physicsClientId=self.client_id)
        self.mark_changed()

    def set_realtime(self, realtime: bool) -> None:
        self._check_alive()
        self._realtime = bool(realtime)
        p.setRealTimeSimulation(1 if realtime else 0, physicsClientId=self.client_id)
        self.mark_changed()

    # -- change tracking ----------------------------------------------------------
    @property
    def tracks_changes(self) -> bool:
        """Whether `version` sees every change: not while PyBullet steps by itself (real time) or a GUI
        window lets the user drag bodies; such worlds count as changed whenever they are asked."""
        return not self._realtime and self.mode != "gui"

    @property
    def is_copy(self) -> bool:
        """Whether this is a world's private copy (prospection.py), whose objects are written without versions."""
        return self._hidden

    @property
    def version(self) -> int:
        """A number that changes whenever the world does, and only then: teleports, joint changes,
        attachments, simulation steps, gravity, objects added or removed (see `mark_changed`).

        Equal versions mean equal poses, velocities, joints and attachments, so whatever was
        derived from the world (the prospection copy's sync, a saved state) can be reused while
        the version stays. Restoring a saved state gives back that state's version.
        """
        if not self.tracks_changes:
            self.mark_changed()
        return self._version

    def mark_changed(self, obj: Object | None = None) -> None:
        """Record a change of `obj` (None: of anything, e.g. a simulation step, which may move every object).

        The world's own methods and Object's call this; code that changes a world through PyBullet
        directly (a test, a benchmark's baseline) must call it too, or cached copies go stale.
        """
        version = next(self._clock)
        self._version = version
        if obj is None:
            self._stepped = version
        else:
            obj._version = version

    def version_of(self, obj: Object) -> int:
        """The version of one object: the newest change of it, or of everything (a step), whichever is later."""
        if not self.tracks_changes:
            self.mark_changed()
        return max(obj._version, self._stepped)

    def simulate(self, seconds: float) -> None:
        """Step the physics for `seconds` at 240 Hz.

        Fixed objects (robots, environments) are kinematic: their joints are held and put
        back exactly afterwards, so they never drift. Attached objects follow their parent
        at every step.
        """
        self._check_alive()
        steps = int(round(seconds * STEP_HZ))
        with self.lock:
            held = [(obj, obj.get_joint_positions()) for obj in self.objects if obj.fixed and obj.movable_joints]
            for _ in range(steps):
                self.step()
            for obj, positions in held:
                obj.reset_joints(positions)
            self._follow_parents()

    def step(self) -> None:
        """One physics step (1/240 s); attached objects then follow their parents.

        Fixed objects' joints are only held by their motors here; `simulate` also puts them back.
        """
        self._check_alive()
        p.stepSimulation(physicsClientId=self.client_id)
        self._steps_taken += 1
        self.mark_changed()
        self._follow_parents()
        for watcher in self._step_watchers:
            watcher(self)

    def _follow_parents(self) -> None:
        """Every parent, in world order, moves what is attached to it (children only: nothing to do)."""
        for obj in self.objects:
            if obj.attachments:
                obj.move_attached()

    def wake_free_objects(self) -> None:
        """Wake every free (not fixed) object.

        PyBullet's restoreState does not restore sleep: an object that fell asleep in between
        would otherwise hang where it was put back.
        """
        self.wake([obj for obj in self.objects if not obj.fixed])

    def wake(self, objects: Sequence[Object]) -> None:
        """Wake `objects` (sleeping bodies are not simulated; restoreState does not restore sleep)."""
        for obj in objects:
            p.changeDynamics(obj.id, -1, activationState=p.ACTIVATION_STATE_WAKE_UP, physicsClientId=self.client_id)

    # -- geometry ---------------------------------------------------------------
    def closest_points(self, a: Object, b: Object, distance: float,
                       link_a: int | None = None, link_b: int | None = None) -> list[ClosestPoint]:
        """The closest points between `a` and `b` (or the given links of them) at most `distance` m apart.

        Read from the collision shapes as they are now, so teleports and joint changes count at
        once without a simulation step; an empty list when they are farther apart.
        """
        points = []
        for row in self._closest_rows(a, b, distance, link_a, link_b):
            # the fields go straight into the new instance: half the cost of the frozen __init__,
            # which counts in the queries' hot paths
            point = object.__new__(ClosestPoint)
            fields = point.__dict__
            (fields["link_a"], fields["link_b"], fields["position_on_a"], fields["position_on_b"],
             fields["normal_on_b"], fields["distance"]) = row[3:9]
            points.append(point)
        return points

    def distance(self, a: Object, b: Object, max_distance: float,
                 link_a: int | None = None, link_b: int | None = None) -> float:
        """The smallest distance between `a` and `b` (negative: they interpenetrate), or inf when
        nothing of them is within `max_distance` m — `closest_points` without building the points."""
        rows = self._closest_rows(a, b, max_distance, link_a, link_b)
        return min(row[8] for row in rows) if rows else math.inf

    def _closest_rows(self, a: Object, b: Object, distance: float, link_a: int | None,
                      link_b: int | None) -> Sequence[Sequence[Any]]:
        """PyBullet's getClosestPoints rows for `closest_points` and `distance` (kept lean: hot path)."""
        if self._exited:
            raise WorldError("this world has exited")
        if a.world is not self or b.world is not self:
            raise WorldError(f"'{a.name}' and '{b.name}' are not both in this world")
        if link_a is None and link_b is None:
            return p.getClosestPoints(a.id, b.id, distance, physicsClientId=self.client_id)
        links: dict[str, int] = {}
        if link_a is not None:
            links["linkIndexA"] = link_a
        if link_b is not None:
            links["linkIndexB"] = link_b
        return p.getClosestPoints(a.id, b.id, distance, physicsClientId=self.client_id, **links)

    def clear_fraction(self, start: Sequence[float], end: Sequence[float], ignore: Sequence[Object] = ()) -> float:
        """How far along the segment from `start` to `end` (0..1) nothing blocks it: 1.0 when the line is
        clear. Objects in `ignore` are seen through (e.g. a camera looking past the robot at its work)."""
        self._check_alive()
        skip = {obj.id for obj in ignore}
        begin = np.asarray(start, dtype=float)
        stop = np.asarray(end, dtype=float)
        length = float(np.linalg.norm(stop - begin))
        if length < 1e-9:
            return 1.0
        done = 0.0
        for _ in range(8):  # through at most 8 ignored objects
            origin = begin + (stop - begin) * done
            hit = p.rayTest(origin.tolist(), stop.tolist(), physicsClientId=self.client_id)[0]
            if hit[0] < 0:
                return 1.0
            reached = done + (1.0 - done) * float(hit[2])
            if hit[0] not in skip:
                return reached
            done = min(1.0, reached + 1e-3 / length)
        return done

    def cast_rays(self, starts: Sequence[Sequence[float]], ends: Sequence[Sequence[float]],
                  ignore: Sequence[Object] = ()) -> list[RayHit | None]:
        """Where each ray from `starts[k]` to `ends[k]` first hits a collision shape, or None; objects in `ignore`
        are seen through. Read as the shapes are now (no simulation step), like `closest_points`."""
        self._check_alive()
        skip = {obj.id for obj in ignore}
        froms = [tuple(float(v) for v in s) for s in starts]
        tos = [tuple(float(v) for v in e) for e in ends]
        hits: list[RayHit | None] = [None] * len(froms)
        for number in range(_RAY_HITS):  # the n-th shape along each ray, until a shape that counts or none is left
            rows = p.rayTestBatch(froms, tos, reportHitNumber=number, physicsClientId=self.client_id)
            more = False
            for k, (body, link, fraction, position, normal) in enumerate(rows):
                if body < 0:
                    continue
                more = True
                if body in skip or (hits[k] is not None and hits[k].fraction <= fraction):  # type: ignore[union-attr]
                    continue
                hits[k] = RayHit(self._by_id.get(body), link, float(fraction), tuple(position), tuple(normal))
            if not more:
                break
        return hits

    # -- rendering --------------------------------------------------------------
    def segmentation(self, width: int, height: int, view: Sequence[float],
                     projection: Sequence[float]) -> np.ndarray:
        """(height, width) ids of the objects seen at each pixel (-1: nothing), for OpenGL-style matrices.

        TinyRenderer (works headless), no shadows; see `camera.view_matrix` and `camera.projection_matrix`.
        """
        self._check_alive()
        return segmentation(self.client_id, width, height, view, projection)

    def segmentation_alone(self, obj: Object, width: int, height: int, view: Sequence[float],
                           projection: Sequence[float]) -> np.ndarray:
        """(height, width) booleans: where `obj` would cover the pixel with nothing else in the world."""
        return self.segmentation_of({obj: None}, width, height, view, projection) == obj.id

    def segmentation_of(self, parts: Mapping[Object, Sequence[int] | None], width: int, height: int,
                        view: Sequence[float], projection: Sequence[float]) -> np.ndarray:
        """(height, width) ids of the objects seen at each pixel (-1: nothing) when only `parts` exist: for each
        object the links to draw (by index, -1: the base) or None for all of them.

        Rendered from the copies in this world's private prospection client (see `view.py`), so nothing here
        is hidden, moved or recoloured, and the renderer pays only for what is drawn (`segmentation` draws
        everything).
        """
        return self.picture_of(parts, width, height, view, projection)[0]

    def picture_of(self, parts: Mapping[Object, Sequence[int] | None], width: int, height: int,
                   view: Sequence[float], projection: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
        """`segmentation_of` and the picture's depth buffer (0..1, growing with distance; 1 where nothing is)."""
        self._check_alive()
        with self.lock:
            if self._view is None:
                self._view = ViewRenderer(self)
            return self._view.picture(parts, width, height, view, projection)

    def prospection(self, objects: Sequence[Object] | None = None, velocities: bool = True) -> Prospection:
        """This world's private copy, brought in sync (all objects, or only `objects`): where queries simulate and
        try joint values, so that this world is only read and keeps every hidden state (see prospection.py)."""
        self._check_alive()
        with self.lock:
            if self._prospection is None:
                from .prospection import Prospection  # why: prospection.py imports this module

                self._prospection = Prospection(self)
            self._prospection.sync(list(objects) if objects is not None else None, velocities)
            return self._prospection

    # -- objects ----------------------------------------------------------------
    def register(self, obj: Object) -> None:
        """Take a newly loaded object into the world's lists (Object's constructor calls this)."""
        self.objects.append(obj)
        self._by_id[obj.id] = obj
        if obj.type == "robot" and self.robot is None:
            self.robot = obj
        self.mark_changed(obj)

    def unregister(self, obj: Object) -> None:
        """Drop a removed object from the world's lists (Object.remove calls this)."""
        self.objects.remove(obj)
        self._by_id.pop(obj.id, None)
        if self.robot is obj:
            self.robot = None
        if self.described_robot is not None and self.described_robot[0] is obj:
            self.described_robot = None
        self.mark_changed()

    def get_objects_by_name(self, name: str) -> list[Object]:
        return [o for o in self.objects if o.name == name]

    def get_object_by_name(self, name: str) -> Object | None:
        found = self.get_objects_by_name(name)
        return found[0] if found else None

    def get_objects_by_type(self, type: str) -> list[Object]:
        return [o for o in self.objects if o.type == type]

    def get_object_by_id(self, id: int) -> Object | None:
        return self._by_id.get(id)

    # -- state ------------------------------------------------------------------
    def save_state(self) -> WorldState:
        """Everything needed to put the world back exactly: poses, joints, velocities, attachments.

        Saved once per change: while the world's version stays, the same state is handed out again
        (PyBullet's saveState serialises every collision shape, 4-20 ms; see state.py)."""
        self._check_alive()
        return self._states.save()

    def restore_state(self, state: WorldState) -> None:
        self._check_alive()
        self._states.restore(state)

    def reset_to(self, state: WorldState) -> None:
        """Put the world back to `state` as if it had just been loaded, the same way whatever ran since.

        PyBullet's restoreState puts poses, joints and velocities back bitwise, but not the contact
        caches a run leaves behind (nor sleep): every object is first moved apart from every other and
        collision detection run (the broadphase drops every pair with its contacts and warm starts, and
        keeps its pairs sorted: `deterministicOverlappingPairs`), then one physics step from the restored
        state makes them anew, and a second restore undoes the step. Worlds reset like this give byte-identical traces
        whatever ran on them before (tests/scenario/test_variations.py): what makes a sweep's
        outcomes independent of its workers, and a projection's of the runs before it. What the layers above kept
        about the world (`cache`: IK answers, walks, searches, floor maps) is forgotten too: an answer kept for a
        question asked within a rounding of another (IK's targets to 1e-6, a search's ends to 1e-9) would answer
        the next run's question with the bits of an earlier run's.
        """
        self.cache.forget()
        fresh = self._fresh_from
        if fresh is not None and fresh[0] is state and fresh[1] == self._steps_taken:
            # nothing stepped since the last reset to this state: the contact caches are the ones that reset
            # made, so the step would make them again (about 2 ms on the kitchen, per projected run)
            self.restore_state(state)
            return
        self.drop_contacts()
        self.restore_state(state)
        self.step()
        self.restore_state(state)
        self.wake_free_objects()
        self._fresh_from = (state, self._steps_taken)

    def drop_contacts(self) -> None:
        """Every object moved far from every other and collision detection run: no pair overlaps, so the broadphase
        drops them all with their contact manifolds and warm starts (its pairs kept sorted, the next step finds
        them in the same order whatever came before). The objects are left there, unmarked: the caller puts them
        back (a restored state, or a sync that writes every object)."""
        for index, obj in enumerate(self.objects):
            p.resetBasePositionAndOrientation(obj.id, (0.0, 0.0, -1000.0 - 100.0 * index), (0, 0, 0, 1),
                                              physicsClientId=self.client_id)
        p.performCollisionDetection(physicsClientId=self.client_id)

    def release_state(self, state: WorldState) -> None:
        """Free the memory PyBullet holds for a saved state (once nobody holds it any more)."""
        self._states.release(state)

    @contextlib.contextmanager
    def snapshot(self) -> Iterator[WorldState]:
        """`with world.snapshot():` — whatever happens inside is undone on leaving."""
        state = self.save_state()
        try:
            yield state
        finally:
            if not self._exited:
                self.restore_state(state)
                self.release_state(state)

    def __repr__(self) -> str:
        return f"BulletWorld(mode={self.mode!r}, client_id={self.client_id}, objects={len(self.objects)})"


def current_world() -> BulletWorld | None:
    return BulletWorld.current_world
