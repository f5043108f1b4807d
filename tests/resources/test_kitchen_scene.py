"""The default breakfast scene is physically stable in the project's kitchen.

Floor, kitchen (fixed base) and the five objects are loaded into one DIRECT client
with gravity; each object is a one-link URDF written to a temporary directory
(mesh as visual and collision, 0.2 kg, inertia of its bounding box).  Objects stand
upright at the positions below and must not move during 2 s of simulation.

Positions are the point the object stands on (mesh origin = centre of the bottom
face).  They are 1 mm above the supporting surface because PyBullet gives convex
mesh shapes a 1 mm collision margin: an object spawned exactly on the surface rises
by 1 mm in the first steps.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

p = pytest.importorskip("pybullet")

REPO = Path(__file__).resolve().parents[2]
KITCHEN = REPO / "resources" / "environments" / "kitchen" / "kitchen.urdf"
FLOOR = REPO / "resources" / "environments" / "floor" / "floor.urdf"
OBJECTS = REPO / "resources" / "objects"

MESH_MARGIN = 0.001          # PyBullet's collision margin of convex mesh shapes
SINK_COUNTER_TOP = 0.85      # top of sink_area_surface
DRAWER_FLOOR = 0.70          # interior floor of sink_area_left_upper_drawer_main (closed)
DRAWER_JOINT = "sink_area_left_upper_drawer_main_joint"

# Recommended default positions (x, y, z of the bottom centre); all upright, yaw 0.
POSITIONS = {
    "milk": (1.3, 1.0, SINK_COUNTER_TOP + MESH_MARGIN),
    "breakfast_cereal": (1.3, 0.6, SINK_COUNTER_TOP + MESH_MARGIN),
    "bowl": (1.3, 0.8, SINK_COUNTER_TOP + MESH_MARGIN),
    "bottle": (1.35, 0.4, SINK_COUNTER_TOP + MESH_MARGIN),
    "spoon": (1.525, 0.89, DRAWER_FLOOR + MESH_MARGIN),  # inside the closed drawer
}
MASS = 0.2
STEPS = 480  # 2 s at 240 Hz


def object_urdf(name: str, directory: Path) -> Path:
    """The one-link URDF pycram itself makes for a mesh (cached by pycram, not written to `directory`)."""
    from pycram_cli.world.model_files import mesh_urdf

    return mesh_urdf(OBJECTS / f"{name}.obj", None, mass=MASS)


def build_scene(tmp_path: Path, drawer_opening: float = 0.0) -> tuple[int, int, dict[str, int]]:
    cid = p.connect(p.DIRECT)
    p.setGravity(0, 0, -9.81, physicsClientId=cid)
    p.setTimeStep(1.0 / 240.0, physicsClientId=cid)
    p.loadURDF(str(FLOOR), physicsClientId=cid)
    kitchen = p.loadURDF(str(KITCHEN), useFixedBase=True, physicsClientId=cid)
    joints = {p.getJointInfo(kitchen, i, physicsClientId=cid)[1].decode(): i
              for i in range(p.getNumJoints(kitchen, physicsClientId=cid))}
    p.resetJointState(kitchen, joints[DRAWER_JOINT], drawer_opening, physicsClientId=cid)
    bodies = {}
    for name, (x, y, z) in POSITIONS.items():
        if name == "spoon":
            x -= drawer_opening  # the spoon travels with the drawer
        bodies[name] = p.loadURDF(str(object_urdf(name, tmp_path)), [x, y, z], physicsClientId=cid)
    return cid, kitchen, bodies


def displacements(cid: int, bodies: dict[str, int]) -> dict[str, float]:
    start = {n: np.array(p.getBasePositionAndOrientation(b, physicsClientId=cid)[0]) for n, b in bodies.items()}
    for _ in range(STEPS):
        p.stepSimulation(physicsClientId=cid)
    result = {}
    for name, body in bodies.items():
        pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
        assert abs(p.getEulerFromQuaternion(orn)[0]) < 0.01 and abs(p.getEulerFromQuaternion(orn)[1]) < 0.01, \
            f"{name} tipped over"
        result[name] = float(np.linalg.norm(np.array(pos) - start[name]))
    return result


@pytest.mark.parametrize("opening", [0.0, 0.3])
def test_objects_rest_still(tmp_path, opening):
    cid, _, bodies = build_scene(tmp_path, opening)
    try:
        moved = displacements(cid, bodies)
        assert all(d < 0.001 for d in moved.values()), moved
    finally:
        p.disconnect(cid)


def test_spoon_stays_inside_the_opened_drawer(tmp_path):
    cid, kitchen, bodies = build_scene(tmp_path, 0.3)
    try:
        displacements(cid, bodies)
        joints = {p.getJointInfo(kitchen, i, physicsClientId=cid)[1].decode(): i
                  for i in range(p.getNumJoints(kitchen, physicsClientId=cid))}
        lo, hi = p.getAABB(kitchen, joints[DRAWER_JOINT], physicsClientId=cid)
        slo, shi = p.getAABB(bodies["spoon"], physicsClientId=cid)
        assert all(lo[k] < slo[k] and shi[k] < hi[k] for k in range(3))
        assert slo[2] < DRAWER_FLOOR + 0.005
    finally:
        p.disconnect(cid)


def visible_pixels(cid: int, body: int, eye, target) -> int:
    view = p.computeViewMatrix(eye, target, (0, 0, 1), physicsClientId=cid)
    projection = p.computeProjectionMatrixFOV(60, 4 / 3, 0.05, 20, physicsClientId=cid)
    _, _, _, _, seg = p.getCameraImage(320, 240, view, projection, renderer=p.ER_TINY_RENDERER,
                                       physicsClientId=cid)
    return int((np.reshape(seg, (240, 320)) == body).sum())


VIEWS = {
    "robot at the counter": ((0.65, 0.7, 1.45), (1.35, 0.7, 0.9)),
    "above the drawer": ((0.6, 0.9, 1.4), (1.2, 0.9, 0.7)),
    "room overview": ((-1.5, -1.5, 2.5), (1.0, 0.8, 0.9)),
}


@pytest.mark.parametrize("view", sorted(VIEWS))
def test_spoon_is_hidden_in_the_closed_drawer_and_visible_when_open(tmp_path, view):
    eye, target = VIEWS[view]
    for opening, visible in ((0.0, False), (0.3, True)):
        cid, _, bodies = build_scene(tmp_path, opening)
        try:
            pixels = visible_pixels(cid, bodies["spoon"], eye, target)
            if visible and view != "room overview":  # too far away to count on
                assert pixels > 20, (view, opening, pixels)
            if not visible:
                assert pixels == 0, (view, opening, pixels)
        finally:
            p.disconnect(cid)


def test_counter_objects_are_visible_from_the_robot(tmp_path):
    cid, _, bodies = build_scene(tmp_path)
    try:
        eye, target = VIEWS["robot at the counter"]
        for name in ("milk", "breakfast_cereal", "bowl", "bottle"):
            assert visible_pixels(cid, bodies[name], eye, target) > 200, name
    finally:
        p.disconnect(cid)
