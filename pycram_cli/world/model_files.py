"""Turning the files a user names into something PyBullet loads.

- STL/OBJ meshes become a generated one-link URDF (with colour and inertia), written
  to the cache folder, never next to the user's file.
- URDFs with ROS `package://` URIs, or with mesh files that are missing, are loaded
  from a patched copy in the cache folder: URIs resolved through ROS_PACKAGE_PATH and
  package folders beside the URDF, elements whose mesh is missing dropped (reported).
- `describe_urdf` reads link and joint names and limits straight from the XML, so that
  world files can be validated without starting a simulation.
"""
from __future__ import annotations

import functools
import hashlib
import math
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import pybullet_data

from ..files import read_bytes, write_atomic
from ..limits import MAX_MODEL_BYTES
from ..paths import cache_dir, resources_dir
from .meshes import PIECES_VERSION, inertial_for, is_binary_stl, obj_objects, read_mesh, write_binary_stl, write_pieces_obj

MESH_SUFFIXES = {".stl", ".obj"}


def simulator_models_dir() -> Path:
    """PyBullet's bundled models folder (plane.urdf, ...), a last place to look for model files."""
    return Path(pybullet_data.getDataPath())


def find_model_file(path: str | Path) -> Path:
    """The model file a name stands for, searched like a world file's `file:` — as given (relative to the current
    folder), then in pycram's bundled resources, then in PyBullet's models — so `Object(..., "plane.urdf")` finds
    PyBullet's plane as the design's scripts expect. FileNotFoundError naming the places looked in otherwise."""
    given = Path(os.path.expanduser(str(path)))
    if given.exists() or given.is_absolute():
        if not given.exists():
            raise FileNotFoundError(f"file not found: {given}")
        return given
    places = [resources_dir(), simulator_models_dir()]
    for folder in places:
        if (folder / given).is_file():
            return (folder / given).resolve()
    raise FileNotFoundError(f"file not found: {given} (looked in the current folder, {', '.join(str(p) for p in places)})")


def _digest(*parts: object) -> str:
    h = hashlib.sha1()
    for part in parts:
        h.update(repr(part).encode())
    return h.hexdigest()[:16]


def mesh_urdf(mesh_path: Path, color: tuple[float, float, float, float] | None, mass: float | None = None) -> Path:
    """A one-link URDF wrapping `mesh_path`, cached by the mesh's content and the colour.

    PyBullet collides a mesh of a body with mass as its convex hull, which fills a bowl or a cup;
    a hollow mesh (`Mesh.is_hollow`) given as one piece therefore collides as convex pieces of its
    surface instead (`Mesh.convex_pieces`, written beside the URDF in the cache), so that its
    inside stays empty. An OBJ of several objects is already pieces (PyBullet takes each one's hull).
    """
    mesh_path = mesh_path.resolve()
    rgba = tuple(color) if color is not None else (0.8, 0.8, 0.8, 1.0)
    stat = mesh_path.stat()
    key = _digest(str(mesh_path), stat.st_size, stat.st_mtime_ns, rgba, mass, 3, PIECES_VERSION)
    target = cache_dir() / "meshes" / f"{mesh_path.stem}-{key}.urdf"
    if target.exists():
        return target
    mesh = read_mesh(mesh_path)
    inertial = inertial_for(mesh, mass=mass)
    name = mesh_path.stem
    collision_path = mesh_path
    if mesh_path.suffix.lower() == ".stl" and not is_binary_stl(mesh_path):
        # PyBullet reads binary STL only: hand it a binary copy of an ASCII file
        binary = target.with_suffix(".stl")
        target.parent.mkdir(parents=True, exist_ok=True)
        write_binary_stl(mesh, binary)
        mesh_path = collision_path = binary
    if mesh.is_hollow() and obj_objects(mesh_path) <= 1:
        collision_path = target.with_suffix(".pieces.obj")
        target.parent.mkdir(parents=True, exist_ok=True)
        write_pieces_obj(mesh.convex_pieces(), collision_path)
    text = f"""<?xml version="1.0"?>
<robot name="{name}">
  <link name="{name}">
    <inertial>
      <origin xyz="{inertial.origin[0]:.6f} {inertial.origin[1]:.6f} {inertial.origin[2]:.6f}" rpy="0 0 0"/>
      <mass value="{inertial.mass:.6f}"/>
      <inertia ixx="{inertial.diagonal[0]:.8f}" ixy="0" ixz="0" iyy="{inertial.diagonal[1]:.8f}" iyz="0" izz="{inertial.diagonal[2]:.8f}"/>
    </inertial>
    <visual>
      <geometry>
        <mesh filename="{mesh_path}" scale="1 1 1"/>
      </geometry>
      <material name="{name}_color">
        <color rgba="{rgba[0]} {rgba[1]} {rgba[2]} {rgba[3] if len(rgba) > 3 else 1.0}"/>
      </material>
    </visual>
    <collision>
      <geometry>
        <mesh filename="{collision_path}" scale="1 1 1"/>
      </geometry>
    </collision>
  </link>
</robot>
"""
    write_atomic(target, text)
    return target


def _package_roots(package: str, urdf_dir: Path) -> list[Path]:
    """Candidate folders for ROS package `package`, in search order."""
    found: list[Path] = []
    for entry in filter(None, os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep)):
        root = Path(entry)
        if root.name == package and root.is_dir():
            found.append(root)
        if (root / package).is_dir():
            found.append(root / package)
        if root.is_dir():
            for manifest in root.glob("*/*/package.xml"):
                if manifest.parent.name == package:
                    found.append(manifest.parent)
    for parent in [urdf_dir, *urdf_dir.parents][:3]:
        if (parent / package).is_dir():
            found.append(parent / package)
    return found


def resolve_uri(uri: str, urdf_dir: Path) -> Path | None:
    """The file a mesh URI names (package://, file://, relative or absolute), or None."""
    if uri.startswith("package://"):
        package, _, rest = uri[len("package://") :].partition("/")
        for root in _package_roots(package, urdf_dir):
            candidate = root / rest
            if candidate.exists():
                return candidate
        return None
    if uri.startswith("file://"):
        uri = uri[len("file://") :]
    path = Path(uri)
    if not path.is_absolute():
        path = urdf_dir / path
    return path if path.exists() else None


@dataclass
class PreparedUrdf:
    path: Path
    missing: list[str] = field(default_factory=list)


def prepare_urdf(urdf: Path) -> PreparedUrdf:
    """The URDF to hand to PyBullet, patched into the cache when it needs to be."""
    urdf = urdf.resolve()
    text = read_bytes(urdf, MAX_MODEL_BYTES, "model file").decode("utf-8", errors="replace")
    tree = ET.fromstring(text)
    meshes = [(parent, el) for parent in tree.iter() for el in parent if el.tag in ("visual", "collision")]
    needs_patch = "package://" in text or "file://" in text
    missing: list[str] = []
    for parent, element in meshes:
        for mesh in element.iter("mesh"):
            uri = mesh.get("filename", "")
            resolved = resolve_uri(uri, urdf.parent)
            if resolved is None:
                missing.append(uri)
                needs_patch = True
    if not needs_patch:
        return PreparedUrdf(urdf)
    stat = urdf.stat()
    key = _digest(str(urdf), stat.st_size, stat.st_mtime_ns, os.environ.get("ROS_PACKAGE_PATH", ""), 1)
    for parent, element in meshes:
        drop = False
        for mesh in element.iter("mesh"):
            resolved = resolve_uri(mesh.get("filename", ""), urdf.parent)
            if resolved is None:
                drop = True
            else:
                mesh.set("filename", str(resolved))
        if drop:
            parent.remove(element)
    target = cache_dir() / "urdf" / f"{urdf.stem}-{key}.urdf"
    ET.indent(tree)
    write_atomic(target, ET.tostring(tree, encoding="unicode"))
    return PreparedUrdf(target, sorted(set(missing)))


@dataclass
class JointInfo:
    name: str
    type: str
    lower: float
    upper: float

    @property
    def movable(self) -> bool:
        return self.type in ("revolute", "prismatic", "continuous")

    @property
    def limited(self) -> bool:
        return self.type in ("revolute", "prismatic") and self.lower <= self.upper


@dataclass
class ModelInfo:
    """Names found in a model file without loading it into a simulation."""

    links: list[str]
    joints: dict[str, JointInfo]


def describe_urdf(urdf: Path) -> ModelInfo:
    tree = ET.fromstring(read_bytes(urdf, MAX_MODEL_BYTES, "model file"))
    links = [link.get("name", "") for link in tree.findall("link")]
    joints: dict[str, JointInfo] = {}
    for joint in tree.findall("joint"):
        limit = joint.find("limit")
        lower = float(limit.get("lower", 0.0)) if limit is not None else 0.0
        upper = float(limit.get("upper", 0.0)) if limit is not None else 0.0
        kind = joint.get("type", "fixed")
        if kind == "continuous":
            lower, upper = -math.inf, math.inf
        joints[joint.get("name", "")] = JointInfo(joint.get("name", ""), kind, lower, upper)
    return ModelInfo(links, joints)


def describe_model(path: Path) -> ModelInfo:
    """The names in a model file (a mesh is read too, so that a broken one is found before anything runs).

    Remembered per file as long as it is unchanged (same size and modification time)."""
    info = os.stat(path)
    if info.st_size > MAX_MODEL_BYTES:
        raise ValueError(f"the file is larger than {MAX_MODEL_BYTES // (1 << 20)} MiB")
    return _describe(str(path), info.st_mtime_ns, info.st_size)


@functools.lru_cache(maxsize=64)
def _describe(path: str, mtime_ns: int, size: int) -> ModelInfo:
    model = Path(path)
    if model.suffix.lower() in MESH_SUFFIXES:
        read_mesh(model)
        return ModelInfo([model.stem], {})
    return describe_urdf(model)
