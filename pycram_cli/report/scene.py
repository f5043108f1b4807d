"""What the report's 3D view draws: the world's visual shapes once, and the links' poses at every step.

`scene(world)` lists every object's links with their visual shapes (boxes, spheres, cylinders,
capsules, and OBJ/STL/COLLADA meshes, each mesh file stored once however many links use it, with at most
MAX_PAGE_TRIANGLES triangles: simplify.py).
`frames(world, replay)` puts the world into the recorded state of every step (see
plan/replay.py: poses of bodies and joint values) and reads the links' poses, which the
page then only has to set: frame 0 has every link, later frames only the links that moved.
"""
from __future__ import annotations

import base64
from pathlib import Path
from typing import Any

import numpy as np

from ..plan.replay import Point, apply_changes, focus_points
from ..robots.description import description_for
from ..world import BulletWorld, Object
from ..world.camera import movable_objects, objects_camera, robot_camera
from ..world.meshes import read_mesh
from ..world.pose import quat_to_matrix, vec3
from .collada import read_collada
from .failures import failed_leaves, focus, framing, named_values
from .simplify import simplify

POSE_DIGITS = 4  # 0.1 mm and 1e-4 of a quaternion: plenty to look at
VIEW_FOV, VIEW_ASPECT = 50.0, 1.6  # the page's camera (vertical field of view) and a typical shape of its view
MESH_FILES = (".obj", ".stl", ".dae")


def _b64(array: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(array).tobytes()).decode("ascii")


class Scene:
    """The drawable content of a world, and where each drawn link sits in the frames' pose lists."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self.meshes: list[dict[str, Any]] = []
        self._mesh_ids: dict[str, int] = {}
        self.bodies: list[dict[str, Any]] = []
        self.links: list[tuple[Object, list[int]]] = []  # per body: the object and its drawn link indices
        self.skipped: list[str] = []
        for obj in world.objects:
            shapes: dict[int, list[dict[str, Any]]] = {}
            for shape in obj.visual_shapes():
                drawn = self._shape(obj, shape)
                if drawn is not None:
                    shapes.setdefault(shape.link, []).append(drawn)
            indices = sorted(shapes)
            self.links.append((obj, indices))
            self.bodies.append({
                "name": obj.name, "type": obj.type,
                "links": [{"name": obj.get_link_name(i), "shapes": shapes[i]} for i in indices],
            })

    def _shape(self, obj: Object, shape: Any) -> dict[str, Any] | None:
        position, orientation = shape.origin
        data: dict[str, Any] = {"kind": shape.kind,
                                "origin": [round(v, 6) for v in (*position, *orientation)],
                                "color": [round(v, 3) for v in shape.rgba]}
        if shape.kind == "box":
            data["size"] = [round(v, 6) for v in shape.size]
        elif shape.kind == "sphere":
            data["radius"] = round(shape.radius, 6)
        elif shape.kind in ("cylinder", "capsule"):
            data["radius"], data["length"] = round(shape.radius, 6), round(shape.length, 6)
        elif shape.kind == "mesh":
            mesh = self._mesh(shape.mesh_file)
            if mesh is None:
                self.skipped.append(f"{obj.name}/{obj.get_link_name(shape.link)}: mesh {shape.mesh_file}")
                return None
            data["mesh"], data["scale"] = mesh, [round(v, 6) for v in shape.scale]
        else:
            self.skipped.append(f"{obj.name}/{obj.get_link_name(shape.link)}: {shape.kind}")
            return None
        return data

    def _mesh(self, path: Path | None) -> int | None:
        """The index of a mesh file's geometry in `meshes` (read once); None when it cannot be drawn."""
        if path is None or path.suffix.lower() not in MESH_FILES or not path.is_file():
            return None
        key = str(path.resolve())
        if key not in self._mesh_ids:
            try:
                if path.suffix.lower() == ".dae":
                    points, triangles = read_collada(path)
                else:
                    mesh = read_mesh(path)
                    points, triangles = mesh.vertices, mesh.triangles
            except (OSError, ValueError, IndexError):  # unreadable: listed as not drawn
                return None
            if not len(triangles):
                return None
            points, triangles = simplify(np.asarray(points, dtype=float), np.asarray(triangles))
            vertices = points.astype("<f4")
            indices = triangles.astype("<u4" if len(vertices) > 65535 else "<u2")
            self._mesh_ids[key] = len(self.meshes)
            self.meshes.append({"name": path.name, "positions": _b64(vertices), "indices": _b64(indices),
                                "index_bytes": indices.dtype.itemsize})
        return self._mesh_ids[key]

    def to_dict(self) -> dict[str, Any]:
        return {"bodies": self.bodies, "meshes": self.meshes, "skipped": self.skipped}

    # -- poses ----------------------------------------------------------------------------------------
    def poses(self, bodies: set[int] | None = None) -> dict[tuple[int, int], list[float]]:
        """(body, link slot) -> [x, y, z, qx, qy, qz, qw] of the drawn links (of `bodies`, default all)."""
        found: dict[tuple[int, int], list[float]] = {}
        for b, (obj, indices) in enumerate(self.links):
            if not indices or (bodies is not None and b not in bodies):
                continue
            for slot, (_index, (position, orientation)) in enumerate(sorted(obj.link_poses(indices).items())):
                found[(b, slot)] = [round(float(v), POSE_DIGITS) + 0.0 for v in (*position, *orientation)]
        return found

    def apply(self, state: dict[str, dict[str, Any]]) -> set[int]:
        """Put the objects named in `state` (a replay record's initial state or a step's changes) where it
        says; the indices of the bodies that changed."""
        touched = set()
        by_name = {obj.name: b for b, (obj, _) in enumerate(self.links)}
        for name, entry in state.items():
            b = by_name.get(name)
            if b is None:
                continue
            obj = self.links[b][0]
            if "position" in entry and "orientation" in entry:
                obj.set_position_and_orientation(entry["position"], entry["orientation"])
            joints = {k: v for k, v in (entry.get("joints") or {}).items() if k in obj.joint_names}
            if joints:
                obj.reset_joints(joints)
            touched.add(b)
        return touched


def _flat(poses: dict[tuple[int, int], list[float]]) -> list[float]:
    """[body, slot, x, y, z, qx, qy, qz, qw, body, slot, ...]: compact in JSON."""
    return [value for (b, slot), pose in sorted(poses.items()) for value in (b, slot, *pose)]


def _camera(world: BulletWorld, focus: list[Any]) -> list[float]:
    camera = robot_camera(world, focus, VIEW_FOV, VIEW_ASPECT)
    return _eye_target(camera)


def _eye_target(camera: Any) -> list[float]:
    return [round(v, 3) + 0.0 for v in (*camera.eye, *camera.target)]


def _detach_all(scene: Scene) -> None:
    for obj, _ in scene.links:  # recorded poses say where everything is: nothing may drag anything along
        for other in list(obj.attachments):
            if other in obj.attachments:
                obj.detach(other)


def _candidates(data: dict[str, Any]) -> dict[str, Any]:
    """A locate step's candidate map for the page: positions as little-endian int16 mm pairs and outcomes as
    bytes (base64), the rest as recorded."""
    xy = np.asarray(data.get("xy") or [], dtype=np.int64)
    outcome = np.asarray(data.get("outcome") or [], dtype=np.int64)
    if len(xy) != 2 * len(outcome) or (len(xy) and np.abs(xy).max() > 32767):
        return {}
    return {**{k: v for k, v in data.items() if k not in ("xy", "outcome")},
            "xy": _b64(xy.astype("<i2")), "outcome": _b64(outcome.astype("u1")), "count": len(outcome)}


def frames(scene: Scene, replay: dict[str, Any] | None, nodes: dict[str, dict[str, Any]]) -> list[dict[str, Any]]:
    """The frames of `replay` (see `Replayer.frames`)."""
    return Replayer(scene, replay, nodes).frames()


class Replayer:
    """Puts the world into every recorded state of a run and reads what the page draws.

    `frames()`: frame 0 (the world before the first step) and one frame after every recorded step: the poses of
    the links that moved (frame 0: all), the step's physics frames (`physics`: the simulated time `t` and the
    links moved since the frame before) and a camera [eye, target] on the robot and what the step works on (a
    step that names nothing keeps the previous step's focus; a failed step frames its object and its target;
    the last frame frames what the run moved). `failures`: every failed step, then filled in (see `failure`).
    """

    def __init__(self, scene: Scene, replay: dict[str, Any] | None, nodes: dict[str, dict[str, Any]],
                 root: dict[str, Any] | None = None) -> None:
        self.scene, self.replay, self.nodes, self.root = scene, replay or {}, nodes, root or {}
        self.failures: list[dict[str, Any]] = []
        self._placed: dict[str, dict[int, list[float]]] = {}  # step path -> body -> its poses as physics began

    # long: one walk over the replay's steps, the scene's state carried from step to step
    def frames(self) -> list[dict[str, Any]]:
        scene, world = self.scene, self.scene.world
        _detach_all(scene)
        scene.apply(self.replay.get("initial") or {})
        state = {name: dict(entry) for name, entry in (self.replay.get("initial") or {}).items()}
        start = {o.name: o.get_position() for o in movable_objects(world)}
        last = scene.poses()
        focus: list[Point] = [vec3((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(world)]
        result = [{"path": None, "status": None, "poses": _flat(last), "camera": _camera(world, focus)}]
        steps = self.replay.get("steps") or []
        by_name = {obj.name: b for b, (obj, _) in enumerate(scene.links)}
        failed = {node.get("path") for node in failed_leaves(self.root)}
        order = [step.get("path") for step in steps]
        for k, step in enumerate(steps, start=1):
            frame: dict[str, Any] = {"path": step.get("path"), "status": step.get("status")}
            physics: list[dict[str, Any]] = []
            touched: set[int] = set()
            for sub in step.get("physics") or []:
                moved_bodies = scene.apply(sub.get("changed") or {})
                touched |= moved_bodies
                now = scene.poses(moved_bodies) if moved_bodies else {}
                moved = {key: pose for key, pose in now.items() if last.get(key) != pose}
                last.update(moved)
                if not physics:  # where each body was as physics began: the pose it was put in
                    self._placed[step.get("path")] = {b: _flat({key: pose for key, pose in now.items() if key[0] == b})
                                                      for b in moved_bodies}
                physics.append({"t": sub.get("t"), "poses": _flat(moved)})
            changed = step.get("changed") or {}
            apply_changes(state, changed)
            # what physics moved and the step's end does not name is back where the step's end has it
            back = {self.scene.links[b][0].name for b in touched} - set(changed)
            touched = scene.apply(changed) | scene.apply({name: state[name] for name in back if name in state})
            now = scene.poses(touched) if touched else {}
            moved = {key: pose for key, pose in now.items() if last.get(key) != pose}
            last.update(moved)
            frame["poses"] = _flat(moved)
            if physics:
                frame["physics"] = physics
            whatif = self.whatif(step.get("prospection") or [], by_name)
            if whatif:
                frame["whatif"] = whatif
            if isinstance(step.get("candidates"), dict):
                frame["candidates"] = _candidates(step["candidates"])
            node = self.nodes.get(step.get("path") or "", {})
            reasoning = reasoning_of(world, node, by_name)
            if reasoning:
                frame["reasoning"] = reasoning
            focus = focus_points(world, node) or focus
            frame["camera"] = _camera(world, focus)
            if step.get("path") in failed and not step.get("folded"):
                failure = self.failure(k, node, order)
                self.failures.append(failure)
                frame["camera"] = failure["camera"]
            result.append(frame)
        moved_objects = [o for o in movable_objects(world)
                         if max(abs(a - b) for a, b in zip(o.get_position(), start.get(o.name, (0, 0, 0)))) > 0.01]
        if len(result) > 1 and moved_objects and not (self.failures and self.failures[-1]["step"] == len(result) - 1):
            result[-1]["camera"] = _eye_target(objects_camera(world, moved_objects, VIEW_FOV, VIEW_ASPECT))
        return result

    def whatif(self, frames: list[dict[str, Any]], by_name: dict[str, int]) -> dict[str, Any] | None:
        """What a query simulated on the prospection copy (a replay step's `prospection`), for the first object it
        moved: its links' poses at each frame (the world itself stays as it is)."""
        names = [name for frame in frames for name in frame.get("changed") or {} if name in by_name]
        if not names:
            return None
        b = by_name[names[0]]
        obj = self.scene.links[b][0]
        pose = obj.get_pose()
        drawn = []
        try:
            for frame in frames:
                entry = (frame.get("changed") or {}).get(names[0])
                if entry and "position" in entry and "orientation" in entry:
                    obj.set_position_and_orientation(entry["position"], entry["orientation"])
                    drawn.append({"t": frame.get("t"), "poses": _flat(self.scene.poses({b}))})
        finally:
            obj.set_position_and_orientation(*pose)
        return {"body": b, "frames": drawn} if drawn else None

    def failure(self, k: int, node: dict[str, Any], order: list[str]) -> dict[str, Any]:
        """A failed step k (the world in its state after it): its failure, the bodies it names, the target meant
        for them and a ghost of the first of them there (its links' poses: as physics began in the step that
        named the target, else moved so that its bottom's centre is at the target), and a camera on all that."""
        world, scene = self.scene.world, self.scene
        by_name = {obj.name: b for b, (obj, _) in enumerate(scene.links)}
        names = {o.name for o in movable_objects(world)}
        found = focus(self.root, node, names, order)
        info = node.get("failure") or {}
        entry: dict[str, Any] = {"step": k, "path": node.get("path"), "type": info.get("type"),
                                 "message": info.get("message"),
                                 "objects": [by_name[name] for name in found.objects if name in by_name],
                                 "target": [round(v, 4) + 0.0 for v in found.target] if found.target else None,
                                 "ghost": None}
        boxes = [scene.links[by_name[name]][0].get_aabb() for name in found.objects if name in by_name]
        if found.objects and found.target is not None and found.objects[0] in by_name:
            b = by_name[found.objects[0]]
            obj = scene.links[b][0]
            placed = self._placed.get(found.target_step or "", {}).get(b)
            pose = obj.get_pose()
            try:
                if placed:
                    obj.set_position_and_orientation(placed[2:5], placed[5:9])
                else:
                    lo, hi = obj.get_aabb()
                    bottom = ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2])
                    obj.set_position_and_orientation([p + t - q for p, t, q in zip(pose[0], found.target, bottom)],
                                                     pose[1])
                entry["ghost"] = {"body": b, "poses": _flat(scene.poses({b}))}
                boxes.append(obj.get_aabb())
            finally:
                obj.set_position_and_orientation(*pose)
        elif found.target is not None:
            boxes.append((vec3(v - 0.05 for v in found.target), vec3(v + 0.05 for v in found.target)))
        if boxes:
            entry["camera"] = _eye_target(framing(world, boxes, VIEW_ASPECT, VIEW_FOV))
        else:
            entry["camera"] = _camera(world, focus_points(world, node))
        return entry


#: step types whose reasoning is what the robot's camera sees: drawn as its view cone
SEEING = ("looking", "detecting", "visible", "occluding")
#: step types whose reasoning is what an arm reaches: drawn as the target and what blocks it
REACHING = ("reachable", "blocking")
CONE_LENGTH = 1.5  # m: a view cone without a target this long


def reasoning_of(world: BulletWorld, node: dict[str, Any], by_name: dict[str, int]) -> dict[str, Any] | None:
    """What a step's reasoning looks like in 3D, read from its record in the trace and the world as the step left
    it: a view cone (the robot's camera: its pose, fields of view and how far it looks), with the visible
    fraction and the occluders (body indices) where the step says them; or a reach target and its blockers."""
    kind = node.get("type")
    values = named_values(node)
    query = _mapping(node.get("query"))
    details = _mapping(query.get("details"))
    result = query.get("result")
    bound = [v for v in (node.get("bound") or {}).values() if isinstance(v, str) and v in by_name]
    target = _point(world, values.get("object") or values.get("target") or (bound[0] if bound else None))
    if kind == "locate":
        return _planned_view(world, node)
    if kind in SEEING:
        robot = world.robot
        desc = description_for(robot) if robot is not None else None
        if robot is None or desc is None or desc.camera is None or values.get("from") not in (None, desc.camera.frame):
            return None
        position, orientation = robot.get_link_position_and_orientation(desc.camera.frame)
        rotation = quat_to_matrix(orientation)
        length = CONE_LENGTH
        if target is not None:
            length = max(0.3, float(np.dot(np.asarray(target) - np.asarray(position), rotation[:, 2])))
        view: dict[str, Any] = {
            "kind": "view", "eye": [round(float(v), 4) for v in position],
            "axes": [round(float(v), 4) for v in rotation.T.reshape(-1)],  # right, down, forward
            "fov": [round(desc.camera.horizontal_fov, 4), round(desc.camera.vertical_fov, 4)],
            "length": round(length, 3), "target": _rounded(target)}
        if isinstance(details.get("fraction"), (int, float)):
            view["fraction"] = round(float(details["fraction"]), 4)
        blockers = result if kind == "occluding" and isinstance(result, list) else []
        view["occluders"] = [by_name[name] for name in blockers if isinstance(name, str) and name in by_name]
        view["seen"] = [by_name[name] for name in _names(values.get("object"), by_name) + bound]
        return view
    if kind in REACHING:
        blockers = result if kind == "blocking" and isinstance(result, list) else []
        return {"kind": "reach", "target": _rounded(target), "reachable": result if kind == "reachable" else None,
                "blockers": [by_name[name] for name in blockers if isinstance(name, str) and name in by_name],
                "objects": [by_name[name] for name in _names(values.get("target"), by_name)]}
    return None


def _mapping(value: Any) -> dict[str, Any]:
    """A trace record's entry when it is a mapping, else an empty one (a step that recorded none)."""
    return value if isinstance(value, dict) else {}


def _planned_view(world: BulletWorld, node: dict[str, Any]) -> dict[str, Any] | None:
    """A locate step that chose where to stand to see something (`found` has a `look-at`): the view cone the
    robot's camera will have from there — its camera where it sits on the robot now, carried to the pose found,
    turned to the point to look at."""
    location = _mapping(node.get("location"))
    found = _mapping(location.get("found"))
    look = _point(world, found.get("look-at"))
    position, orientation = found.get("position"), found.get("orientation")
    robot = world.robot
    desc = description_for(robot) if robot is not None else None
    if look is None or robot is None or desc is None or desc.camera is None or _point(world, position) is None or not (
            isinstance(orientation, list) and len(orientation) == 4 and all(isinstance(v, (int, float)) for v in orientation)):
        return None
    base_position, base_orientation = robot.get_pose()
    camera_position, _ = robot.get_link_position_and_orientation(desc.camera.frame)
    offset = quat_to_matrix(base_orientation).T @ (np.asarray(camera_position) - np.asarray(base_position))
    eye = quat_to_matrix([float(v) for v in orientation]) @ offset + np.asarray(position, dtype=float)
    forward = np.asarray(look) - eye
    length = float(np.linalg.norm(forward))
    if length < 1e-6:
        return None
    forward /= length
    up = np.array([0.0, 0.0, 1.0]) if abs(forward[2]) < 0.999 else np.array([1.0, 0.0, 0.0])
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    return {"kind": "view", "planned": True, "eye": [round(float(v), 4) for v in eye],
            "axes": [round(float(v), 4) for v in (*right, *down, *forward)],
            "fov": [round(desc.camera.horizontal_fov, 4), round(desc.camera.vertical_fov, 4)],
            "length": round(max(0.3, length), 3), "target": _rounded(look), "occluders": [], "seen": []}


def _names(value: Any, by_name: dict[str, int]) -> list[str]:
    return [value] if isinstance(value, str) and value in by_name else []


def _rounded(point: Any) -> list[float] | None:
    return [round(float(v), 4) for v in point] if point is not None else None


def _point(world: BulletWorld, value: Any) -> tuple[float, float, float] | None:
    """An object's bounding box centre (by name) or a position [x, y, z]."""
    if isinstance(value, str):
        obj = world.get_object_by_name(value)
        if obj is None:
            return None
        lo, hi = obj.get_aabb()
        return ((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2)
    if (isinstance(value, (list, tuple)) and len(value) == 3
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        return (float(value[0]), float(value[1]), float(value[2]))
    return None
