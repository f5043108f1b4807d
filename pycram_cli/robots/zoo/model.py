"""The zoo robot's model and the small tools every part of the generator shares.

What: the constants the robots are sized by (the kitchen's counter, the park height, the grasps), the model
(`Shape`, `Link`, `Joint`, `Gripper`, `Camera`, `Head`, `ZooRobot`), fixed-precision numbers (`fmt`: one seed gives
byte-identical files), seeded names, and the `Tree` links and joints are added to.
Why here: the arm, the park search, the builder and the writers all speak this model.
"""
from __future__ import annotations

import math
import random
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from ..urdf_writer import fixed

Vec3 = tuple[float, float, float]

ORIGIN: Vec3 = (0.0, 0.0, 0.0)
X_AXIS: Vec3 = (1.0, 0.0, 0.0)
Z_AXIS: Vec3 = (0.0, 0.0, 1.0)
ALONG_X: Vec3 = (0.0, math.pi / 2, 0.0)  # rpy turning a cylinder's z axis onto x
ALONG_Y: Vec3 = (math.pi / 2, 0.0, 0.0)  # ... onto y
OPTICAL_RPY: Vec3 = (-math.pi / 2, 0.0, -math.pi / 2)  # x-forward frame -> z forward, x right, y down
FRAME_MASS = 0.01
FRAME_INERTIA = 1e-5
COUNTER_TOP = 0.85  # the kitchen's counter height the arms are sized for (m)
PARK_HEIGHT = 1.1  # the parked arm keeps above this where it can (m): over the counters and what stands on them
CAMERA_KINDS = ("head", "mast", "wrist")
GRIPPER_KINDS = ("two_prismatic", "one_prismatic", "two_revolute")
#: quaternions (x, y, z, w) of the tool relative to the base, as the PR2's and the Fetch's
#: (the tool's +x points out of the gripper and equals the base's +x with the arm at zero)
GRASPS: dict[str, tuple[float, float, float, float]] = {
    "front": (0.0, 0.0, 0.0, 1.0),
    "top": (0.0, 0.7071068, 0.0, 0.7071068),
    "left": (0.0, 0.0, -0.7071068, 0.7071068),
    "right": (0.0, 0.0, 0.7071068, 0.7071068),
}
COLOURS = ((0.85, 0.85, 0.87, 1.0), (0.2, 0.35, 0.7, 1.0), (0.75, 0.3, 0.15, 1.0), (0.2, 0.55, 0.3, 1.0),
           (0.3, 0.3, 0.33, 1.0), (0.9, 0.7, 0.1, 1.0))
BLACK = (0.08, 0.08, 0.09, 1.0)


# -- the model -----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Shape:
    """A primitive in link coordinates: box (sx, sy, sz), cylinder (radius, length) along its z, sphere (radius,)."""

    kind: str
    dims: tuple[float, ...]
    xyz: Vec3 = ORIGIN
    rpy: Vec3 = ORIGIN
    rgba: tuple[float, float, float, float] = COLOURS[0]


@dataclass(frozen=True)
class Link:
    """A link; `density` None marks a frame-only link (no geometry, a token inertial)."""

    name: str
    shapes: tuple[Shape, ...] = ()
    density: float | None = None


@dataclass(frozen=True)
class Joint:
    """A joint; `lower`/`upper` None for continuous and fixed joints."""

    name: str
    type: str
    parent: str
    child: str
    xyz: Vec3 = ORIGIN
    rpy: Vec3 = ORIGIN
    axis: Vec3 | None = None
    lower: float | None = None
    upper: float | None = None
    effort: float = 50.0
    velocity: float = 1.0


@dataclass(frozen=True)
class Gripper:
    kind: str  # one of GRIPPER_KINDS
    joints: tuple[str, ...]
    open: float
    closed: float
    max_width: float
    finger_height: float


@dataclass(frozen=True)
class Camera:
    kind: str  # one of CAMERA_KINDS
    frame: str
    horizontal_fov: float
    vertical_fov: float
    near: float = 0.05
    far: float = 6.0


@dataclass(frozen=True)
class Head:
    pan_joint: str
    tilt_joint: str
    pan_link: str
    tilt_link: str
    tilt_down: float  # the tilt joint value that looks 0.45 rad down (its axis' sign is seeded)


@dataclass(frozen=True)
class ZooRobot:
    """One generated robot: its model (links, joints) and what its description says about it."""

    seed: int
    name: str
    root_link: str
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    base_shape: str  # "box" or "cylinder"
    base_radius: float  # half-width of the box, radius of the cylinder (m)
    base_top: float  # height of the base body's top (m)
    torso_joint: str | None
    torso_default: float
    shoulder_height: float  # of the shoulder's pitch axis, torso at its default (m)
    arm_name: str
    arm_kinds: tuple[str, ...]  # pan / pitch / roll / prismatic, shoulder to wrist
    arm_joints: tuple[str, ...]
    arm_links: tuple[str, ...]
    tool_frame: str
    palm_link: str
    gripper: Gripper
    camera: Camera
    head: Head | None
    park: tuple[float, ...]
    weak: bool  # sized too short for a top grasp over the counter from 0.55 m
    grasps: dict[str, tuple[float, float, float, float]] = field(default_factory=lambda: dict(GRASPS))

    def joint(self, name: str) -> Joint:
        """The model's joint of that name."""
        return next(j for j in self.joints if j.name == name)


# -- numbers ----------------------------------------------------------------------------------------------------


fmt = fixed  # a stable short number: fixed precision, no '-0'


def fmt3(values: Iterable[float], digits: int = 6) -> str:
    return " ".join(fmt(v, digits) for v in values)


def seeded(rng: random.Random, lo: float, hi: float, digits: int = 3) -> float:
    """A seeded uniform number, rounded (so the files and the model agree exactly)."""
    return round(rng.uniform(lo, hi), digits)


# -- names -------------------------------------------------------------------------------------------------------

#: word for each part, in three vocabularies; a seed picks one (and a prefix), so that no name is the PR2's or Fetch's
VOCABULARIES: tuple[dict[str, str], ...] = (
    {"pan": "shoulder_yaw", "pitch1": "shoulder_pitch", "pitch2": "elbow_pitch", "pitch3": "wrist_pitch",
     "roll_upper": "upper_arm_twist", "roll_fore": "forearm_twist", "roll_wrist": "wrist_twist",
     "prism_upper": "upper_arm_slide", "prism_fore": "forearm_slide"},
    {"pan": "j1_turn", "pitch1": "j2_lift", "pitch2": "j3_bend", "pitch3": "j4_tip",
     "roll_upper": "j2b_spin", "roll_fore": "j3b_spin", "roll_wrist": "j5_spin",
     "prism_upper": "j2b_extend", "prism_fore": "j3b_extend"},
    {"pan": "azimuth", "pitch1": "boom", "pitch2": "stick", "pitch3": "nod",
     "roll_upper": "boom_roll", "roll_fore": "stick_roll", "roll_wrist": "hand_roll",
     "prism_upper": "boom_telescope", "prism_fore": "stick_telescope"},
)
ARM_NAMES = ("arm", "manipulator", "main", "right")


@dataclass(frozen=True)
class Names:
    """A seed's naming style: `<prefix>_<word><suffix>` for joints and links."""

    prefix: str
    joint_suffix: str
    link_suffix: str
    words: dict[str, str]

    def joint(self, part: str) -> str:
        return f"{self.prefix}_{self.words.get(part, part)}{self.joint_suffix}"

    def link(self, part: str) -> str:
        return f"{self.prefix}_{self.words.get(part, part)}{self.link_suffix}"

    def frame(self, part: str) -> str:
        return f"{self.prefix}_{part}"


def seeded_names(rng: random.Random, seed: int) -> Names:
    """A prefix with the seed in it (`zr3`), a suffix style and a vocabulary."""
    letters = rng.choice(("zr", "zq", "zk", "zv", "zx"))
    joint_suffix, link_suffix = rng.choice((("_joint", "_link"), ("_j", ""), ("", "_lk")))
    return Names(f"{letters}{seed}", joint_suffix, link_suffix, rng.choice(VOCABULARIES))


# -- the builder ------------------------------------------------------------------------------------------------


class Tree:
    """Links and joints in the order they are written (parents first)."""

    def __init__(self, root: Link) -> None:
        self.links: list[Link] = [root]
        self.joints: list[Joint] = []

    def add(self, joint: Joint, link: Link) -> str:
        if joint.child != link.name or joint.parent not in {known.name for known in self.links}:
            raise ValueError(f"{joint.name}: broken tree at {link.name}")
        self.joints.append(joint)
        self.links.append(link)
        return link.name

    def reshape(self, name: str, shapes: tuple[Shape, ...]) -> None:
        """Give a link added before its shapes were known (the palm) its shapes."""
        index = next(i for i, link in enumerate(self.links) if link.name == name)
        self.links[index] = Link(name, shapes, self.links[index].density)


def box(lo: Sequence[float], hi: Sequence[float], rgba=COLOURS[0]) -> Shape:
    """An axis-aligned box spanning the corners lo and hi."""
    return Shape("box", tuple(round(h - low, 6) for low, h in zip(lo, hi)),
                 tuple(round((low + h) / 2, 6) for low, h in zip(lo, hi)), ORIGIN, rgba)  # type: ignore[arg-type]


def tube_x(radius: float, x0: float, x1: float, rgba=COLOURS[0]) -> Shape:
    """A cylinder along the link's x axis from x0 to x1."""
    return Shape("cylinder", (radius, round(x1 - x0, 6)), (round((x0 + x1) / 2, 6), 0.0, 0.0), ALONG_X, rgba)

