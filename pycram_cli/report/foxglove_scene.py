"""The bodies of a world as Foxglove scene entities, and their links' frames: what an MCAP replay draws (foxglove.py).

Every drawn link is one entity (`BODY/LINK`), locked to the link's frame, holding the link's visual shapes
as primitives in that frame: boxes as cubes, spheres, cylinders, capsules as a cylinder and two spheres,
meshes embedded in the file — OBJ and STL read and written as binary STL (no axis conventions to get
wrong), COLLADA and binary glTF as they are, drawn with their own materials. Every body that is not
scenery also gets a label, its name above it.
"""
from __future__ import annotations

import base64
from pathlib import Path
from typing import Any

import numpy as np

from ..world import BulletWorld, Object, VisualShape
from ..world.meshes import read_mesh

DIGITS = 6  # rounding of poses: the same trace gives the same bytes
SCENERY = ("environment",)  # bodies without a label (the robot gets one: it is what the run is about)
WORLD_FRAME = "world"
#: mesh formats embedded as they are (Foxglove reads them), by extension; OBJ and STL are read and written as STL
AS_IS = {".dae": "model/vnd.collada+xml", ".glb": "model/gltf-binary"}
#: formats that carry their own materials: drawn with them, not in the colour PyBullet reports
OWN_LOOK = ("model/vnd.collada+xml", "model/gltf-binary")


def time_of(ns: int) -> dict[str, int]:
    """A Foxglove time (`sec`, `nsec`) of nanoseconds."""
    return {"sec": ns // 1_000_000_000, "nsec": ns % 1_000_000_000}


def vector(values: Any) -> dict[str, float]:
    """A foxglove.Vector3, rounded: the same trace gives the same bytes."""
    return {axis: round(float(v), DIGITS) + 0.0 for axis, v in zip("xyz", values)}


def quaternion(values: Any) -> dict[str, float]:
    """A foxglove.Quaternion (x, y, z, w), rounded."""
    return {axis: round(float(v), DIGITS) + 0.0 for axis, v in zip("xyzw", values)}


def _pose(origin: tuple[Any, Any], offset: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> dict[str, Any]:
    """A shape's pose in its link frame, moved by `offset` along the shape's own axes."""
    position, orientation = origin
    moved = np.asarray(position, dtype=float) + _rotate(orientation, offset)
    return {"position": vector(moved), "orientation": quaternion(orientation)}


def _rotate(quaternion: Any, vector: tuple[float, float, float]) -> np.ndarray:
    x, y, z, w = (float(v) for v in quaternion)
    q = np.array([x, y, z])
    v = np.asarray(vector, dtype=float)
    return v + 2.0 * np.cross(q, np.cross(q, v) + w * v)


def color(rgba: Any) -> dict[str, float]:
    """A foxglove.Color (r, g, b, a in 0-1)."""
    return {channel: round(float(v), 4) + 0.0 for channel, v in zip("rgba", rgba)}


def stl_bytes(vertices: np.ndarray, triangles: np.ndarray) -> bytes:
    """A binary STL of a triangle mesh (Foxglove draws STL models as they are: no axis conventions)."""
    corners = vertices[triangles].astype("<f4")  # (M, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0).astype("<f4")
    rows = np.zeros(len(triangles), dtype=[("normal", "<f4", 3), ("corners", "<f4", 9), ("attribute", "<u2")])
    rows["normal"], rows["corners"] = normals, corners.reshape(-1, 9)
    header = b"pycram: a visual mesh for the MCAP replay".ljust(80, b" ")
    return header + np.uint32(len(triangles)).astype("<u4").tobytes() + rows.tobytes()


class SceneEntities:
    """Every body's drawn links as Foxglove scene entities, each mesh file converted once."""

    def __init__(self, world: BulletWorld) -> None:
        self.world = world
        self._meshes: dict[str, tuple[str, str] | None] = {}  # path -> (media type, base64), None: unreadable
        self.skipped: list[str] = []
        self.links: list[tuple[Object, list[int]]] = []
        self.entities: list[dict[str, Any]] = []
        for obj in world.objects:
            shapes: dict[int, list[VisualShape]] = {}
            for shape in obj.visual_shapes():
                shapes.setdefault(shape.link, []).append(shape)
            drawn = []
            for link in sorted(shapes):
                entity = self._entity(obj, link, shapes[link])
                if entity is not None:
                    self.entities.append(entity)
                    drawn.append(link)
            self.links.append((obj, drawn))
            if obj.type not in SCENERY and drawn:
                self.entities.append(self._label(obj, drawn[0]))

    def _entity(self, obj: Object, link: int, shapes: list[VisualShape]) -> dict[str, Any] | None:
        parts: dict[str, list[dict[str, Any]]] = {"cubes": [], "spheres": [], "cylinders": [], "models": []}
        for shape in shapes:
            rgba = color(shape.rgba)
            if shape.rgba[3] <= 0.0:
                continue
            if shape.kind == "box":
                parts["cubes"].append({"pose": _pose(shape.origin), "size": vector(shape.size), "color": rgba})
            elif shape.kind == "sphere":
                parts["spheres"].append({"pose": _pose(shape.origin), "size": vector([2 * shape.radius] * 3),
                                         "color": rgba})
            elif shape.kind in ("cylinder", "capsule"):
                diameter = 2 * shape.radius
                parts["cylinders"].append({"pose": _pose(shape.origin), "size": vector((diameter, diameter, shape.length)),
                                           "bottom_scale": 1.0, "top_scale": 1.0, "color": rgba})
                if shape.kind == "capsule":  # the rounded ends
                    for end in (-0.5, 0.5):
                        parts["spheres"].append({"pose": _pose(shape.origin, (0.0, 0.0, end * shape.length)),
                                                 "size": vector([diameter] * 3), "color": rgba})
            elif shape.kind == "mesh" and (mesh := self._mesh(shape.mesh_file)) is not None:
                media_type, data = mesh
                own_look = media_type in OWN_LOOK  # its own materials, as the model has them
                parts["models"].append({"pose": _pose(shape.origin), "scale": vector(shape.scale), "color": rgba,
                                        "override_color": not own_look, "url": "", "media_type": media_type,
                                        "data": data})
            else:
                what = f"mesh {shape.mesh_file}" if shape.kind == "mesh" else shape.kind
                self.skipped.append(f"{obj.name}/{obj.get_link_name(link)}: {what}")
        if not any(parts.values()):
            return None
        name = obj.get_link_name(link)
        return {"timestamp": time_of(0), "frame_id": frame_of(obj, link), "id": f"{obj.name}/{name}",
                "lifetime": time_of(0), "frame_locked": True,
                "metadata": [{"key": "body", "value": obj.name}, {"key": "link", "value": name},
                             {"key": "type", "value": obj.type}],
                **{kind: items for kind, items in parts.items() if items}}

    def _label(self, obj: Object, link: int) -> dict[str, Any]:
        """The object's name above it, facing the viewer."""
        lo, hi = obj.get_aabb()
        (x, y, z), _ = obj.link_poses([link])[link]
        above = ((lo[0] + hi[0]) / 2 - x, (lo[1] + hi[1]) / 2 - y, hi[2] - z + 0.08)
        return {"timestamp": time_of(0), "frame_id": frame_of(obj, link), "id": f"label/{obj.name}",
                "lifetime": time_of(0), "frame_locked": True,
                "metadata": [{"key": "body", "value": obj.name}, {"key": "type", "value": obj.type}],
                "texts": [{"pose": {"position": vector(above), "orientation": quaternion((0, 0, 0, 1))},
                           "billboard": True, "font_size": 14.0, "scale_invariant": True,
                           "color": color((0.1, 0.1, 0.1, 1.0)), "text": obj.name}]}

    def _mesh(self, path: Path | None) -> tuple[str, str] | None:
        """(media type, base64 data) of a mesh file: OBJ and STL as STL (read and checked here), formats Foxglove
        reads itself (COLLADA, glTF) as they are; None when it cannot be read."""
        if path is None:
            return None
        key = str(path)
        if key not in self._meshes:
            media_type = AS_IS.get(path.suffix.lower())
            try:
                if media_type is not None:
                    data = path.read_bytes()
                else:
                    mesh = read_mesh(path)
                    media_type, data = "model/stl", stl_bytes(mesh.vertices, mesh.triangles)
                self._meshes[key] = (media_type, base64.b64encode(data).decode("ascii"))
            except (OSError, ValueError):
                self._meshes[key] = None
        return self._meshes[key]

    def transforms(self, ns: int) -> list[dict[str, Any]]:
        """Every drawn link's frame in the world now."""
        found = []
        for obj, links in self.links:
            if not links:
                continue
            for link, (position, orientation) in sorted(obj.link_poses(links).items()):
                found.append({"timestamp": time_of(ns), "parent_frame_id": WORLD_FRAME,
                              "child_frame_id": frame_of(obj, link),
                              "translation": vector(position), "rotation": quaternion(orientation)})
        return found


def frame_of(obj: Object, link: int) -> str:
    return f"{obj.name}/{obj.get_link_name(link)}"
