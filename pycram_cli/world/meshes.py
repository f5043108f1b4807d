"""Reading STL and OBJ meshes: vertices, triangles, volume, centre of mass, inertia.

Used to turn a mesh into a one-link URDF with physically sensible inertial data.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..files import write_atomic


@dataclass
class Mesh:
    vertices: np.ndarray  # (n, 3)
    triangles: np.ndarray  # (m, 3) indices

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.vertices.min(axis=0), self.vertices.max(axis=0)

    def volume_and_centroid(self) -> tuple[float, np.ndarray]:
        """Signed-tetrahedron volume and centroid (valid for closed meshes)."""
        a, b, c = (self.vertices[self.triangles[:, i]] for i in range(3))
        vols = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
        volume = float(vols.sum())
        if abs(volume) < 1e-12:
            lo, hi = self.bounds
            return 0.0, (lo + hi) / 2.0
        centroid = (vols[:, None] * (a + b + c) / 4.0).sum(axis=0) / volume
        return abs(volume), centroid


def is_binary_stl(path: Path) -> bool:
    data = path.read_bytes()
    return len(data) >= 84 and 84 + struct.unpack_from("<I", data, 80)[0] * 50 == len(data)


def write_binary_stl(mesh: Mesh, path: Path) -> None:
    tris = mesh.vertices[mesh.triangles].astype("<f4")
    records = np.zeros(len(tris), dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]))
    records["v"] = tris.reshape(-1, 9)
    write_atomic(path, b"pycram binary stl".ljust(80, b" ") + struct.pack("<I", len(tris)) + records.tobytes())


def _read_stl(path: Path) -> Mesh:
    data = path.read_bytes()
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + count * 50 == len(data):
            raw = np.frombuffer(data, dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]), count=count, offset=84)
            verts = raw["v"].reshape(-1, 3).astype(float)
            return Mesh(verts, np.arange(len(verts)).reshape(-1, 3))
    verts = []
    for line in data.decode("ascii", errors="replace").splitlines():
        parts = line.split()
        if parts and parts[0] == "vertex":
            verts.append([float(x) for x in parts[1:4]])
    arr = np.array(verts, dtype=float).reshape(-1, 3)
    return Mesh(arr, np.arange(len(arr)).reshape(-1, 3))


def _read_obj(path: Path) -> Mesh:
    """Vertices and triangles (faces fanned) of an OBJ file. Every run reads the meshes it validates, so plain
    files (three numbers per vertex, three indices per face) are parsed in bulk by numpy (10x faster than a
    loop over the lines); anything else line by line."""
    lines = path.read_text(errors="replace").splitlines()
    vertex_lines = [line[2:] for line in lines if line.startswith("v ")]
    face_lines = [line[2:] for line in lines if line.startswith("f ")]
    verts = np.fromstring(" ".join(vertex_lines), dtype=float, sep=" ") if vertex_lines else np.zeros(0)
    if verts.size != 3 * len(vertex_lines) or any(len(v.split()) != 3 for v in vertex_lines):
        verts = _vertices(vertex_lines)
    verts = verts.reshape(-1, 3)
    joined = " ".join(face_lines)
    if face_lines and "/" not in joined and "-" not in joined:
        indices = np.fromstring(joined, dtype=np.int64, sep=" ")
        if indices.size == 3 * len(face_lines):
            return Mesh(verts, indices.reshape(-1, 3) - 1)
    return Mesh(verts, _fanned(lines))


def _vertices(vertex_lines: list[str]) -> np.ndarray:
    """Vertices line by line (three coordinates each; a fourth, w, is ignored)."""
    verts = []
    for line in vertex_lines:
        coordinates = line.split()[:3]
        if len(coordinates) != 3:
            raise ValueError(f"a vertex needs three coordinates: {'v ' + line.strip()!r}")
        verts.append([float(x) for x in coordinates])
    return np.array(verts, dtype=float).reshape(-1, 3)


def _fanned(lines: list[str]) -> np.ndarray:
    """Triangles of any faces (polygons fanned; negative indices count back from the vertices read so far)."""
    count = 0
    tris: list[list[int]] = []
    for line in lines:
        if line.startswith("v "):
            count += 1
        elif line.startswith("f "):
            idx = []
            for token in line.split()[1:]:
                i = int(token.split("/")[0])
                idx.append(i - 1 if i > 0 else count + i)
            for k in range(1, len(idx) - 1):
                tris.append([idx[0], idx[k], idx[k + 1]])
    return np.array(tris, dtype=int).reshape(-1, 3)


def read_mesh(path: Path) -> Mesh:
    suffix = path.suffix.lower()
    if suffix == ".stl":
        return _checked(_read_stl(path))
    if suffix == ".obj":
        return _checked(_read_obj(path))
    raise ValueError(f"{path}: unsupported mesh format {suffix!r} (expected .stl or .obj)")


def _checked(mesh: Mesh) -> Mesh:
    """A mesh a body can be made of: some triangles, finite vertices, faces that name existing vertices."""
    if not len(mesh.triangles):
        raise ValueError("the mesh has no triangles")
    if not np.isfinite(mesh.vertices).all():
        raise ValueError("the mesh has vertices that are not finite numbers")
    if mesh.triangles.min() < 0 or mesh.triangles.max() >= len(mesh.vertices):
        raise ValueError("a face of the mesh names a vertex it does not have")
    return mesh


@dataclass
class Inertial:
    mass: float
    origin: tuple[float, float, float]
    diagonal: tuple[float, float, float]


def inertial_for(mesh: Mesh, density: float = 400.0, mass: float | None = None) -> Inertial:
    """Mass from volume × density (unless given), inertia of the bounding box about the centroid."""
    volume, centroid = mesh.volume_and_centroid()
    lo, hi = mesh.bounds
    size = np.maximum(hi - lo, 1e-3)
    if mass is None:
        mass = float(np.clip(volume * density, 0.02, 20.0))
    ix = mass / 12.0 * (size[1] ** 2 + size[2] ** 2)
    iy = mass / 12.0 * (size[0] ** 2 + size[2] ** 2)
    iz = mass / 12.0 * (size[0] ** 2 + size[1] ** 2)
    return Inertial(mass, (float(centroid[0]), float(centroid[1]), float(centroid[2])), (ix, iy, iz))
