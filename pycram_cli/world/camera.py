"""Rendering a world to pixels (PyBullet's TinyRenderer, works headless) and writing PNGs."""
from __future__ import annotations

import math
import struct
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Sequence

import numpy as np
import pybullet as p

from ..files import write_atomic
from ..limits import MAX_MAGNITUDE

if TYPE_CHECKING:
    from .bullet_world import BulletWorld


@dataclass(frozen=True)
class Camera:
    eye: tuple[float, float, float]
    target: tuple[float, float, float]
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    vertical_fov_deg: float = 50.0
    near: float = 0.05
    far: float = 30.0


def default_camera(world: "BulletWorld") -> Camera:
    """A three-quarter view that frames every object except huge ones (floors)."""
    boxes = [o.get_aabb() for o in world.objects]
    boxes = [b for b in boxes if max(b[1][k] - b[0][k] for k in range(2)) < 15.0] or boxes or [((0, 0, 0), (1, 1, 1))]
    lo = np.min([b[0] for b in boxes], axis=0)
    hi = np.max([b[1] for b in boxes], axis=0)
    centre = (lo + hi) / 2.0
    radius = max(float(np.linalg.norm(hi - lo)) / 2.0, 0.5)
    direction = np.array([-1.0, -1.3, 0.9])
    direction /= np.linalg.norm(direction)
    eye = centre + direction * radius / math.tan(math.radians(25.0)) * 0.8
    return Camera(tuple(eye), tuple(centre))


def view_matrix(eye: Sequence[float], target: Sequence[float], up: Sequence[float]) -> tuple[float, ...]:
    """OpenGL view matrix (16 numbers, column-major) of a camera at `eye` looking at `target`."""
    return p.computeViewMatrix(list(eye), list(target), list(up))


def projection_matrix(left: float, right: float, bottom: float, top: float, near: float,
                      far: float) -> tuple[float, ...]:
    """OpenGL projection matrix (16 numbers) of a frustum, possibly off-centre; the window is on the near plane."""
    return p.computeProjectionMatrix(left, right, bottom, top, near, far)


def segmentation(client: int, width: int, height: int, view: Sequence[float],
                 projection: Sequence[float]) -> np.ndarray:
    """(height, width) body ids that a PyBullet client shows at each pixel (-1: nothing); TinyRenderer, no shadows."""
    _, _, _, _, seg = p.getCameraImage(width, height, view, projection, shadow=0, renderer=p.ER_TINY_RENDERER,
                                       physicsClientId=client)
    return np.asarray(seg, dtype=np.int64).reshape(height, width)


def render(world: "BulletWorld", camera: Camera, width: int = 640, height: int = 480) -> np.ndarray:
    """RGB image (height, width, 3) of the world from `camera`."""
    cid = world.client_id
    view = p.computeViewMatrix(camera.eye, camera.target, camera.up, physicsClientId=cid)
    proj = p.computeProjectionMatrixFOV(camera.vertical_fov_deg, width / height, camera.near, camera.far, physicsClientId=cid)
    _, _, rgba, _, _ = p.getCameraImage(width, height, view, proj, renderer=p.ER_TINY_RENDERER, shadow=1,
                                        lightDirection=[-1.0, -0.6, 2.0], physicsClientId=cid)
    return np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]


def write_png(path: Path, rgb: np.ndarray, key: str = "output") -> None:
    """A minimal PNG writer (8-bit RGB), so rendering needs no imaging library."""
    height, width, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[row].astype(np.uint8).tobytes() for row in range(height))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")
    write_atomic(path, png, key=key)


def parse_vector(text: str, what: str) -> tuple[float, float, float]:
    parts = [s for s in text.replace(" ", "").split(",") if s]
    if len(parts) != 3:
        raise ValueError(f"{what}: expected x,y,z (three numbers), got {text!r}")
    try:
        x, y, z = (float(s) for s in parts)
    except ValueError:
        raise ValueError(f"{what}: expected three numbers, got {text!r}") from None
    if not all(math.isfinite(v) and abs(v) <= MAX_MAGNITUDE for v in (x, y, z)):
        raise ValueError(f"{what}: numbers must be finite and at most {MAX_MAGNITUDE:g} in size, got {text!r}")
    return (x, y, z)


def parse_camera(text: str) -> Camera:
    """`EYE:TARGET`, each `x,y,z`, e.g. `-1.5,-1.5,2.5:1,0.8,0.9`."""
    eye, sep, target = text.partition(":")
    if not sep:
        raise ValueError(f"expected EYE:TARGET such as -1.5,-1.5,2.5:1,0.8,0.9, got {text!r}")
    camera = Camera(parse_vector(eye, "camera eye"), parse_vector(target, "camera target"))
    if math.dist(camera.eye, camera.target) < 1e-6:
        raise ValueError(f"the camera's eye and target must differ, got {text!r}")
    return camera
