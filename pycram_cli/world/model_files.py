"""Turning the files a user names into something PyBullet loads.

- STL/OBJ meshes become a generated one-link URDF (with colour and inertia), written
  to the cache folder, never next to the user's file.
- URDFs with ROS `package://` URIs, or with mesh files that are missing, are loaded
  from a patched copy in the cache folder: URIs resolved in the URDF's own folders (upwards) and
  through ROS_PACKAGE_PATH, elements whose mesh is missing dropped (reported), mesh names that
  need escaping given safe links.
- Every URDF is checked for what PyBullet needs first (`urdf_check`): a ModelError names the
  element that is wrong.
- `describe_urdf` reads link and joint names and limits straight from the XML, so that
  world files can be validated without starting a simulation.
"""
from __future__ import annotations

import functools
import hashlib
import math
import os
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from xml.sax.saxutils import escape as xml_escape

import pybullet_data

from ..files import read_bytes, write_atomic
from ..limits import MAX_MODEL_BYTES
from ..paths import cache_dir, resources_dir
from .meshes import PIECES_VERSION, inertial_for, is_binary_stl, obj_objects, read_mesh, write_binary_stl, write_pieces_obj
from .urdf_check import JointRange, ModelError, check_structure, suffix_problem

MESH_SUFFIXES = {".stl", ".obj"}
#: characters a path may have to be written into a URDF as it is (others go through a link with a safe name)
_SAFE_PATH = re.compile(r"[A-Za-z0-9_./+-]+")


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
    name = _safe_stem(mesh_path)  # written into XML and a file name
    target = cache_dir() / "meshes" / f"{name}-{key}.urdf"
    if target.exists():
        return target
    mesh = read_mesh(mesh_path)
    inertial = inertial_for(mesh, mass=mass)
    mesh_path = safe_path(mesh_path)
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
        <mesh filename="{_attribute(mesh_path)}" scale="1 1 1"/>
      </geometry>
      <material name="{name}_color">
        <color rgba="{rgba[0]} {rgba[1]} {rgba[2]} {rgba[3] if len(rgba) > 3 else 1.0}"/>
      </material>
    </visual>
    <collision>
      <geometry>
        <mesh filename="{_attribute(collision_path)}" scale="1 1 1"/>
      </geometry>
    </collision>
  </link>
</robot>
"""  # noqa: E501 (the URDF as written, line for line)
    write_atomic(target, text)
    return target


@functools.lru_cache(maxsize=256)
def _package_name(folder: Path) -> str | None:
    """The <name> in a folder's package.xml, or None (no manifest, or one that cannot be read); read once per
    folder, as every package:// URI of a model looks at the same folders."""
    manifest = folder / "package.xml"
    try:
        if not manifest.is_file():
            return None
        name = ET.fromstring(read_bytes(manifest, 1024 * 1024, "package manifest")).findtext("name")
    except (OSError, ValueError, ET.ParseError):
        return None
    return name.strip() if name else None


def _package_roots(package: str, urdf_dir: Path) -> list[Path]:
    """Candidate folders for ROS package `package`, in search order: the URDF's own folders upwards (a folder
    named after the package, or whose package.xml names it, or one holding a folder of that name), then
    ROS_PACKAGE_PATH."""
    found: list[Path] = []
    for folder in [urdf_dir, *urdf_dir.parents]:
        if folder.name == package or _package_name(folder) == package:
            found.append(folder)
        if (folder / package).is_dir():
            found.append(folder / package)
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
    return found


def resolve_uri(uri: str, urdf_dir: Path) -> Path | None:
    """The file a mesh URI names (package://, file://, relative or absolute), or None.

    ModelError for a package:// URI whose path leaves its package (`package://x/../..`)."""
    if uri.startswith("package://"):
        package, _, rest = uri[len("package://") :].partition("/")
        inside = os.path.normpath(rest or ".")
        if not package or inside == ".." or inside.startswith(("../", "/")):
            raise ModelError(f"mesh '{uri}' leaves its package '{package}'")
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


def _meshes(tree: ET.Element) -> list[tuple[ET.Element, ET.Element, ET.Element]]:
    """(parent, visual or collision, mesh) for every mesh a model names."""
    return [(parent, element, mesh) for parent in tree.iter() for element in parent
            if element.tag in ("visual", "collision") for mesh in element.iter("mesh")]


def _resolve_mesh(uri: str, urdf_dir: Path) -> Path | None:
    """The mesh file a URI names, or None when it is missing; ModelError when PyBullet could not read it."""
    if not uri:
        raise ModelError("a <mesh> has no filename")
    resolved = resolve_uri(uri, urdf_dir)
    if resolved is not None:
        problem = suffix_problem(resolved)
        if problem is not None:
            raise ModelError(f"mesh '{uri}': {problem}")
    return resolved


def safe_path(path: Path) -> Path:
    """`path`, or a link to it in the cache whose name has no character that needs escaping (quotes, <, &,
    spaces, newlines, bytes that are not UTF-8), so that it can be written into a URDF and handed to PyBullet."""
    text = str(path)
    if _SAFE_PATH.fullmatch(text):
        return path
    suffix = path.suffix.lower() if _SAFE_PATH.fullmatch(path.suffix) else ""
    link = cache_dir() / "links" / f"{_digest(os.fsencode(path))}{suffix}"
    if not link.is_symlink() or os.readlink(link) != text:
        link.parent.mkdir(parents=True, exist_ok=True)
        temporary = link.with_name(f"{link.name}.{os.getpid()}.tmp")
        temporary.unlink(missing_ok=True)
        temporary.symlink_to(path)
        os.replace(temporary, link)
    return link


def _safe_stem(path: Path) -> str:
    """A file's stem with every character that would need escaping replaced (for names pycram writes)."""
    return re.sub(r"[^A-Za-z0-9_.+-]", "_", path.stem) or "model"


def _attribute(path: Path) -> str:
    """A path as the value of an XML attribute (the cache folder itself may have any name)."""
    return xml_escape(str(path), {'"': "&quot;"})


@dataclass
class PreparedUrdf:
    path: Path
    missing: list[str] = field(default_factory=list)


def _read_checked(urdf: Path) -> ET.Element:
    """A URDF's XML, checked for what PyBullet needs (ModelError naming the element otherwise)."""
    tree = ET.fromstring(read_bytes(urdf, MAX_MODEL_BYTES, "model file"))
    check_structure(tree)
    return tree


def prepare_urdf(urdf: Path) -> PreparedUrdf:
    """The URDF to hand to PyBullet, patched into the cache when it needs to be: mesh URIs resolved, meshes that
    are missing dropped (listed in `missing`), mesh names that need escaping replaced by safe links."""
    urdf = urdf.resolve()
    tree = _read_checked(urdf)
    meshes = [(parent, element, mesh, _resolve_mesh(mesh.get("filename", ""), urdf.parent))
              for parent, element, mesh in _meshes(tree)]
    missing = sorted({mesh.get("filename", "") for _, _, mesh, resolved in meshes if resolved is None})
    needs_patch = bool(missing) or any(mesh.get("filename", "").startswith(("package://", "file://"))
                                       or not _SAFE_PATH.fullmatch(mesh.get("filename", "")) for _, _, mesh, _ in meshes)
    if not needs_patch and _SAFE_PATH.fullmatch(str(urdf)):
        return PreparedUrdf(urdf)
    stat = urdf.stat()
    key = _digest(str(urdf), stat.st_size, stat.st_mtime_ns, os.environ.get("ROS_PACKAGE_PATH", ""), 2)
    for parent, element, mesh, resolved in meshes:
        if resolved is None:
            if element in list(parent):
                parent.remove(element)
        else:
            mesh.set("filename", str(safe_path(resolved.absolute())))
    target = cache_dir() / "urdf" / f"{_safe_stem(urdf)}-{key}.urdf"
    ET.indent(tree)
    write_atomic(target, ET.tostring(tree, encoding="unicode"))
    return PreparedUrdf(target, missing)


@dataclass
class JointInfo(JointRange):
    name: str
    type: str
    lower: float
    upper: float


@dataclass
class ModelInfo:
    """Names found in a model file without loading it into a simulation."""

    links: list[str]
    joints: dict[str, JointInfo]
    missing: list[str] = field(default_factory=list)  # mesh files named but not found (loaded without them)


def describe_urdf(urdf: Path) -> ModelInfo:
    """A URDF's links and joints, after the checks loading makes (ModelError naming the element otherwise)."""
    tree = _read_checked(urdf)
    missing = sorted({mesh.get("filename", "") for _, _, mesh in _meshes(tree)
                      if _resolve_mesh(mesh.get("filename", ""), urdf.resolve().parent) is None})
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
    return ModelInfo(links, joints, missing)


def describe_model(path: Path) -> ModelInfo:
    """The names in a model file (a mesh is read too, so that a broken one is found before anything runs).

    Remembered per file as long as it is unchanged (same size and modification time)."""
    info = os.stat(path)
    if info.st_size > MAX_MODEL_BYTES:
        raise ValueError(f"the file is larger than {MAX_MODEL_BYTES // (1 << 20)} MiB")
    return _describe(str(path), info.st_mtime_ns, info.st_size, os.environ.get("ROS_PACKAGE_PATH", ""))


@functools.lru_cache(maxsize=64)
def _describe(path: str, mtime_ns: int, size: int, ros_package_path: str) -> ModelInfo:
    model = Path(path)
    if model.suffix.lower() in MESH_SUFFIXES:
        read_mesh(model)
        return ModelInfo([model.stem], {})
    return describe_urdf(model)
