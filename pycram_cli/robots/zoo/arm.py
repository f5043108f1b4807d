"""The zoo robot's arm and gripper: a seeded layout (`ArmPlan`), sized for the kitchen's counter, then built.

What: the base's and column's seeded sizes (`BodyPlan`), the arm's joint kinds and segment lengths, its links'
shapes, and the gripper (one or two prismatic fingers, or two revolute ones) with its tool frame between the pads.
Why: the arm is the part of a robot whose variety tests pycram most (5-7 joints, mount offsets, weak arms).
"""
from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from .model import (
    ALONG_Y,
    BLACK,
    COUNTER_TOP,
    GRIPPER_KINDS,
    ORIGIN,
    X_AXIS,
    Z_AXIS,
    Gripper,
    Joint,
    Link,
    Names,
    Shape,
    Tree,
    Vec3,
    box,
    seeded,
    tube_x,
)


@dataclass(frozen=True)
class BodyPlan:
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


def plan_body(rng: random.Random) -> BodyPlan:
    """The base's and column's sizes; the shoulder stays at least 0.3 m above the base's top at every torso height."""
    shape = rng.choice(("box", "cylinder"))
    radius = seeded(rng, 0.2, 0.35)
    top = seeded(rng, 0.22, 0.38)
    clearance = seeded(rng, 0.02, 0.05)
    depth = seeded(rng, 0.12, 0.2)
    column_x = round(-radius * rng.uniform(0.2, 0.5), 3)
    width = seeded(rng, 0.16, min(0.28, 1.6 * radius))
    travel = seeded(rng, 0.3, 0.4) if rng.random() < 0.6 else 0.0
    shoulder = seeded(rng, 0.72, 1.12)
    default = 0.0
    if travel:
        room = shoulder - top - 0.3  # the shoulder stays >= 0.3 m above the base top with the torso down
        default = round(min(travel * rng.uniform(0.4, 0.85), max(room, 0.0)), 2)
        shoulder = max(shoulder, round(top + 0.3 + default, 3))
    else:
        shoulder = max(shoulder, round(top + 0.3, 3))
    return BodyPlan(shape, radius, top, clearance, column_x, depth, width, travel, default, shoulder)


# -- the robot ---------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ArmPlan:
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


def plan_arm(rng: random.Random, body: BodyPlan, mount_x: float, mount_y: float) -> ArmPlan:
    """Joint kinds and link lengths: long enough for a top grasp over the counter from 0.55-0.7 m (most seeds)."""
    count = rng.choice((5, 6, 7))
    kinds = rng.choice(ARM_LAYOUTS[count])
    offset = (seeded(rng, 0.05, 0.1), seeded(rng, 0.0, 0.05))
    wrist, palm, finger = seeded(rng, 0.08, 0.1), seeded(rng, 0.07, 0.1), seeded(rng, 0.045, 0.06)
    hand = wrist + palm + finger / 2  # wrist pitch -> tool frame
    shoulder_x = mount_x + offset[0]

    def needed(distance: float) -> float:
        return math.hypot(math.hypot(distance - shoulder_x, mount_y), COUNTER_TOP + 0.1 + hand - body.shoulder_height)

    weak = rng.random() < 0.15
    total = needed(0.55) * rng.uniform(0.8, 0.93) if weak else needed(0.7) * rng.uniform(1.03, 1.2)
    upper = round(total * rng.uniform(0.48, 0.58), 3)
    fore = round(total - upper, 3)
    extension = seeded(rng, 0.1, 0.18) if any(k.startswith("prism") for k in kinds) else 0.0
    return ArmPlan(tuple(kinds), upper, fore, wrist, palm, finger, seeded(rng, 0.038, 0.05), offset, extension, weak)


def _pitch_limits(rng: random.Random, kind: str) -> tuple[float, float]:
    """Limits of a pitch joint in 'up' terms (positive raises the link)."""
    if kind == "pitch1":
        return -seeded(rng, 1.3, 1.6), seeded(rng, 1.9, 2.3)
    if kind == "pitch2":
        return -seeded(rng, 2.4, 2.7), seeded(rng, 2.4, 2.7)
    return -seeded(rng, 2.0, 2.3), seeded(rng, 2.0, 2.3)


def _segments(plan: ArmPlan, fractions: dict[str, float]) -> list[float]:
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
        limit = seeded(rng, 1.7, 2.9)
        return Z_AXIS, -limit, limit, "revolute", 0.0
    if kind.startswith("prism"):
        return X_AXIS, 0.0, extension, "prismatic", 0.0
    if kind.startswith("roll"):
        if rng.random() < 0.5:
            return X_AXIS, None, None, "continuous", 0.0
        limit = seeded(rng, 2.6, 3.1)
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


def build_arm(rng: random.Random, tree: Tree, names: Names, plan: ArmPlan, parent: str, mount: Vec3,
         colours: tuple) -> _ArmBuild:
    """The arm's chain from the pan joint to the wrist roll link (the palm, shaped by the gripper)."""
    build = _ArmBuild()
    fractions = {"roll_upper": seeded(rng, 0.35, 0.5), "roll_fore": seeded(rng, 0.35, 0.5), "prism_upper": 0.6, "prism_fore": 0.6}
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


def build_gripper(rng: random.Random, tree: Tree, names: Names, plan: ArmPlan, palm: str, rgba) -> _Hand:
    """Fingers on the palm (two prismatic, one prismatic against a fixed pad, or two revolute claws), spread along
    the tool's y axis, and the tool frame between the pads."""
    roll = random.Random(rng.random())
    kind = roll.choices(GRIPPER_KINDS, weights=(0.5, 0.3, 0.2))[0]
    width = seeded(rng, 0.08, 0.12)
    height = seeded(rng, 0.02, 0.035)
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

