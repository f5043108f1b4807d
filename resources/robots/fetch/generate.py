#!/usr/bin/env python3
"""Generate pycram's own Fetch robot model, ``fetch.urdf``, from the tables below.

What
    A simplified but kinematically exact Fetch mobile manipulator for the
    PyBullet world: a round differential-drive base, a prismatic torso lift,
    a pan/tilt head with the RGB-D head camera's frames, one seven-joint arm
    and a parallel gripper with two prismatic fingers.

Why
    The official Fetch description (``fetch_description``) is licensed for
    non-commercial use only and depends on its meshes, so pycram cannot ship
    it.  pycram needs a self-contained model that loads anywhere, is fast for
    collision and visibility queries, and still answers "where is the gripper,
    where does the camera look" exactly like the real robot.  Therefore:

    * The kinematics (joint names, types, parent/child links, origins, axes and
      limits) are facts of the Fetch.  They are written down in ``JOINTS``,
      taken by hand from the numbers of the official ``fetch.urdf``
      (fetch_ros 0.8.3), and must never be "tuned".
    * The geometry is ours: boxes and cylinders that follow the extents of the
      real collision meshes closely enough for collision, blocking and
      visibility checks.  Each link's shapes are used for both ``<visual>``
      and ``<collision>``; the drive wheels are visual only (they reach 5 mm
      below the floor, so they would always touch it).  Frame-only links
      (camera frames) have no geometry at all.
    * Masses are the real link masses (rounded); inertias are computed from
      the primitives, assuming uniform density.

The script uses pycram's URDF writer (pycram_cli/robots/urdf_writer.py)
only and needs nothing from the original description to run.  Its output is deterministic, so a test can
check that the shipped ``fetch.urdf`` is up to date.

Usage::

    python resources/robots/fetch/generate.py                # writes fetch.urdf next to this file
    python resources/robots/fetch/generate.py --output x.urdf
"""
from __future__ import annotations

from pathlib import Path
from typing import Sequence

from pycram_cli.robots.urdf_writer import (
    HALF_PI,
    NEG_Z_AXIS,
    OPTICAL_RPY,
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

NEG_Y_AXIS: Vec3 = (0.0, -1.0, 0.0)

DEFAULT_OUTPUT = Path(__file__).resolve().parent / "fetch.urdf"


# --------------------------------------------------------------------------
# Kinematics: facts of the Fetch (fetch_description/robots/fetch.urdf)
# --------------------------------------------------------------------------
# Listed depth-first from the root, in the order PyBullet numbers the real
# model's joints.  The real file gives the wheel, torso and torso_fixed joints
# a roll of -6.123e-17 rad (a float artefact of 0); it is written as 0 here.
JOINTS: tuple[Joint, ...] = (
    # ---- drive wheels
    Joint("r_wheel_joint", "continuous", "base_link", "r_wheel_link",
          xyz=(0.0012914, -0.18738, 0.055325), axis=Y_AXIS, limit=Limit(None, None, 8.85, 17.4)),
    Joint("l_wheel_joint", "continuous", "base_link", "l_wheel_link",
          xyz=(0.0012914, 0.18738, 0.055325), axis=Y_AXIS, limit=Limit(None, None, 8.85, 17.4)),
    # ---- torso lift
    Joint("torso_lift_joint", "prismatic", "base_link", "torso_lift_link",
          xyz=(-0.086875, 0.0, 0.37743), axis=Z_AXIS, limit=Limit(0.0, 0.38615, 450.0, 0.1)),
    # ---- head and head camera (Primesense Carmine 1.09)
    Joint("head_pan_joint", "revolute", "torso_lift_link", "head_pan_link",
          xyz=(0.053125, 0.0, 0.603001417713939), axis=Z_AXIS, limit=Limit(-1.57, 1.57, 0.32, 1.57)),
    Joint("head_tilt_joint", "revolute", "head_pan_link", "head_tilt_link",
          xyz=(0.14253, 0.0, 0.057999), axis=Y_AXIS, limit=Limit(-0.76, 1.45, 0.68, 1.57)),
    Joint("head_camera_joint", "fixed", "head_tilt_link", "head_camera_link", xyz=(0.055, 0.0, 0.0225)),
    Joint("head_camera_rgb_joint", "fixed", "head_camera_link", "head_camera_rgb_frame", xyz=(0.0, 0.02, 0.0)),
    Joint("head_camera_rgb_optical_joint", "fixed", "head_camera_rgb_frame", "head_camera_rgb_optical_frame",
          rpy=OPTICAL_RPY),
    Joint("head_camera_depth_joint", "fixed", "head_camera_link", "head_camera_depth_frame",
          xyz=(0.0, 0.045, 0.0)),
    Joint("head_camera_depth_optical_joint", "fixed", "head_camera_depth_frame",
          "head_camera_depth_optical_frame", rpy=OPTICAL_RPY),
    # ---- arm
    Joint("shoulder_pan_joint", "revolute", "torso_lift_link", "shoulder_pan_link",
          xyz=(0.119525, 0.0, 0.34858), axis=Z_AXIS, limit=Limit(-1.6056, 1.6056, 33.82, 1.256)),
    Joint("shoulder_lift_joint", "revolute", "shoulder_pan_link", "shoulder_lift_link",
          xyz=(0.117, 0.0, 0.06), axis=Y_AXIS, limit=Limit(-1.221, 1.518, 131.76, 1.454)),
    Joint("upperarm_roll_joint", "continuous", "shoulder_lift_link", "upperarm_roll_link",
          xyz=(0.219, 0.0, 0.0), axis=X_AXIS, limit=Limit(None, None, 76.94, 1.571)),
    Joint("elbow_flex_joint", "revolute", "upperarm_roll_link", "elbow_flex_link",
          xyz=(0.133, 0.0, 0.0), axis=Y_AXIS, limit=Limit(-2.251, 2.251, 66.18, 1.521)),
    Joint("forearm_roll_joint", "continuous", "elbow_flex_link", "forearm_roll_link",
          xyz=(0.197, 0.0, 0.0), axis=X_AXIS, limit=Limit(None, None, 29.35, 1.571)),
    Joint("wrist_flex_joint", "revolute", "forearm_roll_link", "wrist_flex_link",
          xyz=(0.1245, 0.0, 0.0), axis=Y_AXIS, limit=Limit(-2.16, 2.16, 25.7, 2.268)),
    Joint("wrist_roll_joint", "continuous", "wrist_flex_link", "wrist_roll_link",
          xyz=(0.1385, 0.0, 0.0), axis=X_AXIS, limit=Limit(None, None, 7.36, 2.268)),
    # gripper_link is the point between the finger pads (the real tool frame)
    Joint("gripper_axis", "fixed", "wrist_roll_link", "gripper_link", xyz=(0.16645, 0.0, 0.0)),
    Joint("r_gripper_finger_joint", "prismatic", "gripper_link", "r_gripper_finger_link",
          xyz=(0.0, 0.015425, 0.0), axis=Y_AXIS, limit=Limit(0.0, 0.05, 60.0, 0.05)),
    Joint("l_gripper_finger_joint", "prismatic", "gripper_link", "l_gripper_finger_link",
          xyz=(0.0, -0.015425, 0.0), axis=NEG_Y_AXIS, limit=Limit(0.0, 0.05, 60.0, 0.05)),
    # ---- body parts
    Joint("bellows_joint", "prismatic", "torso_lift_link", "bellows_link",
          axis=NEG_Z_AXIS, limit=Limit(0.0, 0.4, 5.0, 0.1)),
    Joint("bellows_joint2", "fixed", "torso_lift_link", "bellows_link2"),
    Joint("estop_joint", "fixed", "base_link", "estop_link",
          xyz=(-0.12465, 0.23892, 0.31127), rpy=(1.5708, 0.0, 0.0)),
    Joint("laser_joint", "fixed", "base_link", "laser_link",
          xyz=(0.235, 0.0, 0.2878), rpy=(3.14159265359, 0.0, 0.0)),
    Joint("torso_fixed_joint", "fixed", "base_link", "torso_fixed_link", xyz=(-0.086875, 0.0, 0.377425)),
)

ROOT_LINK = "base_link"


# --------------------------------------------------------------------------
# Geometry: our simplification of the real links' volumes
# --------------------------------------------------------------------------
MATERIALS: dict[str, tuple[float, float, float, float]] = {
    "base_white": (0.92, 0.92, 0.93, 1.0),
    "body_blue": (0.1, 0.47, 0.75, 1.0),
    "arm_white": (0.95, 0.95, 0.95, 1.0),
    "arm_blue": (0.1, 0.47, 0.75, 1.0),
    "dark_grey": (0.34, 0.35, 0.38, 1.0),
    "bellows_black": (0.08, 0.08, 0.09, 1.0),
    "camera_black": (0.05, 0.05, 0.06, 1.0),
    "estop_red": (0.8, 0.0, 0.0, 1.0),
    "wheel_black": (0.1, 0.1, 0.1, 1.0),
}

CYLINDER_ALONG_Y: Vec3 = (HALF_PI, 0.0, 0.0)

#: Radius of the arm's link tubes and joint housings (the real meshes are 0.104 m across).
ARM_RADIUS = 0.052


def cylinder_y(radius: float, y0: float, y1: float, material: str, x: float = 0.0, z: float = 0.0,
               collision: bool = True) -> Shape:
    """A cylinder along the link's y axis from ``y0`` to ``y1``."""
    return Shape("cylinder", (radius, y1 - y0), (x, (y0 + y1) / 2, z), CYLINDER_ALONG_Y, material, collision)


def body_links() -> list[Link]:
    """Base, wheels, torso, head (extents follow the *_collision.STL meshes)."""
    return [
        # Round base, 0.56 m across (the real mesh: radius 0.287 m, flattened to
        # |y| <= 0.264 on the sides), top at 0.36 m; 3 cm ground clearance, so
        # that the base never touches the floor it stands on.
        Link("base_link", 70.13, (
            cylinder_z(0.28, 0.03, 0.36, "base_white"),
        )),
        # Drive wheels in their wells: visual only (they reach 5 mm below the floor).
        Link("r_wheel_link", 4.35, (cylinder_y(0.0603, -0.0448, 0.0448, "wheel_black", collision=False),)),
        Link("l_wheel_link", 4.35, (cylinder_y(0.0603, -0.0448, 0.0448, "wheel_black", collision=False),)),
        # The lift: a shell that slides over the fixed column (torso_fixed_link)
        # and carries the shoulder mount in front and the neck on top.
        Link("torso_lift_link", 10.78, (
            box((-0.185, -0.171, 0.03), (0.037, 0.171, 0.49), "body_blue"),       # shell
            box((0.037, -0.052, 0.18), (0.172, 0.052, 0.30), "body_blue"),        # shoulder mount
            box((-0.177, -0.168, 0.49), (0.073, 0.168, 0.54), "body_blue"),       # neck
            box((-0.163, -0.155, 0.54), (0.12, 0.155, 0.58), "body_blue"),
            box((-0.056, -0.126, 0.58), (0.132, 0.126, 0.603), "body_blue"),
        )),
        # The fixed column inside the lift's shell (seen below the shell when the
        # torso is up).
        Link("torso_fixed_link", 13.28, (
            box((-0.168, -0.155, -0.019), (-0.032, 0.155, 0.443), "body_blue"),
        )),
        # The bellows cover the gap in front of the column; they hang from the
        # lift (bellows_link2 is fixed to it; bellows_link, the same part on a
        # joint of its own in the real file, carries no geometry here).
        Link("bellows_link", 0.17),
        Link("bellows_link2", 0.17, (
            box((-0.030, -0.149, -0.298), (0.043, 0.149, 0.028), "bellows_black"),
        )),
        Link("estop_link", 0.002, (
            box((-0.017, -0.024, -0.015), (0.021, 0.017, 0.029), "estop_red"),
        )),
        Link("laser_link", 0.0083, (
            box((-0.047, -0.019, 0.035), (0.028, 0.019, 0.062), "dark_grey"),
        )),
        # Head: a pan plate with a U-bracket holding the tilting camera head.
        Link("head_pan_link", 2.26, (
            box((-0.125, -0.143, 0.0), (0.085, 0.143, 0.09), "dark_grey"),       # pan plate
            box((0.085, 0.108, 0.003), (0.197, 0.143, 0.113), "dark_grey"),      # bracket, left
            box((0.085, -0.143, 0.003), (0.197, -0.108, 0.113), "dark_grey"),    # bracket, right
        )),
        # The camera head; its front face is 5 mm behind the camera frames, so
        # renders from the camera start in free space.
        Link("head_tilt_link", 0.91, (
            box((-0.055, -0.105, -0.055), (0.05, 0.105, 0.055), "body_blue"),
        )),
        Link("head_camera_link"),
        Link("head_camera_rgb_frame"),
        Link("head_camera_rgb_optical_frame"),
        Link("head_camera_depth_frame"),
        Link("head_camera_depth_optical_frame"),
    ]


def arm_links() -> list[Link]:
    """The arm: tubes of radius 0.052 m along each link, housings around each joint.

    The real links are offset sideways in turn (a housing on one side of the
    joint, the next link's housing on the other side); the shapes follow those
    extents.  Links that are not directly connected do not touch with the arm
    stretched out (all joints at zero) or parked.
    """
    r = ARM_RADIUS
    return [
        Link("shoulder_pan_link", 2.56, (
            cylinder_z(r, -0.048, 0.07, "arm_white"),                                  # pan housing
            cylinder_y(0.06, -0.075, 0.017, "arm_white", x=0.117, z=0.06),             # lift housing
        )),
        Link("shoulder_lift_link", 2.66, (
            cylinder_y(0.06, -0.052, 0.0705, "arm_blue"),                              # lift housing
            cylinder_x(r, 0.0, 0.172, "arm_blue"),
        )),
        Link("upperarm_roll_link", 2.33, (
            cylinder_x(r, -0.048, 0.10, "arm_white"),
            cylinder_y(r, -0.071, 0.019, "arm_white", x=0.133),                        # elbow housing
        )),
        Link("elbow_flex_link", 2.13, (
            cylinder_y(r, -0.017, 0.0705, "arm_blue"),                                 # elbow housing
            cylinder_x(r, 0.03, 0.166, "arm_blue"),
        )),
        Link("forearm_roll_link", 1.66, (
            cylinder_x(r, -0.032, 0.06, "arm_white"),
            cylinder_y(r, -0.087, -0.021, "arm_white", x=0.1245),                      # wrist housing
        )),
        Link("wrist_flex_link", 1.73, (
            cylinder_y(r, -0.054, 0.067, "arm_blue"),                                  # wrist housing
            cylinder_x(r, 0.03, 0.1165, "arm_blue"),
        )),
        Link("wrist_roll_link", 0.14, (
            cylinder_x(r, -0.023, 0.0195, "arm_white"),
        )),
        # The gripper body lies behind gripper_link (the point between the pads).
        Link("gripper_link", 1.52, (
            box((-0.154, -0.063, -0.04), (-0.032, 0.063, 0.04), "dark_grey"),
        )),
        # Finger pads, 6 cm long and 2.6 cm tall; closed, they keep a 1 mm gap.
        Link("r_gripper_finger_link", 0.08, (
            box((-0.029, -0.0149, -0.0132), (0.031, -0.0014, 0.0132), "dark_grey"),
        )),
        Link("l_gripper_finger_link", 0.08, (
            box((-0.029, 0.0014, -0.0132), (0.031, 0.0149, 0.0132), "dark_grey"),
        )),
    ]


def all_links() -> dict[str, Link]:
    links = body_links() + arm_links()
    return {link.name: link for link in links}


def build_urdf() -> str:
    """The complete URDF text."""
    comment = ["<!-- GENERATED by resources/robots/fetch/generate.py - do not edit by hand.",
               "     Kinematics: Fetch (fetch_description 0.8.3); geometry: simplified primitives. -->"]
    return table_urdf("fetch", comment, ROOT_LINK, JOINTS, all_links(), MATERIALS)


def main(argv: Sequence[str] | None = None) -> None:
    generator_main(__doc__, DEFAULT_OUTPUT, build_urdf, argv)


if __name__ == "__main__":
    main()
