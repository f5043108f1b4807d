"""Rendering a world to pixels (PyBullet's TinyRenderer, works headless), cameras that frame what
matters (the whole scene, the robot, the objects it works on), and encoding images (PNG, JPEG).

Images are encoded with Pillow, the format chosen by the file's extension (`IMAGE_FORMATS`).
"""
from __future__ import annotations

import contextlib
import io
import math
import mmap
import os
import signal
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pybullet as p
from PIL import Image

from ..errors import BadValue
from ..files import write_atomic
from .pose import vec3

if TYPE_CHECKING:
    from .bullet_world import BulletWorld
    from .object import Object

#: file extensions (lower case) and the image formats they are written in
IMAGE_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG", ".webp": "WEBP", ".bmp": "BMP"}
#: the named views of `named_camera`
VIEWS = ("overview", "robot", "target")
#: types whose objects are scenery, not things a plan works on
SCENERY_TYPES = ("robot", "environment")


@dataclass(frozen=True)
class Camera:
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    vertical_fov_deg: float = 50.0
    near: float = 0.05
    far: float = 30.0


def default_camera(world: BulletWorld) -> Camera:
    """A three-quarter view that frames every object except huge ones (floors): the `overview`."""
    boxes = [o.get_aabb() for o in world.objects]
    boxes = [b for b in boxes if max(b[1][k] - b[0][k] for k in range(2)) < 15.0] or boxes or [((0, 0, 0), (1, 1, 1))]
    lo = np.min([b[0] for b in boxes], axis=0)
    hi = np.max([b[1] for b in boxes], axis=0)
    centre = (lo + hi) / 2.0
    radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 0.5)
    direction = np.array([-1.0, -1.3, 0.9])
    direction /= np.linalg.norm(direction)
    eye = centre + direction * radius / math.tan(math.radians(25.0)) * 0.8
    return Camera(tuple(eye), tuple(centre))



def framing_camera(points: Iterable[Sequence[float]], heading: Sequence[float], fov_deg: float = 50.0,
                   aspect: float = 4 / 3, pitch_deg: float = -40.0, turn_deg: float = 35.0,
                   min_distance: float = 1.2) -> Camera:
    """A camera that sees every one of `points`, looking roughly along `heading` (x, y) from above.

    The camera stands behind the points as seen along `heading`, turned `turn_deg` to the side
    and looking down by `-pitch_deg`, far enough that the points' bounding sphere fits the
    narrower of the two fields of view (`fov_deg` is the vertical one).
    """
    cloud = np.asarray([list(map(float, q)) for q in points], dtype=float).reshape(-1, 3)
    if not len(cloud):
        cloud = np.zeros((1, 3))
    lo, hi = cloud.min(axis=0), cloud.max(axis=0)
    centre = (lo + hi) / 2.0
    radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 0.3)
    yaw = math.atan2(float(heading[1]), float(heading[0])) if math.hypot(heading[0], heading[1]) > 1e-9 else 0.0
    yaw += math.radians(turn_deg)
    pitch = math.radians(pitch_deg)
    forward = np.array([math.cos(pitch) * math.cos(yaw), math.cos(pitch) * math.sin(yaw), math.sin(pitch)])
    half_v = math.radians(fov_deg) / 2.0
    half_h = math.atan(math.tan(half_v) * aspect)
    distance = max(radius / math.sin(min(half_v, half_h)) * 1.05, min_distance)
    eye = centre - forward * distance
    return Camera(vec3(eye), vec3(centre), vertical_fov_deg=fov_deg)


def _corners(box: tuple[Sequence[float], Sequence[float]]) -> list[tuple[float, float, float]]:
    lo, hi = box
    return [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]


def heading_of(obj: Object) -> tuple[float, float]:
    """The direction (x, y) an object's base faces: its x axis, projected on the floor."""
    x, y, z, w = obj.get_orientation()
    return (1 - 2 * (y * y + z * z), 2 * (x * y + z * w))


def clear_camera(world: BulletWorld, points: Sequence[Sequence[float]], heading: Sequence[float],
                 fov_deg: float, aspect: float, pitch_deg: float = -40.0, turn_deg: float = 35.0,
                 min_distance: float = 1.2, focus: Sequence[Sequence[float]] = ()) -> Camera:
    """`framing_camera`, turned until nothing stands between the camera and what it should show.

    Indoors, a camera behind the robot can end up behind a wall or inside a cupboard, or see the
    robot's back instead of what it holds out. Turns around the view are tried in order (the
    given one first); the first that sees its target past every environment and sees the most
    `focus` points past the robot as well wins. When no turn sees the target, the clearest one
    is moved in front of what blocks it.
    """
    robot_and_things = [o for o in world.objects if o.type != "environment"]
    things = [o for o in world.objects if o.type not in SCENERY_TYPES]
    best: tuple[tuple[float, float, float, float], Camera] | None = None
    for order, turn in enumerate((turn_deg, -turn_deg, 2 * turn_deg, -2 * turn_deg, 0.0, 3 * turn_deg,
                                  -3 * turn_deg, 180.0)):
        camera = framing_camera(points, heading, fov_deg, aspect, pitch_deg, turn, min_distance)
        clear = world.clear_fraction(camera.target, camera.eye, robot_and_things)
        seen = 0
        if clear >= 1.0:
            for point in focus:
                length = math.dist(camera.eye, point)
                if (1.0 - world.clear_fraction(camera.eye, point, things)) * length < 0.05:
                    seen += 1
        score = (1.0 if clear >= 1.0 else 0.0, float(seen), clear, -float(order))
        if best is None or score > best[0]:
            best = (score, camera)
        if clear >= 1.0 and seen == len(focus):
            break
    assert best is not None
    score, camera = best
    if score[0]:
        return camera
    clear = score[2]
    eye, target = np.asarray(camera.eye), np.asarray(camera.target)
    distance = float(np.linalg.norm(eye - target))
    closer = target + (eye - target) * max(0.05, clear - 0.1 / max(distance, 1e-6))
    return replace(camera, eye=vec3(closer))


def robot_camera(world: BulletWorld, focus: Iterable[Sequence[float]] = (), fov_deg: float = 50.0,
                 aspect: float = 4 / 3) -> Camera:
    """The robot (and the points in `focus`, e.g. what it works on) seen over its shoulder.

    The camera looks from the robot towards the focus (or the way the robot faces), from the
    room behind the robot, never from behind a wall (see `clear_camera`).
    """
    robot = world.robot
    focus = [tuple(map(float, q)) for q in focus]
    if robot is None:
        return framing_camera(focus, (1.0, 0.0), fov_deg, aspect) if focus else default_camera(world)
    position = robot.get_position()
    heading = heading_of(robot)
    if focus:
        centre = np.mean(np.asarray(focus), axis=0)
        towards = (float(centre[0] - position[0]), float(centre[1] - position[1]))
        if math.hypot(*towards) > 0.3:
            heading = towards
    return clear_camera(world, _corners(robot.get_aabb()) + focus, heading, fov_deg, aspect, pitch_deg=-50.0,
                        focus=focus)


def frame_viewer_on_robot(world: BulletWorld) -> Camera | None:
    """Point the GUI window's camera at the robot and every object it may work on (`robot_camera`, with the
    window's field of view and shape); the camera set, None without a window."""
    current = world.viewer_camera()
    if current is None:
        return None
    focus = [tuple((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(world)]
    camera = robot_camera(world, focus, current.vertical_fov_deg, world.viewer_aspect())
    world.set_viewer_camera(camera)
    return camera


def movable_objects(world: BulletWorld) -> list[Object]:
    """The things a plan works on: every object that is neither a robot nor an environment."""
    return [o for o in world.objects if o.type not in SCENERY_TYPES]


def objects_camera(world: BulletWorld, objects: Sequence[Object] | None = None, fov_deg: float = 50.0,
                   aspect: float = 4 / 3) -> Camera:
    """`objects` (default: every movable one) framed close, seen from the robot's side of them."""
    chosen = list(objects) if objects is not None else movable_objects(world)
    if not chosen:
        return robot_camera(world, (), fov_deg, aspect)
    return boxes_camera(world, [o.get_aabb() for o in chosen], fov_deg, aspect)


def boxes_camera(world: BulletWorld, boxes: Sequence[tuple[Sequence[float], Sequence[float]]],
                 fov_deg: float = 50.0, aspect: float = 4 / 3, min_distance: float = 0.8,
                 pitch_deg: float = -45.0, clear: bool = True,
                 heading: Sequence[float] | None = None) -> Camera:
    """Bounding boxes (lo, hi) framed close, seen from the robot's side of them: `objects_camera`, for boxes that
    are not (only) objects' — a failed object and the box of the pose it was meant to have. `clear=False`: from
    where the framing puts it, even if something stands in the way (a view that shows through walls). `heading`:
    the way (x, y) to look, default from the robot towards the boxes."""
    points = [c for box in boxes for c in _corners(box)]
    centre = np.mean(np.asarray(points), axis=0)
    robot = world.robot
    if heading is None and robot is None:
        heading = (1.0, 0.0)
    elif heading is None and robot is not None:
        position = robot.get_position()
        towards = (float(centre[0] - position[0]), float(centre[1] - position[1]))
        heading = towards if math.hypot(*towards) > 0.3 else heading_of(robot)
    assert heading is not None
    centres = [tuple((a + b) / 2 for a, b in zip(*box)) for box in boxes]
    if not clear:
        return framing_camera(points, heading, fov_deg, aspect, pitch_deg, 20.0, min_distance)
    return clear_camera(world, points, heading, fov_deg, aspect, pitch_deg=pitch_deg, turn_deg=20.0,
                        min_distance=min_distance, focus=centres)


def poses(world: BulletWorld) -> dict[str, tuple[tuple[float, ...], tuple[float, ...]]]:
    """Every object's pose by name, to tell later what moved (`moved_since`)."""
    return {o.name: o.get_pose() for o in world.objects}


def moved_since(world: BulletWorld, before: dict[str, tuple[tuple[float, ...], tuple[float, ...]]],
                tolerance: float = 1e-3) -> list[Object]:
    """The movable objects whose position changed by more than `tolerance` m since `before` (see `poses`)."""
    moved = []
    for obj in movable_objects(world):
        old = before.get(obj.name)
        if old is None or max(abs(a - b) for a, b in zip(obj.get_position(), old[0])) > tolerance:
            moved.append(obj)
    return moved


def named_camera(world: BulletWorld, name: str, targets: Sequence[Object] | None = None,
                 aspect: float = 4 / 3) -> Camera:
    """One of VIEWS: `overview` (the whole scene), `robot` (the robot, over its shoulder) or `target`
    (`targets`, e.g. the objects a plan moved; default: every movable object)."""
    if name == "overview":
        return default_camera(world)
    if name == "robot":
        return robot_camera(world, aspect=aspect)
    if name == "target":
        return objects_camera(world, targets, aspect=aspect)
    raise BadValue(f"unknown view {name!r} (expected one of {', '.join(VIEWS)})")


def view_matrix(eye: Sequence[float], target: Sequence[float], up: Sequence[float]) -> tuple[float, ...]:
    """OpenGL view matrix (16 numbers, column-major) of a camera at `eye` looking at `target`."""
    return p.computeViewMatrix(list(eye), list(target), list(up))


def projection_matrix(left: float, right: float, bottom: float, top: float, near: float,
                      far: float) -> tuple[float, ...]:
    """OpenGL projection matrix (16 numbers) of a frustum, possibly off-centre; the window is on the near plane."""
    return p.computeProjectionMatrix(left, right, bottom, top, near, far)


def segmentation(client: int, width: int, height: int, view: Sequence[float],
                 projection: Sequence[float]) -> np.ndarray:
    """(height, width) body ids that a PyBullet client shows at each pixel (-1: nothing); TinyRenderer, no shadows."""
    _, _, _, _, seg = p.getCameraImage(width, height, view, projection, shadow=0, renderer=p.ER_TINY_RENDERER,
                                       physicsClientId=client)
    return np.asarray(seg, dtype=np.int64).reshape(height, width)


def up_for(camera: Camera) -> tuple[float, float, float]:
    """The camera's up direction, or +y when it looks along it (straight down or up: no image otherwise)."""
    direction = np.subtract(camera.target, camera.eye)
    length = float(np.linalg.norm(direction))
    up = np.asarray(camera.up, dtype=float)
    if length > 0 and float(np.linalg.norm(np.cross(direction / length, up / np.linalg.norm(up)))) < 1e-6:
        return (0.0, 1.0, 0.0) if abs(up[1]) < 0.9 else (1.0, 0.0, 0.0)
    return camera.up


def segmentation_and_depth(client: int, width: int, height: int, view: Sequence[float],
                           projection: Sequence[float]) -> tuple[np.ndarray, np.ndarray]:
    """`segmentation` and the depth buffer of the same picture ((height, width) each; depth in 0..1, growing
    with distance, 1 where nothing is drawn)."""
    _, _, _, depth, seg = p.getCameraImage(width, height, view, projection, shadow=0, renderer=p.ER_TINY_RENDERER,
                                           physicsClientId=client)
    return (np.asarray(seg, dtype=np.int64).reshape(height, width),
            np.asarray(depth, dtype=np.float64).reshape(height, width))


def render(world: BulletWorld, camera: Camera, width: int = 640, height: int = 480) -> np.ndarray:
    """RGB image (height, width, 3) of the world from `camera`."""
    cid = world.client_id
    view = p.computeViewMatrix(camera.eye, camera.target, up_for(camera), physicsClientId=cid)
    far = max(camera.far, 1.5 * math.dist(camera.eye, camera.target) + camera.far)  # a far eye still sees its target
    proj = p.computeProjectionMatrixFOV(camera.vertical_fov_deg, width / height, camera.near, far, physicsClientId=cid)
    if width * height > APART_PIXELS and world.mode != "gui" and hasattr(os, "fork"):
        rgba = _pixels_apart(cid, width, height, view, proj)
        if rgba is not None:
            return rgba[:, :, :3]
    return _pixels(cid, width, height, view, proj)[:, :, :3]


#: images with more pixels are rendered in a child process (about 0.6 s for 800 000 pixels on two cores)
APART_PIXELS = 800_000


def _pixels(cid: int, width: int, height: int, view: Sequence[float], proj: Sequence[float]) -> np.ndarray:
    """RGBA (height, width, 4) from TinyRenderer with shadows."""
    _, _, rgba, _, _ = p.getCameraImage(width, height, view, proj, renderer=p.ER_TINY_RENDERER, shadow=1,
                                        lightDirection=[-1.0, -0.6, 2.0], physicsClientId=cid)
    return np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)


def _pixels_apart(cid: int, width: int, height: int, view: Sequence[float], proj: Sequence[float]) -> np.ndarray | None:
    """`_pixels` computed in a forked child (a copy of this process, the world included), or None when no child
    can be made. TinyRenderer holds the interpreter for the whole image (27 s for 4096x4096) and no signal
    handler or thread runs meanwhile; waiting for a child does not, so Ctrl-C ends a large render at once
    (the child is killed). Same pixels as in-process."""
    size = width * height * 4
    shared = mmap.mmap(-1, size)  # anonymous and shared: the child's pixels are seen here
    try:
        with warnings.catch_warnings():  # the child only renders and leaves: no lock of another thread is needed
            warnings.simplefilter("ignore", DeprecationWarning)
            pid = os.fork()
    except OSError:
        shared.close()
        return None
    if pid == 0:  # the child
        code = 1
        try:
            for signum in (signal.SIGINT, signal.SIGTERM):
                signal.signal(signum, signal.SIG_DFL)
            shared[:] = _pixels(cid, width, height, view, proj).tobytes()
            code = 0
        finally:
            os._exit(code)
    try:
        _, status = os.waitpid(pid, 0)  # a signal's handler raises here (Interrupted): the child is killed below
        pid = 0
    finally:
        if pid:
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
    try:
        if os.waitstatus_to_exitcode(status) != 0:
            return None  # the child failed: render here instead
        return np.frombuffer(shared, dtype=np.uint8).reshape(height, width, 4).copy()
    finally:
        shared.close()


def image_format(suffix: str) -> str | None:
    """The image format a file extension stands for (`.jpg` -> JPEG), or None when it is not one of ours."""
    return IMAGE_FORMATS.get(suffix.lower())


def encode_image(rgb: np.ndarray, suffix: str = ".png") -> bytes:
    """An RGB image (height, width, 3) encoded in the format of the extension `suffix` (see IMAGE_FORMATS)."""
    kind = image_format(suffix)
    if kind is None:
        raise ValueError(f"unknown image type {suffix!r} (expected {', '.join(sorted(IMAGE_FORMATS))})")
    buffer = io.BytesIO()
    options = {"quality": 90} if kind in ("JPEG", "WEBP") else {}
    Image.fromarray(np.ascontiguousarray(rgb[:, :, :3], dtype=np.uint8), "RGB").save(buffer, kind, **options)
    return buffer.getvalue()


def write_png(path: Path | str, rgb: np.ndarray, key: str | None = None) -> None:
    """Write an RGB image as a PNG file, atomically (for pictures the program draws itself: sweep and location maps)."""
    write_atomic(path, encode_image(rgb, ".png"), key=key)
