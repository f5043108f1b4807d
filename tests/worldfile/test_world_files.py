"""World files: one clear message per problem with file:line:column, the key and a suggestion."""
from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from pycram_cli import load_world
from pycram_cli.errors import InputError, InputErrors, as_list
from pycram_cli.worldfile.spec import parse_world

VALID = """\
gravity: [0, 0, -9.81]
objects:
  - name: floor
    type: environment
    file: plane.urdf
  - name: arm
    type: robot
    file: {data}/arm.urdf
    joints: {{shoulder: 0.5}}
  - name: cube
    type: box
    file: {data}/cube.obj
    position: [0.5, 0, 0.2]
    color: [1, 0, 0]
    attach: [{{to: arm, parent_link: hand}}]
"""


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "world.yaml"
    path.write_text(textwrap.dedent(text))
    return path


def problems(path: Path) -> list[str]:
    with pytest.raises((InputError, InputErrors)) as info:
        parse_world(path)
    return [e.format() for e in as_list(info.value)]


def test_a_valid_world_loads_with_joints_and_attachments(tmp_path, data_dir):
    world = load_world(write(tmp_path, VALID.format(data=data_dir)))
    try:
        arm, cube = world.get_object_by_name("arm"), world.get_object_by_name("cube")
        assert world.robot is arm and arm.get_joint_position("shoulder") == 0.5
        assert cube in arm.attachments
        arm.set_position([1, 0, 0])
        assert cube.get_position()[0] == pytest.approx(1.5)
    finally:
        world.exit()


def test_a_loaded_world_remembers_its_world_file(tmp_path, data_dir):
    path = write(tmp_path, VALID.format(data=data_dir))
    world = load_world(path)
    try:
        assert world.source == path
    finally:
        world.exit()


def test_file_paths_resolve_against_the_world_files_folder(tmp_path, data_dir):
    (tmp_path / "cube.obj").write_text((data_dir / "cube.obj").read_text())
    world = load_world(write(tmp_path, "objects:\n  - {name: c, type: box, file: cube.obj}\n"))
    assert world.get_object_by_name("c").path == tmp_path / "cube.obj"
    world.exit()


@pytest.mark.parametrize("text, expected", [
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n    postion: [0, 0, 0]\n",
     ":5:5: postion: unknown key 'postion' in object 'a' (did you mean 'position'?)"),
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n    position: [0, 0]\n",
     ":5:15: position: expected 3 numbers, got 2"),
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n    position: up\n",
     ":5:15: position: expected a list of 3 numbers, got the string 'up'"),
    ("objects:\n  - name: a\n    file: plane.urdf\n",
     ":2:5: type: missing required key 'type' in object 'a'"),
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdff\n",
     ":4:11: file: file not found: 'plane.urdff'"),
    ("objects:\n  - {{name: a, type: box, file: plane.urdf}}\n  - {{name: a, type: box, file: plane.urdf}}\n",
     ":3:5: name: duplicate object name 'a' (first defined at line 2)"),
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n    orientation: [0, 0, 0.5, 0.5]\n",
     ":5:18: orientation: quaternion must have unit length, got norm 0.7071 (normalised: [0, 0, 0.7071, 0.7071])"),
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n    orientation: [0, 0, 1]\n",
     ":5:18: orientation: expected 4 numbers, got 3 (orientation is a quaternion x, y, z, w"),
    ("objects:\n  - name: a\n    type: box\n    file: {data}/arm.urdf\n    joints: {{sholder: 1}}\n",
     ":5:14: joints: the model has no joint 'sholder' (did you mean 'shoulder'?)"),
    ("objects:\n  - name: a\n    type: box\n    file: {data}/arm.urdf\n    joints: {{slide: 3}}\n",
     ":5:21: joints: joint 'slide': 3 is outside its limits [0, 0.2]"),
    ("objects:\n  - name: a\n   type: box\n",
     ":3:4: malformed YAML"),
    ("gravty: [0, 0, -9.81]\nobjects: []\n",
     ":1:1: gravty: unknown key 'gravty' in the world (did you mean 'gravity'?)"),
    ("objects:\n  - name: a\n    type: box\n    file: plane.urdf\n  - {{name: b, type: box, file: plane.urdf, attach: [{{to: aa}}]}}\n",
     ":5:53: attach: 'b' cannot attach to 'aa': no such object (did you mean 'a'?)"),
    ("objects:\n  - name: a\n    type: box\n    name: b\n    file: plane.urdf\n",
     ":4:5: name: duplicate key 'name' (first given at line 2)"),
    ("objects:\n  - name: a\n    type: 3\n    file: plane.urdf\n",
     ":3:11: type: expected a string, got 3"),
])
def test_bad_input_is_reported_at_its_place(tmp_path, data_dir, text, expected):
    path = write(tmp_path, text.format(data=data_dir))
    found = problems(path)
    assert any(str(path) + expected in message for message in found), found


def test_all_problems_are_reported_together_in_file_order(tmp_path):
    path = write(tmp_path, """\
        objects:
          - name: a
            type: box
            file: plane.urdf
            postion: [0, 0, 0]
          - name: a
            type: box
            file: nothing.urdf
            orientation: [0, 0, 1]
        """)
    found = problems(path)
    assert len(found) == 4
    assert [int(m.split(":")[1]) for m in found] == sorted(int(m.split(":")[1]) for m in found)


def test_a_world_file_that_is_not_a_mapping(tmp_path):
    assert "a world file must be a mapping" in problems(write(tmp_path, "- just\n- a list\n"))[0]


def test_the_robot_descriptions_defaults_apply_where_the_world_sets_no_value(tmp_path):
    """The PR2's description says torso 0.3 (as the design's listing 5.1 gets it); a world that sets no torso
    height gets it, a world that sets one keeps its own."""
    def torso(joints: str) -> float:
        path = write(tmp_path, f"""\
            objects:
              - {{name: pr2, type: robot, file: robots/pr2/pr2.urdf{joints}}}
            """)
        world = load_world(path)
        try:
            return world.robot.get_joint_position("torso_lift_joint")
        finally:
            world.exit()

    assert torso("") == pytest.approx(0.3)
    assert torso(", joints: {torso_lift_joint: 0.1}") == pytest.approx(0.1)


def test_the_python_loaders_take_the_names_the_command_line_takes():
    from pycram_cli import load_world
    from pycram_cli.plan import load_plan

    world = load_world("kitchen_fetch")
    try:
        assert world.robot is not None and world.robot.name == "fetch"
    finally:
        world.exit()
    assert load_plan("fetch_spoon").path.name == "fetch_spoon.yaml"
