"""What PyBullet needs of a URDF, checked on the XML before PyBullet reads it.

PyBullet answers a URDF it cannot load with "Cannot load URDF file" and nothing more, and
crashes the process on some (two roots, a link with two parents, two joints of one name).
`check_structure` finds those problems first and names the element that is wrong, so that
`validate` reports them as input errors and loading never reaches PyBullet with them.
"""
from __future__ import annotations

import math
import os
import stat
import xml.etree.ElementTree as ET
from collections.abc import Collection
from pathlib import Path

#: joint types PyBullet's URDF reader knows
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar", "spherical")
#: geometry elements PyBullet's URDF reader knows
GEOMETRIES = ("box", "cylinder", "sphere", "capsule", "mesh")
#: mesh file formats PyBullet reads (compared without case)
MESH_FILE_SUFFIXES = (".obj", ".stl", ".dae")


class JointRange:
    """What a joint's type says of its motion, for the joint records that have `type`, `lower` and `upper`."""

    type: str
    lower: float
    upper: float

    @property
    def movable(self) -> bool:
        return self.type in ("revolute", "prismatic", "continuous")

    @property
    def limited(self) -> bool:
        """Whether it moves between limits (`lower` <= `upper`; PyBullet gives a continuous joint lower > upper)."""
        return self.type in ("revolute", "prismatic") and self.lower <= self.upper


class ModelError(ValueError):
    """A model file PyBullet cannot load (or would crash on), naming the element that is wrong."""


def check_structure(root: ET.Element) -> None:
    """ModelError unless `root` is a <robot> whose links form one tree joined by well-formed joints."""
    if root.tag != "robot":
        raise ModelError(f"the root element is <{root.tag}>, not <robot>")
    if not root.get("name"):
        raise ModelError("<robot> has no name attribute")
    links = _link_names(root)
    parents = _joint_parents(root, links)
    _check_tree(links, parents)
    for link in root.findall("link"):
        _check_link(link)


def _new_name(element: ET.Element, seen: Collection[str]) -> str:
    """The name of a <link> or <joint>: ModelError when it has none or one already `seen`."""
    name = element.get("name")
    if not name:
        raise ModelError(f"a <{element.tag}> has no name attribute")
    if name in seen:
        raise ModelError(f"two {element.tag}s are named '{name}'")
    return name


def _link_names(root: ET.Element) -> list[str]:
    names: list[str] = []
    for link in root.findall("link"):
        names.append(_new_name(link, names))
    if not names:
        raise ModelError("the model has no <link>: PyBullet needs at least one")
    return names


def _joint_parents(root: ET.Element, links: list[str]) -> dict[str, tuple[str, str]]:
    """Each child link's (parent link, joint name)."""
    known = set(links)
    seen: set[str] = set()
    parents: dict[str, tuple[str, str]] = {}
    for joint in root.findall("joint"):
        name = _new_name(joint, seen)
        seen.add(name)
        kind = joint.get("type")
        if kind not in JOINT_TYPES:
            raise ModelError(f"joint '{name}': unknown type '{kind}' (one of {', '.join(JOINT_TYPES)})")
        ends = {}
        for end in ("parent", "child"):
            element = joint.find(end)
            if element is None or not element.get("link"):
                raise ModelError(f"joint '{name}' has no <{end} link=...>")
            if element.get("link") not in known:
                raise ModelError(f"joint '{name}': its {end} '{element.get('link')}' is not a link of the model")
            ends[end] = element.get("link", "")
        if ends["parent"] == ends["child"]:
            raise ModelError(f"joint '{name}' joins link '{ends['child']}' to itself")
        if ends["child"] in parents:
            raise ModelError(f"link '{ends['child']}' is the child of two joints, '{parents[ends['child']][1]}' and '{name}'")
        parents[ends["child"]] = (ends["parent"], name)
        _check_limits(joint, name, kind)
    return parents


def _check_limits(joint: ET.Element, name: str, kind: str) -> None:
    limit = joint.find("limit")
    if limit is None:
        if kind in ("revolute", "prismatic"):
            raise ModelError(f"joint '{name}' ({kind}) has no <limit>")
        return
    for attribute in ("lower", "upper", "effort", "velocity"):
        _number(limit, attribute, f"joint '{name}'")


def _check_tree(links: list[str], parents: dict[str, tuple[str, str]]) -> None:
    for start in links:
        path: list[str] = []
        link = start
        while link in parents:
            parent, joint = parents[link]
            if joint in path:
                cycle = path[path.index(joint):]
                raise ModelError(f"the joints {', '.join(sorted(cycle))} form a cycle")
            path.append(joint)
            link = parent
    roots = [link for link in links if link not in parents]
    if len(roots) > 1:
        raise ModelError(f"links '{roots[0]}' and '{roots[1]}' are both roots (no joint has them as child): "
                         "PyBullet needs one tree of links")


def _check_link(link: ET.Element) -> None:
    name = link.get("name")
    mass = link.find("inertial/mass")
    if mass is not None:
        _number(mass, "value", f"link '{name}'", element="mass")
    inertia = link.find("inertial/inertia")
    if inertia is not None:
        for attribute in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
            _number(inertia, attribute, f"link '{name}'", element="inertia")
    for shape in (*link.findall("visual"), *link.findall("collision")):
        geometry = shape.find("geometry")
        if geometry is None or not any(geometry.find(kind) is not None for kind in GEOMETRIES):
            raise ModelError(f"link '{name}': <{shape.tag}> has no {', '.join(GEOMETRIES[:-1])} or {GEOMETRIES[-1]} "
                             "in its <geometry>")


def _number(node: ET.Element, attribute: str, owner: str, element: str = "limit") -> None:
    """ModelError unless `node`'s `attribute`, when given, is a finite number."""
    text = node.get(attribute)
    if text is None:
        return
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise ModelError(f'{owner}: <{element} {attribute}="{text}"> is not a finite number')


def suffix_problem(mesh: Path) -> str | None:
    """Why PyBullet cannot read an existing mesh file, or None."""
    try:
        mode = os.stat(mesh).st_mode
    except OSError as exc:
        return f"cannot be read ({exc.strerror})"
    if not stat.S_ISREG(mode):
        return "not a regular file (a folder, a device or a named pipe)"
    if mesh.suffix.lower() not in MESH_FILE_SUFFIXES:
        return "PyBullet reads .obj, .stl and .dae meshes"
    return None
