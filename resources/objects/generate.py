#!/usr/bin/env python3
"""Generate the household object meshes (Wavefront OBJ, metres) used in the kitchen demo.

Objects: ``milk`` (1 l gable-top carton), ``breakfast_cereal`` (box), ``bowl`` (hollow,
with a foot), ``spoon`` (thin, flat) and ``bottle`` (revolution solid with shoulder
and neck).

Mesh conventions
----------------
* Units are metres.  The origin is the centre of the object's bottom face: the
  bounding box is centred on x = y = 0 and the object extends upward from z = 0, so
  an object's position is the point on which it stands.
* Every mesh is a single closed, watertight triangle mesh (each edge is shared by
  exactly two triangles) whose triangles are ordered counter-clockwise seen from
  outside, i.e. the normals point outward.
* Output is deterministic (fixed number formatting), so re-running the script
  reproduces the committed files byte for byte.

Usage::

    python resources/objects/generate.py              # writes next to this script
    python resources/objects/generate.py --out /tmp/objects
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

HERE = Path(__file__).resolve().parent

# Number of segments around revolution solids (divisible by 4 so that the bounding
# box of a ring is exactly its diameter in x and y).
SEGMENTS = 48


class Mesh:
    """A triangle mesh: ``vertices`` (N x 3 floats) and ``faces`` (M x 3 vertex indices)."""

    def __init__(self, vertices: Sequence[Sequence[float]], faces: Sequence[Sequence[int]]):
        self.vertices = np.asarray(vertices, dtype=float)
        self.faces = np.asarray(faces, dtype=int)

    def signed_volume(self) -> float:
        a, b, c = (self.vertices[self.faces[:, k]] for k in range(3))
        return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)

    def oriented_outward(self) -> "Mesh":
        """Flip all triangles if the mesh is inside out (negative volume)."""
        if self.signed_volume() < 0:
            return Mesh(self.vertices, self.faces[:, ::-1])
        return self

    def to_obj(self, name: str, comment: str) -> str:
        lines = [f"# {line}" for line in comment.strip().splitlines()]
        lines.append(f"# {len(self.vertices)} vertices, {len(self.faces)} triangles; units: metres")
        lines.append(f"o {name}")
        for v in self.vertices:
            lines.append("v " + " ".join(_fmt(c) for c in v))
        for f in self.faces:
            lines.append("f " + " ".join(str(int(i) + 1) for i in f))
        return "\n".join(lines) + "\n"


def _fmt(value: float) -> str:
    text = f"{value:.6f}"
    return "0.000000" if text == "-0.000000" else text


# --------------------------------------------------------------------------------------
# Generic constructions
# --------------------------------------------------------------------------------------
def prism(polygon: Sequence[tuple[float, float]], height: float) -> Mesh:
    """Extrude a simple polygon in the x-y plane from z = 0 to z = height.

    The polygon must be star-shaped with respect to its vertex centroid (true for
    the convex polygons used here); the caps are triangulated as a fan around an
    extra centre vertex.
    """
    pts = np.asarray(polygon, dtype=float)
    return prism_star(pts, height, (float(pts[:, 0].mean()), float(pts[:, 1].mean())))


def prism_star(polygon: Sequence[tuple[float, float]] | np.ndarray, height: float,
               centre: tuple[float, float]) -> Mesh:
    """Extrude a polygon from z = 0 to z = height, fanning the caps around ``centre``.

    The polygon must be star-shaped with respect to ``centre`` (every vertex visible
    from it); it may be given in either orientation.
    """
    pts = np.asarray(polygon, dtype=float)
    rel = pts - np.asarray(centre)
    if np.sum(rel[:, 0] * np.roll(rel[:, 1], -1) - np.roll(rel[:, 0], -1) * rel[:, 1]) < 0:
        pts, rel = pts[::-1], rel[::-1]
    fan = rel[:, 0] * np.roll(rel[:, 1], -1) - np.roll(rel[:, 0], -1) * rel[:, 1]
    assert np.all(fan > 0), "polygon is not star-shaped with respect to the centre"
    n = len(pts)
    verts = [(x, y, 0.0) for x, y in pts] + [(x, y, height) for x, y in pts]
    verts += [(centre[0], centre[1], 0.0), (centre[0], centre[1], height)]
    cb, ct = 2 * n, 2 * n + 1
    faces: list[tuple[int, int, int]] = []
    for i in range(n):
        j = (i + 1) % n
        faces.append((cb, j, i))              # bottom cap, normal -z
        faces.append((ct, n + i, n + j))      # top cap, normal +z
        faces.append((i, j, n + j))           # side
        faces.append((i, n + j, n + i))
    return Mesh(verts, faces).oriented_outward()


def extrude_xz(polygon: Sequence[tuple[float, float]], depth: float) -> Mesh:
    """Extrude a convex polygon given in the x-z plane symmetrically along y."""
    mesh = prism(polygon, depth)  # polygon coordinates act as (x, z), extrusion as y
    v = mesh.vertices
    vertices = np.column_stack([v[:, 0], v[:, 2] - depth / 2.0, v[:, 1]])
    return Mesh(vertices, mesh.faces).oriented_outward()


def lathe(profile: Sequence[tuple[float, float]], segments: int = SEGMENTS) -> Mesh:
    """Revolve an open (r, z) profile about the z axis into a closed solid.

    The profile must start and end on the axis (r = 0); all other points have r > 0.
    """
    prof = [(float(r), float(z)) for r, z in profile]
    assert prof[0][0] == 0.0 and prof[-1][0] == 0.0, "profile must start and end on the axis"
    assert all(r > 0 for r, _ in prof[1:-1])
    angles = [2.0 * math.pi * k / segments for k in range(segments)]
    vertices: list[tuple[float, float, float]] = [(0.0, 0.0, prof[0][1])]
    rings: list[int] = []
    for r, z in prof[1:-1]:
        rings.append(len(vertices))
        vertices += [(r * math.cos(a), r * math.sin(a), z) for a in angles]
    vertices.append((0.0, 0.0, prof[-1][1]))
    first_pole, last_pole = 0, len(vertices) - 1
    faces: list[tuple[int, int, int]] = []
    for k in range(segments):
        k1 = (k + 1) % segments
        faces.append((first_pole, rings[0] + k1, rings[0] + k))
        for a, b in zip(rings[:-1], rings[1:]):
            faces.append((a + k, a + k1, b + k1))
            faces.append((a + k, b + k1, b + k))
        faces.append((last_pole, rings[-1] + k, rings[-1] + k1))
    return Mesh(vertices, faces).oriented_outward()


def box(sx: float, sy: float, sz: float) -> Mesh:
    hx, hy = sx / 2.0, sy / 2.0
    return prism([(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)], sz)


# --------------------------------------------------------------------------------------
# The objects
# --------------------------------------------------------------------------------------
def milk() -> Mesh:
    """1 l carton: 0.07 x 0.07 x 0.20 body with a gable roof, ridge (along y) at 0.22."""
    w, body, ridge = 0.07, 0.20, 0.22
    h = w / 2.0
    return extrude_xz([(-h, 0.0), (h, 0.0), (h, body), (0.0, ridge), (-h, body)], w)


def breakfast_cereal() -> Mesh:
    """Cereal box: 0.07 deep (x) x 0.19 wide (y) x 0.27 tall (z)."""
    return box(0.07, 0.19, 0.27)


def bowl() -> Mesh:
    """Hollow bowl: outer diameter 0.15, height 0.06, ~4 mm wall, flat foot (r 0.035)."""
    outer_r, height, wall, foot_r = 0.075, 0.06, 0.004, 0.035
    n = 14
    # Outer wall: quarter ellipse centred on the axis at rim height.
    outer_b = height - 0.002
    phi0 = math.asin(0.036 / outer_r)
    outer = [(outer_r * math.sin(p), height - outer_b * math.cos(p))
             for p in np.linspace(phi0, math.pi / 2, n)]
    # Inner wall: the outer ellipse shrunk by the wall thickness.
    inner_a, inner_b = outer_r - wall, outer_b - wall - 0.002
    inner = [(inner_a * math.sin(p), height - inner_b * math.cos(p))
             for p in np.linspace(math.pi / 2, 0.0, n + 4)]
    profile = [(0.0, 0.0), (foot_r, 0.0)] + outer + inner  # rim: outer top -> inner top
    return lathe(profile)


def bottle() -> Mesh:
    """Bottle: diameter 0.065, height 0.25, with a rounded shoulder, a neck and a lip."""
    r, neck_r, lip_r = 0.0325, 0.0135, 0.0155
    profile = [(0.0, 0.0), (r - 0.003, 0.0), (r, 0.003), (r, 0.155)]
    # shoulder: cosine blend from the body radius to the neck radius
    for t in np.linspace(0.0, 1.0, 10)[1:]:
        profile.append((neck_r + (r - neck_r) * 0.5 * (1 + math.cos(math.pi * t)), 0.155 + 0.055 * t))
    profile += [(neck_r, 0.236), (lip_r, 0.237), (lip_r, 0.249), (lip_r - 0.001, 0.25), (0.0, 0.25)]
    return lathe(profile)


def spoon() -> Mesh:
    """Flat spoon lying on z = 0: 0.16 long along x, bowl at +x, 4 mm thick."""
    length, thickness = 0.16, 0.004
    bowl_a, bowl_b = 0.031, 0.021            # half length / half width of the oval bowl
    bowl_cx = length / 2.0 - bowl_a
    end_r = 0.0085                           # half width at the rounded handle end
    neck_w = 0.005                           # half width where the handle meets the bowl
    end_cx = -length / 2.0 + end_r

    def half_width(x: float) -> float:
        return neck_w + (end_r - neck_w) * (bowl_cx - x) / (bowl_cx - end_cx)

    # where the handle edge y = half_width(x) meets the ellipse (bisection)
    lo, hi = end_cx, bowl_cx
    for _ in range(60):
        mid = (lo + hi) / 2.0
        inside = ((mid - bowl_cx) / bowl_a) ** 2 + (half_width(mid) / bowl_b) ** 2 < 1.0
        lo, hi = (lo, mid) if inside else (mid, hi)
    x_join = hi
    t_join = math.atan2(half_width(x_join) / bowl_b, (x_join - bowl_cx) / bowl_a)

    outline: list[tuple[float, float]] = []
    # oval bowl from the lower junction, around the tip, to the upper junction (ccw)
    for t in np.linspace(-t_join, t_join, 41):
        outline.append((bowl_cx + bowl_a * math.cos(t), bowl_b * math.sin(t)))
    # upper handle edge towards the end
    for x in np.linspace(x_join, end_cx, 12)[1:]:
        outline.append((x, half_width(x)))
    # rounded end (semicircle from +y over -x to -y)
    for t in np.linspace(math.pi / 2, 3 * math.pi / 2, 13)[1:-1]:
        outline.append((end_cx + end_r * math.cos(t), end_r * math.sin(t)))
    # lower handle edge back to the bowl
    for x in np.linspace(end_cx, x_join, 12)[:-1]:
        outline.append((x, -half_width(x)))
    mesh = prism_star(outline, thickness, centre=(x_join + 0.004, 0.0))
    # centre the bounding box on x = y = 0
    v = mesh.vertices.copy()
    v[:, 0] -= (v[:, 0].max() + v[:, 0].min()) / 2.0
    v[:, 1] -= (v[:, 1].max() + v[:, 1].min()) / 2.0
    return Mesh(v, mesh.faces)


OBJECTS: dict[str, tuple[Callable[[], Mesh], str]] = {
    "milk": (milk, "1 l milk carton, 0.07 x 0.07 x 0.20 body with gable top, 0.22 tall"),
    "breakfast_cereal": (breakfast_cereal, "cereal box, 0.07 (x) x 0.19 (y) x 0.27 (z)"),
    "bowl": (bowl, "hollow bowl, outer diameter 0.15, height 0.06, wall ~4 mm, flat foot"),
    "spoon": (spoon, "flat spoon, 0.16 long (x), 0.042 wide, 4 mm thick, bowl at +x"),
    "bottle": (bottle, "bottle, diameter 0.065, height 0.25, shoulder and neck"),
}


def obj_text(name: str) -> str:
    make, description = OBJECTS[name]
    header = (f"{description}\n"
              "Generated by resources/objects/generate.py - do not edit by hand.\n"
              "Origin: centre of the bottom face (z = 0 at the bottom, object extends upward).")
    return make().to_obj(name, header)


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=HERE, help="output directory")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for name in OBJECTS:
        path = args.out / f"{name}.obj"
        path.write_text(obj_text(name), encoding="utf-8")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
