"""Robot descriptions read from `resources/robots/<name>/<name>.yaml`.

Everything a process module or a reasoning query needs to know about a particular robot
(joint names, tool and camera frames, park poses, gripper joints, grasp orientations)
lives in that file, so that another robot is added with data, not code.
"""
from __future__ import annotations

import functools
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import yaml

from ..paths import resources_dir

if TYPE_CHECKING:
    from ..world import Object


@dataclass(frozen=True)
class GripperDescription:
    joints: tuple[str, ...]
    open: float
    closed: float
    max_width: float = float("inf")  # metres between the fingers when fully open
    finger_height: float = 0.0  # side grasps (front, left, right) need objects at least this tall

    def angle_for_width(self, width: float) -> float:
        """The finger joint value that leaves `width` between the fingers (linear between closed and open)."""
        if width >= self.max_width or self.max_width == float("inf"):
            return self.open
        return self.closed + (self.open - self.closed) * max(width, 0.0) / self.max_width


@dataclass(frozen=True)
class ArmDescription:
    name: str
    joints: tuple[str, ...]
    tool_frame: str
    palm_link: str
    gripper: GripperDescription
    links: tuple[str, ...]
    poses: dict[str, tuple[float, ...]] = field(default_factory=dict)


@dataclass(frozen=True)
class CameraDescription:
    frame: str
    horizontal_fov: float
    vertical_fov: float
    near: float = 0.05
    far: float = 6.0


@dataclass(frozen=True)
class HeadDescription:
    pan_joint: str
    tilt_joint: str
    pan_link: str = ""
    tilt_link: str = ""


@dataclass(frozen=True)
class RobotDescription:
    name: str
    urdf: Path
    base_link: str
    camera: CameraDescription
    head: HeadDescription
    arms: dict[str, ArmDescription]
    grasps: dict[str, tuple[float, float, float, float]]
    torso_joint: str | None = None
    torso_default: float = 0.0

    def arm(self, name: str) -> ArmDescription:
        try:
            return self.arms[name]
        except KeyError:
            raise KeyError(f"robot '{self.name}' has no arm '{name}' (arms: {', '.join(self.arms)})") from None

    def grasp_orientation(self, grasp: str | tuple[float, ...] | list[float],
                          base_orientation: tuple[float, float, float, float]) -> tuple[float, float, float, float]:
        """World orientation of the tool frame for a named grasp (relative to the base) or a world quaternion."""
        from ..world.pose import check_quaternion, quat_multiply

        if isinstance(grasp, str):
            if grasp not in self.grasps:
                raise KeyError(f"robot '{self.name}' has no grasp '{grasp}' (grasps: {', '.join(self.grasps)})")
            return quat_multiply(base_orientation, self.grasps[grasp])
        return check_quaternion(grasp, "grasp")

    def arm_of_link(self, link: str) -> str | None:
        for arm in self.arms.values():
            if link in arm.links:
                return arm.name
        return None


def load_description(path: Path) -> RobotDescription:
    data = yaml.safe_load(path.read_text())
    arms = {}
    for name, arm in data["arms"].items():
        gripper = arm["gripper"]
        arms[name] = ArmDescription(
            name=name, joints=tuple(arm["joints"]), tool_frame=arm["tool_frame"], palm_link=arm["palm_link"],
            gripper=GripperDescription(tuple(gripper["joints"]), float(gripper["open"]), float(gripper["closed"]),
                                       float(gripper.get("max_width", float("inf"))),
                                       float(gripper.get("finger_height", 0.0))),
            links=tuple(arm.get("links", ())),
            poses={k: tuple(float(v) for v in vals) for k, vals in arm.get("poses", {}).items()},
        )
    cam = data["camera"]
    torso = data.get("torso") or {}
    return RobotDescription(
        name=data["name"], urdf=(path.parent / data["urdf"]).resolve(), base_link=data["base_link"],
        camera=CameraDescription(cam["frame"], float(cam["horizontal_fov"]), float(cam["vertical_fov"]),
                                 float(cam.get("near", 0.05)), float(cam.get("far", 6.0))),
        head=HeadDescription(**data["head"]), arms=arms,
        grasps={k: tuple(float(x) for x in v) for k, v in data.get("grasps", {}).items()},  # type: ignore[misc]
        torso_joint=torso.get("joint"), torso_default=float(torso.get("default", 0.0)),
    )


@functools.lru_cache(maxsize=None)
def _bundled() -> dict[str, RobotDescription]:
    found = {}
    for path in sorted((resources_dir() / "robots").glob("*/*.yaml")):
        try:
            desc = load_description(path)
        except (KeyError, TypeError, yaml.YAMLError):
            continue
        found[desc.name] = desc
    return found


def _urdf_robot_name(path: Path) -> str | None:
    if path.suffix.lower() != ".urdf":
        return None
    try:
        for _, element in ET.iterparse(path, events=("start",)):
            return element.get("name") if element.tag == "robot" else None
    except ET.ParseError:
        return None
    return None


def description_for(obj: "Object") -> RobotDescription | None:
    """The description of a robot object: matched by its URDF's robot name (then its file name)."""
    cached = getattr(obj, "_description", False)
    if cached is not False:
        return cached  # type: ignore[return-value]
    known = _bundled()
    name = _urdf_robot_name(obj.path) or obj.path.stem
    desc = known.get(name) or known.get(obj.path.stem)
    obj._description = desc  # type: ignore[attr-defined]
    return desc
