"""Robot descriptions: everything robot-specific, kept as data in a YAML file.

Which arms a robot has (any number, any names), their joints, tool frames, grippers and
named poses, the grasp orientations, the camera, head and torso, whether the base can
drive, which physical resources steps may share, and which process module serves a
designator: process modules, reasoning queries and plan validation read all of it from
here, so a new robot is added with data, not code (docs/robots.md).

A robot object finds its description (`find_description`):
1. the file named by `description:` on the robot in the world file;
2. `<urdf stem>.yaml` beside the robot's URDF (a user's own robot);
3. a bundled description (`resources/robots/*/*.yaml`) whose `name` is the URDF's robot
   name (so the real PR2's URDF gets our PR2 description), then the URDF's file name.
A broken description is an input error naming its file, line and key.
"""
from __future__ import annotations

import dataclasses
import functools
import math
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import InputError, Location, UnknownName, did_you_mean, raise_if_any
from ..files import probe
from ..paths import resources_dir
from ..schema import check_keys, describe, expect, is_number, names_only, number_list, quaternion
from ..world.model_files import ModelInfo, describe_model
from ..world.pose import check_quaternion, quat_multiply
from ..yamlsource import LList, LMap, load_yaml
from .tool import astray_grasps, hand, joint_coupling, model_grasps

if TYPE_CHECKING:
    from ..world import Object

DESCRIPTION_KEYS = ("name", "urdf", "base_link", "mobile", "torso", "camera", "head", "arms", "grasps",
                    "resources", "process_modules")
ARM_KEYS = ("joints", "tool_frame", "palm_link", "gripper", "links", "poses")
GRIPPER_KEYS = ("joints", "open", "closed", "max_width", "finger_height", "approach", "coupling", "grasp_point")
#: how a hand approaches what it takes: along the wrist's roll axis, fingers first, or along the palm's normal
APPROACHES = ("fingers", "palm")
CAMERA_KEYS = ("frame", "horizontal_fov", "vertical_fov", "near", "far")
HEAD_KEYS = ("pan_joint", "tilt_joint", "pan_link", "tilt_link")
TORSO_KEYS = ("joint", "default")
#: the roles a step can drive besides the arms (each arm is a role of its own: `arm:<name>`)
ROLES = ("base", "head")


class GraspWarning(UserWarning):
    """A hand-written named grasp approaches from elsewhere than its name says (for the model's tool frame)."""


@dataclass(frozen=True)
class GripperDescription:
    joints: tuple[str, ...] = ()
    open: float = 0.0
    closed: float = 0.0
    max_width: float = math.inf  # metres between the fingers when fully open
    finger_height: float = 0.0  # side grasps (front, left, right) need objects at least this tall
    approach: str = ""  # "fingers" or "palm"; "" = as the model shows (robots/tool.py `hand`)
    coupling: tuple[float, ...] = ()  # per joint: its value is this times the gripper's; () = from the model's limits
    grasp_point: tuple[float, float, float] | None = None  # in the palm's frame; None = as the model shows

@dataclass(frozen=True)
class ArmDescription:
    name: str
    joints: tuple[str, ...]
    tool_frame: str
    palm_link: str = ""
    gripper: GripperDescription = field(default_factory=GripperDescription)
    links: tuple[str, ...] = ()
    poses: dict[str, tuple[float, ...]] = field(default_factory=dict)

    def owns_link(self, link: str) -> bool:
        return link == self.tool_frame or link in self.links


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
    path: Path  # the description file
    base_link: str
    arms: dict[str, ArmDescription]
    grasps: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    camera: CameraDescription | None = None
    head: HeadDescription | None = None
    torso_joint: str | None = None
    torso_default: float = 0.0
    mobile: bool = True
    urdf: Path | None = None
    resources: dict[str, str] = field(default_factory=dict)  # role -> the resource it drives
    process_modules: dict[str, str] = field(default_factory=dict)  # designator -> process module name
    #: no `grasps:` in the file: the named grasps (front, top, left, right) are computed from the model when the robot
    #: is loaded (robots/tool.py); until then they stand as names
    grasps_from_model: bool = False
    places: dict[str, Location] = field(default_factory=dict, compare=False, repr=False)  # key -> where in the file

    def where(self, key: str) -> Location:
        """The place of a key (`arms.left.joints`) in the description file, for error messages."""
        return self.places.get(key) or self.places.get(key.rsplit(".", 1)[0]) or Location(str(self.path))

    def arm(self, name: str) -> ArmDescription:
        try:
            return self.arms[name]
        except KeyError:
            raise UnknownName(f"robot '{self.name}' has no arm '{name}' (arms: {', '.join(self.arms)})") from None

    def resource(self, role: str) -> str:
        """The physical resource a role drives (`base`, `head`, `arm:<name>`); roles share one when the description says
        so. Without a head, looking moves what carries the camera: the arm whose `links` name its frame, else the base."""
        if role in self.resources:
            return self.resources[role]
        if role == "head" and self.head is None and self.camera is not None:
            arm = self.arm_of_link(self.camera.frame)
            return f"arm:{arm}" if arm else "base"
        return role

    def grasp_orientation(self, grasp: str | Sequence[float],
                          base_orientation: Sequence[float]) -> tuple[float, float, float, float]:
        """World orientation of the tool frame for a named grasp (relative to the base) or a world quaternion."""
        if isinstance(grasp, str):
            if grasp not in self.grasps:
                raise UnknownName(f"robot '{self.name}' has no grasp '{grasp}' (grasps: {', '.join(self.grasps) or 'none'})")
            return quat_multiply(base_orientation, self.grasps[grasp])
        return check_quaternion(grasp, "grasp")

    def default_joints(self) -> dict[str, float]:
        """Joint values the robot takes when its world file sets none: the torso at `torso.default`."""
        return {self.torso_joint: self.torso_default} if self.torso_joint else {}

    def arm_of_link(self, link: str) -> str | None:
        for arm in self.arms.values():
            if arm.owns_link(link):
                return arm.name
        return None

    def joint_names(self) -> list[tuple[str, str]]:
        """Every joint the description names, with the key that names it (checked against the model)."""
        names: list[tuple[str, str]] = []
        if self.torso_joint:
            names.append((self.torso_joint, "torso.joint"))
        if self.head is not None:
            names += [(self.head.pan_joint, "head.pan_joint"), (self.head.tilt_joint, "head.tilt_joint")]
        for arm in self.arms.values():
            names += [(j, f"arms.{arm.name}.joints") for j in arm.joints]
            names += [(j, f"arms.{arm.name}.gripper.joints") for j in arm.gripper.joints]
        return names

    def link_names(self) -> list[tuple[str, str]]:
        names = [(self.base_link, "base_link")]
        if self.camera is not None:
            names.append((self.camera.frame, "camera.frame"))
        if self.head is not None:
            names += [(link, f"head.{key}") for key, link in (("pan_link", self.head.pan_link),
                                                               ("tilt_link", self.head.tilt_link)) if link]
        for arm in self.arms.values():
            names.append((arm.tool_frame, f"arms.{arm.name}.tool_frame"))
            if arm.palm_link:
                names.append((arm.palm_link, f"arms.{arm.name}.palm_link"))
            names += [(link, f"arms.{arm.name}.links") for link in arm.links]
        return names


# -- reading a description ---------------------------------------------------------------------


class _Reader:
    """Checks one description file, collecting every problem with its place."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.errors: list[InputError] = []
        self.places: dict[str, Location] = {}

    def mark(self, key: str, data: LMap, name: str) -> None:
        """Remember where `data[name]` is, as `key`."""
        if name in data:
            self.places[key] = data.loc(name, True)

    def error(self, message: str, where: Location, key: str, suggestion: str | None = None) -> None:
        self.errors.append(InputError(message, where, key=key, suggestion=suggestion))

    def mapping(self, data: LMap, key: str, allowed: Sequence[str], required: Sequence[str]) -> LMap | None:
        value = data.get(key)
        if not isinstance(value, LMap):
            self.error(f"expected a mapping, got {describe(value)}", data.loc(key, True), key)
            return None
        check_keys(value, allowed, required, key, self.errors)
        return value

    def name(self, data: LMap, key: str, required: bool = True) -> str:
        if key not in data:
            return ""
        value = data[key]
        if not isinstance(value, str) or not value:
            self.error(f"expected a name, got {describe(value)}", data.loc(key, True), key)
            return ""
        return value

    def number(self, data: LMap, key: str, default: float, positive: bool = False) -> float:
        if key not in data:
            return default
        value = data[key]
        if not is_number(value) or (positive and value <= 0):
            self.error(f"expected {'a positive' if positive else 'a'} number, got {describe(value)}",
                       data.loc(key, True), key)
            return default
        return float(value)

    def names(self, data: LMap, key: str) -> tuple[str, ...]:
        if key not in data:
            return ()
        value = data[key]
        if not isinstance(value, LList) or not all(isinstance(v, str) and v for v in value):
            self.error(f"expected a list of names, got {describe(value)}", data.loc(key, True), key)
            return ()
        return tuple(value)

    def gripper(self, arm: LMap, arm_name: str) -> GripperDescription:
        if "gripper" not in arm or arm["gripper"] is None:
            return GripperDescription()
        data = self.mapping(arm, "gripper", GRIPPER_KEYS, ("joints", "open", "closed"))
        if data is None:
            return GripperDescription()
        joints = self.names(data, "joints")
        approach = ""
        if "approach" in data:
            value = data["approach"]
            if value not in APPROACHES:
                self.error(f"expected how the hand approaches ({' or '.join(APPROACHES)}), got {describe(value)}",
                           data.loc("approach", True), f"arms.{arm_name}.gripper.approach",
                           did_you_mean(str(value), APPROACHES) or f"one of: {', '.join(APPROACHES)}")
            elif value == "palm" and not isinstance(arm.get("palm_link"), str):
                self.error("a palm-first hand needs the arm's palm_link (the palm's normal is the approach)",
                           data.loc("approach", True), f"arms.{arm_name}.gripper.approach",
                           "add palm_link: <the palm's link> to the arm")
            else:
                approach = str(value)
        coupling: tuple[float, ...] = ()
        if "coupling" in data and joints:
            key = f"arms.{arm_name}.gripper.coupling"
            numbers = number_list(data["coupling"], len(joints), data.loc("coupling", True), key, self.errors)
            if numbers is not None and any(v == 0 for v in numbers):
                self.error("a coupling of 0 would leave a gripper joint still: give each joint a factor, -1 for one "
                           "that turns the other way", data.loc("coupling", True), key)
            elif numbers is not None:
                coupling = tuple(numbers)
        grasp_point = None
        if "grasp_point" in data:
            point = number_list(data["grasp_point"], 3, data.loc("grasp_point", True),
                                f"arms.{arm_name}.gripper.grasp_point", self.errors)
            if point is not None:
                grasp_point = (point[0], point[1], point[2])
        return GripperDescription(joints, self.number(data, "open", 0.0),
                                  self.number(data, "closed", 0.0), self.number(data, "max_width", math.inf, True),
                                  self.number(data, "finger_height", 0.0), approach, coupling, grasp_point)

    def poses(self, arm: LMap, arm_name: str, joints: tuple[str, ...]) -> dict[str, tuple[float, ...]]:
        if "poses" not in arm:
            return {}
        value = arm["poses"]
        if not isinstance(value, LMap):
            self.error(f"expected a mapping of pose name to joint values, got {describe(value)}", arm.loc("poses", True),
                       "poses")
            return {}
        poses = {}
        for name, values in names_only(value, self.errors).items():
            self.places[f"arms.{arm_name}.poses.{name}"] = value.loc(name, True)
            numbers = number_list(values, len(joints), value.loc(name, True), f"poses.{name}", self.errors) \
                if joints else None
            if numbers is not None:
                poses[str(name)] = tuple(numbers)
        return poses

    def arm(self, arms: LMap, name: str) -> ArmDescription | None:
        data = arms[name]
        if not isinstance(data, LMap):
            self.error(f"arm '{name}': expected a mapping with joints and tool_frame, got {describe(data)}",
                       arms.loc(name, True), f"arms.{name}")
            return None
        check_keys(data, ARM_KEYS, ("joints", "tool_frame"), f"arm '{name}'", self.errors)
        for key in ARM_KEYS:
            self.mark(f"arms.{name}.{key}", data, key)
        if isinstance(data.get("gripper"), LMap):
            for key in ("joints", "open", "closed", "approach", "coupling", "grasp_point"):
                self.mark(f"arms.{name}.gripper.{key}", data["gripper"], key)
        joints = self.names(data, "joints")
        if "joints" in data and not joints and isinstance(data["joints"], LList):
            self.error("an arm needs at least one joint", data.loc("joints", True), "joints")
        return ArmDescription(name=str(name), joints=joints, tool_frame=self.name(data, "tool_frame"),
                              palm_link=self.name(data, "palm_link"), gripper=self.gripper(data, str(name)),
                              links=self.names(data, "links"), poses=self.poses(data, str(name), joints))

    # long: every key of a description read in turn, all problems collected at once
    def read(self) -> RobotDescription:
        data = load_yaml(self.path)
        if not isinstance(data, LMap):
            raise InputError("a robot description must be a mapping with name, base_link and arms",
                             Location(str(self.path), 1, 1))
        check_keys(data, DESCRIPTION_KEYS, ("name", "base_link", "arms"), "the robot description", self.errors)
        for key in DESCRIPTION_KEYS:
            self.mark(key, data, key)
        for key, fields in (("camera", CAMERA_KEYS), ("head", HEAD_KEYS), ("torso", TORSO_KEYS)):
            if isinstance(data.get(key), LMap):
                for name in fields:
                    self.mark(f"{key}.{name}", data[key], name)
        name = self.name(data, "name")
        base_link = self.name(data, "base_link")
        mobile = True
        if "mobile" in data and expect(data["mobile"], bool, data.loc("mobile", True), "mobile", self.errors):
            mobile = data["mobile"]
        urdf = None
        if "urdf" in data and self.name(data, "urdf"):
            urdf = (self.path.parent / data["urdf"]).resolve()
            problem = probe(urdf)
            if problem is not None:
                message = f"file not found: {data['urdf']} (relative to {self.path.parent})" if problem == "not found" \
                    else f"cannot read {data['urdf']}: {problem}"
                self.error(message, data.loc("urdf", True), "urdf")
                urdf = None
        arms: dict[str, ArmDescription] = {}
        if "arms" in data:
            raw = data["arms"]
            if not isinstance(raw, LMap):
                self.error(f"expected a mapping of arm name to arm, got {describe(raw)}", data.loc("arms", True), "arms")
            else:
                for arm_name in list(names_only(raw, self.errors)):
                    arm = self.arm(raw, arm_name)
                    if arm is not None:
                        arms[arm.name] = arm
        camera = None
        if "camera" in data and data["camera"] is not None:
            cam = self.mapping(data, "camera", CAMERA_KEYS, ("frame", "horizontal_fov", "vertical_fov"))
            if cam is not None:
                camera = self.camera(cam)
        head = None
        if "head" in data and data["head"] is not None:
            raw_head = self.mapping(data, "head", HEAD_KEYS, ("pan_joint", "tilt_joint"))
            if raw_head is not None:
                head = HeadDescription(self.name(raw_head, "pan_joint"), self.name(raw_head, "tilt_joint"),
                                       self.name(raw_head, "pan_link"), self.name(raw_head, "tilt_link"))
        torso_joint, torso_default = None, 0.0
        if "torso" in data and data["torso"] is not None:
            torso = self.mapping(data, "torso", TORSO_KEYS, ("joint",))
            if torso is not None:
                torso_joint = self.name(torso, "joint") or None
                torso_default = self.number(torso, "default", 0.0)
        grasps: dict[str, tuple[float, float, float, float]] = {}
        from_model = "grasps" not in data and bool(arms)
        if from_model:  # named now, computed for the tool frame when the robot is loaded (assign_description)
            grasps = {name: (0.0, 0.0, 0.0, 1.0) for name in ("front", "top", "left", "right")}
        if "grasps" in data:
            raw_grasps = data["grasps"]
            if not isinstance(raw_grasps, LMap):
                self.error(f"expected a mapping of grasp name to quaternion, got {describe(raw_grasps)}",
                           data.loc("grasps", True), "grasps")
            else:
                for grasp, value in names_only(raw_grasps, self.errors).items():
                    q = quaternion(value, raw_grasps.loc(grasp, True), f"grasps.{grasp}", self.errors)
                    if q is not None:
                        grasps[str(grasp)] = (q[0], q[1], q[2], q[3])
        resources = self.string_map(data, "resources", [*ROLES, *(f"arm:{a}" for a in arms)])
        modules = self.string_map(data, "process_modules", None)
        raise_if_any(self.errors)
        return RobotDescription(name=name, path=self.path, base_link=base_link, arms=arms, grasps=grasps, camera=camera,
                                head=head, torso_joint=torso_joint, torso_default=torso_default, mobile=mobile,
                                urdf=urdf, resources=resources, process_modules=modules, places=self.places,
                                grasps_from_model=from_model)

    def camera(self, cam: LMap) -> CameraDescription:
        """The camera: fields of view are angles in (0, pi), and near comes before far."""
        fovs = []
        for key, default in (("horizontal_fov", 1.0), ("vertical_fov", 0.75)):
            fov = self.number(cam, key, default, True)
            if not fov < math.pi:
                self.error(f"a field of view must be an angle between 0 and pi (radians), got {fov:g}",
                           cam.loc(key, True), f"camera.{key}")
                fov = default
            fovs.append(fov)
        near, far = self.number(cam, "near", 0.05, True), self.number(cam, "far", 6.0, True)
        if not near < far:
            self.error(f"near ({near:g}) must be less than far ({far:g}): nothing would be seen",
                       cam.loc("near" if "near" in cam else "far", True), f"camera.{'near' if 'near' in cam else 'far'}")
            near, far = 0.05, 6.0
        return CameraDescription(self.name(cam, "frame"), fovs[0], fovs[1], near, far)

    def string_map(self, data: LMap, key: str, allowed_keys: list[str] | None) -> dict[str, str]:
        if key not in data or data[key] is None:
            return {}
        value = data[key]
        if not isinstance(value, LMap):
            self.error(f"expected a mapping of names, got {describe(value)}", data.loc(key, True), key)
            return {}
        result = {}
        for k, v in names_only(value, self.errors).items():
            if allowed_keys is not None and k not in allowed_keys:
                self.error(f"unknown role '{k}' (roles: {', '.join(allowed_keys)})", value.loc(k), f"{key}.{k}",
                           did_you_mean(str(k), allowed_keys))
                continue
            if not isinstance(v, str) or not v:
                self.error(f"expected a name, got {describe(v)}", value.loc(k, True), f"{key}.{k}")
                continue
            self.places[f"{key}.{k}"] = value.loc(k)
            result[str(k)] = v
        return result


@functools.lru_cache(maxsize=64)
def _load_cached(path: Path, mtime_ns: int) -> RobotDescription:
    return _Reader(path).read()


def load_description(path: str | Path) -> RobotDescription:
    """Read and check a description file; InputError(s) with file, line and key on problems."""
    path = Path(path).resolve()
    try:
        mtime = path.stat().st_mtime_ns
    except OSError:
        raise InputError("robot description not found", Location(str(path))) from None
    return _load_cached(path, mtime)


def check_against_model(desc: RobotDescription, model: ModelInfo, model_path: Path) -> list[InputError]:
    """Names in the description that the robot's model does not have (each at the description's file)."""
    errors: list[InputError] = []
    for joint, key in desc.joint_names():
        if joint not in model.joints:
            errors.append(InputError(f"the model {model_path.name} has no joint '{joint}'", desc.where(key), key=key,
                                     suggestion=did_you_mean(joint, model.joints)))
    for link, key in desc.link_names():
        if link not in model.links:
            errors.append(InputError(f"the model {model_path.name} has no link '{link}'", desc.where(key), key=key,
                                     suggestion=did_you_mean(link, model.links)))
    return errors + _values_outside_limits(desc, model)


def _outside(value: float, joint: str, model: ModelInfo) -> str | None:
    """`joint is V, outside its limits [lo, hi]` when the model limits the joint and `value` is beyond, else None."""
    info = model.joints.get(joint)
    if info is None or not info.limited or info.lower - 1e-9 <= value <= info.upper + 1e-9:
        return None
    return f"{joint} is {value:g}, outside its limits [{info.lower:g}, {info.upper:g}]"


def _values_outside_limits(desc: RobotDescription, model: ModelInfo) -> list[InputError]:
    """Named poses and gripper values the model's joint limits do not allow (continuous joints have none)."""
    errors: list[InputError] = []
    for arm in desc.arms.values():
        for pose, values in arm.poses.items():
            key = f"arms.{arm.name}.poses.{pose}"
            for joint, value in zip(arm.joints, values):
                problem = _outside(value, joint, model)
                if problem:
                    errors.append(InputError(f"pose '{pose}': {problem}", desc.where(key), key=key))
                    break
        coupling = joint_coupling(arm.gripper, lambda name: (model.joints[name].limited, model.joints[name].lower,
                                                            model.joints[name].upper) if name in model.joints else None)
        for which in ("open", "closed"):
            for joint, factor in zip(arm.gripper.joints, coupling):
                value = getattr(arm.gripper, which) * factor
                info = model.joints.get(joint)
                if _outside(value, joint, model) and info is not None:
                    key = f"arms.{arm.name}.gripper.{which}"
                    if arm.gripper.coupling and not _outside(-value, joint, model):  # coupled the wrong way round
                        key = f"arms.{arm.name}.gripper.coupling"
                        errors.append(InputError(
                            f"the gripper's {which} value coupled by {factor:g} is {value:g}, outside {joint}'s limits "
                            f"[{info.lower:g}, {info.upper:g}]", desc.where(key), key=key,
                            suggestion=f"a coupling of {-factor:g} for {joint} turns it the other way"))
                        break
                    errors.append(InputError(f"the gripper's {which} value {value:g} is outside {joint}'s limits "
                                             f"[{info.lower:g}, {info.upper:g}]", desc.where(key), key=key))
                    break
    return errors


# -- finding the description of a robot -----------------------------------------------------------


def bundled_paths() -> list[Path]:
    """The bundled description files (`resources/robots/<name>/<name>.yaml`)."""
    return sorted(p for p in (resources_dir() / "robots").glob("*/*.yaml") if p.stem == p.parent.name)


def bundled_descriptions() -> list[RobotDescription]:
    """Every bundled description (a broken one is an input error, not skipped)."""
    return [load_description(path) for path in bundled_paths()]


def _bundled_by_name(name: str) -> RobotDescription | None:
    for path in bundled_paths():
        desc = load_description(path)
        if desc.name == name:
            return desc
    return None


def urdf_robot_name(path: Path) -> str | None:
    if path.suffix.lower() != ".urdf":
        return None
    try:
        for _, element in ET.iterparse(path, events=("start",)):
            return element.get("name") if element.tag == "robot" else None
    except (ET.ParseError, OSError):
        return None
    return None


def find_description(model_path: Path, explicit: Path | None = None) -> RobotDescription | None:
    """The description of the robot loaded from `model_path` (see the module docstring for the order)."""
    if explicit is not None:
        return load_description(explicit)
    beside = model_path.with_suffix(".yaml")
    if model_path.suffix.lower() == ".urdf" and beside.is_file():
        return load_description(beside)
    name = urdf_robot_name(model_path)
    return (_bundled_by_name(name) if name else None) or _bundled_by_name(model_path.stem)


def check_description(desc: RobotDescription, model_path: Path) -> None:
    """Raise the description's names that the robot model lacks (InputErrors)."""
    try:
        model = describe_model(model_path)
    except Exception:  # an unreadable model is reported where the model is named
        return
    raise_if_any(check_against_model(desc, model, model_path))


def assign_description(obj: Object, desc: RobotDescription | None) -> None:
    """Give a robot object its description, once (the world loader does, for `description:` in a world file): its
    world keeps it (`BulletWorld.described_robot`)."""
    obj.world.described_robot = (obj, _prepared(obj, desc))


def _prepared(obj: Object, desc: RobotDescription | None) -> RobotDescription | None:
    """A description made ready for its robot object: a description without `grasps:` gets the named grasps of its
    first arm's tool frame as the model has it. Each hand is read from the model now (robots/tool.py `hand`), while
    it holds nothing."""
    if desc is not None:
        for arm in desc.arms.values():
            if arm.gripper.joints:
                hand(obj, arm)
    if desc is not None and desc.grasps_from_model and desc.arms:
        desc = dataclasses.replace(desc, grasps=model_grasps(obj, next(iter(desc.arms.values()))))
    elif desc is not None and desc.arms and desc.grasps:
        for name, where, better in astray_grasps(obj, next(iter(desc.arms.values())), desc.grasps):
            warnings.warn(GraspWarning(
                f"{desc.where(f'grasps.{name}')}: grasps.{name}: the tool approaches {where}, not as '{name}' says, "
                f"for the tool frame of {obj.path.name} (its approach axis is the wrist's roll axis); "
                f"[{', '.join(f'{v:.4g}' for v in better)}] would, or leave grasps: out to have them computed"),
                stacklevel=3)
    return desc


def description_for(obj: Object) -> RobotDescription | None:
    """The description of a robot object: the one its world keeps (assigned by the loader), else found by
    `find_description` (a world built in Python) — once for the world's robot, which the world then keeps."""
    kept = obj.world.described_robot
    if kept is not None and kept[0] is obj:
        return kept[1]
    desc = _prepared(obj, find_description(obj.path))
    if obj is obj.world.robot:
        obj.world.described_robot = (obj, desc)
    return desc
