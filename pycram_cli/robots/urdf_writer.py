"""Writing a robot's URDF from primitive shapes: inertia from the shapes, links, joints, and the tree in order.

What: `rpy_matrix`, the inertia of boxes, cylinders and spheres (`volume`, `inertia_about`), the number spellings
(`general`, `fixed`, `Numbers`), `link_xml`, `joint_xml` (with `Joint` and `Limit`), `check_tree` and `urdf_text`;
for robots written from tables (the bundled PR2 and Fetch): `Shape`, `Link`, `box`, `cylinder_x`, `cylinder_z`,
`link_inertial`, `table_urdf` and the scripts' command line, `generator_main`.
Why one module: the bundled robots' generators (resources/robots/{pr2,fetch}/generate.py) and the robot zoo
(robots/zoo/files.py) write the same URDF; each keeps only its tables, its masses and how it spells numbers, so the
files they write stay byte for byte what they were.
"""
from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np

Vec3 = tuple[float, float, float]
ORIGIN: Vec3 = (0.0, 0.0, 0.0)


class Solid(Protocol):
    """A primitive in link coordinates: box (sx, sy, sz), cylinder (radius, length) along its z, sphere (radius,)."""

    @property
    def kind(self) -> str: ...
    @property
    def dims(self) -> tuple[float, ...]: ...
    @property
    def xyz(self) -> Vec3: ...
    @property
    def rpy(self) -> Vec3: ...


@dataclass(frozen=True)
class Limit:
    """A joint's `<limit>`; continuous joints have no lower/upper."""

    lower: float | None
    upper: float | None
    effort: float
    velocity: float


@dataclass(frozen=True)
class Joint:
    """One joint of a URDF; `mimic` names the joint it follows (multiplier 1, offset 0)."""

    name: str
    type: str
    parent: str
    child: str
    xyz: Vec3 = ORIGIN
    rpy: Vec3 = ORIGIN
    axis: Vec3 | None = None
    limit: Limit | None = None
    mimic: str | None = None


@dataclass(frozen=True)
class Visual:
    """A shape as the URDF shows it: its material (name, colour) and whether it also collides."""

    shape: Solid
    material: str
    rgba: Sequence[float]
    collision: bool = True


# -- inertia ------------------------------------------------------------------------------------------------------


def rpy_matrix(rpy: Sequence[float]) -> np.ndarray:
    """URDF fixed-axis roll-pitch-yaw: R = Rz(yaw) @ Ry(pitch) @ Rx(roll)."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def volume(shape: Solid) -> float:
    if shape.kind == "box":
        return float(np.prod(shape.dims))
    if shape.kind == "cylinder":
        radius, length = shape.dims
        return math.pi * radius**2 * length
    if shape.kind == "sphere":
        return 4.0 / 3.0 * math.pi * shape.dims[0] ** 3
    raise ValueError(f"unknown shape kind {shape.kind!r}")


def _own_inertia(shape: Solid, mass: float) -> np.ndarray:
    """The inertia tensor of a solid primitive about its centre, in link axes."""
    if shape.kind == "box":
        sx, sy, sz = shape.dims
        diag = [sy**2 + sz**2, sx**2 + sz**2, sx**2 + sy**2]
        local = np.diag([mass / 12.0 * d for d in diag])
    elif shape.kind == "cylinder":
        radius, length = shape.dims
        side = mass * (3 * radius**2 + length**2) / 12.0
        local = np.diag([side, side, mass * radius**2 / 2.0])
    else:
        local = np.eye(3) * (0.4 * mass * shape.dims[0] ** 2)
    rot = rpy_matrix(shape.rpy)
    return rot @ local @ rot.T


def inertia_about(solids: Sequence[Solid], masses: np.ndarray, total: float) -> tuple[np.ndarray, np.ndarray]:
    """(centre of mass, diagonal inertia about it) of solids of these masses (`total` their sum).

    Products of inertia are dropped (PyBullet only uses the diagonal); the diagonal of a valid inertia tensor is
    positive and obeys the triangle inequality, so the result is still physically plausible.
    """
    centres = np.array([s.xyz for s in solids], dtype=float)
    com = (masses[:, None] * centres).sum(axis=0) / total
    tensor = np.zeros((3, 3))
    for shape, mass, centre in zip(solids, masses, centres):
        d = centre - com
        tensor += _own_inertia(shape, mass) + mass * (d @ d * np.eye(3) - np.outer(d, d))
    return com, np.diag(tensor).copy()


# -- numbers ------------------------------------------------------------------------------------------------------


def general(value: float, digits: int = 12) -> str:
    """A stable short number, `digits` significant (no '-0', no trailing zeros)."""
    text = f"{float(value) + 0.0:.{digits}g}"
    return "0" if text in ("-0", "0") else text


def fixed(value: float, digits: int = 6) -> str:
    """A stable short number, `digits` after the point (no '-0', no trailing zeros)."""
    text = f"{round(float(value), digits) + 0.0:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


@dataclass(frozen=True)
class Numbers:
    """How a generator spells its numbers: the spelling, and its digits for lengths, masses, inertias, colours."""

    spell: Callable[[float, int], str]
    digits: int
    mass: int
    inertia: int
    colour: int

    def one(self, value: float, digits: int | None = None) -> str:
        return self.spell(value, self.digits if digits is None else digits)

    def three(self, values: Iterable[float], digits: int | None = None) -> str:
        return " ".join(self.one(v, digits) for v in values)


# -- writing ------------------------------------------------------------------------------------------------------


def _geometry_xml(shape: Solid, n: Numbers) -> str:
    if shape.kind == "box":
        return f'<box size="{n.three(shape.dims)}"/>'
    if shape.kind == "cylinder":
        return f'<cylinder radius="{n.one(shape.dims[0])}" length="{n.one(shape.dims[1])}"/>'
    return f'<sphere radius="{n.one(shape.dims[0])}"/>'


def link_xml(name: str, inertial: tuple[float, np.ndarray, np.ndarray], visuals: Iterable[Visual],
             n: Numbers) -> list[str]:
    """A `<link>`: its inertial (mass, centre of mass, diagonal inertia), then each shape's visual and collision."""
    mass, com, diag = inertial
    lines = [f'  <link name="{name}">',
             "    <inertial>",
             f'      <origin xyz="{n.three(com, n.mass)}" rpy="0 0 0"/>',
             f'      <mass value="{n.one(mass, n.mass)}"/>',
             f'      <inertia ixx="{n.one(diag[0], n.inertia)}" ixy="0" ixz="0" '
             f'iyy="{n.one(diag[1], n.inertia)}" iyz="0" izz="{n.one(diag[2], n.inertia)}"/>',
             "    </inertial>"]
    for visual in visuals:
        shape = visual.shape
        origin = f'<origin xyz="{n.three(shape.xyz)}" rpy="{n.three(shape.rpy)}"/>'
        lines += ["    <visual>",
                  f"      {origin}",
                  f"      <geometry>{_geometry_xml(shape, n)}</geometry>",
                  f'      <material name="{visual.material}"><color rgba="{n.three(visual.rgba, n.colour)}"/></material>',
                  "    </visual>"]
        if visual.collision:
            lines += ["    <collision>",
                      f"      {origin}",
                      f"      <geometry>{_geometry_xml(shape, n)}</geometry>",
                      "    </collision>"]
    lines.append("  </link>")
    return lines


def joint_xml(joint: Joint, n: Numbers) -> list[str]:
    """A `<joint>`: parent, child, origin, and its axis, limit and mimic where it has them."""
    lines = [f'  <joint name="{joint.name}" type="{joint.type}">',
             f'    <parent link="{joint.parent}"/>',
             f'    <child link="{joint.child}"/>',
             f'    <origin xyz="{n.three(joint.xyz)}" rpy="{n.three(joint.rpy)}"/>']
    if joint.axis is not None:
        lines.append(f'    <axis xyz="{n.three(joint.axis)}"/>')
    if joint.limit is not None:
        lim = joint.limit
        bounds = ""
        if lim.lower is not None and lim.upper is not None:
            bounds = f'lower="{n.one(lim.lower)}" upper="{n.one(lim.upper)}" '
        lines.append(f'    <limit {bounds}effort="{n.one(lim.effort)}" velocity="{n.one(lim.velocity)}"/>')
    if joint.mimic is not None:
        lines.append(f'    <mimic joint="{joint.mimic}" multiplier="1" offset="0"/>')
    lines.append("  </joint>")
    return lines


def check_tree(root: str, joints: Sequence[Joint], links: Iterable[str]) -> None:
    """Fail loudly on a broken table: every link used once, parents defined first."""
    seen = {root}
    for joint in joints:
        if joint.parent not in seen:
            raise ValueError(f"{joint.name}: parent {joint.parent} not defined before use")
        if joint.child in seen:
            raise ValueError(f"{joint.name}: child {joint.child} already in the tree")
        seen.add(joint.child)
    if seen != set(links):
        raise ValueError(f"links without joints or joints without links: {seen ^ set(links)}")


def urdf_text(name: str, comment: Sequence[str], root: str, joints: Sequence[Joint],
              link: Callable[[str], list[str]], n: Numbers) -> str:
    """The whole URDF, one element a line (PyBullet cannot parse a URDF written on one line): the root link, then
    each joint followed by its child link (`link(name)` writes one), so PyBullet numbers the joints in this order."""
    lines = ['<?xml version="1.0"?>', *comment, f'<robot name="{name}">']
    lines += link(root)
    for joint in joints:
        lines += joint_xml(joint, n)
        lines += link(joint.child)
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


# -- robots written from tables: the bundled PR2 and Fetch (resources/robots/*/generate.py) -----------------------

#: mass and inertia of links that are only coordinate frames
FRAME_MASS = 0.01
FRAME_INERTIA = 1e-5
HALF_PI = math.pi / 2
X_AXIS: Vec3 = (1.0, 0.0, 0.0)
Y_AXIS: Vec3 = (0.0, 1.0, 0.0)
Z_AXIS: Vec3 = (0.0, 0.0, 1.0)
NEG_Z_AXIS: Vec3 = (0.0, 0.0, -1.0)
#: rpy of the optical frames (x-forward camera frame -> z forward, x right, y down), as the real robots' files write it
OPTICAL_RPY: Vec3 = (-1.57079632679, 0.0, -1.57079632679)
ALONG_X: Vec3 = (0.0, HALF_PI, 0.0)  # rpy turning a cylinder's z axis onto x


@dataclass(frozen=True)
class Shape:
    """A primitive in link coordinates, coloured by a material's name; `collision=False` for one only drawn.

    `dims` is (sx, sy, sz) for a box, (radius, length) for a cylinder (whose axis is its local z, turned by `rpy`)
    and (radius,) for a sphere.
    """

    kind: str
    dims: tuple[float, ...]
    xyz: Vec3
    rpy: Vec3
    material: str
    collision: bool = True


@dataclass(frozen=True)
class Link:
    """A link; `mass=None` marks a frame-only link without geometry."""

    name: str
    mass: float | None = None
    shapes: tuple[Shape, ...] = ()


def box(lo: Vec3, hi: Vec3, material: str) -> Shape:
    """An axis-aligned box spanning the corners `lo` and `hi`."""
    size = tuple(h - low for low, h in zip(lo, hi))
    centre = tuple((low + h) / 2 for low, h in zip(lo, hi))
    return Shape("box", size, centre, ORIGIN, material)  # type: ignore[arg-type]  # three of each


def cylinder_x(radius: float, x0: float, x1: float, material: str, y: float = 0.0, z: float = 0.0) -> Shape:
    """A cylinder along the link's x axis from `x0` to `x1`."""
    return Shape("cylinder", (radius, x1 - x0), ((x0 + x1) / 2, y, z), ALONG_X, material)


def cylinder_z(radius: float, z0: float, z1: float, material: str, x: float = 0.0, y: float = 0.0) -> Shape:
    """A cylinder along the link's z axis from `z0` to `z1`."""
    return Shape("cylinder", (radius, z1 - z0), (x, y, (z0 + z1) / 2), ORIGIN, material)


def link_inertial(link: Link) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, diagonal inertia) of a link of uniform density.

    The solids are the collision shapes, or the drawn ones for a link that has only those (the Fetch's wheels); a
    link without mass or shapes gets a token inertia.
    """
    solids = [s for s in link.shapes if s.collision] or list(link.shapes)
    if link.mass is None or not solids:
        return FRAME_MASS if link.mass is None else link.mass, np.zeros(3), np.full(3, FRAME_INERTIA)
    volumes = np.array([volume(s) for s in solids])
    masses = link.mass * volumes / volumes.sum()
    com, diag = inertia_about(solids, masses, link.mass)
    return link.mass, com, diag


def table_urdf(name: str, comment: Sequence[str], root: str, joints: Sequence[Joint], links: dict[str, Link],
               materials: dict[str, tuple[float, float, float, float]]) -> str:
    """The URDF of a robot written from tables, its numbers to 12 significant digits (6 for masses, inertias and
    colours); ValueError for a broken tree."""
    check_tree(root, joints, links)
    numbers = Numbers(general, 12, 6, 6, 6)

    def link_text(link_name: str) -> list[str]:
        link = links[link_name]
        visuals = [Visual(s, s.material, materials[s.material], s.collision) for s in link.shapes]
        return link_xml(link.name, link_inertial(link), visuals, numbers)

    return urdf_text(name, comment, root, joints, link_text, numbers)


def generator_main(doc: str, default_output: Path, build: Callable[[], str], argv: Sequence[str] | None) -> None:
    """A generator script's command line: write the URDF to `--output` (default: `default_output`)."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--output", type=Path, default=default_output,
                        help=f"where to write the URDF (default: {default_output.name} next to this script)")
    args = parser.parse_args(argv)
    args.output.write_text(build(), encoding="utf-8", newline="\n")
    print(f"wrote {args.output}")
