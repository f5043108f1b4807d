"""Reading STL and OBJ meshes: vertices, triangles, volume, centre of mass, inertia.

Used to turn a mesh into a one-link URDF with physically sensible inertial data.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np


#: a closed mesh enclosing less than this fraction of its bounding box is hollow (see Mesh.is_hollow)
HOLLOW = 0.3
#: the grid cell for convex pieces of hollow meshes (m)
PIECE_CELL = 0.015


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


    def is_hollow(self) -> bool:
        """A closed mesh enclosing less than 30 % of its bounding box: a bowl, a cup, a pitcher (thin walls around
        empty space), which its convex hull would fill. An open mesh (no volume) is not hollow: it has no inside."""
        volume, _ = self.volume_and_centroid()
        lo, hi = self.bounds
        box = float(np.prod(np.maximum(hi - lo, 1e-9)))
        return volume > 0.0 and volume < HOLLOW * box

    def surface_points(self, spacing: float) -> np.ndarray:
        """Points on every triangle, at most `spacing` apart (its vertices included)."""
        tris = self.vertices[self.triangles]  # (m, 3, 3)
        longest = np.max(np.linalg.norm(tris - np.roll(tris, 1, axis=1), axis=2), axis=1)
        counts = np.maximum(1, np.ceil(longest / spacing).astype(int))
        found = [self.vertices]
        for n in np.unique(counts):
            if n == 1:
                continue
            i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
            keep = i + j <= n
            weights = np.stack([i[keep], j[keep], n - i[keep] - j[keep]], axis=1) / n  # (k, 3) barycentric
            found.append(np.einsum("kc,mcd->mkd", weights, tris[counts == n]).reshape(-1, 3))
        return np.concatenate(found)

    def convex_pieces(self, cell: float = PIECE_CELL) -> list[np.ndarray]:
        """The mesh cut into convex pieces for collision: the points of its surface in each cell of a grid (cells of
        about `cell` metres, overlapping by the sample spacing so that the pieces leave no gaps), in grid order.

        Each piece is the convex hull of a patch of the surface, so a thin wall stays a thin slab and the empty
        space it encloses stays empty; a curved wall is approximated within cell² / (8 × its radius) (1 mm for a
        bowl of radius 7 cm).
        """
        lo, hi = self.bounds
        size = np.maximum(hi - lo, 1e-9)
        counts = np.clip(np.round(size / cell), 1, 12).astype(int)
        step = size / counts
        spacing = float(step.min()) / 4.0
        points = self.surface_points(spacing)
        rel = (points - lo) / step
        pieces: dict[tuple[int, int, int], list[np.ndarray]] = {}
        overlap = spacing / step
        low = np.clip(np.floor(rel - overlap), 0, counts - 1).astype(int)
        high = np.clip(np.floor(rel + overlap), 0, counts - 1).astype(int)
        for dx in (0, 1):
            for dy in (0, 1):
                for dz in (0, 1):
                    index = np.where(np.array([dx, dy, dz], dtype=bool), high, low)
                    keys = index[:, 0] * 10000 + index[:, 1] * 100 + index[:, 2]
                    for key in np.unique(keys):
                        pieces.setdefault((int(key) // 10000, int(key) // 100 % 100, int(key) % 100), []).append(
                            points[keys == key])
        result = []
        for key in sorted(pieces):
            cloud = np.unique(np.round(np.concatenate(pieces[key]), 7), axis=0)
            if len(cloud) >= 4:
                result.append(cloud)
        return result



def write_pieces_obj(pieces: list[np.ndarray], path: Path) -> None:
    """Convex pieces as a Wavefront OBJ with one object per piece (PyBullet collides each as its convex hull)."""
    lines = ["# convex pieces for collision, one object each (written by pycram)"]
    first = 1
    for k, cloud in enumerate(pieces):
        lines.append(f"o piece{k}")
        lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in cloud]
        lines += [f"f {first} {first + i} {first + i + 1}" for i in range(1, len(cloud) - 1)]
        first += len(cloud)
    path.write_text("\n".join(lines) + "\n")


def obj_objects(path: Path) -> int:
    """How many objects (`o`/`g` groups) an OBJ file has: PyBullet collides each as a convex hull of its own."""
    if path.suffix.lower() != ".obj":
        return 1
    return sum(1 for line in path.read_text(errors="replace").splitlines() if line.startswith(("o ", "g ")))


def is_binary_stl(path: Path) -> bool:
    data = path.read_bytes()
    return len(data) >= 84 and 84 + struct.unpack_from("<I", data, 80)[0] * 50 == len(data)


def write_binary_stl(mesh: Mesh, path: Path) -> None:
    tris = mesh.vertices[mesh.triangles].astype("<f4")
    records = np.zeros(len(tris), dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]))
    records["v"] = tris.reshape(-1, 9)
    path.write_bytes(b"pycram binary stl".ljust(80, b" ") + struct.pack("<I", len(tris)) + records.tobytes())


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
    verts: list[list[float]] = []
    tris: list[list[int]] = []
    for line in path.read_text(errors="replace").splitlines():
        if line.startswith("v "):
            verts.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            idx = []
            for token in line.split()[1:]:
                i = int(token.split("/")[0])
                idx.append(i - 1 if i > 0 else len(verts) + i)
            for k in range(1, len(idx) - 1):
                tris.append([idx[0], idx[k], idx[k + 1]])
    return Mesh(np.array(verts, dtype=float).reshape(-1, 3), np.array(tris, dtype=int).reshape(-1, 3))


def read_mesh(path: Path) -> Mesh:
    suffix = path.suffix.lower()
    if suffix == ".stl":
        return _read_stl(path)
    if suffix == ".obj":
        return _read_obj(path)
    raise ValueError(f"{path}: unsupported mesh format {suffix!r} (expected .stl or .obj)")


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
