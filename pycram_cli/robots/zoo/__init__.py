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
The package, by part: `model.py` (the model, numbers, names), `arm.py` (arm and gripper), `park.py` (the
park search), `build.py` (`generate`), `files.py` (URDF, description, world file, command line).
"""
from __future__ import annotations

from .build import generate
from .files import description_text, main, urdf_text, world_joints, write, write_world
from .model import BLACK, CAMERA_KINDS, GRIPPER_KINDS, Camera, Gripper, Head, Joint, Link, Shape, ZooRobot, box

__all__ = ["BLACK", "CAMERA_KINDS", "GRIPPER_KINDS", "Camera", "Gripper", "Head", "Joint", "Link", "Shape", "ZooRobot",
           "box", "description_text", "generate", "main", "urdf_text", "world_joints", "write", "write_world"]
