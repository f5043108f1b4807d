"""COLLADA (.dae) meshes for the report's 3D view: the triangles of every geometry the file's scene places.

Real robot descriptions (the PR2's and the Fetch's from ROS) give their links' looks as COLLADA files, which
PyBullet draws itself; the report draws them in the browser, so it reads them here: the positions of
`<triangles>`, `<polylist>` and `<polygons>` (fanned), placed by the scene's node transforms (`matrix`,
`translate`, `rotate`, `scale`), in metres (`<unit meter=...>`). `<up_axis>` is not applied, as in PyBullet's
drawing of these robots: the PR2's files say Y_UP but are z up, as their collision STLs are (a test checks that
the two agree). Normals, texture coordinates and materials are not read.
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from ..limits import MAX_MODEL_BYTES

#: at most this many triangles are read from one file (beyond: a ValueError)
MAX_TRIANGLES = 2_000_000


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _children(element: ET.Element, name: str) -> list[ET.Element]:
    return [child for child in element if _local(child.tag) == name]


def _numbers(text: str | None, kind: type = float) -> np.ndarray:
    return np.array((text or "").split(), dtype=np.float64 if kind is float else np.int64)


def _rotation(axis: np.ndarray, degrees: float) -> np.ndarray:
    x, y, z = axis / (np.linalg.norm(axis) or 1.0)
    a = math.radians(degrees)
    c, s, t = math.cos(a), math.sin(a), 1 - math.cos(a)
    m = np.eye(4)
    m[:3, :3] = [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                 [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                 [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]
    return m


def _node_transform(node: ET.Element) -> np.ndarray:
    """The node's own transform: its transform elements multiplied in document order."""
    m = np.eye(4)
    for child in node:
        name = _local(child.tag)
        values = _numbers(child.text)
        if name == "matrix" and len(values) == 16:
            m = m @ values.reshape(4, 4)
        elif name == "translate" and len(values) == 3:
            t = np.eye(4)
            t[:3, 3] = values
            m = m @ t
        elif name == "rotate" and len(values) == 4:
            m = m @ _rotation(values[:3], float(values[3]))
        elif name == "scale" and len(values) == 3:
            m = m @ np.diag([*values, 1.0])
    return m


# long: COLLADA's sources, vertices and primitives index each other: read in one pass
def _geometry(mesh: ET.Element) -> tuple[np.ndarray, np.ndarray]:
    """A <mesh>'s positions (n, 3) and triangles (m, 3)."""
    sources = {}
    for source in _children(mesh, "source"):
        arrays = _children(source, "float_array")
        if not arrays:
            continue
        values = _numbers(arrays[0].text)
        stride = 3
        for accessor in source.iter():
            if _local(accessor.tag) == "accessor":
                stride = int(accessor.get("stride", "3"))
                break
        if stride >= 3 and len(values) >= stride:
            sources[source.get("id")] = values[: len(values) // stride * stride].reshape(-1, stride)[:, :3]
    vertices = {}
    for vertex in _children(mesh, "vertices"):
        for put in _children(vertex, "input"):
            if put.get("semantic") == "POSITION":
                vertices[vertex.get("id")] = (put.get("source") or "").lstrip("#")
    positions: list[np.ndarray] = []
    triangles: list[np.ndarray] = []
    base = 0
    for primitive in mesh:
        kind = _local(primitive.tag)
        if kind not in ("triangles", "polylist", "polygons"):
            continue
        inputs = _children(primitive, "input")
        stride = 1 + max((int(i.get("offset", "0")) for i in inputs), default=0)
        offset: int | None = None
        positions_id: str | None = None
        for put in inputs:
            target = (put.get("source") or "").lstrip("#")
            if put.get("semantic") == "VERTEX":
                offset, positions_id = int(put.get("offset", "0")), vertices.get(target, target)
            elif put.get("semantic") == "POSITION" and offset is None:
                offset, positions_id = int(put.get("offset", "0")), target
        if offset is None or positions_id not in sources:
            continue
        points = sources[positions_id]
        faces: list[np.ndarray] = []
        if kind == "polygons":
            for p in _children(primitive, "p"):
                corners = _numbers(p.text, int).reshape(-1, stride)[:, offset]
                faces.extend(np.array([corners[0], corners[k], corners[k + 1]]) for k in range(1, len(corners) - 1))
            tris = np.array(faces, dtype=np.int64).reshape(-1, 3)
        else:
            index = np.concatenate([_numbers(p.text, int) for p in _children(primitive, "p")] or [np.zeros(0, np.int64)])
            corners = index[: len(index) // stride * stride].reshape(-1, stride)[:, offset]
            if kind == "triangles":
                tris = corners[: len(corners) // 3 * 3].reshape(-1, 3)
            else:
                counts = _numbers((_children(primitive, "vcount") or [ET.Element("x")])[0].text, int)
                starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
                tris = np.array([(corners[s], corners[s + k], corners[s + k + 1]) for s, n in zip(starts, counts)
                                 for k in range(1, n - 1) if s + n <= len(corners)], dtype=np.int64).reshape(-1, 3)
        if len(tris) and (tris.min() < 0 or tris.max() >= len(points)):
            raise ValueError("a triangle names a vertex the mesh does not have")
        positions.append(points)
        triangles.append(tris + base)
        base += len(points)
        if base > 3 * MAX_TRIANGLES or sum(len(t) for t in triangles) > MAX_TRIANGLES:
            raise ValueError(f"more than {MAX_TRIANGLES} triangles")
    if not positions:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    return np.concatenate(positions), np.concatenate(triangles)


def read_collada(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """The file's triangles as placed by its scene, z up, in metres: vertices (n, 3) float64, triangles (m, 3).
    A ValueError for a file that is not COLLADA, too large, or names what it does not have."""
    if path.stat().st_size > MAX_MODEL_BYTES:
        raise ValueError(f"{path}: larger than {MAX_MODEL_BYTES} bytes")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise ValueError(f"{path}: not XML ({exc})") from None
    if _local(root.tag) != "COLLADA":
        raise ValueError(f"{path}: not a COLLADA file")
    scale = 1.0
    for asset in _children(root, "asset"):
        for unit in _children(asset, "unit"):
            scale = float(unit.get("meter", "1") or 1)
    geometries = {}
    for library in _children(root, "library_geometries"):
        for geometry in _children(library, "geometry"):
            meshes = _children(geometry, "mesh")
            if meshes:
                geometries[geometry.get("id")] = meshes[0]
    cache: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    parts: list[tuple[np.ndarray, np.ndarray]] = []

    def visit(node: ET.Element, above: np.ndarray, depth: int) -> None:
        if depth > 64:
            raise ValueError("nodes nested more than 64 deep")
        here = above @ _node_transform(node)
        for child in node:
            name = _local(child.tag)
            if name == "instance_geometry":
                key = (child.get("url") or "").lstrip("#")
                if key in geometries:
                    if key not in cache:
                        cache[key] = _geometry(geometries[key])
                    vertices, triangles = cache[key]
                    moved = vertices @ here[:3, :3].T + here[:3, 3]
                    parts.append((moved, triangles))
            elif name == "node":
                visit(child, here, depth + 1)

    scenes = [scene for library in _children(root, "library_visual_scenes")
              for scene in _children(library, "visual_scene")]
    if scenes:
        for node in _children(scenes[0], "node"):
            visit(node, np.eye(4), 0)
    else:  # no scene: every geometry where it is
        parts = [_geometry(mesh) for mesh in geometries.values()]
    vertices_list, triangles_list, base = [], [], 0
    for vertices, triangles in parts:
        vertices_list.append(vertices)
        triangles_list.append(triangles + base)
        base += len(vertices)
    if not vertices_list:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    return np.concatenate(vertices_list) * scale, np.concatenate(triangles_list)
