"""The whole zoo robot: `generate(seed)` builds the base, wheels, column or torso, arm, gripper, camera and head.

What: the seeded robot put together from the parts (`arm.py`), its arm parked (`park.py`).
Why: one function reads as the robot's recipe; the parts keep their own sizes and shapes.
"""
from __future__ import annotations

import functools
import math
import random
from collections.abc import Sequence
from dataclasses import dataclass

from .arm import ArmPlan, BodyPlan, build_arm, build_gripper, plan_arm, plan_body
from .model import (
    ALONG_Y,
    ARM_NAMES,
    BLACK,
    CAMERA_KINDS,
    COLOURS,
    OPTICAL_RPY,
    ORIGIN,
    Z_AXIS,
    Camera,
    Head,
    Joint,
    Link,
    Names,
    Shape,
    Tree,
    Vec3,
    ZooRobot,
    box,
    seeded,
    seeded_names,
)
from .park import Obstacle, ParkProblem, find_park

# -- the whole robot ---------------------------------------------------------------------------------------------


def _wheels(rng: random.Random, tree: Tree, names: Names, base: str, body: BodyPlan, lift: float) -> None:
    """Drive wheels and casters whose collision shapes touch the floor at z = 0 (the base link is `lift` up)."""
    radius, width = seeded(rng, 0.05, 0.08), seeded(rng, 0.03, 0.05)
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
    caster_radius = seeded(rng, 0.025, 0.04)
    for name, x in casters:
        tree.add(Joint(names.frame(f"{name}_joint"), "fixed", base, names.frame(name), (x, 0.0, round(caster_radius - lift, 4))),
                 Link(names.frame(name), (Shape("sphere", (caster_radius,), rgba=BLACK),), 1200.0))


def _column_sink(body: BodyPlan) -> float:
    """How far the torso column reaches down into the base (it slides in a sleeve on the base)."""
    return round(min(body.torso_travel, body.top - 0.1), 3) if body.torso_travel else 0.02


def _base_shapes(body: BodyPlan, lift: float, rgba) -> tuple[Shape, ...]:
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
    horizontal = seeded(rng, 0.9, 1.25)
    return horizontal, round(2 * math.atan(0.75 * math.tan(horizontal / 2)), 3)


def _optical(tree: Tree, names: Names, parent: str, xyz: Vec3, rpy: Vec3) -> str:
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


def _root(rng: random.Random, names: Names, body: BodyPlan, rgba) -> tuple[Tree, str, float]:
    """A footprint frame on the floor with the base link above it, or the base link itself as the root;
    returns the tree, the base link and its height above the floor."""
    if rng.random() < 0.5:
        root, base, lift = names.frame("base_footprint"), names.link("base"), seeded(rng, 0.05, 0.12)
        tree = Tree(Link(root))
        tree.add(Joint(f"{root}_joint", "fixed", root, base, (0.0, 0.0, lift)), Link(base, _base_shapes(body, lift, rgba), 400.0))
        return tree, base, lift
    base = names.link("base")
    return Tree(Link(base, _base_shapes(body, 0.0, rgba), 400.0)), base, 0.0


def _column(rng: random.Random, tree: Tree, names: Names, body: BodyPlan, base: str, lift: float, mount_y: float,
            plan: ArmPlan, camera_kind: str, rgba) -> _Column:
    """The torso lift (prismatic) or fixed mast, tall enough for the head or the mast camera, with the shoulder bracket."""
    mount_z = round(body.shoulder_height - plan.pan_offset[1] - body.top - body.torso_default, 3)
    if camera_kind == "head":
        top = max(round(seeded(rng, 1.15, 1.5) - 0.09 - body.top - body.torso_default, 3), mount_z + 0.15)
    elif camera_kind == "mast":
        top = max(round(seeded(rng, 1.1, 1.45) - 0.04 - body.top - body.torso_default, 3), mount_z + 0.12)
    else:
        top = round(mount_z + seeded(rng, 0.08, 0.2), 3)
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


def _head(rng: random.Random, tree: Tree, names: Names, body: BodyPlan, column: _Column,
          rgba) -> tuple[Head, str, Obstacle]:
    """A pan/tilt head on the column's top (the tilt axis' sign is seeded); returns it, its camera frame and its box."""
    pan, tilt = names.joint("head_pan"), names.joint("head_tilt")
    pan_link, tilt_link = names.link("head_pan"), names.link("head_tilt")
    limit, sign = seeded(rng, 1.5, 2.6), rng.choice((1.0, -1.0))
    tree.add(Joint(pan, "revolute", column.link, pan_link, (0.0, 0.0, column.top), ORIGIN, Z_AXIS, -limit, limit, 5.0, 2.0),
             Link(pan_link, (Shape("cylinder", (0.05, 0.06), (0.0, 0.0, 0.03), ORIGIN, rgba),), 600.0))
    lower, upper = (-0.6, 1.2) if sign > 0 else (-1.2, 0.6)
    tree.add(Joint(tilt, "revolute", pan_link, tilt_link, (0.0, 0.0, 0.09), ORIGIN, (0.0, sign, 0.0), lower, upper, 5.0, 2.0),
             Link(tilt_link, (box((-0.05, -0.1, -0.035), (0.045, 0.1, 0.035), rgba),), 600.0))
    frame = _optical(tree, names, tilt_link, (0.05, 0.0, 0.0), ORIGIN)
    top = column.floor_z + column.top
    return (Head(pan, tilt, pan_link, tilt_link, round(0.45 * sign, 3)), frame,
            Obstacle((body.column_x - 0.15, -0.15, top - 0.02), (body.column_x + 0.15, 0.15, top + 0.25)))


def _mast_camera(rng: random.Random, tree: Tree, names: Names, body: BodyPlan, column: _Column,
                 rgba) -> tuple[str, Obstacle]:
    """A camera fixed on the column's top, looking forward and down; returns its frame and its housing's box."""
    half_d = body.column_depth / 2
    housing = names.link("camera_housing")
    tree.add(Joint(names.joint("camera_housing"), "fixed", column.link, housing, (half_d, 0.0, column.top)),
             Link(housing, (box((-0.03, -0.06, 0.0), (0.015, 0.06, 0.06), rgba),), 600.0))
    frame = _optical(tree, names, housing, (0.02, 0.0, 0.03), (0.0, seeded(rng, 0.3, 0.6), 0.0))
    top = column.floor_z + column.top
    return frame, Obstacle((body.column_x + half_d - 0.03, -0.06, top), (body.column_x + half_d + 0.02, 0.06, top + 0.06))


def _wrist_camera(rng: random.Random, tree: Tree, names: Names, plan: ArmPlan, palm: str, palm_half: float,
                  rgba) -> tuple[str, list[str]]:
    """A camera on the palm's top, looking along the tool (a little down); returns its frame and its links."""
    housing = names.link("camera_housing")
    tree.add(Joint(names.joint("camera_housing"), "fixed", palm, housing, (0.0, 0.0, palm_half)),
             Link(housing, (box((0.035, -0.03, 0.0), (plan.palm - 0.01, 0.03, 0.03), rgba),), 600.0))
    frame = _optical(tree, names, housing, (round(plan.palm - 0.005, 3), 0.0, 0.015), (0.0, seeded(rng, 0.1, 0.3), 0.0))
    return frame, [housing, names.frame("camera_link"), frame]


@functools.lru_cache(maxsize=64)
def generate(seed: int) -> ZooRobot:
    """The zoo robot of a seed (deterministic: the same seed gives the same robot; generated once per process, as
    finding its park pose takes a few tenths of a second, and a `ZooRobot` is frozen)."""
    rng = random.Random(seed)
    names = seeded_names(rng, seed)
    colours = tuple(rng.sample(COLOURS, 3))
    body = plan_body(rng)
    camera_kind = CAMERA_KINDS[seed % 3] if seed < 3 else rng.choice(CAMERA_KINDS)
    tree, base, lift = _root(rng, names, body, colours[0])
    _wheels(rng, tree, names, base, body, lift)
    # the column (a torso lift or a fixed mast) with the arm mounted on its front
    mount_x = round(body.column_x + body.column_depth / 2 + 0.07, 3)
    mount_y = seeded(rng, -0.08, 0.08)
    plan = plan_arm(rng, body, mount_x, mount_y)
    column = _column(rng, tree, names, body, base, lift, mount_y, plan, camera_kind, colours[1])
    obstacles = [Obstacle((body.column_x - body.column_depth / 2, -body.column_width / 2, body.top),
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
    arm = build_arm(rng, tree, names, plan, column.link, (round(body.column_depth / 2 + 0.07, 4), mount_y, column.mount_z),
               colours[1:])
    hand = build_gripper(rng, tree, names, plan, arm.palm, colours[0])
    hand_links = list(hand.links)
    if camera_kind == "wrist":
        frame, camera_links = _wrist_camera(rng, tree, names, plan, arm.palm, hand.palm_half_height, colours[2])
        hand_links += camera_links
    tree.reshape(arm.palm, hand.palm_shapes)
    camera = Camera(camera_kind, frame, *_fov(rng))
    # the park pose, searched for with the torso at its default
    pan_index = next(i for i, j in enumerate(tree.joints) if j.name == arm.joints[0])
    problem = ParkProblem(_subtree(tree.joints, pan_index), {link.name: link for link in tree.links}, tuple(arm.joints),
                           arm.up_sign, (mount_x, mount_y, round(column.floor_z + column.mount_z, 4)),
                           frozenset({arm.palm, *hand_links}), tuple(obstacles), body.shape, body.radius,
                           body.top + body.torso_default + 0.03, sight)
    return ZooRobot(seed=seed, name=f"zoo_{names.prefix}", root_link=tree.links[0].name, links=tuple(tree.links),
                    joints=tuple(tree.joints), base_shape=body.shape, base_radius=body.radius, base_top=body.top,
                    torso_joint=column.joint, torso_default=body.torso_default, shoulder_height=body.shoulder_height,
                    arm_name=rng.choice(ARM_NAMES), arm_kinds=plan.kinds, arm_joints=tuple(arm.joints),
                    arm_links=tuple(arm.links + hand_links), tool_frame=hand.tool, palm_link=arm.palm, gripper=hand.gripper,
                    camera=camera, head=head, park=find_park(problem), weak=plan.weak)


def _subtree(joints: Sequence[Joint], first: int) -> tuple[Joint, ...]:
    """The joint at `first` and every joint below it, parents first."""
    inside = {joints[first].child}
    chosen = [joints[first]]
    for joint in joints[first + 1:]:
        if joint.parent in inside:
            inside.add(joint.child)
            chosen.append(joint)
    return tuple(chosen)

