"""The JSON Schemas of the Foxglove message types an MCAP replay holds (see foxglove.py).

Foxglove recognises a channel's messages by the schema's name (`foxglove.SceneUpdate`, ...) and reads
JSON-encoded messages with the schema's field types (bytes as base64 strings). These are written here
from Foxglove's documented message definitions, only the fields pycram writes, so that the file is
self-describing for any other MCAP tool too.
"""
from __future__ import annotations

from typing import Any

Schema = dict[str, Any]


def _object(title: str, properties: dict[str, Schema]) -> Schema:
    return {"title": title, "type": "object", "properties": properties}


def _numbers(title: str, names: str) -> Schema:
    return _object(title, {name: {"type": "number"} for name in names})


TIME = _object("time", {"sec": {"type": "integer", "minimum": 0},
                        "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999}})
VECTOR3 = _numbers("foxglove.Vector3", "xyz")
QUATERNION = _numbers("foxglove.Quaternion", "xyzw")
COLOR = _numbers("foxglove.Color", "rgba")
POSE = _object("foxglove.Pose", {"position": VECTOR3, "orientation": QUATERNION})
BYTES = {"type": "string", "contentEncoding": "base64"}


def _array(item: Schema) -> Schema:
    return {"type": "array", "items": item}


ENTITY = _object("foxglove.SceneEntity", {
    "timestamp": TIME,
    "frame_id": {"type": "string"},
    "id": {"type": "string"},
    "lifetime": _object("duration", {"sec": {"type": "integer"}, "nsec": {"type": "integer", "minimum": 0}}),
    "frame_locked": {"type": "boolean"},
    "metadata": _array(_object("foxglove.KeyValuePair", {"key": {"type": "string"}, "value": {"type": "string"}})),
    "cubes": _array(_object("foxglove.CubePrimitive", {"pose": POSE, "size": VECTOR3, "color": COLOR})),
    "spheres": _array(_object("foxglove.SpherePrimitive", {"pose": POSE, "size": VECTOR3, "color": COLOR})),
    "cylinders": _array(_object("foxglove.CylinderPrimitive", {
        "pose": POSE, "size": VECTOR3, "bottom_scale": {"type": "number"}, "top_scale": {"type": "number"},
        "color": COLOR})),
    "texts": _array(_object("foxglove.TextPrimitive", {
        "pose": POSE, "billboard": {"type": "boolean"}, "font_size": {"type": "number"},
        "scale_invariant": {"type": "boolean"}, "color": COLOR, "text": {"type": "string"}})),
    "models": _array(_object("foxglove.ModelPrimitive", {
        "pose": POSE, "scale": VECTOR3, "color": COLOR, "override_color": {"type": "boolean"},
        "url": {"type": "string"}, "media_type": {"type": "string"}, "data": BYTES})),
})

SCHEMAS: dict[str, Schema] = {
    "foxglove.SceneUpdate": _object("foxglove.SceneUpdate", {
        "deletions": _array(_object("foxglove.SceneEntityDeletion", {
            "timestamp": TIME, "type": {"type": "integer"}, "id": {"type": "string"}})),
        "entities": _array(ENTITY)}),
    "foxglove.FrameTransforms": _object("foxglove.FrameTransforms", {
        "transforms": _array(_object("foxglove.FrameTransform", {
            "timestamp": TIME, "parent_frame_id": {"type": "string"}, "child_frame_id": {"type": "string"},
            "translation": VECTOR3, "rotation": QUATERNION}))}),
    "foxglove.Log": _object("foxglove.Log", {
        "timestamp": TIME,
        "level": {"type": "integer", "description": "0 unknown, 1 debug, 2 info, 3 warning, 4 error, 5 fatal"},
        "message": {"type": "string"}, "name": {"type": "string"}, "file": {"type": "string"},
        "line": {"type": "integer", "minimum": 0}}),
    "foxglove.CompressedImage": _object("foxglove.CompressedImage", {
        "timestamp": TIME, "frame_id": {"type": "string"}, "data": BYTES, "format": {"type": "string"}}),
    "foxglove.CameraCalibration": _object("foxglove.CameraCalibration", {
        "timestamp": TIME, "frame_id": {"type": "string"},
        "width": {"type": "integer", "minimum": 0}, "height": {"type": "integer", "minimum": 0},
        "distortion_model": {"type": "string"}, "D": _array({"type": "number"}),
        "K": {**_array({"type": "number"}), "minItems": 9, "maxItems": 9},
        "R": {**_array({"type": "number"}), "minItems": 9, "maxItems": 9},
        "P": {**_array({"type": "number"}), "minItems": 12, "maxItems": 12}}),
}
