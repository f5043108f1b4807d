#!/usr/bin/env python3
"""Generate pycram's own PR2 robot model, ``pr2.urdf``, from the tables below.

What
    A simplified but kinematically exact PR2 for the PyBullet world: base,
    torso lift, pan/tilt head with the wide stereo camera chain, two
    seven-joint arms and two parallel grippers.

Why
    The official PR2 description depends on ROS packages and on large meshes.
    pycram needs a self-contained model that loads anywhere, is fast for
    collision and visibility queries, and still answers "where is the gripper,
    where does the camera look" exactly like the real robot.  Therefore:

    * The kinematics (joint names, types, parent/child links, origins, axes and
      limits) are facts of the PR2.  They are written down in ``JOINTS`` (the arms in ``arm_joints``),
      copied by hand from the official ``pr2.urdf`` (iai_pr2_description),
      and must never be "tuned".
    * The geometry is ours: boxes and cylinders that follow the volumes of the
      real collision meshes closely enough for collision, blocking and
      visibility checks.  Each link's shapes are used for both ``<visual>`` and
      ``<collision>``; a few purely cosmetic shapes (the caster wheels) are
      visual only.  Frame-only links (tool frames, camera frames, roll links)
      have no geometry at all.
    * Masses are the real link masses (rounded); inertias are computed from
      the primitives, assuming uniform density.

The script uses pycram's URDF writer (pycram_cli/robots/urdf_writer.py)
only and needs nothing from the original description to run.  Its output is deterministic, so a test can
check that the shipped ``pr2.urdf`` is up to date.

Usage::

    python resources/robots/pr2/generate.py                # writes pr2.urdf next to this file
    python resources/robots/pr2/generate.py --output x.urdf
"""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

from pycram_cli.robots.urdf_writer import (
    HALF_PI,
    NEG_Z_AXIS,
    OPTICAL_RPY,
    ORIGIN,
    X_AXIS,
    Y_AXIS,
    Z_AXIS,
    Joint,
    Limit,
    Link,
    Shape,
    Vec3,
    box,
    cylinder_x,
    cylinder_z,
    generator_main,
    table_urdf,
)


DEFAULT_OUTPUT = Path(__file__).resolve().parent / "pr2.urdf"


# --------------------------------------------------------------------------
# Kinematics: facts of the PR2 (from iai_pr2_description's pr2.urdf)
# --------------------------------------------------------------------------
def arm_joints(side: str, shoulder_y: float, pan: tuple[float, float],
               upper_arm_roll: tuple[float, float]) -> tuple[Joint, ...]:
    """One arm's joints, ``side`` "r" or "l": the two arms differ only in the shoulder's offset and the limits of
    the shoulder pan and upper arm roll (mirrored), so one table written once keeps the two from drifting apart."""
    s = side
    finger = f"{s}_gripper_l_finger_joint"  # the joint the other three finger joints mimic
    return (
        Joint(f"{s}_shoulder_pan_joint", "revolute", "torso_lift_link", f"{s}_shoulder_pan_link",
              xyz=(0.0, shoulder_y, 0.0), axis=Z_AXIS, limit=Limit(*pan, 30, 2.088)),
        Joint(f"{s}_shoulder_lift_joint", "revolute", f"{s}_shoulder_pan_link", f"{s}_shoulder_lift_link",
              xyz=(0.1, 0.0, 0.0), axis=Y_AXIS, limit=Limit(-0.5236, 1.3963, 30, 2.082)),
        Joint(f"{s}_upper_arm_roll_joint", "revolute", f"{s}_shoulder_lift_link", f"{s}_upper_arm_roll_link",
              axis=X_AXIS, limit=Limit(*upper_arm_roll, 30, 3.27)),
        Joint(f"{s}_upper_arm_joint", "fixed", f"{s}_upper_arm_roll_link", f"{s}_upper_arm_link"),
        Joint(f"{s}_elbow_flex_joint", "revolute", f"{s}_upper_arm_link", f"{s}_elbow_flex_link",
              xyz=(0.4, 0.0, 0.0), axis=Y_AXIS, limit=Limit(-2.3213, 0.0, 30, 3.3)),
        Joint(f"{s}_forearm_roll_joint", "continuous", f"{s}_elbow_flex_link", f"{s}_forearm_roll_link",
              axis=X_AXIS, limit=Limit(None, None, 30, 3.6)),
        Joint(f"{s}_forearm_joint", "fixed", f"{s}_forearm_roll_link", f"{s}_forearm_link"),
        Joint(f"{s}_wrist_flex_joint", "revolute", f"{s}_forearm_link", f"{s}_wrist_flex_link",
              xyz=(0.321, 0.0, 0.0), axis=Y_AXIS, limit=Limit(-2.18, 0.0, 10, 3.078)),
        Joint(f"{s}_wrist_roll_joint", "continuous", f"{s}_wrist_flex_link", f"{s}_wrist_roll_link",
              axis=X_AXIS, limit=Limit(None, None, 10, 3.6)),
        Joint(f"{s}_gripper_palm_joint", "fixed", f"{s}_wrist_roll_link", f"{s}_gripper_palm_link"),
        Joint(finger, "revolute", f"{s}_gripper_palm_link", f"{s}_gripper_l_finger_link",
              xyz=(0.07691, 0.01, 0.0), axis=Z_AXIS, limit=Limit(0.0, 0.548, 1000.0, 0.5)),
        Joint(f"{s}_gripper_l_finger_tip_joint", "revolute", f"{s}_gripper_l_finger_link",
              f"{s}_gripper_l_finger_tip_link", xyz=(0.09137, 0.00495, 0.0), axis=NEG_Z_AXIS,
              limit=Limit(0.0, 0.548, 1000.0, 0.5), mimic=finger),
        Joint(f"{s}_gripper_r_finger_joint", "revolute", f"{s}_gripper_palm_link", f"{s}_gripper_r_finger_link",
              xyz=(0.07691, -0.01, 0.0), axis=NEG_Z_AXIS, limit=Limit(0.0, 0.548, 1000.0, 0.5), mimic=finger),
        Joint(f"{s}_gripper_r_finger_tip_joint", "revolute", f"{s}_gripper_r_finger_link",
              f"{s}_gripper_r_finger_tip_link", xyz=(0.09137, -0.00495, 0.0), axis=Z_AXIS,
              limit=Limit(0.0, 0.548, 1000.0, 0.5), mimic=finger),
        Joint(f"{s}_gripper_tool_joint", "fixed", f"{s}_gripper_palm_link", f"{s}_gripper_tool_frame",
              xyz=(0.18, 0.0, 0.0)),
    )


# Listed depth-first from the root; the URDF is written in this order, which is
# also the order of PyBullet's joint indices.
JOINTS: tuple[Joint, ...] = (
    # ---- base and torso
    Joint("base_footprint_joint", "fixed", "base_footprint", "base_link", xyz=(0.0, 0.0, 0.051)),
    Joint("torso_lift_joint", "prismatic", "base_link", "torso_lift_link",
          xyz=(-0.05, 0.0, 0.739675), axis=Z_AXIS, limit=Limit(0.0, 0.33, 10000, 0.013)),
    # ---- head and wide stereo camera
    Joint("head_pan_joint", "revolute", "torso_lift_link", "head_pan_link",
          xyz=(-0.01707, 0.0, 0.38145), axis=Z_AXIS, limit=Limit(-3.007, 3.007, 2.645, 6)),
    Joint("head_tilt_joint", "revolute", "head_pan_link", "head_tilt_link",
          xyz=(0.068, 0.0, 0.0), axis=Y_AXIS, limit=Limit(-0.471238, 1.39626, 18, 5)),
    Joint("head_plate_frame_joint", "fixed", "head_tilt_link", "head_plate_frame",
          xyz=(0.0232, 0.0, 0.0645)),
    Joint("sensor_mount_frame_joint", "fixed", "head_plate_frame", "sensor_mount_link"),
    Joint("double_stereo_frame_joint", "fixed", "sensor_mount_link", "double_stereo_link"),
    Joint("wide_stereo_frame_joint", "fixed", "double_stereo_link", "wide_stereo_link",
          xyz=(0.045, 0.03, 0.0501)),
    Joint("wide_stereo_optical_frame_joint", "fixed", "wide_stereo_link",
          "wide_stereo_optical_frame", rpy=OPTICAL_RPY),
    # ---- the arms (right first, as in the official file): mirror images but for these facts of each side
    *arm_joints("r", shoulder_y=-0.188, pan=(-2.2853981634, 0.714601836603), upper_arm_roll=(-3.9, 0.8)),
    *arm_joints("l", shoulder_y=0.188, pan=(-0.714601836603, 2.2853981634), upper_arm_roll=(-0.8, 3.9)),
)

ROOT_LINK = "base_footprint"


# --------------------------------------------------------------------------
# Geometry: our simplification of the real links' volumes
# --------------------------------------------------------------------------
MATERIALS: dict[str, tuple[float, float, float, float]] = {
    "base_grey": (0.72, 0.72, 0.74, 1.0),
    "body_white": (0.9, 0.9, 0.9, 1.0),
    "shoulder_white": (0.82, 0.82, 0.84, 1.0),
    "arm_grey": (0.42, 0.45, 0.54, 1.0),
    "joint_dark": (0.25, 0.26, 0.3, 1.0),
    "gripper_blue": (0.3, 0.45, 0.78, 1.0),
    "finger_blue": (0.16, 0.26, 0.55, 1.0),
    "camera_black": (0.08, 0.08, 0.1, 1.0),
    "wheel_black": (0.1, 0.1, 0.1, 1.0),
}

CYLINDER_ALONG_Y: Vec3 = (HALF_PI, 0.0, 0.0)


def cylinder_y(radius: float, length: float, material: str, at: Vec3 = ORIGIN,
               collision: bool = True) -> Shape:
    """A cylinder along the link's y axis, centred at ``at``."""
    return Shape("cylinder", (radius, length), at, CYLINDER_ALONG_Y, material, collision)


def caster_wheels() -> list[Shape]:
    """Cosmetic (visual-only) wheels: two per caster, as placed in the real base."""
    wheels = []
    for cx in (0.2246, -0.2246):
        for cy in (0.2246, -0.2246):
            for dy in (0.049, -0.049):
                wheels.append(cylinder_y(0.079, 0.034, "wheel_black",
                                         at=(cx, cy + dy, 0.0282), collision=False))
    return wheels


def body_links() -> list[Link]:
    """Base, torso and head (extents follow base_L, torso_lift_L, head_*_L meshes)."""
    return [
        Link("base_footprint"),
        Link("base_link", 116.0, (
            box((-0.334, -0.334, 0.0), (0.334, 0.334, 0.23), "base_grey"),     # main body
            box((-0.316, -0.241, 0.23), (0.302, 0.241, 0.295), "base_grey"),   # top deck
            *caster_wheels(),
        )),
        # The column reaches down into the base so that it never floats above it,
        # even at full lift (0.33 m).
        Link("torso_lift_link", 36.25, (
            box((-0.28, -0.13, -0.78), (-0.06, 0.13, 0.157), "body_white"),     # lift column
            box((-0.288, -0.264, 0.157), (0.112, 0.264, 0.24), "body_white"),  # shoulder cover
            box((-0.26, -0.19, 0.24), (0.09, 0.19, 0.314), "body_white"),      # head mount
        )),
        Link("head_pan_link", 6.34, (
            box((-0.1, -0.15, -0.066), (0.12, 0.15, 0.04), "joint_dark"),
        )),
        # The stereo camera housing lives on head_tilt_link (the real file only
        # draws it on double_stereo_link, a frame); its front face is 5 mm behind
        # the wide stereo lens, so rays and renders from the camera start in free
        # space.
        Link("head_tilt_link", 4.48, (
            box((-0.183, -0.147, 0.046), (0.045, 0.147, 0.155), "body_white"),   # head
            box((0.0132, -0.04, 0.0745), (0.0632, 0.1, 0.1545), "camera_black"),  # stereo cams
        )),
        Link("head_plate_frame"),
        Link("sensor_mount_link"),
        Link("double_stereo_link"),
        Link("wide_stereo_link"),
        Link("wide_stereo_optical_frame"),
    ]


def finger_shapes(side_sign: float) -> tuple[Shape, ...]:
    """Proximal finger: +y side for the l finger (side_sign=1), -y for the r finger."""
    s = side_sign
    return (box((0.0, min(0.002 * s, 0.032 * s), -0.012),
                (0.085, max(0.002 * s, 0.032 * s), 0.012), "gripper_blue"),)


def finger_tip_shapes(side_sign: float) -> tuple[Shape, ...]:
    """Finger tip; the pad faces the other finger.  Closed tips keep a 2 mm gap."""
    s = side_sign
    return (box((-0.012, min(-0.014 * s, 0.016 * s), -0.011),
                (0.031, max(-0.014 * s, 0.016 * s), 0.011), "finger_blue"),)


def arm_links(side: str) -> list[Link]:
    """One arm, ``side`` 'l' or 'r'; the arm geometry is symmetric.

    Clearances are designed so that links which are not (through frame-only
    links) directly connected do not touch at zero joint angles and in the park
    poses: the upper arm starts beyond the shoulder-lift housing, the forearm
    starts beyond the elbow knuckle, the palm beyond the wrist knuckle, and the
    elbow end of the upper arm is low on its +z side where the forearm folds in.
    """
    p = side
    return [
        # Shoulder housing around the pan axis (real mesh: x -0.127..0.068 below
        # the lift joint), ending 2.5 cm above the base deck at torso height 0.
        # The hanging upper arm only reaches it beyond shoulder lift 1.26 rad.
        Link(f"{p}_shoulder_pan_link", 25.8, (
            cylinder_z(0.105, -0.42, 0.142, "shoulder_white", x=-0.04),
        )),
        Link(f"{p}_shoulder_lift_link", 2.75, (
            cylinder_y(0.12, 0.15, "shoulder_white"),
        )),
        Link(f"{p}_upper_arm_roll_link"),
        Link(f"{p}_upper_arm_link", 6.02, (
            cylinder_x(0.075, 0.125, 0.28, "arm_grey"),
            box((0.28, -0.065, -0.085), (0.47, 0.065, 0.025), "arm_grey"),  # elbow end
        )),
        Link(f"{p}_elbow_flex_link", 1.9, (
            cylinder_y(0.07, 0.09, "joint_dark"),
        )),
        Link(f"{p}_forearm_roll_link"),
        Link(f"{p}_forearm_link", 2.58, (
            cylinder_x(0.055, 0.08, 0.16, "arm_grey"),                       # roll bearing
            box((0.16, -0.058, -0.042), (0.26, 0.058, 0.042), "arm_grey"),   # forearm body
            box((0.26, 0.036, -0.035), (0.335, 0.056, 0.035), "arm_grey"),   # wrist clevis
            box((0.26, -0.056, -0.035), (0.335, -0.036, 0.035), "arm_grey"),
        )),
        Link(f"{p}_wrist_flex_link", 0.61, (
            cylinder_y(0.035, 0.07, "joint_dark"),
        )),
        Link(f"{p}_wrist_roll_link"),
        Link(f"{p}_gripper_palm_link", 0.58, (
            box((0.04, -0.03, -0.022), (0.06, 0.03, 0.022), "gripper_blue"),     # neck
            box((0.06, -0.05, -0.024), (0.115, 0.05, 0.024), "gripper_blue"),    # palm
        )),
        Link(f"{p}_gripper_l_finger_link", 0.17, finger_shapes(1.0)),
        Link(f"{p}_gripper_l_finger_tip_link", 0.044, finger_tip_shapes(1.0)),
        Link(f"{p}_gripper_r_finger_link", 0.17, finger_shapes(-1.0)),
        Link(f"{p}_gripper_r_finger_tip_link", 0.044, finger_tip_shapes(-1.0)),
        Link(f"{p}_gripper_tool_frame"),
    ]


def all_links() -> dict[str, Link]:
    links = body_links() + arm_links("r") + arm_links("l")
    return {link.name: link for link in links}


def build_urdf() -> str:
    """The complete URDF text."""
    comment = ["<!-- GENERATED by resources/robots/pr2/generate.py - do not edit by hand.",
               "     Kinematics: PR2 (iai_pr2_description); geometry: simplified primitives. -->"]
    return table_urdf("pr2", comment, ROOT_LINK, JOINTS, all_links(), MATERIALS)


def main(argv: Sequence[str] | None = None) -> None:
    generator_main(__doc__, DEFAULT_OUTPUT, build_urdf, argv)


if __name__ == "__main__":
    main()
