"""The parts of an object as the world indexed them: its joints, its visual shapes, what it is attached to.

Plain frozen records, read once from PyBullet when a model is loaded (`Object._index_model`), so that every layer
above reads joints and shapes without asking PyBullet again; and the errors and warnings about them.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import pybullet as p

from .pose import Quat, Vec3
from .urdf_check import JointRange

if TYPE_CHECKING:
    from .object import Object


class MissingMeshWarning(UserWarning):
    """A URDF names mesh files that do not exist; it was loaded without them."""


class JointLimitError(ValueError):
    """A joint value outside the joint's limits."""


@dataclass(frozen=True)
class Attachment:
    """`child` follows `parent`: the child link keeps `transform` relative to the parent link."""

    parent: Object
    child: Object
    parent_link: int
    child_link: int
    transform: tuple[Vec3, Quat]


_IDENTITY: tuple[Vec3, Quat] = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


@dataclass(frozen=True)
class Joint(JointRange):
    """A joint as PyBullet indexed it: the joint's index is also its child link's index.

    The constants a kinematic chain of this body needs, read once when the model is indexed, in
    PyBullet's convention (it chains centre-of-mass frames): `parent_frame` leads from the parent
    link's centre of mass to the joint origin, turned like the child's centre-of-mass frame at
    joint position 0; `axis` is given in that frame, as PyBullet reports it (not normalised);
    `inertial_frame` is the child's centre-of-mass frame in its URDF link frame.
    """

    index: int
    name: str
    type: str  # revolute, prismatic, continuous, fixed, ...
    lower: float
    upper: float
    child_link: str
    parent_index: int = -1  # the parent link's index (-1: the base)
    axis: Vec3 = (0.0, 0.0, 0.0)
    parent_frame: tuple[Vec3, Quat] = _IDENTITY
    inertial_frame: tuple[Vec3, Quat] = _IDENTITY


@dataclass(frozen=True)
class VisualShape:
    """One visual shape of a link, as drawn: kind, size, colour, and pose in the link's URDF frame.

    `kind` is box (`size`: full extents), sphere (`radius`), cylinder or capsule (`radius`, `length`
    along the z axis), mesh (`mesh_file`, `scale`) or plane.
    """

    link: int  # -1: the base
    kind: str
    origin: tuple[Vec3, Quat]
    rgba: tuple[float, float, float, float]
    size: Vec3 = (0.0, 0.0, 0.0)
    radius: float = 0.0
    length: float = 0.0
    mesh_file: Path | None = None
    scale: Vec3 = (1.0, 1.0, 1.0)


#: PyBullet's geometry and joint type codes, by name
SHAPE_KINDS = {p.GEOM_SPHERE: "sphere", p.GEOM_BOX: "box", p.GEOM_CYLINDER: "cylinder", p.GEOM_MESH: "mesh",
                p.GEOM_PLANE: "plane", p.GEOM_CAPSULE: "capsule"}


JOINT_TYPES = {p.JOINT_REVOLUTE: "revolute", p.JOINT_PRISMATIC: "prismatic", p.JOINT_FIXED: "fixed",
                p.JOINT_SPHERICAL: "spherical", p.JOINT_PLANAR: "planar", p.JOINT_POINT2POINT: "point2point",
                p.JOINT_GEAR: "gear"}
