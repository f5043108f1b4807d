"""A run's replay as an MCAP file that Foxglove (and any MCAP tool) opens: `pycram run --mcap`, `trace show --mcap`.

The file holds, with JSON-encoded messages and the schemas of foxglove_schemas.py:

- `/scene` (`foxglove.SceneUpdate`, once at the start): an entity for every drawn link of every body, with
  its visual shapes, locked to the link's frame, and a text label on every object that is not scenery
  (foxglove_scene.py); each entity's metadata names its body, link and type;
- `/tf` (`foxglove.FrameTransforms`): the world pose of every link (frame `BODY/LINK`, parent `world`)
  before the first step and after each recorded step, all of them each time, so that seeking anywhere
  shows the whole world;
- `/plan` (`foxglove.Log`): one message per recorded step (its path, what it did, its failure), at the
  level of its outcome (info, warning for folded failed attempts, error for a failure), with the plan
  file and line;
- `/failures` (`foxglove.SceneUpdate`): at a step that failed, red spheres on what it worked on and its
  failure written above them, for that step's second;
- `/camera/image` (`foxglove.CompressedImage`, PNG): what the robot's camera (its description's `camera`)
  saw after each step of a designator that uses the camera (`detecting`), in the camera's optical frame
  (`ROBOT/LINK/optical`: x right, y down, z forward), which `/camera/tf` places and `/camera/calibration`
  (`foxglove.CameraCalibration`, a pinhole from the description's fields of view) describes, so that
  Foxglove's 3D panel can draw the camera's view cone and the image in the scene.

The file's metadata record `pycram` names the plan, the world, the outcome, the number of steps and the
visual shapes that could not be drawn (a mesh file that cannot be read, or of another format). Time is the
step index: the state before the first step at 0 s, step k at k s, so the file is the same byte for byte
for the same trace and plays one step per second.
"""
from __future__ import annotations

import base64
import io
import json
import math
from collections.abc import Iterator
from dataclasses import dataclass
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

from ..designators.declaration import DESIGNATORS
from ..plan.replay import focus_points
from ..plan.trace import REPLAY_KEY
from ..reasoning.visibility import resolve_camera
from ..world import BulletWorld
from ..world.camera import Camera, encode_image, render
from ..world.pose import matrix_to_quat, vec3
from ..worldfile.loader import load_world
from .foxglove_scene import WORLD_FRAME, SceneEntities, color, quaternion, time_of, vector
from .foxglove_schemas import SCHEMAS

__all__ = ["MCAP_FORMATS", "STEP_NS", "build_mcap", "messages", "step_text"]

MCAP_FORMATS = {".mcap": "MCAP"}
STEP_NS = 1_000_000_000  # one second of replay time per step
IMAGE_WIDTH = 320  # the camera images' width; their height follows the camera's fields of view
LEVELS = {"succeeded": 2, "folded": 3, "failed": 4}  # foxglove.Log levels: info, warning, error


def _library() -> str:
    try:
        return f"pycram {version('pycram-cli')}"
    except PackageNotFoundError:
        return "pycram dev"


def put_state(world: BulletWorld, state: dict[str, dict[str, Any]]) -> None:
    """Put the objects named in a replay state (initial state or a step's changes) where it says."""
    for name, entry in state.items():
        obj = world.get_object_by_name(name)
        if obj is None:
            continue
        if "position" in entry and "orientation" in entry:
            obj.set_position_and_orientation(entry["position"], entry["orientation"])
        joints = {k: v for k, v in (entry.get("joints") or {}).items() if k in obj.joint_names}
        if joints:
            obj.reset_joints(joints)


def _nodes(node: dict[str, Any], into: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    into[node.get("path", "")] = node
    for child in node.get("children") or []:
        _nodes(child, into)
    return into


def _short(value: Any, limit: int = 60) -> str:
    text = value if isinstance(value, str) else json.dumps(value, ensure_ascii=False, separators=(", ", ": "),
                                                           sort_keys=True)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def step_text(step: dict[str, Any], node: dict[str, Any]) -> str:
    """`PATH: slot=value, ...` (slots in name order: a trace run now and the same trace read from its file give
    the same text) and, for a failed step, its failure; a folded entry says how many it stands for."""
    values: dict[str, Any] = {}
    if isinstance(node.get("designator"), dict):
        values = node["designator"].get("resolved") or node["designator"].get("slots") or {}
    elif isinstance(node.get("query"), dict):
        values = node["query"].get("args") or {}
    text = str(step.get("path"))
    if values:
        text += ": " + ", ".join(f"{k}={_short(v)}" for k, v in sorted(values.items()))  # as a saved trace has them
    if "message" in node:
        text += f" “{node['message']}”"
    if step.get("folded"):
        text += f" ({step['folded']} entries of failed attempts folded)"
    failure = node.get("failure")
    if isinstance(failure, dict) and node.get("status") == "failed" and failure.get("path") == node.get("path"):
        text += f" — {failure.get('type')}: {failure.get('message')}"
    return text


def _level(step: dict[str, Any]) -> int:
    if step.get("folded"):
        return LEVELS["folded"]
    return LEVELS.get(str(step.get("status")), 2)


def _line(node: dict[str, Any]) -> int:
    source = str(node.get("source") or "")
    head = source.split(":", 1)[0]
    return int(head) if head.isdigit() else 0


def _takes_picture(node: dict[str, Any]) -> bool:
    """A step of a designator that uses the robot's camera (its declaration's resource)."""
    spec = DESIGNATORS.get(str(node.get("type"))) if "designator" in node else None
    return spec is not None and spec.resource == "camera"


@dataclass(frozen=True)
class RobotCamera:
    """The robot's camera now: a rendering camera, its optical frame (x right, y down, z forward) and its image size."""

    camera: Camera
    frame: str  # BODY/LINK/optical
    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    width: int
    height: int
    fov: tuple[float, float]  # horizontal, vertical (rad)

    def calibration(self, ns: int) -> dict[str, Any]:
        """A pinhole model without distortion, from the fields of view (foxglove.CameraCalibration)."""
        fx = self.width / 2 / math.tan(self.fov[0] / 2)
        fy = self.height / 2 / math.tan(self.fov[1] / 2)
        cx, cy = self.width / 2, self.height / 2
        k = [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0]
        return {"timestamp": time_of(ns), "frame_id": self.frame, "width": self.width, "height": self.height,
                "distortion_model": "plumb_bob", "D": [0.0] * 5, "K": [round(v, 6) + 0.0 for v in k],
                "R": [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                "P": [round(v, 6) + 0.0 for v in (fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0)]}

    def transform(self, ns: int) -> dict[str, Any]:
        return {"transforms": [{"timestamp": time_of(ns), "parent_frame_id": WORLD_FRAME, "child_frame_id": self.frame,
                                "translation": vector(self.position), "rotation": quaternion(self.orientation)}]}


def robot_camera(world: BulletWorld) -> RobotCamera | None:
    """The robot's camera (from its description) where it is now; None when the robot has none."""
    robot = world.robot
    if robot is None:
        return None
    try:
        pose = resolve_camera(robot)
    except (ValueError, KeyError):
        return None
    eye = pose.position
    forward, down = pose.rotation[:, 2], pose.rotation[:, 1]
    horizontal, vertical = pose.fov if pose.fov else (math.radians(60.0), math.radians(45.0))
    aspect = math.tan(horizontal / 2) / math.tan(vertical / 2)
    camera = Camera(vec3(eye), vec3(eye + forward), vec3(-down), vertical_fov_deg=math.degrees(vertical),
                    near=max(0.01, float(pose.near)))
    return RobotCamera(camera, f"{robot.name}/{pose.label}/optical", vec3(eye), matrix_to_quat(pose.rotation),
                       IMAGE_WIDTH, max(1, round(IMAGE_WIDTH / aspect)), (horizontal, vertical))


def messages(trace: dict[str, Any], world: BulletWorld,
             skipped: list[str] | None = None) -> Iterator[tuple[str, int, dict[str, Any]]]:
    """(topic, time in ns, message) of the whole replay, in time order; what could not be drawn is added to
    `skipped` (`BODY/LINK: what`)."""
    replay = trace.get(REPLAY_KEY) or {}
    for obj in world.objects:  # recorded poses say where everything is: nothing may drag anything along
        for other in list(obj.attachments):
            if other in obj.attachments:
                obj.detach(other)
    put_state(world, replay.get("initial") or {})
    scene = SceneEntities(world)
    if skipped is not None:
        skipped.extend(scene.skipped)
    yield "/scene", 0, {"deletions": [], "entities": scene.entities}
    yield "/tf", 0, {"transforms": scene.transforms(0)}
    nodes = _nodes(trace.get("root") or {}, {})
    plan = str(trace.get("plan") or "")
    for k, step in enumerate(replay.get("steps") or [], start=1):
        ns = k * STEP_NS
        put_state(world, step.get("changed") or {})
        node = nodes.get(str(step.get("path")), {})
        yield "/tf", ns, {"transforms": scene.transforms(ns)}
        yield "/plan", ns, {"timestamp": time_of(ns), "level": _level(step), "message": step_text(step, node),
                            "name": f"step {k}", "file": plan, "line": _line(node)}
        if (marker := failure_marker(world, node, ns)) is not None:
            yield "/failures", ns, {"deletions": [], "entities": [marker]}
        if _takes_picture(node) and (eye := robot_camera(world)) is not None:
            image = encode_image(render(world, eye.camera, eye.width, eye.height), ".png")
            yield "/camera/tf", ns, eye.transform(ns)
            yield "/camera/calibration", ns, eye.calibration(ns)
            yield "/camera/image", ns, {"timestamp": time_of(ns), "frame_id": eye.frame,
                                        "data": base64.b64encode(image).decode("ascii"), "format": "png"}


def failure_marker(world: BulletWorld, node: dict[str, Any], ns: int) -> dict[str, Any] | None:
    """For a step that failed itself: red spheres on what it worked on (the objects and places it names, where
    they are after it) and its failure written above them, shown for the step's second; else None."""
    failure = node.get("failure")
    if node.get("status") != "failed" or not isinstance(failure, dict) or failure.get("path") != node.get("path"):
        return None
    named = {key: node[key] for key in ("designator", "query") if isinstance(node.get(key), dict)}
    condition = node.get("condition")
    if isinstance(condition, dict) and isinstance(condition.get("query"), dict):  # an assert's query
        named.setdefault("query", condition["query"])
    points = focus_points(world, named)
    if not points and world.robot is not None:
        lo, hi = world.robot.get_aabb()
        points = [((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2])]
    top = max((p[2] for p in points), default=1.0)
    x, y = (points[0][0], points[0][1]) if points else (0.0, 0.0)
    red = color((0.85, 0.1, 0.1, 0.45))
    identity = quaternion((0.0, 0.0, 0.0, 1.0))
    return {"timestamp": time_of(ns), "frame_id": WORLD_FRAME, "id": "failure", "lifetime": time_of(STEP_NS),
            "frame_locked": False, "metadata": [{"key": "path", "value": str(node.get("path"))}],
            "spheres": [{"pose": {"position": vector(p), "orientation": identity}, "size": vector((0.15, 0.15, 0.15)),
                         "color": red} for p in points],
            "texts": [{"pose": {"position": vector((x, y, top + 0.3)), "orientation": identity}, "billboard": True,
                       "font_size": 16.0, "scale_invariant": True, "color": color((0.8, 0.05, 0.05, 1.0)),
                       "text": f"{failure.get('type')}: {failure.get('message')}"}]}


TOPICS = {"/scene": "foxglove.SceneUpdate", "/failures": "foxglove.SceneUpdate", "/tf": "foxglove.FrameTransforms",
          "/plan": "foxglove.Log",
          "/camera/tf": "foxglove.FrameTransforms", "/camera/calibration": "foxglove.CameraCalibration",
          "/camera/image": "foxglove.CompressedImage"}


def build_mcap(trace: dict[str, Any], world_path: Path) -> bytes:
    """The MCAP file of a run (a trace with its replay record) in the world file `world_path`."""
    from mcap.writer import CompressionType, Writer  # why: importing it takes 40 ms, paid only when a file is written

    world = load_world(world_path)
    stream = io.BytesIO()
    writer = Writer(stream, compression=CompressionType.ZSTD)
    writer.start(profile="", library=_library())
    channels: dict[str, int] = {}
    sequence: dict[str, int] = {}
    skipped: list[str] = []
    try:
        for topic, ns, message in messages(trace, world, skipped):
            if topic not in channels:
                schema = TOPICS[topic]
                schema_id = writer.register_schema(name=schema, encoding="jsonschema",
                                                   data=json.dumps(SCHEMAS[schema], sort_keys=True).encode())
                channels[topic] = writer.register_channel(topic=topic, message_encoding="json", schema_id=schema_id)
            sequence[topic] = sequence.get(topic, 0) + 1
            writer.add_message(channels[topic], log_time=ns, publish_time=ns, sequence=sequence[topic],
                               data=json.dumps(message, separators=(",", ":"), ensure_ascii=False,
                                               allow_nan=False).encode())
    finally:
        world.exit()
    # the run at a glance, for tools that list a file's metadata (values are strings in MCAP)
    writer.add_metadata("pycram", {"plan": str(trace.get("plan") or ""), "world": str(trace.get("world") or ""),
                                   "status": str(trace.get("status") or ""),
                                   "steps": str(len((trace.get(REPLAY_KEY) or {}).get("steps") or [])),
                                   "not drawn": "; ".join(skipped)})
    writer.finish()
    return stream.getvalue()
