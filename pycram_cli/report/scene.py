"""What the report's 3D view draws: the world's visual shapes once, and the links' poses at every step.

`scene(world)` lists every object's links with their visual shapes (boxes, spheres, cylinders,
capsules, and OBJ/STL meshes, each mesh file stored once however many links use it).
`frames(world, replay)` puts the world into the recorded state of every step (see
plan/replay.py: poses of bodies and joint values) and reads the links' poses, which the
page then only has to set: frame 0 has every link, later frames only the links that moved.
"""
from __future__ import annotations

import base64
from pathlib import Path
from typing import Any

import numpy as np

from ..plan.replay import focus_points
from ..world import BulletWorld, Object
from ..world.camera import movable_objects, robot_camera
from ..world.meshes import read_mesh

POSE_DIGITS = 4  # 0.1 mm and 1e-4 of a quaternion: plenty to look at
VIEW_FOV, VIEW_ASPECT = 50.0, 1.6  # the page's camera (vertical field of view) and a typical shape of its view
MESH_FILES = (".obj", ".stl")


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
                mesh = read_mesh(path)
            except (OSError, ValueError):
                return None
            if not len(mesh.triangles):
                return None
            vertices = mesh.vertices.astype("<f4")
            indices = mesh.triangles.astype("<u4" if len(vertices) > 65535 else "<u2")
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
            for slot, (index, (position, orientation)) in enumerate(sorted(obj.link_poses(indices).items())):
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
    return [round(v, 3) + 0.0 for v in (*camera.eye, *camera.target)]


def frames(scene: Scene, replay: dict[str, Any] | None, nodes: dict[str, dict[str, Any]]) -> list[dict[str, Any]]:
    """Frame 0 (the world before the first step) and one frame after every recorded step: the poses of
    the links that moved (frame 0: all) and a camera [eye, target] on the robot and what the step works on
    (a step that names nothing keeps the previous step's focus)."""
    world = scene.world
    for obj, _ in scene.links:  # recorded poses say where everything is: nothing may drag anything along
        for other in list(obj.attachments):
            if other in obj.attachments:
                obj.detach(other)
    if replay:
        scene.apply(replay.get("initial") or {})
    last = scene.poses()
    focus = [tuple((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(world)]
    result = [{"path": None, "status": None, "poses": _flat(last), "camera": _camera(world, focus)}]
    for step in (replay or {}).get("steps") or []:
        touched = scene.apply(step.get("changed") or {})
        now = scene.poses(touched) if touched else {}
        moved = {key: pose for key, pose in now.items() if last.get(key) != pose}
        last.update(moved)
        focus = focus_points(world, nodes.get(step.get("path") or "", {})) or focus
        result.append({"path": step.get("path"), "status": step.get("status"), "poses": _flat(moved),
                       "camera": _camera(world, focus)})
    return result
