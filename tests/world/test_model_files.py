"""Model files checked before PyBullet sees them (issue 29): a URDF PyBullet cannot load, or would crash on,
is a `ModelError` naming the element that is wrong, found by `describe_model` (what `validate` reads) and by
`prepare_urdf` (what loading reads) alike; a mesh with any name the file system allows loads."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from pycram_cli import Object
from pycram_cli.world.model_files import ModelError, describe_model, prepare_urdf, resolve_uri

DATA = Path(__file__).resolve().parents[1] / "data"


def urdf(tmp_path: Path, body: str, name: str = "m.urdf", root: str = 'robot name="m"') -> Path:
    tag = root.split()[0]
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"<?xml version='1.0'?>\n<{root}>{body}</{tag}>\n")
    return path


LINK = '<link name="{}"/>'


def joint(name: str, parent: str, child: str, kind: str = "fixed") -> str:
    return f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/></joint>'


BROKEN = {
    "root": ('<link name="a"/>', 'model name="m"', "the root element is <model>, not <robot>"),
    "no links": ("", 'robot name="m"', "has no <link>"),
    "unnamed robot": ('<link name="a"/>', "robot", "<robot> has no name"),
    "unnamed link": ("<link/>", 'robot name="m"', "a <link> has no name"),
    "two links named alike": ('<link name="a"/><link name="a"/>', 'robot name="m"', "two links are named 'a'"),
    "cycle": (LINK.format("a") + LINK.format("b") + joint("j1", "a", "b") + joint("j2", "b", "a"),
              'robot name="m"', "the joints j1, j2 form a cycle"),
    "two roots": (LINK.format("a") + LINK.format("b"), 'robot name="m"',
                  "links 'a' and 'b' are both roots (no joint has them as child)"),
    "two parents": (LINK.format("a") + LINK.format("b") + LINK.format("c") + joint("j", "a", "c") + joint("k", "b", "c"),
                    'robot name="m"', "link 'c' is the child of two joints, 'j' and 'k'"),
    "unknown link": (LINK.format("a") + joint("j", "a", "zz"), 'robot name="m"', "joint 'j': its child 'zz' is not a link"),
    "no child": (LINK.format("a") + '<joint name="j" type="fixed"><parent link="a"/></joint>', 'robot name="m"',
                 "joint 'j' has no <child link=...>"),
    "own parent": (LINK.format("a") + joint("j", "a", "a"), 'robot name="m"', "joint 'j' joins link 'a' to itself"),
    "two joints named alike": (LINK.format("a") + LINK.format("b") + LINK.format("c") + joint("j", "a", "b")
                               + joint("j", "a", "c"), 'robot name="m"', "two joints are named 'j'"),
    "joint type": (LINK.format("a") + LINK.format("b") + joint("j", "a", "b", "weird"), 'robot name="m"',
                   "joint 'j': unknown type 'weird'"),
    "no limit": (LINK.format("a") + LINK.format("b") + joint("j", "a", "b", "revolute"), 'robot name="m"',
                 "joint 'j' (revolute) has no <limit>"),
    "nan limit": (LINK.format("a") + LINK.format("b")
                  + '<joint name="j" type="revolute"><parent link="a"/><child link="b"/><limit lower="nan" upper="1"/></joint>',
                  'robot name="m"', "joint 'j': <limit lower=\"nan\"> is not a finite number"),
    "mass": ('<link name="a"><inertial><mass value="abc"/></inertial></link>', 'robot name="m"',
             "link 'a': <mass value=\"abc\"> is not a finite number"),
    "empty geometry": ('<link name="a"><visual><geometry/></visual></link>', 'robot name="m"',
                       "link 'a': <visual> has no box, cylinder, sphere, capsule or mesh in its <geometry>"),
}


@pytest.mark.parametrize("case", sorted(BROKEN))
def test_a_urdf_pybullet_cannot_load_is_a_model_error_naming_the_element(tmp_path, case):
    body, root, message = BROKEN[case]
    path = urdf(tmp_path, body, root=root)
    for read in (describe_model, prepare_urdf):
        with pytest.raises(ModelError) as caught:
            read(path)
        assert message in str(caught.value)


def test_a_package_uri_that_climbs_out_of_its_package_is_refused(tmp_path):
    (tmp_path / "x").mkdir()
    path = urdf(tmp_path, '<link name="a"><visual><geometry><mesh filename="package://x/../../../etc/passwd"/>'
                          '</geometry></visual></link>')
    for read in (describe_model, prepare_urdf):
        with pytest.raises(ModelError, match=r"mesh 'package://x/../../../etc/passwd' leaves its package 'x'"):
            read(path)


@pytest.mark.parametrize("kind", ["fifo", "dev-zero", "unsupported"])
def test_a_mesh_that_is_not_a_mesh_file_is_refused_before_pybullet_reads_it(tmp_path, kind):
    mesh = tmp_path / ("thing.txt" if kind == "unsupported" else "thing.obj")
    if kind == "fifo":
        os.mkfifo(mesh)
    elif kind == "dev-zero":
        mesh.symlink_to("/dev/zero")
    else:
        mesh.write_text("hello\n")
    path = urdf(tmp_path, f'<link name="a"><visual><geometry><mesh filename="{mesh.name}"/></geometry></visual></link>')
    expected = "PyBullet reads .obj, .stl and .dae meshes" if kind == "unsupported" else "not a regular file"
    for read in (describe_model, prepare_urdf):
        with pytest.raises(ModelError, match=f"mesh '{mesh.name}': .*{expected}"):
            read(path)


def test_missing_meshes_are_listed_by_describe_model(tmp_path):
    path = urdf(tmp_path, '<link name="a"><visual><geometry><mesh filename="gone.obj"/></geometry></visual></link>')
    assert describe_model(path).missing == ["gone.obj"]


def test_a_package_is_found_in_the_urdfs_own_folders_before_ros_package_path(tmp_path, monkeypatch):
    # the URDF lies inside its package (pkg/urdf/m.urdf), named by its folder or by its package.xml
    for folder, manifest in (("test_pkg", None), ("checkout", "<package><name>test_pkg</name></package>")):
        package = tmp_path / folder
        shutil.copytree(DATA / "ros_ws" / "test_pkg" / "meshes", package / "meshes")
        if manifest:
            (package / "package.xml").write_text(manifest)
        path = urdf(package / "urdf", '<link name="a"><visual><geometry><mesh filename="package://test_pkg/meshes/cube.obj"/>'
                                      '</geometry></visual></link>')
        monkeypatch.setenv("ROS_PACKAGE_PATH", str(DATA / "ros_ws"))
        assert resolve_uri("package://test_pkg/meshes/cube.obj", path.parent) == package / "meshes" / "cube.obj"
        assert describe_model(path).missing == []


@pytest.mark.parametrize("name", ['m"i<l>k&.obj', "a b\nc'.obj", "[b]{x}.obj"])
def test_a_mesh_with_xml_metacharacters_in_its_name_loads(world, tmp_path, name):
    mesh = tmp_path / name
    shutil.copy(DATA / "cube.obj", mesh)
    thing = Object("thing", "box", mesh)
    lo, hi = thing.get_aabb()
    assert hi[0] - lo[0] > 0.01


def test_a_urdf_with_xml_metacharacters_in_its_own_name_loads(world, tmp_path):
    folder = tmp_path / 'a "b" <c> & d'
    folder.mkdir()
    shutil.copy(DATA / "cube.obj", folder / "cube.obj")
    path = urdf(folder, '<link name="a"><visual><geometry><mesh filename="cube.obj"/></geometry></visual>'
                        '<collision><geometry><mesh filename="cube.obj"/></geometry></collision></link>',
                name="m'\"<x>&.urdf")
    thing = Object("thing", "box", path)
    lo, hi = thing.get_aabb()
    assert hi[0] - lo[0] > 0.01
