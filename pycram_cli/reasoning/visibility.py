"""visible(obj, camera) and occluding(obj, camera): what a camera sees of an object.

As in the design, the object's pixels are counted twice: once with the whole scene (the
pixels where it is in front) and once alone (all the pixels it covers). Two things make it
fast and exact:

* Only a small window is rendered: an off-centre perspective projection whose frustum is
  cropped to the object's bounding box as seen from the camera, about 32×32 pixels, with
  the far plane just behind the object. TinyRenderer's cost is mostly per pixel.
* Only what can be seen is drawn. TinyRenderer touches every triangle of every body it holds,
  wherever it is (15 ms for the real PR2 in the real kitchen, whatever the window), so both
  pictures come from the world's private client (`world/view.py`: the prospection copy, the
  world itself never touched: no colours to hide and restore, no bodies to move) with only the
  links whose boxes meet the window's frustum — between the near plane and the far plane just
  behind the object — drawn: the object alone, then the rest without it in the part of the window
  the object covers, the object showing where it is nearer than the rest (depth buffers), so that
  it is drawn once. A link's collision box grown by `MARGIN` bounds what is drawn of it; links
  without collision shapes are always drawn.

Camera: None (the robot's camera frame from its description, with its field of view), a
link name of the robot (its camera frame: as None; any other link: a position at that link's
origin), a `(position, orientation)` pose whose orientation is an optical frame (+z forward,
+x right, +y down; the robot camera's field of view), or a bare position (looking straight
at the object, no field-of-view limit). With a field of view, pixels outside it are not
seen: an object outside the view is 0 % visible.
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import BadValue
from ..robots import description_for
from ..signature import Param
from ..world.camera import projection_matrix, view_matrix
from ..world.pose import check_position, check_quaternion, quat_to_matrix
from ._common import world_of
from .query import AN_OBJECT, Call, QueryAnswer, QuerySpec, declare_query, parameters, place

if TYPE_CHECKING:
    from ..world import BulletWorld, Object

#: pixels of the rendered window (about 32 x 32, shaped like the object's image)
PIXEL_BUDGET = 1024
MAX_SIDE = 128
MIN_SIDE = 4
#: default field of view (rad) for a pose camera when the robot has no description
DEFAULT_FOV = (0.995, 0.75)
DEFAULT_NEAR = 0.05
POSITION_NEAR = 0.01
#: half-angle limit of a window when the object reaches behind the camera
WIDE = math.tan(math.radians(80.0))
#: a link's collision box grown by this much (m) holds what is drawn of it (checked against full renders of the
#: real PR2 and kitchen: their visual meshes lie within their collision boxes give or take a few millimetres)
MARGIN = 0.02
#: the fraction of an object's pixels that must be seen: the function's default and the query's declared one
SEEN = 0.8


@dataclass(frozen=True)
class VisibleAnswer:
    """Truthy when at least `threshold` of the object's pixels are seen. `fraction`: seen / all;
    `pixels`: the seen pixels (in the rendered window); `total`: the object's pixels alone."""

    visible: bool
    fraction: float
    pixels: int
    total: int = 0

    def __bool__(self) -> bool:
        return self.visible


@dataclass(frozen=True)
class CameraPose:
    """An optical frame in the world: `rotation` columns are the camera's x (right), y (down), z (forward)."""

    position: np.ndarray
    rotation: np.ndarray
    fov: tuple[float, float] | None  # horizontal, vertical (rad); None: unlimited
    near: float
    label: str


# -- cameras ---------------------------------------------------------------------------


def look_at(eye: Sequence[float] | np.ndarray, target: Sequence[float] | np.ndarray) -> np.ndarray:
    """Optical-frame rotation (x right, y down, z forward) looking from `eye` at `target`, upright."""
    z = np.asarray(target, dtype=float) - np.asarray(eye, dtype=float)
    norm = float(np.linalg.norm(z))
    z = z / norm if norm > 1e-12 else np.array([1.0, 0.0, 0.0])
    up = np.array([0.0, 0.0, 1.0]) if abs(z[2]) < 0.999 else np.array([1.0, 0.0, 0.0])
    x = np.cross(z, up)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return np.column_stack([x, y, z])


def _robot_camera(world: BulletWorld) -> tuple[Object, Any]:
    robot = world.robot
    if robot is None:
        raise BadValue("no camera given and the world has no robot to take it from")
    desc = description_for(robot)
    if desc is None or desc.camera is None:
        why = "has no description naming its camera" if desc is None else "has no camera in its description"
        raise BadValue(f"no camera given and robot '{robot.name}' {why}")
    return robot, desc.camera


def _frame_camera(robot: Object, cam: Any) -> CameraPose:
    pos, orn = robot.get_link_position_and_orientation(cam.frame)
    return CameraPose(np.asarray(pos, dtype=float), quat_to_matrix(orn), (cam.horizontal_fov, cam.vertical_fov),
                      cam.near, cam.frame)


def resolve_camera(obj: Object, camera: Any = None) -> CameraPose:
    """Turn any accepted camera argument into an optical frame pose."""
    world = obj.world
    centre = _aabb_centre(obj)
    if camera is None:
        robot, cam = _robot_camera(world)
        return _frame_camera(robot, cam)
    if isinstance(camera, str):
        body = world.robot
        if body is None:
            raise BadValue(f"camera link '{camera}': the world has no robot")
        desc = description_for(body)
        if desc is not None and desc.camera is not None and camera == desc.camera.frame:
            return _frame_camera(body, desc.camera)
        pos = body.get_link_position(camera)  # KeyError with a suggestion for unknown links
        return CameraPose(np.asarray(pos, dtype=float), look_at(pos, centre), None, POSITION_NEAR, camera)
    if isinstance(camera, CameraPose):
        return camera
    items = list(camera)
    if len(items) == 2 and all(hasattr(v, "__len__") for v in items):
        position = check_position(items[0], "camera position")
        orientation = check_quaternion(items[1], "camera orientation")
        fov, near = DEFAULT_FOV, DEFAULT_NEAR
        desc = description_for(world.robot) if world.robot is not None else None
        if desc is not None and desc.camera is not None:
            fov, near = (desc.camera.horizontal_fov, desc.camera.vertical_fov), desc.camera.near
        return CameraPose(np.asarray(position), quat_to_matrix(orientation), fov, near, "pose")
    position = check_position(items, "camera position")
    return CameraPose(np.asarray(position), look_at(position, centre), None, POSITION_NEAR,
                      ",".join(f"{v:g}" for v in position))


def _aabb(obj: Object) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = obj.get_aabb(-1) if not obj.joints else obj.get_aabb()
    return np.asarray(lo), np.asarray(hi)


def _aabb_centre(obj: Object) -> np.ndarray:
    lo, hi = _aabb(obj)
    return (lo + hi) / 2.0


# -- rendering --------------------------------------------------------------------------


@dataclass
class _Views:
    scene: np.ndarray  # segmentation of the whole scene (body ids, -1 background)
    alone: np.ndarray  # True where the object covers the pixel when rendered alone
    in_view: np.ndarray  # True for pixels inside the camera's field of view


def _window(obj: Object, cam: CameraPose) -> tuple[float, float, float, float, float, float] | None:
    """(umin, umax, vmin, vmax, near, far) of the object's box on the image plane, or None if behind."""
    lo, hi = _aabb(obj)
    corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    local = (corners - cam.position) @ cam.rotation  # camera coordinates
    depth = local[:, 2]
    far = float(depth.max()) * 1.02 + 0.01
    if far <= cam.near:
        return None
    front = depth > cam.near
    u = local[front, 0] / depth[front]
    v = local[front, 1] / depth[front]
    if front.all():
        umin, umax, vmin, vmax = float(u.min()), float(u.max()), float(v.min()), float(v.max())
    else:  # the box reaches behind the camera: its image is unbounded
        umin, umax, vmin, vmax = -WIDE, WIDE, -WIDE, WIDE
    umin, umax = max(umin, -WIDE), min(umax, WIDE)
    vmin, vmax = max(vmin, -WIDE), min(vmax, WIDE)
    if umax - umin < 1e-9 or vmax - vmin < 1e-9:
        return None
    return umin, umax, vmin, vmax, cam.near, far


def _render(world: BulletWorld, obj: Object, cam: CameraPose) -> _Views | None:
    window = _window(obj, cam)
    if window is None:
        return None
    umin, umax, vmin, vmax, near, far = window
    if cam.fov is not None:
        tu, tv = math.tan(cam.fov[0] / 2.0), math.tan(cam.fov[1] / 2.0)
        if umax < -tu or umin > tu or vmax < -tv or vmin > tv:
            return None  # entirely outside the field of view
    ratio = (umax - umin) / (vmax - vmin)
    width = int(min(MAX_SIDE, max(MIN_SIDE, round(math.sqrt(PIXEL_BUDGET * ratio)))))
    height = int(min(MAX_SIDE, max(MIN_SIDE, round(math.sqrt(PIXEL_BUDGET / ratio)))))
    eye = cam.position
    forward, down = cam.rotation[:, 2], cam.rotation[:, 1]
    view = view_matrix(eye.tolist(), (eye + forward).tolist(), (-down).tolist())
    proj = projection_matrix(near * umin, near * umax, -near * vmax, -near * vmin, near, far)
    if cam.fov is not None:
        us = umin + (np.arange(width) + 0.5) / width * (umax - umin)
        vs = vmin + (np.arange(height) + 0.5) / height * (vmax - vmin)
        in_view = (np.abs(vs)[:, None] <= tv) & (np.abs(us)[None, :] <= tu)
    else:
        in_view = np.ones((height, width), dtype=bool)
    # the object is drawn once: alone (where it covers the window, and how far), then everything else that
    # may show in front of those pixels, in the smallest part of the window that holds them (same pixel grid);
    # the scene is the nearer of the two at each pixel
    ids, depth = world.picture_of({obj: None}, width, height, view, proj)
    alone = ids == obj.id
    scene = np.full((height, width), -1, dtype=np.int64)
    rows, cols = np.nonzero(alone & in_view)
    if len(rows):
        r0, r1, c0, c1 = int(rows.min()), int(rows.max()) + 1, int(cols.min()), int(cols.max()) + 1
        du, dv = (umax - umin) / width, (vmax - vmin) / height
        crop = (umin + c0 * du, umin + c1 * du, vmin + r0 * dv, vmin + r1 * dv, near, far)
        cropped = projection_matrix(near * crop[0], near * crop[1], -near * crop[3], -near * crop[2], near, far)
        others = {o: links for o, links in _seen_parts(world, obj, cam, crop).items() if o is not obj}
        behind = np.full((height, width), -1, dtype=np.int64)
        behind_depth = np.ones((height, width))
        behind[r0:r1, c0:c1], behind_depth[r0:r1, c0:c1] = world.picture_of(others, c1 - c0, r1 - r0, view, cropped)
        scene = np.where(alone & (depth < behind_depth), obj.id, behind)
    return _Views(scene, alone, in_view)


def _seen_parts(world: BulletWorld, obj: Object, cam: CameraPose,
                window: tuple[float, float, float, float, float, float]) -> dict[Object, list[int] | None]:
    """What may show in the window: for each object the links whose boxes meet the frustum (None: all)."""
    objects, owners, links, boxes, unbounded, counts = _scene_boxes(world)
    inside = _in_frustum(boxes, cam, window) | unbounded
    parts: dict[Object, list[int] | None] = {obj: None}
    for index in sorted(set(owners[inside].tolist())):
        other = objects[index]
        if other is obj:
            continue
        chosen = inside & (owners == index)
        hits = int(chosen.sum())
        parts[other] = None if hits == counts[index] else [links[i] for i in np.flatnonzero(chosen)]
    return parts


def _scene_boxes(world: BulletWorld) -> tuple[list[Object], np.ndarray, list[int], np.ndarray, np.ndarray,
                                                np.ndarray]:
    """Every drawn link of the world at once: the objects, each link's owner (index into them), link, box and
    whether it has none; and how many links each object draws. Kept (in the world's cache) while the world's version
    and its objects (the very same, compared by identity) stay."""
    return world.cache.kept("scene boxes", world, (world.version, tuple(world.objects)), lambda: _build_scene(world))


def _build_scene(world: BulletWorld) -> tuple[list[Object], np.ndarray, list[int], np.ndarray, np.ndarray,
                                              np.ndarray]:
    objects = list(world.objects)
    drawn = [_drawn_boxes(o) for o in objects]
    owners = np.concatenate([np.full(len(d[0]), i) for i, d in enumerate(drawn)] or [np.zeros(0)]).astype(int)
    links = [link for d in drawn for link in d[0]]
    boxes = np.concatenate([d[1] for d in drawn] or [np.zeros((0, 2, 3))])
    unbounded = np.concatenate([d[2] for d in drawn] or [np.zeros(0, dtype=bool)])
    counts = np.array([len(d[0]) for d in drawn])
    return objects, owners, links, boxes, unbounded, counts


def _drawn_boxes(obj: Object) -> tuple[list[int], np.ndarray, np.ndarray]:
    """The links `obj` draws, their boxes (n, 2, 3) grown by MARGIN, and which have no box (no collision shape);
    kept (in the world's cache) while the object's version stays."""
    return obj.world.cache.kept("drawn boxes", obj, obj.version, lambda: _build_drawn_boxes(obj))


def _build_drawn_boxes(obj: Object) -> tuple[list[int], np.ndarray, np.ndarray]:
    drawn = obj.drawn_links()
    links = [link for link, _ in drawn]
    boxes = np.array([obj.get_aabb(link) for link in links], dtype=float).reshape(-1, 2, 3)
    boxes[:, 0] -= MARGIN
    boxes[:, 1] += MARGIN
    unbounded = np.array([not has_collision for _, has_collision in drawn], dtype=bool)
    return links, boxes, unbounded


def _in_frustum(boxes: np.ndarray, cam: CameraPose, window: tuple[float, float, float, float, float, float]) -> np.ndarray:
    """Which boxes (n, 2, 3) may meet the window's frustum: those not wholly beyond one of its six planes."""
    umin, umax, vmin, vmax, near, far = window
    if not len(boxes):
        return np.zeros(0, dtype=bool)
    pick = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    corners = boxes[:, pick, [0, 1, 2]]  # (n, 8, 3)
    local = (corners - cam.position) @ cam.rotation  # optical frame: x right, y down, z forward
    x, y, z = local[..., 0], local[..., 1], local[..., 2]
    outside = ((z < near).all(axis=1) | (z > far).all(axis=1)
               | (x < umin * z).all(axis=1) | (x > umax * z).all(axis=1)
               | (y < vmin * z).all(axis=1) | (y > vmax * z).all(axis=1))
    return ~outside


# -- the queries --------------------------------------------------------------------------


def visible(obj: Object, camera: Any = None, world: BulletWorld | None = None,
            threshold: float = SEEN) -> VisibleAnswer:
    """Whether at least `threshold` (default 80 %) of `obj`'s pixels are seen from `camera`."""
    world = world_of(obj, world)
    if not 0.0 <= threshold <= 1.0:
        raise BadValue(f"threshold must be a fraction between 0 and 1, got {threshold!r}")
    with world.lock:
        cam = resolve_camera(obj, camera)
        views = _render(world, obj, cam)
    if views is None:
        return VisibleAnswer(False, 0.0, 0, 0)
    total = int(views.alone.sum())
    seen = int((views.alone & views.in_view & (views.scene == obj.id)).sum())
    fraction = seen / total if total else 0.0
    return VisibleAnswer(total > 0 and fraction >= threshold, fraction, seen, total)


def occluding(obj: Object, camera: Any = None, world: BulletWorld | None = None) -> list[Object]:
    """The objects in front of `obj`'s pixels as seen from `camera` (sorted by name; never obj itself)."""
    world = world_of(obj, world)
    with world.lock:
        cam = resolve_camera(obj, camera)
        views = _render(world, obj, cam)
    if views is None:
        return []
    covered = views.scene[views.alone & views.in_view]
    ids = {int(i) for i in np.unique(covered)} - {obj.id, -1}
    found = [o for o in (world.get_object_by_id(i) for i in ids) if o is not None]
    return sorted(found, key=lambda o: (o.name, o.id))


# -- the query, by name (plans, `pycram query`, docs) --------------------------------------------------


_FROM = Param("from", "camera", doc="camera: a link of the robot or a position [x, y, z] looking at the object",
             default_doc="the robot's camera frame")


def _visible(call: Call) -> QueryAnswer:
    obj = call.object("object")
    camera = call.camera()
    threshold = call.number("threshold")
    answer = visible(obj, camera, threshold=threshold)
    return QueryAnswer("visible", call.resolved, answer.visible,
                       {"fraction": answer.fraction, "pixels": answer.pixels, "total": answer.total,
                        "camera": call.resolved["from"]}, answer.visible)


def _say_visible(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    seen = f"{d['fraction']:.0%} of its pixels seen from {place(d['camera'])} (threshold {a['threshold']:.0%})"
    return f"{a['object']} is visible: {seen}" if answer.result else f"{a['object']} is NOT visible: {seen}"


declare_query(QuerySpec(
    "visible", "Are at least 80 % of the object's pixels seen from the camera?",
    parameters(Param("object", "object", True, AN_OBJECT, positional=True), _FROM,
               Param("threshold", "fraction", doc="the fraction of pixels that must be seen", default=SEEN)),
    _visible, _say_visible))


def _occluding(call: Call) -> QueryAnswer:
    obj = call.object("object")
    camera = call.camera()
    found = occluding(obj, camera)
    return QueryAnswer("occluding", call.resolved, [o.name for o in found],
                       {"count": len(found), "camera": call.resolved["from"]}, found)


def _say_occluding(answer: QueryAnswer) -> str:
    a, d = answer.args, answer.details
    if answer.result:
        return f"{a['object']} is occluded by: {', '.join(answer.result)} (seen from {place(d['camera'])})"
    return f"nothing occludes {a['object']} (seen from {place(d['camera'])})"


declare_query(QuerySpec(
    "occluding", "Which objects cover the object's pixels, seen from the camera?",
    parameters(Param("object", "object", True, AN_OBJECT, positional=True), _FROM), _occluding, _say_occluding))
