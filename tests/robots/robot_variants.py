"""Variants of the bundled Fetch that a user's robot is likely to be: wheels that touch the floor, a camera without
a pan/tilt head (fixed on the body), a camera on the wrist. Each is written as a URDF, a description and a kitchen
world into a folder, from the bundled files alone (the Fetch's kinematics and names stay; only what varies changes).
"""
from __future__ import annotations

import re
from pathlib import Path

from pycram_cli.paths import resources_dir, worlds_dir

#: collision cylinders for the drive wheels (axles 55.325 mm high): they reach the floor exactly
WHEEL_COLLISION = """    <collision>
      <origin xyz="0 0 0" rpy="1.57079632679 0 0"/>
      <geometry><cylinder radius="0.055325" length="0.0896"/></geometry>
    </collision>
"""
#: an optical frame on the wrist, 6 cm above the gripper's axis, looking along it (+z forward, +x right, +y down)
WRIST_CAMERA = """  <joint name="wrist_camera_joint" type="fixed">
    <parent link="wrist_roll_link"/>
    <child link="wrist_camera_optical_frame"/>
    <origin xyz="0.05 0 0.06" rpy="-1.57079632679 0 -1.57079632679"/>
  </joint>
  <link name="wrist_camera_optical_frame"/>
"""


def write_variant(folder: Path, name: str, camera: str = "head") -> Path:
    """A wheeled Fetch named `name` (wheels on the floor) with its camera on the `head`, fixed on the `body` (the head
    is not described: it stays as the world sets it) or on the `wrist`; returns its kitchen world file."""
    fetch = resources_dir() / "robots" / "fetch"
    urdf = (fetch / "fetch.urdf").read_text().replace('<robot name="fetch"', f'<robot name="{name}"')
    for wheel in ("r_wheel_link", "l_wheel_link"):
        start = urdf.index(f'<link name="{wheel}">')
        end = urdf.index("</link>", start)
        urdf = urdf[:end] + WHEEL_COLLISION + "  " + urdf[end:]
    description = (fetch / "fetch.yaml").read_text().replace("name: fetch", f"name: {name}")
    description = description.replace("urdf: fetch.urdf", f"urdf: {name}.urdf")
    if camera != "head":
        description = re.sub(r"\nhead: \{[^}]*\}\n", "\n", description)
    if camera == "wrist":
        urdf = urdf.replace("</robot>", WRIST_CAMERA + "</robot>")
        description = description.replace("frame: head_camera_rgb_optical_frame", "frame: wrist_camera_optical_frame")
    (folder / f"{name}.urdf").write_text(urdf)
    (folder / f"{name}.yaml").write_text(description)
    world = (worlds_dir() / "kitchen_fetch.yaml").read_text()
    world = world.replace("# yaml-language-server: $schema=../resources/schemas/world.schema.json\n", "")
    world = world.replace("file: robots/fetch/fetch.urdf", f"file: {folder / (name + '.urdf')}")
    if camera == "body":  # the camera held tilted down, as a fixed one is mounted to see a counter
        world = world.replace("head_tilt_joint: 0.45", "head_tilt_joint: 0.6")
    path = folder / f"{name}_kitchen.yaml"
    path.write_text(world)
    return path
