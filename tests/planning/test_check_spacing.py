"""The checks along a path are spaced by a sound bound (planning/pace.py): over a step, no point of a moving part
travels farther than the bound says, measured finely along real motions in the bundled kitchens; and the bound
lets a path take fewer checks than the levers alone, with the same verdicts."""
from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from pycram_cli import BulletWorld, load_world
from pycram_cli.paths import worlds_dir
from pycram_cli.planning import motion, pace
from pycram_cli.robots import Robot
from pycram_cli.world.pose import quat_to_matrix

#: how much farther a point may seem to travel than the bound (m): PyBullet's link frames are float32
NOISE = 1e-6
#: the allowances of travel stepped (m): a part at the floor (motion.SPACING), near things, far from them
TRAVELS = (0.002, motion.SPACING, 0.05, 0.3)
#: how many points of a step the travel is measured at (the bound without its curvature term fails four of the five
#: soundness tests at this density)
SAMPLES = 30


@pytest.fixture(scope="module")
def fetch_kitchen() -> Iterator[BulletWorld]:
    world = load_world(worlds_dir() / "kitchen_fetch.yaml")
    yield world
    world.exit()


def frames(m: motion.Motion) -> list[np.ndarray]:
    """Each mover's frame now (4×4): its link's, or the held object's."""
    poses = m.body.link_poses(m.links)
    placed = [poses[link] for link in m.links] + [obj.get_pose() for obj in m.held]
    found = []
    for position, orientation in placed:
        frame = np.eye(4)
        frame[:3, :3] = quat_to_matrix(orientation)
        frame[:3, 3] = position
        found.append(frame)
    return found


def farthest_travel(m: motion.Motion, at: np.ndarray, delta: np.ndarray, step: float, k: int) -> float:
    """How far the points of mover k's box (where the path is at `at`) travel from there over `step` of the path,
    sampled every 1/SAMPLES of it (a rigid motion moves a box's points farthest at a corner)."""
    m._put(at)
    points = pace.corners(*m._mover_boxes())[k]
    local = np.linalg.inv(frames(m)[k]) @ np.c_[points, np.ones(len(points))].T
    farthest = 0.0
    for s in np.linspace(0.0, step, SAMPLES + 1)[1:]:
        m._put(at + s * delta)
        moved = (frames(m)[k] @ local)[:3].T
        farthest = max(farthest, float(np.linalg.norm(moved - points, axis=1).max()))
    return farthest


def assert_sound(m: motion.Motion, goal: dict[str, float]) -> None:
    """At ten places along the path to `goal`, for every mover and allowance: the step the bound allows moves no
    point of the mover farther than the allowance, and is never shorter than the levers' step."""
    start, end = m._endpoints(goal)
    delta = end - start
    below, inner = m._nesting()
    pacer = pace.Pacer(delta, m._prismatic, below, inner)
    checked = 0
    try:
        for t in np.linspace(0.0, 0.9, 10):
            m._put(start + t * delta)
            bound = pacer.at(pace.corners(*m._mover_boxes()), *m._axes())
            levers_only = pace.Pace.of_levers(bound.base, bound.weight)
            for travel in TRAVELS:
                allowed = np.full(len(bound.base), travel)
                steps, lever_steps = bound.steps(allowed), levers_only.steps(allowed)
                assert np.all(steps >= lever_steps)
                for k in np.flatnonzero(np.isfinite(steps)):
                    assert farthest_travel(m, start + t * delta, delta, float(steps[k]), k) <= travel + NOISE, \
                        (m._mover_name(k), t, travel)
                    checked += 1
    finally:
        m._put(start)
    assert checked


def test_an_arm_reaching_out_over_the_counter_stays_within_the_bound(counter):
    robot, joints, out = counter
    assert_sound(motion.Motion(robot, joints), out)


def test_an_arm_holding_the_milk_stays_within_the_bound(counter, world):
    robot, joints, out = counter
    tool = robot.description.arm("left").tool_frame
    milk = world.get_object_by_name("milk")
    hand = robot.body.get_link_position(tool)
    milk.set_position((hand[0] + 0.05, hand[1], hand[2] - 0.05))
    world.robot.attach(milk, tool)
    m = motion.Motion(robot, joints)
    assert m.held == [milk]
    assert_sound(m, out)


def test_a_gripper_opening_stays_within_the_bound(counter):
    robot, _, _ = counter
    fingers = motion.joints_of(robot, ["right"], gripper=True)
    robot.body.reset_joints({name: 0.0 for name in fingers})
    assert_sound(motion.Motion(robot, fingers), {name: 0.5 for name in fingers})


def test_the_fetch_arm_and_its_sliding_fingers_stay_within_the_bound(fetch_kitchen):
    with fetch_kitchen.snapshot():
        robot = Robot.of(fetch_kitchen)
        arm = motion.joints_of(robot, ["arm"])
        values = robot.body.get_joint_positions(arm)
        assert_sound(motion.Motion(robot, arm), {name: values[name] + (0.6 if i % 2 else -0.5)
                                                 for i, name in enumerate(arm)})
        fingers = motion.joints_of(robot, ["arm"], gripper=True)
        robot.body.reset_joints({name: 0.0 for name in fingers})
        assert_sound(motion.Motion(robot, fingers), {name: 0.05 for name in fingers})


def test_the_travel_a_step_needs_is_what_steps_allows_inverted():
    """`Pace.needed` (how much clearance a mover must have for a given step) gives back the step `steps` takes."""
    rng = np.random.default_rng(7)
    for _ in range(50):
        base, weight, speed, curve, bend = rng.uniform(0.0, 2.0, size=(5, 3))
        speed = np.minimum(speed, base)  # the Jacobian's speed is never above the levers'
        bound = pace.Pace(base, weight, speed, curve, bend)
        travel = rng.uniform(0.001, 0.5, size=3)
        steps = bound.steps(travel)
        for k in range(3):
            assert bound.needed(float(steps[k]), k) == pytest.approx(travel[k], rel=1e-9)


def count_checks(monkeypatch: pytest.MonkeyPatch, m: motion.Motion, goal: dict[str, float],
                 levers_only: bool) -> tuple[int, float, list[tuple[str, str]]]:
    """The checks a walk to `goal` makes (with the lever bound alone, or the better of both), how far it is free
    and what it runs into."""
    calls = []
    original = motion.Motion.clearances
    real_at = motion.Pacer.at

    def counted(self: motion.Motion, *args: object, **kwargs: object) -> object:
        calls.append(1)
        return original(self, *args, **kwargs)

    def lever_pace(self: pace.Pacer, *args: np.ndarray) -> pace.Pace:
        found = real_at(self, *args)
        return pace.Pace.of_levers(found.base, found.weight)

    with monkeypatch.context() as patch:
        patch.setattr(motion.Motion, "clearances", counted)
        if levers_only:
            patch.setattr(motion.Pacer, "at", lever_pace)
        fraction, hits, _ = m.walk(goal)
    m.world.cache.forget(motion.MEMO)
    return len(calls), fraction, [(h.mover, h.obstacle.name) for h in hits]


def test_a_known_motion_takes_fewer_checks_than_with_the_levers_alone(counter, monkeypatch):
    """The arm out over the counter (free) and down into it (blocked): a third fewer checks or better, the same
    verdicts, the blocked one stopped by the same part in the same thing at about the same place."""
    robot, joints, out = counter
    free_levers = count_checks(monkeypatch, motion.Motion(robot, joints), out, levers_only=True)
    free = count_checks(monkeypatch, motion.Motion(robot, joints), out, levers_only=False)
    assert free[1:] == free_levers[1:] == (1.0, [])
    assert free[0] <= 0.67 * free_levers[0]
    down = {**out, joints[1]: 1.2}
    blocked_levers = count_checks(monkeypatch, motion.Motion(robot, joints), down, levers_only=True)
    blocked = count_checks(monkeypatch, motion.Motion(robot, joints), down, levers_only=False)
    assert blocked[2] and blocked[2][0] == blocked_levers[2][0]
    assert blocked[1] == pytest.approx(blocked_levers[1], abs=0.05)
    assert blocked[0] < blocked_levers[0]


def test_the_torso_rising_while_the_arm_reaches_stays_within_the_bound(counter):
    """A sliding joint above turning ones: the Jacobian's columns of both kinds add up with their signs."""
    robot, joints, out = counter
    torso = robot.body.get_joint_positions(["torso_lift_joint"])["torso_lift_joint"]
    assert_sound(motion.Motion(robot, ["torso_lift_joint", *joints]), {"torso_lift_joint": torso + 0.2, **out})
