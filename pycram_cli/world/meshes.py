"""Reading STL and OBJ meshes: vertices, triangles, volume, centre of mass, inertia.

Used to turn a mesh into a one-link URDF with physically sensible inertial data.
"""
from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..files import write_atomic

#: a closed mesh enclosing less than this fraction of its bounding box is hollow (see Mesh.is_hollow)
HOLLOW = 0.3
#: the grid cell for convex pieces of hollow meshes (m), and how far the normals of one piece may spread (rad)
PIECE_CELL = 0.015
PIECE_SPREAD = math.radians(8.0)
#: the bottom this high of a hollow mesh is one piece (m)
FOOT = 0.01
#: what a cached decomposition was made with (part of the cache key: change it with the algorithm)
PIECES_VERSION = (4, PIECE_CELL, FOOT, round(PIECE_SPREAD, 6))


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

    def surface_points(self, spacing: float) -> tuple[np.ndarray, np.ndarray]:
        """Points on every triangle, at most `spacing` apart (its corners included), with the triangle's unit normal."""
        tris = self.vertices[self.triangles]  # (m, 3, 3)
        normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
        normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
        longest = np.max(np.linalg.norm(tris - np.roll(tris, 1, axis=1), axis=2), axis=1)
        counts = np.maximum(1, np.ceil(longest / spacing).astype(int))
        points, point_normals = [], []
        for n in np.unique(counts):
            i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
            keep = i + j <= n
            weights = np.stack([i[keep], j[keep], n - i[keep] - j[keep]], axis=1) / n  # (k, 3) barycentric
            chosen = counts == n
            points.append(np.einsum("kc,mcd->mkd", weights, tris[chosen]).reshape(-1, 3))
            point_normals.append(np.repeat(normals[chosen], len(weights), axis=0))
        return np.concatenate(points), np.concatenate(point_normals)

    # long: one numpy pipeline (sample, cut, merge) whose steps share a dozen arrays
    def convex_pieces(self, cell: float = PIECE_CELL, spread: float = PIECE_SPREAD) -> list[np.ndarray]:
        """The mesh cut into convex pieces for collision, each the points of a patch of its surface.

        The surface is sampled and cut by a grid (cells of about `cell` metres, overlapping by the sample spacing so
        that the pieces leave no gaps); neighbouring cells are then merged while the patch stays nearly flat (every
        normal within `spread` radians of the patch's main axis, either side: a thin wall's two faces count as one
        flat patch). So a thin wall stays a thin slab, the empty space it encloses stays empty, and a flat part (a
        bowl's bottom) is one piece; a curved patch bulges off the surface by at most about its length × spread / 8
        (2-3 mm for a bowl).
        """
        lo, hi = self.bounds
        size = np.maximum(hi - lo, 1e-9)
        counts = np.clip(np.round(size / cell), 1, 12).astype(int)
        step = size / counts
        spacing = float(step.min()) / 4.0
        points, normals = self.surface_points(spacing)
        # what the object stands on is one piece: everything within FOOT of its bottom (the bottom of a bowl's
        # inside, if that low, is filled: nothing goes there); resting on a table it then touches with one piece
        foot_top = lo[2] + min(FOOT, size[2] / 4.0)
        foot = points[points[:, 2] <= foot_top + spacing]
        upper = points[:, 2] >= foot_top - spacing
        points, normals = points[upper], normals[upper]
        lo = np.array([lo[0], lo[1], foot_top])
        size = np.maximum(hi - lo, 1e-9)
        counts = np.clip(np.round(size / cell), 1, 12).astype(int)
        step = size / counts
        rel = (points - lo) / step
        overlap = spacing / step
        low = np.clip(np.floor(rel - overlap), 0, counts - 1).astype(int)
        high = np.clip(np.floor(rel + overlap), 0, counts - 1).astype(int)
        members: dict[tuple[int, int, int], set[int]] = {}
        for bits in ((x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)):
            index = np.where(np.array(bits, dtype=bool), high, low)
            keys = (index[:, 0] * 10000 + index[:, 1] * 100 + index[:, 2])
            order = np.argsort(keys, kind="stable")
            unique, starts = np.unique(keys[order], return_index=True)
            for key, chunk in zip(unique, np.split(order, starts[1:])):
                cell_key = (int(key) // 10000, int(key) // 100 % 100, int(key) % 100)
                members.setdefault(cell_key, set()).update(chunk.tolist())
        cells = {key: np.array(sorted(found)) for key, found in members.items()}
        flat = math.cos(spread)

        def nearly_flat(indices: np.ndarray) -> bool:
            n = normals[indices]
            axis = np.linalg.eigh(n.T @ n)[1][:, -1]
            return bool(np.min(np.abs(n @ axis)) >= flat)

        done: set[tuple[int, int, int]] = set()
        result = [_extremes(foot)] if len(foot) >= 4 else []
        for key in sorted(cells):
            if key in done:
                continue
            region, indices, frontier = {key}, cells[key], [key]
            done.add(key)
            while frontier:
                x, y, z = frontier.pop(0)
                for other in ((x + 1, y, z), (x - 1, y, z), (x, y + 1, z), (x, y - 1, z), (x, y, z + 1), (x, y, z - 1)):
                    if other in done or other not in cells:
                        continue
                    merged = np.union1d(indices, cells[other])
                    if nearly_flat(merged):
                        region.add(other)
                        done.add(other)
                        indices = merged
                        frontier.append(other)
            if len(indices) >= 4:
                result.append(_extremes(points[indices]))
        return result


#: directions to keep a piece's outermost points in: every non-zero vector of {-2..2}³ (98 directions, at most
#: about 20° apart), so a piece of 1.5 cm loses at most about 0.3 mm to the hull of its full point cloud
_DIRECTIONS = np.unique(np.array([v / np.linalg.norm(v) for v in np.stack(np.meshgrid(*[np.arange(-2, 3)] * 3), -1)
                                  .reshape(-1, 3) if np.any(v)]).round(9), axis=0)


def _extremes(points: np.ndarray) -> np.ndarray:
    """The points of a cloud that are outermost in some direction: its convex hull, nearly, for a fraction of the
    points (PyBullet builds the hull of each piece when it loads it, at a cost that grows with the points)."""
    keep = np.unique(np.argmax(points @ _DIRECTIONS.T, axis=0))
    return np.unique(np.round(points[keep], 7), axis=0)


def write_pieces_obj(pieces: list[np.ndarray], path: Path) -> None:
    """Convex pieces as a Wavefront OBJ with one object per piece (PyBullet collides each as its convex hull)."""
    lines = ["# convex pieces for collision, one object each (written by pycram)"]
    first = 1
    for k, cloud in enumerate(pieces):
        lines.append(f"o piece{k}")
        lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in cloud]
        lines += [f"f {first} {first + i} {first + i + 1}" for i in range(1, len(cloud) - 1)]
        first += len(cloud)
    write_atomic(path, "\n".join(lines) + "\n")


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
    write_atomic(path, b"pycram binary stl".ljust(80, b" ") + struct.pack("<I", len(tris)) + records.tobytes())


def _read_stl(path: Path) -> Mesh:
    data = path.read_bytes()
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + count * 50 == len(data):
            raw = np.frombuffer(data, dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]), count=count, offset=84)
            verts = raw["v"].reshape(-1, 3).astype(float)
            return Mesh(verts, np.arange(len(verts)).reshape(-1, 3))
    corners: list[list[float]] = []
    for line in data.decode("ascii", errors="replace").splitlines():
        parts = line.split()
        if parts and parts[0] == "vertex":
            corners.append([float(x) for x in parts[1:4]])
    arr = np.array(corners, dtype=float).reshape(-1, 3)
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
