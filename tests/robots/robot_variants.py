"""Variants of the bundled Fetch that a user's robot is likely to be: wheels that touch the floor, a camera without
a pan/tilt head (fixed on the body), a camera on the wrist. Each is written as a URDF, a description and a kitchen
world into a folder, from the bundled files alone (the Fetch's kinematics and names stay; only what varies changes).
"""
from __future__ import annotations

import dataclasses
import functools
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


#: the multi-finger hand's fingers: two on the palm's +y edge and a thumb on its -y edge, each of two links that curl
#: (about the palm's x axis) towards the palm's -z face; the thumb's joints curl with negative values
HAND_PALM = (0.075, 0.05, 0.035)  # the palm box: x from 0 to this, y within ± this, z up to this (m)
HAND_FACE = 0.045  # the palm's face is this far below its axis (z), beyond the wrist's 3.6 cm (m)
HAND_FINGERS = (("finger_a", 0.018, 1.0), ("finger_b", 0.057, 1.0), ("thumb", 0.0375, -1.0))  # name, x, side
HAND_SEGMENTS = (0.05, 0.04)  # proximal and distal link lengths (m)
HAND_CLOSED = 1.5  # how far each joint curls (rad)
HAND_OPEN = 0.5  # open, the fingers stay a little curled: spread flat, they would span 28 cm


@functools.lru_cache(maxsize=2)
def multi_finger_robot(seed: int = 2, opened: float = HAND_OPEN):
    """The zoo robot of `seed` (a wheeled base, its camera on the wrist for seed 2) with its gripper replaced by a
    three-finger hand whose fingers curl towards the palm: it takes things palm-first and wraps them. Its tool frame
    is the wrist's (the palm's origin): where the hand holds things is the palm's face, as the model shows."""
    from pycram_cli.robots.zoo import BLACK, Gripper, Joint, Link, box, generate

    robot = generate(seed)
    palm, prefix = robot.palm_link, robot.palm_link.split("_")[0]
    old = {j.child for j in robot.joints if j.parent == palm and not j.child.startswith(f"{prefix}_camera")}
    joints = [j for j in robot.joints if j.child not in old]
    px, py, pz = HAND_PALM
    links = [Link(palm, (box((0.0, -py, -HAND_FACE), (px, py, pz)),), 700.0) if link.name == palm else link
             for link in robot.links if link.name not in old]
    names, hand_links = [], []
    for finger, x, side in HAND_FINGERS:
        parent, origin = palm, (x, side * py, -HAND_FACE)
        for k, length in enumerate(HAND_SEGMENTS):
            link, joint = f"{prefix}_{finger}_{k + 1}", f"{prefix}_{finger}_{k + 1}_joint"
            y0, y1 = (0.0, length) if side > 0 else (-length, 0.0)
            lower, upper = (0.0, HAND_CLOSED) if side > 0 else (-HAND_CLOSED, 0.0)
            joints.append(Joint(joint, "revolute", parent, link, origin, (0.0, 0.0, 0.0), (-1.0, 0.0, 0.0), lower, upper,
                                5.0, 1.0))
            links.append(Link(link, (box((-0.009, y0, -0.012), (0.009, y1, 0.0), BLACK),), 900.0))
            names.append(joint)
            hand_links.append(link)
            parent, origin = link, (0.0, side * length, 0.0)
    tool = f"{prefix}_hand_tcp"
    joints.append(Joint(f"{tool}_joint", "fixed", palm, tool, (0.0, 0.0, 0.0)))  # at the wrist, not where it holds
    links.append(Link(tool))
    arm_links = tuple(l for l in robot.arm_links if l not in old) + tuple(hand_links) + (tool,)
    gripper = Gripper("two_revolute", tuple(names), opened, HAND_CLOSED, 0.1, 0.0)
    return dataclasses.replace(robot, name=f"{robot.name}_hand", links=tuple(links), joints=tuple(joints),
                               tool_frame=tool, gripper=gripper, arm_links=arm_links)


def write_multi_finger_robot(folder: Path, gripper_keys: str = "", kitchen: bool = True,
                             opened: float = HAND_OPEN) -> Path:
    """The multi-finger robot (`multi_finger_robot`) in the bundled kitchen in place of the PR2 (or, `kitchen=False`,
    alone on a floor); its description leaves `grasps:` out (computed for the hand as the model has it) and its
    gripper gets `gripper_keys` (YAML lines such as `approach: fingers`) besides joints, open, closed, max_width and
    finger_height; `opened` is its open value. Returns the world file."""
    from pycram_cli.robots.zoo import write, write_world

    robot = multi_finger_robot(opened=opened)
    if kitchen:
        world = write_world(robot, folder)
    else:
        urdf = write(robot, folder)
        world = folder / "floor.yaml"
        world.write_text("objects:\n  - {name: floor, type: environment, file: environments/floor/floor.urdf}\n"
                         f"  - {{name: {robot.name}, type: robot, file: {urdf}, description: {urdf.with_suffix('.yaml')}}}\n")
    path = folder / f"{robot.name}.yaml"
    text = path.read_text()
    text = text.replace("# two revolute fingers", "# three fingers of two curling links each")
    text = text[:text.index("# Tool orientation")] + text[text.index("# The camera is on the wrist"):]
    if gripper_keys:
        extra = "".join(f"      {line}\n" for line in gripper_keys.strip().splitlines())
        marker = "      finger_height: 0\n"
        text = text.replace(marker, marker + extra)
    path.write_text(text)
    return world
