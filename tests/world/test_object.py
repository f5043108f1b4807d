"""Object: loading URDF/STL/OBJ, names to ids, poses, joints and limits."""
from __future__ import annotations

import math
import shutil
import warnings

import pybullet_data
import pytest

from pycram_cli import Object
from pycram_cli.world import JointLimitError, MissingMeshWarning


def test_urdf_objects_have_name_type_world_and_body_id(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf", [1, 2, 0])
    assert (arm.name, arm.type, arm.world) == ("arm", "robot", world)
    assert isinstance(arm.id, int) and arm.id >= 0
    assert arm.get_position() == (1.0, 2.0, 0.0)


@pytest.mark.parametrize("mesh", ["cube.obj"])
def test_a_mesh_becomes_a_cached_one_link_urdf_never_written_beside_the_users_file(world, data_dir, tmp_path, mesh):
    user_dir = tmp_path / "mine"
    user_dir.mkdir()
    shutil.copy(data_dir / mesh, user_dir / mesh)
    cube = Object("cube", "box", user_dir / mesh, [0, 0, 0.5], color=[1, 0, 0])
    assert sorted(p.name for p in user_dir.iterdir()) == [mesh]
    assert cube.get_position() == (0.0, 0.0, 0.5)
    lo, hi = cube.get_aabb()
    assert hi[2] - lo[2] == pytest.approx(0.1, abs=0.01)


def test_stl_meshes_load(world, tmp_path, data_dir):
    # write the test cube as ASCII STL
    verts, faces = [], []
    for line in (data_dir / "cube.obj").read_text().splitlines():
        if line.startswith("v "):
            verts.append(line.split()[1:])
        elif line.startswith("f "):
            faces.append([int(i) - 1 for i in line.split()[1:]])
    stl = ["solid cube"] + [
        "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {' '.join(verts[i])}\n" for i in f) + "endloop\nendfacet"
        for f in faces
    ] + ["endsolid cube"]
    (tmp_path / "cube.stl").write_text("\n".join(stl))
    cube = Object("cube", "box", tmp_path / "cube.stl", [0, 0, 1])
    lo, hi = cube.get_aabb()
    assert hi[0] - lo[0] == pytest.approx(0.1, abs=0.01)


def test_a_missing_file_is_a_clear_error(world, tmp_path):
    with pytest.raises(FileNotFoundError, match="object 'x': file not found"):
        Object("x", "thing", tmp_path / "nope.urdf")


def test_link_and_joint_names_map_to_ids(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    assert arm.get_link_id("base") == -1
    assert arm.get_joint_id("shoulder") == 0 and arm.get_link_id("upper") == 0
    assert arm.get_joint_id("wrist") == arm.get_link_id("hand") == 2
    with pytest.raises(KeyError, match="did you mean 'shoulder'"):
        arm.get_joint_id("sholder")


def test_pose_getters_and_setters(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    quarter = (0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4))
    arm.set_position_and_orientation([1, 0, 0], quarter)
    assert arm.get_pose()[0] == (1.0, 0.0, 0.0)
    assert arm.get_orientation() == pytest.approx(quarter)
    arm.set_position([2, 0, 0])
    assert arm.get_orientation() == pytest.approx(quarter)
    arm.set_orientation([0, 0, 0, 1])
    assert arm.get_position() == (2.0, 0.0, 0.0)
    # the shoulder sits 0.2 above the base; the upper arm link starts there
    assert arm.get_link_position("upper") == pytest.approx((2.0, 0.0, 0.2))
    assert arm.get_link_orientation("upper") == pytest.approx((0, 0, 0, 1))


@pytest.mark.parametrize("bad, message", [
    ([0, 0, 0, 2], "unit length"),
    ([0, 0, 1], "expected 4 numbers, got 3"),
])
def test_orientations_are_validated_at_the_boundary(world, data_dir, bad, message):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    with pytest.raises(ValueError, match=message):
        arm.set_orientation(bad)


def test_joint_positions_by_name_within_limits(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    arm.set_joint_position("shoulder", 1.0)
    arm.set_joint_position("wrist", 12.0)  # continuous: no limits
    assert arm.get_joint_position("shoulder") == 1.0
    assert arm.get_joint_positions() == {"shoulder": 1.0, "slide": 0.0, "wrist": 12.0}
    with pytest.raises(JointLimitError, match=r"joint 'slide' of 'arm': 0.5 is outside its limits \[0, 0.2\]"):
        arm.set_joint_position("slide", 0.5)


def test_joint_changes_move_links_at_once(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    arm.set_joint_position("shoulder", 1.5)
    assert arm.get_link_position("slider") == pytest.approx((0.3 * math.cos(1.5), 0.3 * math.sin(1.5), 0.2), abs=1e-6)


def test_ros_package_uris_resolve_beside_the_urdf_and_missing_meshes_warn_once(world, data_dir):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        obj = Object("thing", "box", data_dir / "ros_ws" / "uses_package.urdf")
    missing = [w for w in caught if issubclass(w.category, MissingMeshWarning)]
    assert len(missing) == 1 and "does_not_exist.dae" in str(missing[0].message)
    assert obj.link_names == ["body", "lid"]
    lo, hi = obj.get_aabb("body")
    assert hi[0] - lo[0] == pytest.approx(0.1, abs=0.01)


def test_ros_package_path_is_searched(world, data_dir, tmp_path, monkeypatch):
    (tmp_path / "elsewhere").mkdir()
    urdf = tmp_path / "elsewhere" / "uses_package.urdf"
    shutil.copy(data_dir / "ros_ws" / "uses_package.urdf", urdf)
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(data_dir / "ros_ws"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MissingMeshWarning)
        obj = Object("thing", "box", urdf)
    lo, hi = obj.get_aabb("body")
    assert hi[2] - lo[2] == pytest.approx(0.1, abs=0.01)


def test_aabb_covers_all_links(world, data_dir):
    arm = Object("arm", "robot", data_dir / "arm.urdf")
    lo, hi = arm.get_aabb()
    assert lo[0] == pytest.approx(-0.1, abs=0.01) and hi[0] == pytest.approx(0.5, abs=0.01)


def test_robots_and_environments_are_kinematic_and_never_drift(world, data_dir):
    floor = Object("floor", "environment", f"{pybullet_data.getDataPath()}/plane.urdf")
    arm = Object("arm", "robot", data_dir / "arm.urdf", [0, 0, 0.3])
    arm.set_joint_positions({"shoulder": 0.7, "slide": 0.1})
    world.simulate(2.0)
    assert arm.get_position() == (0.0, 0.0, 0.3)
    assert arm.get_joint_positions() == {"shoulder": 0.7, "slide": 0.1, "wrist": 0.0}
    assert floor.get_position() == (0.0, 0.0, 0.0)


def test_removing_an_object(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj")
    cube.remove()
    assert world.objects == []
