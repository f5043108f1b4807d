"""A seeded robot zoo: mobile pick-and-place robots nobody tuned pycram for, generated from a seed.

What
    `generate(seed)` builds a `ZooRobot`: a wheeled base (box or cylinder) whose wheels and
    casters have collision shapes touching the floor at exactly z = 0, with or without a
    prismatic torso, one arm of 5-7 joints (pan, three pitches and a wrist roll, plus roll
    and sometimes prismatic joints) mounted at a seeded height and offset, a gripper with one
    or two prismatic fingers (or two revolute ones) and a tool frame between the pads, and a
    camera on a pan/tilt head, fixed on the mast, or on the wrist. `write(robot, folder)`
    writes its URDF and its robot description (docs/robots.md); `write_world` writes the
    bundled kitchen with the zoo robot in place of the PR2.

Why
    The bundled PR2 and Fetch were written together with pycram and tuned for it (their
    wheels, for one, have no collision shapes). A zoo of robots described only as
    docs/robots.md says, with the properties real URDFs have (wheels on the floor, frame-only
    links without geometry, continuous joints, names of their own), shows whether pycram works
    on robots it has never seen, and where it fails, honestly or not.

Everything is deterministic: one seed gives byte-identical files (numbers are written with a
fixed precision). Only primitive shapes are used, so no meshes are needed. The arm's `park`
pose is found by a search of the arm's pan and pitch joints against a sphere cover of the
shapes, so that the arm is tucked over the base (or at most 0.2 m beside it), above its top at
every torso height, clear of the body and of itself and, where it can be, out of the body
camera's view of the counter in front.

    python -m pycram_cli.robots.zoo 0 1 2 --out /tmp/zoo
"""
from __future__ import annotations

import argparse
import math
import random
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Sequence

import numpy as np

from ..paths import worlds_dir

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


def fmt(value: float, digits: int = 6) -> str:
    """A stable short number: fixed precision, no '-0'."""
    text = f"{round(float(value), digits) + 0.0:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def fmt3(values: Iterable[float], digits: int = 6) -> str:
    return " ".join(fmt(v, digits) for v in values)


def _r(rng: random.Random, lo: float, hi: float, digits: int = 3) -> float:
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


def _names(rng: random.Random, seed: int) -> Names:
    """A prefix with the seed in it (`zr3`), a suffix style and a vocabulary."""
    letters = rng.choice(("zr", "zq", "zk", "zv", "zx"))
    joint_suffix, link_suffix = rng.choice((("_joint", "_link"), ("_j", ""), ("", "_lk")))
    return Names(f"{letters}{seed}", joint_suffix, link_suffix, rng.choice(VOCABULARIES))


# -- the builder ------------------------------------------------------------------------------------------------


class _Tree:
    """Links and joints in the order they are written (parents first)."""

    def __init__(self, root: Link) -> None:
        self.links: list[Link] = [root]
        self.joints: list[Joint] = []

    def add(self, joint: Joint, link: Link) -> str:
        if joint.child != link.name or joint.parent not in {l.name for l in self.links}:
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
    return Shape("box", tuple(round(h - l, 6) for l, h in zip(lo, hi)),
                 tuple(round((l + h) / 2, 6) for l, h in zip(lo, hi)), ORIGIN, rgba)  # type: ignore[arg-type]


def tube_x(radius: float, x0: float, x1: float, rgba=COLOURS[0]) -> Shape:
    """A cylinder along the link's x axis from x0 to x1."""
    return Shape("cylinder", (radius, round(x1 - x0, 6)), (round((x0 + x1) / 2, 6), 0.0, 0.0), ALONG_X, rgba)


@dataclass(frozen=True)
class _Body:
    """The seeded sizes of the base and column, in the floor frame of the root (z = 0 on the floor)."""

    shape: str
    radius: float
    top: float
    clearance: float
    column_x: float
    column_depth: float  # along x
    column_width: float  # along y
    torso_travel: float  # 0: no torso
    torso_default: float
    shoulder_height: float


def _body(rng: random.Random) -> _Body:
    """The base's and column's sizes; the shoulder stays at least 0.3 m above the base's top at every torso height."""
    shape = rng.choice(("box", "cylinder"))
    radius = _r(rng, 0.2, 0.35)
    top = _r(rng, 0.22, 0.38)
    clearance = _r(rng, 0.02, 0.05)
    depth = _r(rng, 0.12, 0.2)
    column_x = round(-radius * rng.uniform(0.2, 0.5), 3)
    width = _r(rng, 0.16, min(0.28, 1.6 * radius))
    travel = _r(rng, 0.3, 0.4) if rng.random() < 0.6 else 0.0
    shoulder = _r(rng, 0.72, 1.12)
    default = 0.0
    if travel:
        room = shoulder - top - 0.3  # the shoulder stays >= 0.3 m above the base top with the torso down
        default = round(min(travel * rng.uniform(0.4, 0.85), max(room, 0.0)), 2)
        shoulder = max(shoulder, round(top + 0.3 + default, 3))
    else:
        shoulder = max(shoulder, round(top + 0.3, 3))
    return _Body(shape, radius, top, clearance, column_x, depth, width, travel, default, shoulder)


# -- the robot ---------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _ArmPlan:
    """The arm's seeded layout and sizes, before it is built."""

    kinds: tuple[str, ...]  # per joint: pan, pitch1..3, roll_upper, roll_fore, roll_wrist, prism_upper, prism_fore
    upper: float  # shoulder pitch -> elbow pitch (m)
    fore: float  # elbow pitch -> wrist pitch (m)
    wrist: float  # wrist pitch -> wrist roll (m)
    palm: float  # wrist roll -> finger base (m)
    finger: float  # finger pad length (m)
    radius: float  # the upper arm's tube radius (m)
    pan_offset: tuple[float, float]  # pan axis -> shoulder pitch axis (forward, up)
    extension: float  # travel of a prismatic arm joint (m), 0 without
    weak: bool


ARM_LAYOUTS: dict[int, tuple[tuple[str, ...], ...]] = {
    5: (("pan", "pitch1", "pitch2", "pitch3", "roll_wrist"),),
    6: (("pan", "pitch1", "roll_upper", "pitch2", "pitch3", "roll_wrist"),
        ("pan", "pitch1", "pitch2", "roll_fore", "pitch3", "roll_wrist"),
        ("pan", "pitch1", "prism_upper", "pitch2", "pitch3", "roll_wrist")),
    7: (("pan", "pitch1", "roll_upper", "pitch2", "roll_fore", "pitch3", "roll_wrist"),
        ("pan", "pitch1", "prism_upper", "pitch2", "roll_fore", "pitch3", "roll_wrist"),
        ("pan", "pitch1", "roll_upper", "pitch2", "prism_fore", "pitch3", "roll_wrist")),
}


def _arm_plan(rng: random.Random, body: _Body, mount_x: float, mount_y: float) -> _ArmPlan:
    """Joint kinds and link lengths: long enough for a top grasp over the counter from 0.55-0.7 m (most seeds)."""
    count = rng.choice((5, 6, 7))
    kinds = rng.choice(ARM_LAYOUTS[count])
    offset = (_r(rng, 0.05, 0.1), _r(rng, 0.0, 0.05))
    wrist, palm, finger = _r(rng, 0.08, 0.1), _r(rng, 0.07, 0.1), _r(rng, 0.045, 0.06)
    hand = wrist + palm + finger / 2  # wrist pitch -> tool frame
    shoulder_x = mount_x + offset[0]

    def needed(distance: float) -> float:
        return math.hypot(math.hypot(distance - shoulder_x, mount_y), COUNTER_TOP + 0.1 + hand - body.shoulder_height)

    weak = rng.random() < 0.15
    total = needed(0.55) * rng.uniform(0.8, 0.93) if weak else needed(0.7) * rng.uniform(1.03, 1.2)
    upper = round(total * rng.uniform(0.48, 0.58), 3)
    fore = round(total - upper, 3)
    extension = _r(rng, 0.1, 0.18) if any(k.startswith("prism") for k in kinds) else 0.0
    return _ArmPlan(tuple(kinds), upper, fore, wrist, palm, finger, _r(rng, 0.038, 0.05), offset, extension, weak)


def _pitch_limits(rng: random.Random, kind: str) -> tuple[float, float]:
    """Limits of a pitch joint in 'up' terms (positive raises the link)."""
    if kind == "pitch1":
        return -_r(rng, 1.3, 1.6), _r(rng, 1.9, 2.3)
    if kind == "pitch2":
        return -_r(rng, 2.4, 2.7), _r(rng, 2.4, 2.7)
    return -_r(rng, 2.0, 2.3), _r(rng, 2.0, 2.3)


def _segments(plan: _ArmPlan, fractions: dict[str, float]) -> list[float]:
    """For each joint, the distance along the arm (x) to the next joint; 0 after the wrist roll (the palm follows)."""
    lengths: list[float] = []
    kinds = plan.kinds
    for i, kind in enumerate(kinds):
        after = kinds[i + 1] if i + 1 < len(kinds) else ""
        if kind == "pan":
            lengths.append(0.0)  # the pan link's offset is plan.pan_offset
        elif kind == "pitch1":
            lengths.append(plan.upper * fractions[after] if after in fractions else plan.upper)
        elif kind in ("roll_upper", "prism_upper"):
            lengths.append(plan.upper * (1.0 - fractions[kind]))
        elif kind == "pitch2":
            lengths.append(plan.fore * fractions[after] if after in fractions else plan.fore)
        elif kind in ("roll_fore", "prism_fore"):
            lengths.append(plan.fore * (1.0 - fractions[kind]))
        elif kind == "pitch3":
            lengths.append(plan.wrist)
        else:
            lengths.append(0.0)
    return [round(length, 3) for length in lengths]


def _arm_link_shapes(kind: str, length: float, tube: float, before: float, extension: float, into_pitch: bool,
                     rgba) -> tuple[Shape, ...]:
    """A link's shapes: a housing around its own joint (pitch joints) and a tube to the next joint.

    `before` is the length of the link before (a prismatic link's tube slides back into it).
    """
    if kind == "pan":
        return (Shape("cylinder", (round(tube * 1.15, 4), 0.09), ORIGIN, ORIGIN, rgba),)
    shapes: list[Shape] = []
    start = 0.0
    if kind.startswith("pitch"):
        shapes.append(Shape("cylinder", (round(tube * 1.1, 4), round(tube * 2.4, 4)), ORIGIN, ALONG_Y, rgba))
    elif kind.startswith("prism"):
        start = -round(min(extension, 0.35 * before), 3)
        tube = round(tube * 0.8, 4)
    end = length - (tube / 2 if into_pitch else 0.01)
    if end - start > 0.02:  # a tube into a pitch joint stops inside the next link's housing
        shapes.append(tube_x(tube, start, round(end, 4), rgba))
    return tuple(shapes)


def _joint_axis(rng: random.Random, kind: str, extension: float) -> tuple[Vec3, float | None, float | None, str, float]:
    """Axis, limits, type and up-sign of a joint (pitch: +1 when a positive value raises the link)."""
    if kind == "pan":
        limit = _r(rng, 1.7, 2.9)
        return Z_AXIS, -limit, limit, "revolute", 0.0
    if kind.startswith("prism"):
        return X_AXIS, 0.0, extension, "prismatic", 0.0
    if kind.startswith("roll"):
        if rng.random() < 0.5:
            return X_AXIS, None, None, "continuous", 0.0
        limit = _r(rng, 2.6, 3.1)
        return X_AXIS, -limit, limit, "revolute", 0.0
    low, high = _pitch_limits(rng, kind)
    sign = rng.choice((1.0, -1.0))  # axis -y: positive raises the link; +y: positive lowers it
    lower, upper = (low, high) if sign > 0 else (-high, -low)
    return (0.0, -sign, 0.0), lower, upper, "revolute", sign


@dataclass
class _ArmBuild:
    """The arm as built: its joints and links, shoulder to palm."""

    joints: list[str] = field(default_factory=list)
    links: list[str] = field(default_factory=list)
    up_sign: dict[str, float] = field(default_factory=dict)  # pitch joint -> +1 when positive values raise the link
    palm: str = ""


def _arm(rng: random.Random, tree: _Tree, names: Names, plan: _ArmPlan, parent: str, mount: Vec3,
         colours: tuple) -> _ArmBuild:
    """The arm's chain from the pan joint to the wrist roll link (the palm, shaped by the gripper)."""
    build = _ArmBuild()
    fractions = {"roll_upper": _r(rng, 0.35, 0.5), "roll_fore": _r(rng, 0.35, 0.5), "prism_upper": 0.6, "prism_fore": 0.6}
    lengths = _segments(plan, fractions)
    previous, xyz, tube, before = parent, mount, plan.radius, 0.0
    for i, kind in enumerate(plan.kinds):
        if kind == "pitch2":
            tube = round(plan.radius * 0.85, 4)
        elif kind == "pitch3":
            tube = round(plan.radius * 0.75, 4)
        axis, lower, upper, jtype, sign = _joint_axis(rng, kind, plan.extension)
        joint_name, link_name = names.joint(kind), names.link(kind)
        into_pitch = i + 1 < len(plan.kinds) and plan.kinds[i + 1].startswith("pitch")
        shapes = () if kind == "roll_wrist" else _arm_link_shapes(kind, lengths[i], tube, before, plan.extension,
                                                                   into_pitch, colours[i % 2])
        tree.add(Joint(joint_name, jtype, previous, link_name, xyz, ORIGIN, axis, lower, upper, 40.0, 1.5),
                 Link(link_name, shapes, 700.0))
        if sign:
            build.up_sign[joint_name] = sign
        build.joints.append(joint_name)
        build.links.append(link_name)
        previous, before = link_name, lengths[i]
        xyz = (plan.pan_offset[0], 0.0, plan.pan_offset[1]) if kind == "pan" else (lengths[i], 0.0, 0.0)
    build.palm = previous
    return build


# -- the gripper -------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Hand:
    """The gripper as built: what the description says of it, and the palm's shapes (the palm link exists already)."""

    gripper: Gripper
    tool: str  # the tool frame, between the finger pads
    links: tuple[str, ...]  # the fingers and the tool frame
    palm_shapes: tuple[Shape, ...]
    palm_half_height: float  # where a wrist camera sits


def _gripper(rng: random.Random, tree: _Tree, names: Names, plan: _ArmPlan, palm: str, rgba) -> _Hand:
    """Fingers on the palm (two prismatic, one prismatic against a fixed pad, or two revolute claws), spread along
    the tool's y axis, and the tool frame between the pads."""
    roll = random.Random(rng.random())
    kind = roll.choices(GRIPPER_KINDS, weights=(0.5, 0.3, 0.2))[0]
    width = _r(rng, 0.08, 0.12)
    height = _r(rng, 0.02, 0.035)
    thick, gap = 0.012, 0.002
    length, x0 = plan.finger, plan.palm
    half_width = round(width / 2 + thick + 0.012, 3)
    half_height = round(max(height / 2 + 0.01, plan.radius * 0.8), 3)
    palm_shapes = [box((0.0, -half_width, -half_height), (x0, half_width, half_height), rgba)]
    links: list[str] = []
    pad = lambda y0, y1: box((0.0, y0, -height / 2), (length, y1, height / 2), BLACK)  # noqa: E731
    if kind == "two_prismatic":
        opening = round((width - gap) / 2, 4)
        for side, sign in (("left", 1.0), ("right", -1.0)):
            name = names.frame(f"{side}_finger")
            shape = pad(0.0, thick) if sign > 0 else pad(-thick, 0.0)
            tree.add(Joint(names.frame(f"{side}_finger_joint"), "prismatic", palm, name, (x0, sign * gap / 2, 0.0),
                           ORIGIN, (0.0, sign, 0.0), 0.0, opening, 20.0, 0.05), Link(name, (shape,), 900.0))
            links.append(name)
        gripper = Gripper(kind, tuple(names.frame(f"{s}_finger_joint") for s in ("left", "right")), opening, 0.0,
                          round(gap + 2 * opening, 4), height)
    elif kind == "one_prismatic":
        opening = round(width - gap, 4)
        palm_shapes.append(box((x0, -width / 2 - thick, -height / 2), (x0 + length, -width / 2, height / 2), BLACK))
        name = names.frame("finger")
        tree.add(Joint(names.frame("finger_joint"), "prismatic", palm, name, (x0, round(-width / 2 + gap, 4), 0.0),
                       ORIGIN, (0.0, 1.0, 0.0), 0.0, opening, 20.0, 0.05), Link(name, (pad(0.0, thick),), 900.0))
        links.append(name)
        gripper = Gripper(kind, (names.frame("finger_joint"),), opening, 0.0, width, height)
    else:
        opening = round(math.asin(min((width - gap) / (2 * length), 0.95)), 4)
        for side, sign in (("left", 1.0), ("right", -1.0)):
            name = names.frame(f"{side}_claw")
            hinge = (x0, round(sign * (gap / 2 + thick / 2), 4), 0.0)
            shape = pad(-thick / 2, thick / 2)
            tree.add(Joint(names.frame(f"{side}_claw_joint"), "revolute", palm, name, hinge, ORIGIN,
                           (0.0, 0.0, sign), 0.0, opening, 5.0, 1.0), Link(name, (shape,), 900.0))
            links.append(name)
        gripper = Gripper(kind, tuple(names.frame(f"{s}_claw_joint") for s in ("left", "right")), opening, 0.0,
                          round(gap + 2 * length * math.sin(opening), 4), height)
    tool = names.frame(rng.choice(("tool_frame", "tcp", "grasp_point")))
    tree.add(Joint(f"{tool}_joint", "fixed", palm, tool, (round(x0 + length / 2, 4), 0.0, 0.0)), Link(tool))
    links.append(tool)
    return _Hand(gripper, tool, tuple(links), tuple(palm_shapes), half_height)


# -- kinematics and a sphere cover, for the park search --------------------------------------------------------


def _rotation(rpy: Sequence[float]) -> np.ndarray:
    """URDF roll-pitch-yaw: Rz(yaw) @ Ry(pitch) @ Rx(roll)."""
    r, p, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(p), 0, math.sin(p)], [0, 1, 0], [-math.sin(p), 0, math.cos(p)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    return rz @ ry @ rx


def _axis_rotations(axis: Sequence[float], angles: np.ndarray) -> np.ndarray:
    """Rotation matrices (N, 3, 3) about a unit axis by each angle (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    s, c = np.sin(angles)[:, None, None], np.cos(angles)[:, None, None]
    return np.eye(3) + s * kx + (1 - c) * (kx @ kx)


def _spheres(shape: Shape) -> tuple[np.ndarray, np.ndarray]:
    """Spheres (centres in link coordinates, radii) whose union covers the shape."""
    rot, centre = _rotation(shape.rpy), np.asarray(shape.xyz, dtype=float)
    if shape.kind == "sphere":
        return centre[None, :], np.array([shape.dims[0]])
    if shape.kind == "cylinder":
        radius, length = shape.dims
        count = max(1, math.ceil(length / radius))
        step = length / count
        along = np.linspace(-length / 2 + step / 2, length / 2 - step / 2, count)
        local = np.column_stack([np.zeros(count), np.zeros(count), along])
        return centre + local @ rot.T, np.full(count, math.hypot(radius, step / 2))
    dims = np.asarray(shape.dims, dtype=float)
    cell = max(float(dims.min()) / 2, 0.015)
    counts = [max(1, math.ceil(d / cell)) for d in dims]
    axes = [np.linspace(-d / 2 + d / (2 * n), d / 2 - d / (2 * n), n) for d, n in zip(dims, counts)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    half = np.array([d / (2 * n) for d, n in zip(dims, counts)])
    return centre + grid @ rot.T, np.full(len(grid), float(np.linalg.norm(half)))


@dataclass(frozen=True)
class _Obstacle:
    """An axis-aligned box of the body in the floor frame (torso at its default)."""

    lo: tuple[float, float, float]
    hi: tuple[float, float, float]


def _box_distance(points: np.ndarray, obstacle: _Obstacle) -> np.ndarray:
    lo, hi = np.asarray(obstacle.lo), np.asarray(obstacle.hi)
    outside = np.maximum(np.maximum(lo - points, points - hi), 0.0)
    return np.linalg.norm(outside, axis=-1)


@dataclass(frozen=True)
class _ParkProblem:
    """What the park search needs: the arm's subtree, where it is mounted, and the body to keep clear of."""

    joints: tuple[Joint, ...]  # the arm's subtree, parents first (its first joint is the pan joint)
    links: dict[str, Link]
    arm_joints: tuple[str, ...]
    up_sign: dict[str, float]
    mount: Vec3  # the pan joint in the floor frame, torso at its default
    hand: frozenset[str]  # links rigid with the palm (their pairs are not checked)
    obstacles: tuple[_Obstacle, ...]
    base_shape: str
    base_radius: float
    floor_z: float  # every arm sphere stays above this (the base top plus the torso's default plus a margin)
    sight: tuple[float, float] | None  # the camera (x, z) on the body; the parked arm stays below its view of the counter


def _candidates(problem: _ParkProblem, steps: int = 13) -> np.ndarray:
    """Joint values (N, arm joints) to try: the pan at 0, ±45°, ±90° or ±135°, the rolls and slides at 0, the pitches
    on a grid."""
    axes: list[np.ndarray] = []
    for name in problem.arm_joints:
        joint = next(j for j in problem.joints if j.name == name)
        if name == problem.arm_joints[0]:
            pans = (0.0, math.pi / 4, -math.pi / 4, math.pi / 2, -math.pi / 2, 3 * math.pi / 4, -3 * math.pi / 4)
            axes.append(np.array([v for v in pans if joint.lower <= v <= joint.upper]))
        elif name in problem.up_sign:
            axes.append(np.linspace(joint.lower, joint.upper, steps + 2)[1:-1])
        else:
            axes.append(np.array([0.0]))
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(axes))


def _link_spheres(problem: _ParkProblem, values: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each arm link's sphere centres (N, k, 3) in the floor frame and radii (k,), for N joint value rows."""
    count = len(values)
    frames: dict[str, np.ndarray] = {}
    root = np.tile(np.eye(4), (count, 1, 1))
    root[:, :3, 3] = problem.mount
    column = {name: i for i, name in enumerate(problem.arm_joints)}
    out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for joint in problem.joints:
        local = np.eye(4)
        local[:3, :3] = _rotation(joint.rpy)
        parent = frames.get(joint.parent)
        if parent is None:  # the pan joint: at the mount
            base = root @ local
        else:
            local[:3, 3] = joint.xyz
            base = parent @ local
        q = values[:, column[joint.name]] if joint.name in column else np.zeros(count)
        motion = np.tile(np.eye(4), (count, 1, 1))
        if joint.type in ("revolute", "continuous"):
            motion[:, :3, :3] = _axis_rotations(joint.axis or Z_AXIS, q)
        elif joint.type == "prismatic":
            motion[:, :3, 3] = np.outer(q, joint.axis or X_AXIS)
        frames[joint.child] = base @ motion
        link = problem.links[joint.child]
        if link.shapes:
            pieces = [_spheres(shape) for shape in link.shapes]
            centres = np.concatenate([c for c, _ in pieces])
            radii = np.concatenate([r for _, r in pieces])
            world = np.einsum("nij,kj->nki", frames[joint.child][:, :3, :3], centres) + frames[joint.child][:, None, :3, 3]
            out[joint.child] = (world, radii)
    return out


@dataclass(frozen=True)
class _Rating:
    """How each row of joint values does: breaks of the body rules, how far past the footprint, how low."""

    body: np.ndarray  # how far it breaks the rules against the body (0: none)
    outside: np.ndarray  # how far the arm reaches past the base's footprint (m)
    lowest: np.ndarray  # the lowest point of the arm past the pan link (m)
    highest: np.ndarray  # its highest point (m)
    in_view: np.ndarray  # how far the arm reaches into the body camera's view of the counter (m)


def _rate(problem: _ParkProblem, spheres: dict[str, tuple[np.ndarray, np.ndarray]], count: int) -> _Rating:
    first = problem.joints[0].child  # the pan link: fixed to the body, not checked against it
    bad, outside = np.zeros(count), np.zeros(count)
    lowest, highest = np.full(count, np.inf), np.full(count, -np.inf)
    in_view = np.zeros(count)
    for name, (centres, radii) in spheres.items():
        bottom = centres[..., 2] - radii
        bad += np.maximum(problem.floor_z - bottom, 0.0).max(axis=1)
        if problem.base_shape == "box":
            reach = np.maximum(np.abs(centres[..., 0]), np.abs(centres[..., 1])) + radii
        else:
            reach = np.hypot(centres[..., 0], centres[..., 1]) + radii
        outside = np.maximum(outside, (reach - problem.base_radius).max(axis=1))
        if name == first:
            continue
        lowest = np.minimum(lowest, bottom.min(axis=1))
        highest = np.maximum(highest, (centres[..., 2] + radii).max(axis=1))
        if problem.sight is not None:
            in_view = np.maximum(in_view, _into_view(problem.sight, centres, radii))
        for obstacle in problem.obstacles:
            bad += np.maximum(0.02 - (_box_distance(centres, obstacle) - radii), 0.0).max(axis=1)
    return _Rating(bad, outside, lowest, highest, in_view)


#: what a camera on the body must see past the parked arm: things this high (m) this far in front of the base (m)
VIEW_TARGET = (0.55, 0.85)


def _into_view(sight: tuple[float, float], centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """How far (m) spheres in front of the camera reach above its line of sight down to VIEW_TARGET (x-z plane):
    above it, the parked arm would hide the counter's front from the camera."""
    (cx, cz), (tx, tz) = sight, VIEW_TARGET
    x = centres[..., 0]
    line = cz + (x - cx) * (tz - cz) / (tx - cx)
    above = centres[..., 2] + radii + 0.02 - line
    return np.where(x + radii > cx - 0.05, np.maximum(above, 0.0), 0.0).max(axis=1)


def _self_clear(problem: _ParkProblem, spheres: dict[str, tuple[np.ndarray, np.ndarray]], rows: np.ndarray) -> np.ndarray:
    """Whether, in each of the rows, links not joined to each other keep 1.5 cm apart (the hand counts as one)."""
    parents = {j.child: j.parent for j in problem.joints}
    clear = np.ones(len(rows), dtype=bool)
    names = sorted(spheres)
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            if parents.get(a) == b or parents.get(b) == a or (a in problem.hand and b in problem.hand):
                continue
            (ca, ra), (cb, rb) = spheres[a], spheres[b]
            gap = np.linalg.norm(ca[rows][:, :, None, :] - cb[rows][:, None, :, :], axis=-1) - ra[:, None] - rb[None, :]
            clear &= gap.reshape(len(rows), -1).min(axis=1) >= 0.015
    return clear


def _park(problem: _ParkProblem) -> tuple[float, ...]:
    """A park pose: clear of the body and of itself; out of the body camera's view of the counter and within the
    tightest footprint (up to 0.2 m past the base's edge) that allows one, else in its view, else farther out; its
    lowest point as high as it goes up to PARK_HEIGHT (above the counters and what stands on them), its highest as
    low as can be."""
    values = _candidates(problem)
    spheres = _link_spheres(problem, values)
    rating = _rate(problem, spheres, len(values))
    near = [(view, tolerance) for view in (0.0, math.inf) for tolerance in (0.0, 0.05, 0.1, 0.2)]
    far = [(view, tolerance) for tolerance in (0.4, math.inf) for view in (0.0, math.inf)]
    for view, tolerance in near + far:  # the view kept free, the arm within 0.2 m of the footprint, first
        rows = np.flatnonzero((rating.body <= 0.0) & (rating.outside <= tolerance) & (rating.in_view <= view))
        rows = rows[np.lexsort((rating.highest[rows], -np.minimum(rating.lowest[rows], PARK_HEIGHT)))]
        for start in range(0, len(rows), 256):  # the highest first; self-collision is checked on few rows
            chunk = rows[start:start + 256]
            clear = np.flatnonzero(_self_clear(problem, spheres, chunk))
            if len(clear):
                return tuple(round(float(v), 3) + 0.0 for v in values[chunk[clear[0]]])
    raise ValueError("no park pose clear of the body")


# -- the whole robot ---------------------------------------------------------------------------------------------


def _wheels(rng: random.Random, tree: _Tree, names: Names, base: str, body: _Body, lift: float) -> None:
    """Drive wheels and casters whose collision shapes touch the floor at z = 0 (the base link is `lift` up)."""
    radius, width = _r(rng, 0.05, 0.08), _r(rng, 0.03, 0.05)
    side = round(body.radius - width / 2 - 0.005, 3)
    places = [("left_wheel", 0.0, side), ("right_wheel", 0.0, -side)]
    casters: list[tuple[str, float]] = []
    if rng.random() < 0.4:  # four wheels, no casters
        ahead = round(body.radius * 0.55, 3)
        places = [(f"{end}_{name}", x, y) for end, x in (("front", ahead), ("rear", -ahead)) for name, _, y in places]
    else:
        reach = round(body.radius * 0.7, 3)
        casters = [("front_caster", reach), ("rear_caster", -reach)][: rng.choice((1, 2))]
    for name, x, y in places:
        tree.add(Joint(names.frame(f"{name}_joint"), "continuous", base, names.frame(name), (x, y, round(radius - lift, 4)),
                       ORIGIN, (0.0, 1.0, 0.0), effort=20.0, velocity=10.0),
                 Link(names.frame(name), (Shape("cylinder", (radius, width), ORIGIN, ALONG_Y, BLACK),), 1200.0))
    caster_radius = _r(rng, 0.025, 0.04)
    for name, x in casters:
        tree.add(Joint(names.frame(f"{name}_joint"), "fixed", base, names.frame(name), (x, 0.0, round(caster_radius - lift, 4))),
                 Link(names.frame(name), (Shape("sphere", (caster_radius,), rgba=BLACK),), 1200.0))


def _column_sink(body: _Body) -> float:
    """How far the torso column reaches down into the base (it slides in a sleeve on the base)."""
    return round(min(body.torso_travel, body.top - 0.1), 3) if body.torso_travel else 0.02


def _base_shapes(body: _Body, lift: float, rgba) -> tuple[Shape, ...]:
    """The base body, clear of the floor, and the torso's sleeve above it (inside the column when it is down)."""
    bottom, top = body.clearance - lift, body.top - lift
    if body.shape == "box":
        shapes = [box((-body.radius, -body.radius, bottom), (body.radius, body.radius, top), rgba)]
    else:
        shapes = [Shape("cylinder", (body.radius, round(top - bottom, 4)), (0.0, 0.0, round((top + bottom) / 2, 4)),
                        ORIGIN, rgba)]
    sleeve = body.torso_travel - _column_sink(body) + 0.02
    if body.torso_travel and sleeve > 0.03:
        half_d, half_w = body.column_depth / 2 - 0.01, body.column_width / 2 - 0.01
        shapes.append(box((body.column_x - half_d, -half_w, top - 0.01), (body.column_x + half_d, half_w, top + sleeve),
                          BLACK))
    return tuple(shapes)


def _fov(rng: random.Random) -> tuple[float, float]:
    horizontal = _r(rng, 0.9, 1.25)
    return horizontal, round(2 * math.atan(0.75 * math.tan(horizontal / 2)), 3)


def _optical(tree: _Tree, names: Names, parent: str, xyz: Vec3, rpy: Vec3) -> str:
    """A camera link (frame only) and its optical frame; returns the optical frame's name."""
    camera, optical = names.frame("camera_link"), names.frame("camera_optical_frame")
    tree.add(Joint(names.frame("camera_joint"), "fixed", parent, camera, xyz, rpy), Link(camera))
    tree.add(Joint(names.frame("camera_optical_joint"), "fixed", camera, optical, ORIGIN, OPTICAL_RPY), Link(optical))
    return optical


@dataclass(frozen=True)
class _Column:
    """The column (torso lift or fixed mast) as built: its link, its height and the arm's mount on it."""

    link: str
    joint: str | None  # the torso joint, None for a fixed mast
    top: float  # its top, in its own frame (m)
    mount_z: float  # the pan joint's height in its frame (m)
    floor_z: float  # the height of its frame, torso at its default (m)


def _root(rng: random.Random, names: Names, body: _Body, rgba) -> tuple[_Tree, str, float]:
    """A footprint frame on the floor with the base link above it, or the base link itself as the root;
    returns the tree, the base link and its height above the floor."""
    if rng.random() < 0.5:
        root, base, lift = names.frame("base_footprint"), names.link("base"), _r(rng, 0.05, 0.12)
        tree = _Tree(Link(root))
        tree.add(Joint(f"{root}_joint", "fixed", root, base, (0.0, 0.0, lift)), Link(base, _base_shapes(body, lift, rgba), 400.0))
        return tree, base, lift
    base = names.link("base")
    return _Tree(Link(base, _base_shapes(body, 0.0, rgba), 400.0)), base, 0.0


def _column(rng: random.Random, tree: _Tree, names: Names, body: _Body, base: str, lift: float, mount_y: float,
            plan: _ArmPlan, camera_kind: str, rgba) -> _Column:
    """The torso lift (prismatic) or fixed mast, tall enough for the head or the mast camera, with the shoulder bracket."""
    mount_z = round(body.shoulder_height - plan.pan_offset[1] - body.top - body.torso_default, 3)
    if camera_kind == "head":
        top = max(round(_r(rng, 1.15, 1.5) - 0.09 - body.top - body.torso_default, 3), mount_z + 0.15)
    elif camera_kind == "mast":
        top = max(round(_r(rng, 1.1, 1.45) - 0.04 - body.top - body.torso_default, 3), mount_z + 0.12)
    else:
        top = round(mount_z + _r(rng, 0.08, 0.2), 3)
    half_d, half_w = body.column_depth / 2, body.column_width / 2
    shapes = (box((-half_d, -half_w, -_column_sink(body)), (half_d, half_w, top), rgba),
              box((half_d, mount_y - 0.04, mount_z - 0.1), (half_d + 0.02, mount_y + 0.04, mount_z - 0.045), rgba))
    link = names.link("torso" if body.torso_travel else "mast")
    origin = (body.column_x, 0.0, round(body.top - lift, 4))
    joint = None
    if body.torso_travel:
        joint = names.joint("torso")
        tree.add(Joint(joint, "prismatic", base, link, origin, ORIGIN, Z_AXIS, 0.0, body.torso_travel, 500.0, 0.1),
                 Link(link, shapes, 500.0))
    else:
        tree.add(Joint(names.joint("mast"), "fixed", base, link, origin), Link(link, shapes, 500.0))
    return _Column(link, joint, top, mount_z, body.top + body.torso_default)


def _head(rng: random.Random, tree: _Tree, names: Names, body: _Body, column: _Column,
          rgba) -> tuple[Head, str, _Obstacle]:
    """A pan/tilt head on the column's top (the tilt axis' sign is seeded); returns it, its camera frame and its box."""
    pan, tilt = names.joint("head_pan"), names.joint("head_tilt")
    pan_link, tilt_link = names.link("head_pan"), names.link("head_tilt")
    limit, sign = _r(rng, 1.5, 2.6), rng.choice((1.0, -1.0))
    tree.add(Joint(pan, "revolute", column.link, pan_link, (0.0, 0.0, column.top), ORIGIN, Z_AXIS, -limit, limit, 5.0, 2.0),
             Link(pan_link, (Shape("cylinder", (0.05, 0.06), (0.0, 0.0, 0.03), ORIGIN, rgba),), 600.0))
    lower, upper = (-0.6, 1.2) if sign > 0 else (-1.2, 0.6)
    tree.add(Joint(tilt, "revolute", pan_link, tilt_link, (0.0, 0.0, 0.09), ORIGIN, (0.0, sign, 0.0), lower, upper, 5.0, 2.0),
             Link(tilt_link, (box((-0.05, -0.1, -0.035), (0.045, 0.1, 0.035), rgba),), 600.0))
    frame = _optical(tree, names, tilt_link, (0.05, 0.0, 0.0), ORIGIN)
    top = column.floor_z + column.top
    return (Head(pan, tilt, pan_link, tilt_link, round(0.45 * sign, 3)), frame,
            _Obstacle((body.column_x - 0.15, -0.15, top - 0.02), (body.column_x + 0.15, 0.15, top + 0.25)))


def _mast_camera(rng: random.Random, tree: _Tree, names: Names, body: _Body, column: _Column,
                 rgba) -> tuple[str, _Obstacle]:
    """A camera fixed on the column's top, looking forward and down; returns its frame and its housing's box."""
    half_d = body.column_depth / 2
    housing = names.link("camera_housing")
    tree.add(Joint(names.joint("camera_housing"), "fixed", column.link, housing, (half_d, 0.0, column.top)),
             Link(housing, (box((-0.03, -0.06, 0.0), (0.015, 0.06, 0.06), rgba),), 600.0))
    frame = _optical(tree, names, housing, (0.02, 0.0, 0.03), (0.0, _r(rng, 0.3, 0.6), 0.0))
    top = column.floor_z + column.top
    return frame, _Obstacle((body.column_x + half_d - 0.03, -0.06, top), (body.column_x + half_d + 0.02, 0.06, top + 0.06))


def _wrist_camera(rng: random.Random, tree: _Tree, names: Names, plan: _ArmPlan, palm: str, palm_half: float,
                  rgba) -> tuple[str, list[str]]:
    """A camera on the palm's top, looking along the tool (a little down); returns its frame and its links."""
    housing = names.link("camera_housing")
    tree.add(Joint(names.joint("camera_housing"), "fixed", palm, housing, (0.0, 0.0, palm_half)),
             Link(housing, (box((0.035, -0.03, 0.0), (plan.palm - 0.01, 0.03, 0.03), rgba),), 600.0))
    frame = _optical(tree, names, housing, (round(plan.palm - 0.005, 3), 0.0, 0.015), (0.0, _r(rng, 0.1, 0.3), 0.0))
    return frame, [housing, names.frame("camera_link"), frame]


def generate(seed: int) -> ZooRobot:
    """The zoo robot of a seed (deterministic: the same seed gives the same robot)."""
    rng = random.Random(seed)
    names = _names(rng, seed)
    colours = tuple(rng.sample(COLOURS, 3))
    body = _body(rng)
    camera_kind = CAMERA_KINDS[seed % 3] if seed < 3 else rng.choice(CAMERA_KINDS)
    tree, base, lift = _root(rng, names, body, colours[0])
    _wheels(rng, tree, names, base, body, lift)
    # the column (a torso lift or a fixed mast) with the arm mounted on its front
    mount_x = round(body.column_x + body.column_depth / 2 + 0.07, 3)
    mount_y = _r(rng, -0.08, 0.08)
    plan = _arm_plan(rng, body, mount_x, mount_y)
    column = _column(rng, tree, names, body, base, lift, mount_y, plan, camera_kind, colours[1])
    obstacles = [_Obstacle((body.column_x - body.column_depth / 2, -body.column_width / 2, body.top),
                           (body.column_x + body.column_depth / 2, body.column_width / 2, column.floor_z + column.top))]
    # the camera on a pan/tilt head or fixed on the mast (a wrist camera comes with the hand)
    head, sight = None, None
    if camera_kind == "head":
        head, frame, extra = _head(rng, tree, names, body, column, colours[2])
        obstacles.append(extra)
        sight = (body.column_x + 0.05, column.floor_z + column.top + 0.09)
    elif camera_kind == "mast":
        frame, extra = _mast_camera(rng, tree, names, body, column, colours[2])
        obstacles.append(extra)
        sight = (body.column_x + body.column_depth / 2 + 0.02, column.floor_z + column.top + 0.06)
    # the arm and its gripper
    arm = _arm(rng, tree, names, plan, column.link, (round(body.column_depth / 2 + 0.07, 4), mount_y, column.mount_z),
               colours[1:])
    hand = _gripper(rng, tree, names, plan, arm.palm, colours[0])
    hand_links = list(hand.links)
    if camera_kind == "wrist":
        frame, camera_links = _wrist_camera(rng, tree, names, plan, arm.palm, hand.palm_half_height, colours[2])
        hand_links += camera_links
    tree.reshape(arm.palm, hand.palm_shapes)
    camera = Camera(camera_kind, frame, *_fov(rng))
    # the park pose, searched for with the torso at its default
    pan_index = next(i for i, j in enumerate(tree.joints) if j.name == arm.joints[0])
    problem = _ParkProblem(_subtree(tree.joints, pan_index), {link.name: link for link in tree.links}, tuple(arm.joints),
                           arm.up_sign, (mount_x, mount_y, round(column.floor_z + column.mount_z, 4)),
                           frozenset({arm.palm, *hand_links}), tuple(obstacles), body.shape, body.radius,
                           body.top + body.torso_default + 0.03, sight)
    return ZooRobot(seed=seed, name=f"zoo_{names.prefix}", root_link=tree.links[0].name, links=tuple(tree.links),
                    joints=tuple(tree.joints), base_shape=body.shape, base_radius=body.radius, base_top=body.top,
                    torso_joint=column.joint, torso_default=body.torso_default, shoulder_height=body.shoulder_height,
                    arm_name=rng.choice(ARM_NAMES), arm_kinds=plan.kinds, arm_joints=tuple(arm.joints),
                    arm_links=tuple(arm.links + hand_links), tool_frame=hand.tool, palm_link=arm.palm, gripper=hand.gripper,
                    camera=camera, head=head, park=_park(problem), weak=plan.weak)


def _subtree(joints: Sequence[Joint], first: int) -> tuple[Joint, ...]:
    """The joint at `first` and every joint below it, parents first."""
    inside = {joints[first].child}
    chosen = [joints[first]]
    for joint in joints[first + 1:]:
        if joint.parent in inside:
            inside.add(joint.child)
            chosen.append(joint)
    return tuple(chosen)


# -- inertia ------------------------------------------------------------------------------------------------------


def _volume(shape: Shape) -> float:
    if shape.kind == "box":
        return float(np.prod(shape.dims))
    if shape.kind == "cylinder":
        return math.pi * shape.dims[0] ** 2 * shape.dims[1]
    return 4.0 / 3.0 * math.pi * shape.dims[0] ** 3


def _own_inertia(shape: Shape, mass: float) -> np.ndarray:
    """The inertia tensor of a solid primitive about its centre, in link axes."""
    if shape.kind == "box":
        sx, sy, sz = shape.dims
        local = np.diag([sy**2 + sz**2, sx**2 + sz**2, sx**2 + sy**2]) * mass / 12.0
    elif shape.kind == "cylinder":
        radius, length = shape.dims
        side = mass * (3 * radius**2 + length**2) / 12.0
        local = np.diag([side, side, mass * radius**2 / 2.0])
    else:
        local = np.eye(3) * 0.4 * mass * shape.dims[0] ** 2
    rot = _rotation(shape.rpy)
    return rot @ local @ rot.T


def inertial(link: Link) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, diagonal inertia) of a link of uniform density; a token one for a frame-only link."""
    if link.density is None or not link.shapes:
        return FRAME_MASS, np.zeros(3), np.full(3, FRAME_INERTIA)
    volumes = np.array([_volume(s) for s in link.shapes])
    masses = link.density * volumes
    centres = np.array([s.xyz for s in link.shapes], dtype=float)
    mass = float(masses.sum())
    com = (masses[:, None] * centres).sum(axis=0) / mass
    tensor = np.zeros((3, 3))
    for shape, part, centre in zip(link.shapes, masses, centres):
        d = centre - com
        tensor += _own_inertia(shape, part) + part * (d @ d * np.eye(3) - np.outer(d, d))
    return mass, com, np.maximum(np.diag(tensor), FRAME_INERTIA)


# -- writing ------------------------------------------------------------------------------------------------------


def _geometry(shape: Shape) -> str:
    if shape.kind == "box":
        return f'<box size="{fmt3(shape.dims)}"/>'
    if shape.kind == "cylinder":
        return f'<cylinder radius="{fmt(shape.dims[0])}" length="{fmt(shape.dims[1])}"/>'
    return f'<sphere radius="{fmt(shape.dims[0])}"/>'


def _link_xml(link: Link) -> list[str]:
    mass, com, diag = inertial(link)
    lines = [f'  <link name="{link.name}">',
             "    <inertial>",
             f'      <origin xyz="{fmt3(com)}" rpy="0 0 0"/>',
             f'      <mass value="{fmt(mass)}"/>',
             f'      <inertia ixx="{fmt(diag[0], 8)}" ixy="0" ixz="0" iyy="{fmt(diag[1], 8)}" iyz="0" '
             f'izz="{fmt(diag[2], 8)}"/>',
             "    </inertial>"]
    for shape in link.shapes:
        origin = f'<origin xyz="{fmt3(shape.xyz)}" rpy="{fmt3(shape.rpy)}"/>'
        lines += ["    <visual>", f"      {origin}", f"      <geometry>{_geometry(shape)}</geometry>",
                  f'      <material name="c{fmt3(shape.rgba, 2).replace(" ", "_")}"><color rgba="{fmt3(shape.rgba, 3)}"/>'
                  "</material>",
                  "    </visual>",
                  "    <collision>", f"      {origin}", f"      <geometry>{_geometry(shape)}</geometry>", "    </collision>"]
    lines.append("  </link>")
    return lines


def _joint_xml(joint: Joint) -> list[str]:
    lines = [f'  <joint name="{joint.name}" type="{joint.type}">',
             f'    <parent link="{joint.parent}"/>',
             f'    <child link="{joint.child}"/>',
             f'    <origin xyz="{fmt3(joint.xyz)}" rpy="{fmt3(joint.rpy)}"/>']
    if joint.axis is not None:
        lines.append(f'    <axis xyz="{fmt3(joint.axis)}"/>')
    if joint.type != "fixed":
        bounds = f'lower="{fmt(joint.lower)}" upper="{fmt(joint.upper)}" ' if joint.lower is not None else ""
        lines.append(f'    <limit {bounds}effort="{fmt(joint.effort)}" velocity="{fmt(joint.velocity)}"/>')
    lines.append("  </joint>")
    return lines


def urdf_text(robot: ZooRobot) -> str:
    """The robot's URDF (one element a line: PyBullet cannot parse a URDF written on one line)."""
    lines = ['<?xml version="1.0"?>',
             f"<!-- GENERATED by pycram_cli/robots/zoo.py from seed {robot.seed} - a robot of the zoo, not a real one. -->",
             f'<robot name="{robot.name}">']
    links = {link.name: link for link in robot.links}
    lines += _link_xml(links[robot.root_link])
    for joint in robot.joints:
        lines += _joint_xml(joint)
        lines += _link_xml(links[joint.child])
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


def _flow(values: Iterable[float | str]) -> str:
    return "[" + ", ".join(v if isinstance(v, str) else fmt(v) for v in values) + "]"


def description_text(robot: ZooRobot) -> str:
    """The robot description (docs/robots.md), with only the keys that document defines."""
    g, c, arm = robot.gripper, robot.camera, robot.arm_name
    lines = [f"# Robot description of {robot.name}, a robot of pycram's zoo (seed {robot.seed}):",
             "# GENERATED by pycram_cli/robots/zoo.py - do not edit by hand.",
             f"name: {robot.name}",
             f"base_link: {robot.root_link}",
             "mobile: true"]
    if robot.torso_joint:
        lines.append(f"torso: {{joint: {robot.torso_joint}, default: {fmt(robot.torso_default)}}}")
    lines += ["camera:",
              f"  frame: {c.frame}   # on the {c.kind}; optical: +z forward, +x right, +y down",
              f"  horizontal_fov: {fmt(c.horizontal_fov)}",
              f"  vertical_fov: {fmt(c.vertical_fov)}",
              f"  near: {fmt(c.near)}",
              f"  far: {fmt(c.far)}"]
    if robot.head is not None:
        h = robot.head
        lines.append(f"head: {{pan_joint: {h.pan_joint}, tilt_joint: {h.tilt_joint}, pan_link: {h.pan_link}, "
                     f"tilt_link: {h.tilt_link}}}")
    lines += ["arms:",
              f"  {arm}:",
              f"    joints: {_flow(robot.arm_joints)}",
              f"    tool_frame: {robot.tool_frame}",
              f"    palm_link: {robot.palm_link}",
              f"    gripper:   # {g.kind.replace('_', ' ')} fingers",
              f"      joints: {_flow(g.joints)}",
              f"      open: {fmt(g.open)}",
              f"      closed: {fmt(g.closed)}",
              f"      max_width: {fmt(g.max_width)}",
              f"      finger_height: {fmt(g.finger_height)}",
              f"    links: {_flow(robot.arm_links)}",
              "    poses:",
              f"      park: {_flow(robot.park)}",
              "# Tool orientation (x, y, z, w) relative to the base: the tool's +x points out of the gripper, the",
              "# fingers close along its y; with the arm at zero it is aligned with the base (stretched forward).",
              "grasps:"]
    lines += [f"  {name}: {_flow(q)}" for name, q in robot.grasps.items()]
    if robot.camera.kind == "wrist":
        lines += ["# The camera is on the wrist: looking moves the arm.", f'resources: {{head: "arm:{arm}"}}']
    return "\n".join(lines) + "\n"


def write(robot: ZooRobot, folder: Path) -> Path:
    """Write `<name>.urdf` and its description `<name>.yaml` into folder; returns the URDF's path."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    urdf = folder / f"{robot.name}.urdf"
    urdf.write_text(urdf_text(robot), encoding="utf-8", newline="\n")
    (folder / f"{robot.name}.yaml").write_text(description_text(robot), encoding="utf-8", newline="\n")
    return urdf


def world_joints(robot: ZooRobot) -> dict[str, float]:
    """The joint values a zoo world starts with: the torso's default, the head looking down, the arm parked."""
    values: dict[str, float] = {}
    if robot.torso_joint:
        values[robot.torso_joint] = robot.torso_default
    if robot.head is not None:
        values[robot.head.tilt_joint] = robot.head.tilt_down
    values.update(zip(robot.arm_joints, robot.park))
    return values


def write_world(robot: ZooRobot, folder: Path, base: Sequence[float] = (0.0, 0.7, 0.0),
                template: Path | None = None) -> Path:
    """Write `<name>_kitchen.yaml`: the bundled kitchen (worlds/kitchen.yaml) with this robot in place of the PR2.

    The robot's files are written into the same folder (`write`) and named by absolute paths.
    """
    folder = Path(folder).resolve()
    urdf = write(robot, folder)
    source = (template or worlds_dir() / "kitchen.yaml").read_text(encoding="utf-8").splitlines()
    start = next(i for i, line in enumerate(source) if line.strip() == "- name: pr2")
    end = next(i for i in range(start + 1, len(source)) if source[i].lstrip().startswith("- name:"))
    block = [f"  - name: {robot.name}",
             "    type: robot",
             f"    file: {urdf}",
             f"    description: {urdf.with_suffix('.yaml')}",
             f"    position: {_flow(base)}",
             "    joints:"]
    block += [f"      {name}: {fmt(value)}" for name, value in world_joints(robot).items()]
    lines = [f"# GENERATED by pycram_cli/robots/zoo.py: worlds/kitchen.yaml with the zoo robot {robot.name}"
             f" (seed {robot.seed}) in place of the PR2."]
    for line in source[:start]:
        if line.startswith("#"):
            continue  # the template's own comments speak of the PR2 and of paths relative to it
        if line.startswith("description:"):
            line = f"description: {robot.name} (robot zoo, seed {robot.seed}) in the IAI kitchen, breakfast items on the sink counter"
        lines.append(line)
    lines += block + source[end:]
    world = folder / f"{robot.name}_kitchen.yaml"
    world.write_text("\n".join(lines) + "\n", encoding="utf-8", newline="\n")
    return world


# -- command line -----------------------------------------------------------------------------------------------


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pycram_cli.robots.zoo",
                                     description="Write zoo robots (URDF + description) and a kitchen world for each seed.")
    parser.add_argument("seeds", nargs="+", type=int, metavar="SEED")
    parser.add_argument("--out", type=Path, required=True, help="the folder to write into")
    args = parser.parse_args(argv)
    for seed in args.seeds:
        robot = generate(seed)
        world = write_world(robot, args.out)
        print(f"seed {seed}: {robot.name} ({len(robot.arm_joints)}-joint arm, {robot.gripper.kind} gripper, "
              f"camera on the {robot.camera.kind}{', torso' if robot.torso_joint else ''}) -> {world}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
