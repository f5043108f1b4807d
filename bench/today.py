"""Today's methods (before issue 15), kept as the baselines of bench/scale.py, measured in the same run.

* `stable`: the whole world is simulated on the prospection copy, which is brought in sync from the
  world on every call (every object read and written, contacts forgotten); the early exit waits for
  every free object of the world to come to rest.
* `visible` / `occluding`: the cropped window is rendered with the whole scene in the world's own
  client (every body, every triangle), and the object alone in a private client holding copies of the
  objects asked about (the others parked far below: still drawn), as pycram_cli/world/solo.py did.
* `sync`: the prospection sync as it was (every object read from the world and written, contacts
  forgotten), for the save/restore row.
"""
from __future__ import annotations

import importlib
import math
from typing import Any

import numpy as np
import pybullet as p

from pycram_cli.reasoning import visibility as V
from pycram_cli.reasoning.stable import StableAnswer
from pycram_cli.world.camera import projection_matrix, segmentation, view_matrix
from pycram_cli.world.model_files import MESH_SUFFIXES, mesh_urdf, prepare_urdf

stable_module = importlib.import_module("pycram_cli.reasoning.stable")  # (the package exports the function)
STEP_HZ = stable_module.STEP_HZ


def sync(world: Any) -> Any:
    """The prospection copy brought in sync as before versions: every object read and written."""
    world.mark_changed()  # as if anything might have changed: nothing is reused
    return world.prospection()


def stable(obj: Any, world: Any = None, seconds: float = 2.0, distance: float = 0.001,
           angle: float = math.radians(1.0)) -> StableAnswer:
    world = obj.world
    if obj.fixed:
        return StableAnswer(True, 0.0, 0.0, 0.0)
    with world.lock:
        twin = sync(world)
        twin.copy.wake_free_objects()
        return _watch(twin.copy, twin.copy_of(obj), int(round(seconds * STEP_HZ)), distance, angle)


def _watch(world: Any, obj: Any, total: int, distance: float, angle: float) -> StableAnswer:
    s = stable_module
    start = obj.get_com_pose()
    free = [o for o in world.objects if not o.fixed and not any(a.child is o for a in o.attachments.values())]
    min_steps = int(s.MIN_SECONDS * STEP_HZ)
    window_time = s.WINDOW / STEP_HZ
    last = {o.id: o.get_com_pose() for o in free}
    previous_motion = None
    calm = 0
    worst_d = worst_a = 0.0
    for step in range(1, total + 1):
        world.step()
        d, a = s._moved(start, obj.get_com_pose())
        worst_d, worst_a = max(worst_d, d), max(worst_a, a)
        if d > distance or a > angle:
            return StableAnswer(False, worst_d, worst_a, step / STEP_HZ)
        if step % s.WINDOW:
            continue
        scene_at_rest = True
        motion = (0.0, 0.0)
        for other in free:
            pose = other.get_com_pose()
            md, ma = s._moved(last[other.id], pose)
            last[other.id] = pose
            if other is obj:
                motion = (md, ma)
            if md > s.REST_SPEED * window_time or ma > s.REST_SPIN * window_time:
                scene_at_rest = False
        remaining = (total - step) / STEP_HZ
        settled = False
        if scene_at_rest and previous_motion is not None and step >= min_steps:
            settled = True
            for now_m, before_m, done, limit, noise in ((motion[0], previous_motion[0], d, distance, s.NOISE_DISTANCE),
                                                         (motion[1], previous_motion[1], a, angle, s.NOISE_ANGLE)):
                if now_m <= noise:
                    continue
                speed = now_m / window_time
                accel = max(0.0, (now_m - before_m) / window_time ** 2)
                if now_m > 1.2 * before_m or done + speed * remaining + 0.5 * accel * remaining ** 2 > 0.5 * limit:
                    settled = False
        previous_motion = motion
        calm = calm + 1 if settled else 0
        if calm >= s.CALM_WINDOWS:
            return StableAnswer(True, worst_d, worst_a, step / STEP_HZ)
    return StableAnswer(True, worst_d, worst_a, total / STEP_HZ)


class _Solo:
    """The private client that rendered one object alone (copies of the objects asked about, others parked)."""

    clients: dict[int, "_Solo"] = {}

    def __init__(self) -> None:
        self.client = p.connect(p.DIRECT)
        self.bodies: dict[int, int] = {}

    @classmethod
    def of(cls, world: Any) -> "_Solo":
        if id(world) not in cls.clients:
            cls.clients[id(world)] = cls()
        return cls.clients[id(world)]

    def mask(self, obj: Any, width: int, height: int, view: Any, proj: Any) -> np.ndarray:
        body = self.bodies.get(obj.id)
        if body is None:
            path = mesh_urdf(obj.path, None) if obj.path.suffix.lower() in MESH_SUFFIXES else prepare_urdf(obj.path).path
            body = self.bodies[obj.id] = p.loadURDF(str(path), useFixedBase=True, physicsClientId=self.client)
        position, orientation = obj.get_com_pose()
        p.resetBasePositionAndOrientation(body, position, orientation, physicsClientId=self.client)
        for joint in obj.movable_joints:
            p.resetJointState(body, joint.index, obj.get_joint_position(joint.name), 0.0, physicsClientId=self.client)
        try:
            return segmentation(self.client, width, height, view, proj) == body
        finally:
            p.resetBasePositionAndOrientation(body, (0.0, 0.0, -1000.0 - 50.0 * body), (0, 0, 0, 1),
                                              physicsClientId=self.client)


def _views(obj: Any, camera: Any = None) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    world = obj.world
    cam = V.resolve_camera(obj, camera)
    window = V._window(obj, cam)
    if window is None:
        return None
    umin, umax, vmin, vmax, near, far = window
    tu = tv = math.inf
    if cam.fov is not None:
        tu, tv = math.tan(cam.fov[0] / 2.0), math.tan(cam.fov[1] / 2.0)
        if umax < -tu or umin > tu or vmax < -tv or vmin > tv:
            return None
    ratio = (umax - umin) / (vmax - vmin)
    width = int(min(V.MAX_SIDE, max(V.MIN_SIDE, round(math.sqrt(V.PIXEL_BUDGET * ratio)))))
    height = int(min(V.MAX_SIDE, max(V.MIN_SIDE, round(math.sqrt(V.PIXEL_BUDGET / ratio)))))
    eye, forward, down = cam.position, cam.rotation[:, 2], cam.rotation[:, 1]
    view = view_matrix(eye.tolist(), (eye + forward).tolist(), (-down).tolist())
    proj = projection_matrix(near * umin, near * umax, -near * vmax, -near * vmin, near, far)
    scene = world.segmentation(width, height, view, proj)  # every body of the world
    alone = _Solo.of(world).mask(obj, width, height, view, proj)
    us = umin + (np.arange(width) + 0.5) / width * (umax - umin)
    vs = vmin + (np.arange(height) + 0.5) / height * (vmax - vmin)
    in_view = (np.abs(vs)[:, None] <= tv) & (np.abs(us)[None, :] <= tu)
    return scene, alone, in_view


def visible(obj: Any, camera: Any = None, world: Any = None, threshold: float = 0.8) -> V.VisibleAnswer:
    views = _views(obj, camera)
    if views is None:
        return V.VisibleAnswer(False, 0.0, 0, 0)
    scene, alone, in_view = views
    total = int(alone.sum())
    seen = int((alone & in_view & (scene == obj.id)).sum())
    fraction = seen / total if total else 0.0
    return V.VisibleAnswer(total > 0 and fraction >= threshold, fraction, seen, total)


def occluding(obj: Any, camera: Any = None, world: Any = None) -> list[Any]:
    views = _views(obj, camera)
    if views is None:
        return []
    scene, alone, in_view = views
    ids = {int(i) for i in np.unique(scene[alone & in_view])} - {obj.id, -1}
    return sorted((obj.world.get_object_by_id(i) for i in ids), key=lambda o: (o.name, o.id))


def swap_in() -> None:
    """Make plans use today's stable, visible and occluding (for the plan-time baseline)."""
    from pycram_cli.process_modules import perception

    stable_module = importlib.import_module("pycram_cli.reasoning.stable")  # the package's `stable` is the function
    stable_module.stable, V.visible, V.occluding = stable, visible, occluding  # what the queries call
    perception.visible, perception.occluding = visible, occluding
