"""The robot zoo (pycram_cli/robots/zoo): seeded robots nobody tuned pycram for, written as data.

A seed gives one robot, always the same one, byte for byte. Every robot of seeds 0..19 loads in
PyBullet, its description passes pycram's own checks (`pycram validate` on its kitchen world),
names only joints and links its model has, parks its arm within the joint limits, over the base,
above the base's top and clear of itself, and stands on wheels whose collision shapes touch the
floor (as nearly every real robot's do). Across those seeds the zoo has every camera place (a
pan/tilt head, fixed on the mast, on the wrist), robots with and without a torso, arms of 5, 6 and 7
joints and grippers with one and two finger joints.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pybullet as p
import pytest
import yaml
from click.testing import CliRunner

from pycram_cli.cli.main import cli
from pycram_cli.robots.zoo import CAMERA_KINDS, ZooRobot, generate, main, world_joints, write, write_world

#: the module's tests on one pytest-xdist worker: the 20 robots (`zoo`, about 20 s) are generated once, not once on
#: each worker that gets some of the module's tests
pytestmark = pytest.mark.xdist_group("zoo")

SEEDS = range(20)


@pytest.fixture(scope="module")
def zoo(tmp_path_factory) -> dict[int, tuple[ZooRobot, Path]]:
    """Seeds 0..19: each robot and its kitchen world, written into one folder. Generated once for the module (a
    robot takes a second or two): the tests only read them, and a seed always gives the same robot (the first
    test generates two of them twice to show it)."""
    folder = tmp_path_factory.mktemp("zoo")
    return {seed: (robot, write_world(robot, folder)) for seed in SEEDS for robot in [generate(seed)]}


@pytest.fixture(scope="module")
def bullet():
    client = p.connect(p.DIRECT)
    yield client
    p.disconnect(client)


class Loaded:
    """A zoo robot loaded in PyBullet, its joints at the world's values (torso default, arm parked)."""

    def __init__(self, robot: ZooRobot, urdf: Path, client: int) -> None:
        self.client = client
        self.body = p.loadURDF(str(urdf), useFixedBase=True, physicsClientId=client)
        infos = [p.getJointInfo(self.body, i, physicsClientId=client) for i in range(self.count)]
        self.joints = {info[1].decode(): info for info in infos}
        self.links = {info[12].decode(): info[0] for info in infos}
        self.links[p.getBodyInfo(self.body, physicsClientId=client)[0].decode()] = -1
        self.parent = {info[0]: info[16] for info in infos}
        for name, value in world_joints(robot).items():
            p.resetJointState(self.body, self.joints[name][0], value, physicsClientId=client)
        p.performCollisionDetection(physicsClientId=client)

    @property
    def count(self) -> int:
        return p.getNumJoints(self.body, physicsClientId=self.client)

    def solid(self, link: int) -> bool:
        return bool(p.getCollisionShapeData(self.body, link, physicsClientId=self.client))

    def aabb(self, link: int) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = p.getAABB(self.body, link, physicsClientId=self.client)
        return np.asarray(lo), np.asarray(hi)

    def penetrations(self) -> list[tuple[int, int, float]]:
        """Pairs of links not joined to each other whose collision shapes overlap."""
        found = []
        links = [i for i in range(-1, self.count) if self.solid(i)]
        for k, a in enumerate(links):
            for b in links[k + 1:]:
                if self.parent.get(b) == a or self.parent.get(a) == b:
                    continue
                points = p.getClosestPoints(self.body, self.body, 0.0, a, b, physicsClientId=self.client)
                depth = min((c[8] for c in points), default=1.0)
                if depth < -1e-4:
                    found.append((a, b, depth))
        return found

    def remove(self) -> None:
        p.removeBody(self.body, physicsClientId=self.client)


@pytest.fixture
def loaded(zoo, bullet):
    made: list[Loaded] = []

    def load(seed: int) -> tuple[ZooRobot, Loaded]:
        robot, world = zoo[seed]
        made.append(Loaded(robot, world.parent / f"{robot.name}.urdf", bullet))
        return robot, made[-1]

    yield load
    for item in made:
        item.remove()


def description(robot: ZooRobot, world: Path) -> dict:
    return yaml.safe_load((world.parent / f"{robot.name}.yaml").read_text())


# -- the same seed, the same robot -------------------------------------------------------------------------------


def test_a_seed_gives_byte_identical_files(tmp_path: Path):
    for seed in (0, 7):
        first = write_world(generate(seed), tmp_path / "a")
        second = write_world(generate.__wrapped__(seed), tmp_path / "b")  # generated afresh, not the process's copy
        for name in (first.name, first.name.replace("_kitchen.yaml", ".urdf"), first.name.replace("_kitchen", "")):
            ours, theirs = (first.parent / name).read_bytes(), (second.parent / name).read_bytes()
            assert ours.replace(b"/a/", b"/b/") == theirs, name


def test_different_seeds_give_different_robots(zoo, tmp_path: Path):
    texts = {write(zoo[seed][0], tmp_path).read_text() for seed in (0, 1, 2, 3)}
    assert len(texts) == 4
    assert len({zoo[seed][0].name for seed in SEEDS}) == len(SEEDS)


def test_no_name_is_the_pr2s_or_the_fetchs(zoo):
    bundled = Path(__file__).resolve().parents[2] / "resources" / "robots"
    theirs = "\n".join((bundled / name / f"{name}.urdf").read_text() for name in ("pr2", "fetch"))
    for seed in (0, 1, 2):
        robot = zoo[seed][0]
        for name in [j.name for j in robot.joints] + [l.name for l in robot.links]:
            assert f'"{name}"' not in theirs, name


# -- every robot is sound ------------------------------------------------------------------------------------------


@pytest.mark.parametrize("seed", SEEDS)
def test_the_robot_loads_and_its_world_passes_pycrams_checks(zoo, seed):
    robot, world = zoo[seed]
    result = CliRunner().invoke(cli, ["validate", str(world)])
    assert result.exit_code == 0, result.output
    assert "valid world file" in result.stdout


@pytest.mark.parametrize("seed", SEEDS)
def test_every_joint_and_link_the_description_names_is_in_the_model(zoo, loaded, seed):
    robot, world = zoo[seed]
    robot, body = loaded(seed)
    desc = description(robot, world)
    (arm,) = desc["arms"].values()
    joints = list(arm["joints"]) + list(arm["gripper"]["joints"])
    joints += [desc["torso"]["joint"]] if "torso" in desc else []
    joints += [desc["head"]["pan_joint"], desc["head"]["tilt_joint"]] if "head" in desc else []
    links = [desc["base_link"], desc["camera"]["frame"], arm["tool_frame"], arm["palm_link"], *arm["links"]]
    assert not set(joints) - set(body.joints)
    assert not set(links) - set(body.links)
    assert body.links[desc["base_link"]] == -1  # the root link
    assert set(desc) <= {"name", "base_link", "mobile", "torso", "camera", "head", "arms", "grasps", "resources"}


@pytest.mark.parametrize("seed", SEEDS)
def test_the_park_pose_is_within_the_joint_limits(zoo, loaded, seed):
    robot, body = loaded(seed)
    for name, value in zip(robot.arm_joints, robot.park):
        lower, upper = body.joints[name][8:10]
        if body.joints[name][2] == p.JOINT_REVOLUTE and lower > upper:  # continuous: no limits
            continue
        assert lower <= value <= upper, name
    assert robot.torso_joint is None or 0.0 <= robot.torso_default <= body.joints[robot.torso_joint][9]


@pytest.mark.parametrize("seed", SEEDS)
def test_parked_the_arm_is_clear_of_the_body_of_itself_and_above_the_base(zoo, loaded, seed):
    robot, body = loaded(seed)
    assert body.penetrations() == []
    arm = [body.links[name] for name in robot.arm_links if body.solid(body.links[name])]
    lowest = min(body.aabb(link)[0][2] for link in arm)
    assert lowest > robot.base_top + robot.torso_default  # also with the torso all the way down
    reach = max(np.abs(body.aabb(link)[k][:2]).max() for link in arm for k in (0, 1))
    assert reach <= robot.base_radius + 0.22  # tucked over the base (at most 0.2 m past its edge, and the margin)


@pytest.mark.parametrize("seed", SEEDS)
def test_the_wheels_touch_the_floor(loaded, seed):
    robot, body = loaded(seed)
    bottoms = {link: body.aabb(link)[0][2] for link in range(-1, body.count) if body.solid(link)}
    assert min(bottoms.values()) == pytest.approx(0.0, abs=0.005)  # PyBullet's AABBs carry a margin of a few mm
    touching = [link for link, z in bottoms.items() if z < 0.005]
    assert len(touching) >= 3  # wheels and casters: the robot stands
    assert all(link != body.links[robot.root_link] for link in touching)  # the base body itself is clear


def test_the_zoo_has_every_kind_of_camera_torso_arm_and_gripper(zoo):
    robots = [zoo[seed][0] for seed in SEEDS]
    assert {r.camera.kind for r in robots} == set(CAMERA_KINDS)
    assert {r.torso_joint is not None for r in robots} == {True, False}
    assert {len(r.arm_joints) for r in robots} == {5, 6, 7}
    assert {len(r.gripper.joints) for r in robots} == {1, 2}
    assert {r.root_link.endswith("base_footprint") for r in robots} == {True, False}
    assert any("prismatic" == r.joint(j).type for r in robots for j in r.arm_joints)
    assert any("continuous" == r.joint(j).type for r in robots for j in r.arm_joints)


def test_the_shoulder_is_mounted_between_0_7_and_1_15_m(zoo):
    heights = [robot.shoulder_height for robot, _ in zoo.values()]
    assert all(0.7 <= h <= 1.15 for h in heights)
    assert max(heights) - min(heights) > 0.2


def test_the_world_is_the_kitchen_with_the_robot_parked_in_place_of_the_pr2(zoo):
    robot, world = zoo[0]
    data = yaml.safe_load(world.read_text())
    names = [o["name"] for o in data["objects"]]
    assert "pr2" not in names and robot.name in names
    (ours,) = [o for o in data["objects"] if o["type"] == "robot"]
    assert Path(ours["file"]).is_absolute() and Path(ours["description"]).is_file()
    assert ours["position"] == [0, 0.7, 0]
    assert all(ours["joints"][j] == pytest.approx(v) for j, v in zip(robot.arm_joints, robot.park))
    assert {"milk", "cereal", "bowl", "spoon", "kitchen", "floor"} <= set(names)


def test_the_command_line_writes_robots_and_worlds(zoo, tmp_path: Path, capsys):
    assert main(["3", "4", "--out", str(tmp_path)]) == 0
    for seed in (3, 4):
        name = zoo[seed][0].name
        assert (tmp_path / f"{name}.urdf").is_file() and (tmp_path / f"{name}.yaml").is_file()
        assert (tmp_path / f"{name}_kitchen.yaml").is_file()
    assert "seed 3:" in capsys.readouterr().out


def test_the_urdf_is_written_one_element_a_line_and_frames_have_no_geometry(zoo, tmp_path: Path):
    robot = zoo[5][0]
    text = write(robot, tmp_path).read_text()
    assert text.count("\n") > 100
    frames = [link for link in robot.links if link.density is None]
    assert {robot.tool_frame, robot.camera.frame} <= {link.name for link in frames}
    assert all(not link.shapes for link in frames)
    assert not math.isclose(robot.park[1], 0.0)
