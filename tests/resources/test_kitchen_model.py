"""Specification of the project's kitchen model (resources/environments/kitchen).

The kitchen is a primitive re-creation of the IAI kitchen; it is loaded in PyBullet
with ``useFixedBase=True`` and a separate floor (resources/environments/floor).
When the real IAI description is available next to the repository (in
``../shared/models/kitchen/kitchen.urdf``) the shared joints are compared with it;
otherwise those checks are skipped.
"""
from __future__ import annotations

import math
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

p = pytest.importorskip("pybullet")

REPO = Path(__file__).resolve().parents[2]
KITCHEN_DIR = REPO / "resources" / "environments" / "kitchen"
KITCHEN = KITCHEN_DIR / "kitchen.urdf"
FLOOR = REPO / "resources" / "environments" / "floor" / "floor.urdf"
GENERATOR = KITCHEN_DIR / "generate.py"
REAL_KITCHEN = REPO.parent / "shared" / "models" / "kitchen" / "kitchen.urdf"

DRAWER_JOINT = "sink_area_left_upper_drawer_main_joint"
DRAWER = "sink_area_left_upper_drawer_main"
HANDLE = "sink_area_left_upper_drawer_handle"

REQUIRED_LINKS = [
    "room_link", "sink_area_footprint", "sink_area", "sink_area_surface", "sink_area_sink",
    DRAWER, HANDLE, "kitchen_island", "kitchen_island_surface", "oven_area_area",
    "fridge_area", "iai_fridge_main", "iai_fridge_door", "kitchen_walls", "table_area_main",
]
REQUIRED_JOINTS = [
    DRAWER_JOINT, "sink_area_left_upper_drawer_handle_joint", "sink_area_surface_joint",
    "sink_area_main_joint", "sink_area_footprint_joint", "kitchen_island_surface_joint",
    "sink_area_left_middle_drawer_main_joint", "sink_area_trash_drawer_main_joint",
    "iai_fridge_door_joint",
]

# Counter tops: (x range, y range, top z) in the world frame.
SINK_SURFACE = ((1.25, 1.82), (-0.29, 1.32), 0.85)
ISLAND_SURFACE = ((-1.47, -0.67), (0.49, 2.94), 0.861)

# Regions that must stay free of kitchen geometry (world frame, min and max corners).
FREE_REGIONS = {
    "floor between counter and island": ((-0.6, -0.3, 0.0), (0.95, 2.0, 2.0)),
    "above the sink counter": ((1.25, -0.29, 0.86), (1.82, 1.32, 1.5)),
    "above the island": ((-1.47, 0.49, 0.87), (-0.67, 2.94, 1.5)),
    "robot base at the counter (0.65, 0.7)": ((0.315, 0.365, 0.0), (0.985, 1.035, 1.4)),
    "robot base at the island (-0.3, 1.0)": ((-0.635, 0.665, 0.0), (0.035, 1.335, 1.4)),
}


# ----------------------------------------------------------------------------- helpers
@pytest.fixture(scope="module")
def sim():
    """A DIRECT PyBullet client with the kitchen loaded (fixed base)."""
    cid = p.connect(p.DIRECT)
    kitchen = p.loadURDF(str(KITCHEN), useFixedBase=True, physicsClientId=cid)
    yield cid, kitchen
    p.disconnect(cid)


def link_indices(cid: int, body: int) -> dict[str, int]:
    names = {p.getBodyInfo(body, physicsClientId=cid)[0].decode(): -1}
    for i in range(p.getNumJoints(body, physicsClientId=cid)):
        names[p.getJointInfo(body, i, physicsClientId=cid)[12].decode()] = i
    return names


def joint_indices(cid: int, body: int) -> dict[str, int]:
    return {p.getJointInfo(body, i, physicsClientId=cid)[1].decode(): i
            for i in range(p.getNumJoints(body, physicsClientId=cid))}


def link_frame(cid: int, body: int, link: int) -> np.ndarray:
    return np.array(p.getLinkState(body, link, computeForwardKinematics=True, physicsClientId=cid)[4])


def _origin(element: ET.Element | None) -> np.ndarray:
    """4x4 transform of a URDF <origin> element (rpy as fixed-axis x-y-z)."""
    xyz = [0.0, 0.0, 0.0]
    rpy = [0.0, 0.0, 0.0]
    if element is not None:
        xyz = [float(v) for v in element.get("xyz", "0 0 0").split()]
        rpy = [float(v) for v in element.get("rpy", "0 0 0").split()]
    r, pt, y = rpy
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    ry = np.array([[math.cos(pt), 0, math.sin(pt)], [0, 1, 0], [-math.sin(pt), 0, math.cos(pt)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    m = np.eye(4)
    m[:3, :3] = rz @ ry @ rx
    m[:3, 3] = xyz
    return m


def urdf_world_positions(path: Path, root: str = "room_link") -> dict[str, np.ndarray]:
    """World position of every link below ``root`` with all joints at zero."""
    robot = ET.parse(path).getroot()
    by_child = {j.find("child").get("link"): j for j in robot.findall("joint")}
    poses: dict[str, np.ndarray] = {root: np.eye(4)}

    def pose(link: str) -> np.ndarray:
        if link not in poses:
            joint = by_child[link]
            poses[link] = pose(joint.find("parent").get("link")) @ _origin(joint.find("origin"))
        return poses[link]

    positions = {}
    for link in by_child:
        try:
            positions[link] = pose(link)[:3, 3]
        except KeyError:  # a link that is not below root (e.g. the real file's "world")
            continue
    positions[root] = np.zeros(3)
    return positions


def urdf_joints(path: Path) -> dict[str, ET.Element]:
    return {j.get("name"): j for j in ET.parse(path).getroot().findall("joint")}


# ------------------------------------------------------------------------------- tests
def test_kitchen_loads_with_required_links_and_joints(sim):
    cid, kitchen = sim
    links = link_indices(cid, kitchen)
    joints = joint_indices(cid, kitchen)
    assert next(iter(links)) == "room_link", "the root link must be room_link"
    missing_links = [name for name in REQUIRED_LINKS if name not in links]
    missing_joints = [name for name in REQUIRED_JOINTS if name not in joints]
    assert not missing_links and not missing_joints, (missing_links, missing_joints)


def test_every_link_has_positive_mass_inertial():
    robot = ET.parse(KITCHEN).getroot()
    for link in robot.findall("link"):
        inertial = link.find("inertial")
        assert inertial is not None, f"{link.get('name')} has no <inertial>"
        assert float(inertial.find("mass").get("value")) > 0, link.get("name")
        inertia = inertial.find("inertia")
        assert all(float(inertia.get(k)) > 0 for k in ("ixx", "iyy", "izz")), link.get("name")


def test_urdf_is_pretty_printed():
    text = KITCHEN.read_text()
    assert text.count("\n") > 500, "PyBullet needs a multi-line URDF"
    assert "<floor" not in text and FLOOR.read_text().count("\n") > 10


def test_upper_drawer_joint_is_prismatic_with_limits(sim):
    cid, kitchen = sim
    info = p.getJointInfo(kitchen, joint_indices(cid, kitchen)[DRAWER_JOINT], physicsClientId=cid)
    assert info[2] == p.JOINT_PRISMATIC
    assert info[8] == pytest.approx(0.0) and info[9] == pytest.approx(0.48)
    assert info[12].decode() == DRAWER


def test_drawer_and_handle_closed_positions(sim):
    cid, kitchen = sim
    links = link_indices(cid, kitchen)
    assert link_frame(cid, kitchen, links[DRAWER]) == pytest.approx([1.525, 0.89, 0.755], abs=1e-3)
    assert link_frame(cid, kitchen, links[HANDLE]) == pytest.approx([1.1925, 0.89, 0.7725], abs=1e-3)


def test_opening_the_drawer_moves_it_towards_minus_x(sim):
    cid, kitchen = sim
    links, joints = link_indices(cid, kitchen), joint_indices(cid, kitchen)
    closed = {name: link_frame(cid, kitchen, links[name]) for name in (DRAWER, HANDLE)}
    p.resetJointState(kitchen, joints[DRAWER_JOINT], 0.3, physicsClientId=cid)
    try:
        for name in (DRAWER, HANDLE):
            moved = link_frame(cid, kitchen, links[name]) - closed[name]
            assert moved == pytest.approx([-0.3, 0.0, 0.0], abs=1e-6), name
    finally:
        p.resetJointState(kitchen, joints[DRAWER_JOINT], 0.0, physicsClientId=cid)


@pytest.mark.parametrize("link, expected", [("sink_area_surface", SINK_SURFACE),
                                            ("kitchen_island_surface", ISLAND_SURFACE)])
def test_counter_top_extent_and_height(sim, link, expected):
    cid, kitchen = sim
    (x0, x1), (y0, y1), top = expected
    lo, hi = p.getAABB(kitchen, link_indices(cid, kitchen)[link], physicsClientId=cid)
    assert [lo[0], hi[0], lo[1], hi[1], hi[2]] == pytest.approx([x0, x1, y0, y1, top], abs=0.01)


@pytest.mark.parametrize("region", sorted(FREE_REGIONS))
def test_free_space_for_the_robot(sim, region):
    cid, kitchen = sim
    lo, hi = (np.array(v) for v in FREE_REGIONS[region])
    shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=(hi - lo) / 2, physicsClientId=cid)
    probe = p.createMultiBody(0, shape, -1, (lo + hi) / 2, physicsClientId=cid)
    try:
        hits = p.getClosestPoints(kitchen, probe, 0.0, physicsClientId=cid)
    finally:
        p.removeBody(probe, physicsClientId=cid)
    names = {i: n for n, i in link_indices(cid, kitchen).items()}
    assert not hits, sorted({names[h[3]] for h in hits})


def test_no_geometry_below_the_floor(sim):
    cid, kitchen = sim
    for link in link_indices(cid, kitchen).values():
        lo, _ = p.getAABB(kitchen, link, physicsClientId=cid)
        assert lo[2] > -0.002  # 1 mm of that is PyBullet's AABB margin


def test_movable_parts_move_freely_through_their_range():
    """No movable link (or its children) touches the rest of the kitchen at any position.

    A second, unmoved copy of the kitchen provides the static geometry, because
    PyBullet does not report contacts between links of one body.
    """
    cid = p.connect(p.DIRECT)
    try:
        moving_kitchen = p.loadURDF(str(KITCHEN), useFixedBase=True, physicsClientId=cid)
        static_kitchen = p.loadURDF(str(KITCHEN), useFixedBase=True, physicsClientId=cid)
        n = p.getNumJoints(moving_kitchen, physicsClientId=cid)
        info = [p.getJointInfo(moving_kitchen, i, physicsClientId=cid) for i in range(n)]
        movable = [i for i in range(n) if info[i][2] in (p.JOINT_PRISMATIC, p.JOINT_REVOLUTE)]
        assert len(movable) >= 2
        problems = []
        for j in movable:
            subtree = {j}
            for i in range(n):  # links are ordered parent-first
                if info[i][16] in subtree:
                    subtree.add(i)
            others = [-1] + [i for i in range(n) if i not in subtree]
            for q in np.linspace(info[j][8], info[j][9], 9):
                p.resetJointState(moving_kitchen, j, q, physicsClientId=cid)
                for m in subtree:
                    for o in others:
                        if p.getClosestPoints(moving_kitchen, static_kitchen, 0.0, linkIndexA=m,
                                              linkIndexB=o, physicsClientId=cid):
                            problems.append((info[j][1].decode(), round(float(q), 3),
                                             info[m][12].decode(), o))
            p.resetJointState(moving_kitchen, j, 0.0, physicsClientId=cid)
        assert not problems, problems[:10]
    finally:
        p.disconnect(cid)


def test_generated_files_are_up_to_date(tmp_path):
    kitchen, floor = tmp_path / "kitchen.urdf", tmp_path / "floor.urdf"
    subprocess.run([sys.executable, str(GENERATOR), "--kitchen", str(kitchen), "--floor", str(floor)],
                   check=True, capture_output=True)
    assert kitchen.read_bytes() == KITCHEN.read_bytes(), "re-run resources/environments/kitchen/generate.py"
    assert floor.read_bytes() == FLOOR.read_bytes(), "re-run resources/environments/kitchen/generate.py"


def test_floor_is_static_with_top_at_zero():
    cid = p.connect(p.DIRECT)
    try:
        floor = p.loadURDF(str(FLOOR), physicsClientId=cid)
        assert p.getBodyInfo(floor, physicsClientId=cid)[0].decode() == "floor"
        assert p.getDynamicsInfo(floor, -1, physicsClientId=cid)[0] == 0.0  # mass 0: static
        lo, hi = p.getAABB(floor, -1, physicsClientId=cid)
        assert hi[2] == pytest.approx(0.0, abs=0.002)
        assert hi[0] - lo[0] == pytest.approx(20.0, abs=0.01)
    finally:
        p.disconnect(cid)


# ------------------------------------------------------------- against the IAI kitchen
needs_real_kitchen = pytest.mark.skipif(not REAL_KITCHEN.exists(),
                                        reason=f"real IAI kitchen not found at {REAL_KITCHEN}")


@needs_real_kitchen
def test_shared_joints_match_the_iai_kitchen():
    ours, real = urdf_joints(KITCHEN), urdf_joints(REAL_KITCHEN)
    shared = sorted(set(ours) & set(real))
    assert DRAWER_JOINT in shared and len(shared) >= 20
    for name in shared:
        a, b = ours[name], real[name]
        assert a.get("type") == b.get("type"), name
        if a.get("type") == "fixed":
            continue  # the IAI file carries meaningless <limit> tags on fixed joints
        la, lb = a.find("limit"), b.find("limit")
        for key in ("lower", "upper"):
            assert float(la.get(key)) == pytest.approx(float(lb.get(key)), abs=1e-6), (name, key)
        axis_a = np.array([float(v) for v in a.find("axis").get("xyz").split()])
        axis_b = np.array([float(v) for v in b.find("axis").get("xyz").split()])
        assert axis_a == pytest.approx(axis_b, abs=1e-6), name


@needs_real_kitchen
def test_drawer_and_handle_positions_match_the_iai_kitchen():
    ours, real = urdf_world_positions(KITCHEN), urdf_world_positions(REAL_KITCHEN)
    for link in (DRAWER, HANDLE):
        assert np.linalg.norm(ours[link] - real[link]) < 0.01, (link, ours[link], real[link])
    # all other shared frames agree too, except the deliberately moved dining table
    moved = {"table_area_main"}
    for link in sorted((set(ours) & set(real)) - moved):
        assert np.linalg.norm(ours[link] - real[link]) < 0.01, (link, ours[link], real[link])
