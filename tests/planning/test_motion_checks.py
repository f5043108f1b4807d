"""Collision-checked paths cost what they must and answer as before: a walk or search made again in the same
situation is answered from memory (and from nowhere else: any change of the robot's base or of the joints the moving
part hangs below, of what it holds or of another object asks again; the head turned or the other arm moved does not), and a check measures only the pairs of parts whose distance can matter."""
from __future__ import annotations

import math

import numpy as np

from pycram_cli.planning import motion, paths


def counting(monkeypatch, name):
    calls = []
    original = getattr(motion.Motion, name) if name != "_search" else paths._Search.run

    def counted(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    if name == "_search":
        monkeypatch.setattr(paths._Search, "run", counted)
    else:
        monkeypatch.setattr(motion.Motion, name, counted)
    return calls


def test_a_walk_made_again_in_the_same_situation_is_remembered(counter, world, monkeypatch):
    robot, joints, out = counter
    follows = counting(monkeypatch, "_follow")
    first = motion.Motion(robot, joints).walk(out)
    before = world.robot.get_joint_positions(joints)
    again = motion.Motion(robot, joints).walk(out)
    assert len(follows) == 1
    assert again == first
    assert world.robot.get_joint_positions(joints) == before  # left as a walk leaves it: where it started


def test_a_remembered_answer_is_a_copy(counter):
    robot, joints, out = counter
    first = motion.Motion(robot, joints).walk(out)
    first[1].append("changed by the caller")
    first[2].clear()
    again = motion.Motion(robot, joints).walk(out)
    assert "changed by the caller" not in again[1] and again[2]


def test_an_object_moved_into_the_way_is_seen(counter, world, monkeypatch):
    robot, joints, out = counter
    fraction, hits, _ = motion.Motion(robot, joints).walk(out)
    assert fraction == 1.0 and not hits
    milk = world.get_object_by_name("milk")
    with robot.body.joints_kept(joints):  # where the hand ends up: the milk goes there
        robot.body.reset_joints(out)
        hand = robot.body.get_link_position(robot.description.arm("left").tool_frame)
    milk.set_position((hand[0], hand[1], hand[2] - 0.05))
    follows = counting(monkeypatch, "_follow")
    fraction, hits, _ = motion.Motion(robot, joints).walk(out)
    assert len(follows) == 1
    assert hits and fraction < 1.0


def test_the_robot_elsewhere_or_holding_something_asks_again(counter, world, monkeypatch):
    robot, joints, out = counter
    motion.Motion(robot, joints).walk(out)
    follows = counting(monkeypatch, "_follow")
    world.robot.set_position_and_orientation((0.64, 0.7, 0.0), (0.0, 0.0, 0.0, 1.0))
    motion.Motion(robot, joints).walk(out)
    assert len(follows) == 1
    spoon = world.get_object_by_name("spoon") or world.get_object_by_name("cereal")
    tool = robot.description.arm("left").tool_frame
    world.robot.attach(spoon, tool)
    motion.Motion(robot, joints).walk(out)
    assert len(follows) == 2


def test_the_head_turned_or_the_other_arm_moved_leaves_a_walk_what_it_was(counter, world, monkeypatch):
    """The robot's own links are no obstacle: only the joints the moving arm hangs below (the torso) place it. The
    location test walks an arm's ways before the robot looks at the object; the pick-up walks them after."""
    robot, joints, out = counter
    first = motion.Motion(robot, joints).walk(out)
    follows = counting(monkeypatch, "_follow")
    world.robot.reset_joints({"head_pan_joint": 0.4, "head_tilt_joint": 0.3, "r_shoulder_pan_joint": -0.5})
    assert motion.Motion(robot, joints).walk(out) == first and not follows
    world.robot.reset_joints({"torso_lift_joint": 0.1})  # above the arm: it places the arm elsewhere
    motion.Motion(robot, joints).walk(out)
    assert len(follows) == 1  # walked anew


def test_the_robot_put_back_where_it_stood_is_the_situation_it_was(counter, world, monkeypatch):
    """PyBullet normalises a base orientation it is given: the robot turned and put back at its own pose (as a floor
    map puts it back after reading its footprint) stands a rounding error apart, and must not be asked again (the
    pick-up's own test at the pose its location had tested walked every way anew: 175 ms for the bowl's)."""
    robot, joints, out = counter
    body = world.robot
    body.set_position_and_orientation((0.75, 0.65, 0.0), (0.0, 0.0, -0.041395069399583616, 0.9991428567674413))
    first = motion.Motion(robot, joints).walk(out)
    stood = body.get_pose()
    for _ in range(3):
        body.set_position_and_orientation(*body.get_pose())
    assert body.get_pose() != stood  # the drift this is about (else the test proves nothing)
    follows = counting(monkeypatch, "_follow")
    assert motion.Motion(robot, joints).walk(out) == first and not follows
    body.set_position_and_orientation((0.75, 0.6501, 0.0), stood[1])  # a tenth of a millimetre is another place
    motion.Motion(robot, joints).walk(out)
    assert len(follows) == 1


def test_a_state_restored_is_the_situation_it_was(counter, world, monkeypatch):
    robot, joints, out = counter
    with world.snapshot():
        first = motion.Motion(robot, joints).walk(out)
        world.get_object_by_name("milk").set_position((5.0, 5.0, 0.5))
    follows = counting(monkeypatch, "_follow")
    assert motion.Motion(robot, joints).walk(out) == first
    assert not follows


def test_a_world_that_does_not_track_its_changes_remembers_nothing(counter, world, monkeypatch):
    robot, joints, out = counter
    monkeypatch.setattr(type(world), "tracks_changes", property(lambda self: False))
    assert motion.Motion(robot, joints).situation() is None
    follows = counting(monkeypatch, "_follow")
    motion.Motion(robot, joints).walk(out)
    motion.Motion(robot, joints).walk(out)
    assert len(follows) == 2


def test_a_search_made_again_is_remembered_even_when_it_found_nothing(counter, monkeypatch):
    robot, joints, out = counter
    searches = counting(monkeypatch, "_search")
    first = paths.search_path(robot, out, edges=3)
    again = paths.search_path(robot, out, edges=3)
    assert again == first and len(searches) == 1
    paths.search_path(robot, out, edges=4)  # another budget is another question
    assert len(searches) == 2


def test_a_way_found_within_a_budget_is_the_answer_for_a_larger_one(counter, monkeypatch):
    robot, joints, out = counter
    searches = counting(monkeypatch, "_search")
    first = paths.search_path(robot, out, edges=300)  # as a location test asks (the way back from a handle)
    assert first is not None
    assert paths.search_path(robot, out, edges=2500) == first  # as the action's park then asks
    assert len(searches) == 1


def test_no_way_within_a_budget_is_the_answer_for_a_smaller_one_and_not_a_larger(counter, monkeypatch):
    robot, joints, out = counter
    searches = counting(monkeypatch, "_search")
    assert paths.search_path(robot, out, edges=1) is None
    assert paths.search_path(robot, out, edges=0) is None
    assert len(searches) == 1
    assert paths.search_path(robot, out, edges=300) is not None
    assert len(searches) == 2


def every_pair(m: motion.Motion) -> tuple[float, list[tuple[str, str, float]]]:
    """The check as it was before pairs were skipped: every pair of boxes nearer than NEAR measured."""
    m_lo, m_hi = m._mover_boxes()
    gap = np.maximum(0.0, np.maximum(m._o_lo[None] - m_hi[:, None], m_lo[:, None] - m._o_hi[None]))
    gaps = np.sqrt(np.sum(gap * gap, axis=2))
    far = gaps[gaps >= motion.NEAR]
    clearance = float(far.min()) if far.size else math.inf
    hits = []
    for k, o in np.argwhere(gaps < motion.NEAR):
        distance = m._distance(k, o, motion.NEAR)
        clearance = min(clearance, max(distance, 0.0) if distance < motion.NEAR else motion.NEAR)
        if distance < -motion.PENETRATION:
            hits.append((m._mover_name(k), m._obstacle_boxes[o][0].name, -distance))
    return clearance, sorted(hits, key=lambda h: -h[2])


def test_a_check_skips_only_pairs_that_cannot_matter(counter):
    """Along the arm's way from park down into the counter: the same hits as measuring every pair, and the same
    clearance wherever it is above SPACING (below it, every check steps SPACING anyway)."""
    robot, joints, out = counter
    down = {**out, joints[1]: 1.2}
    m = motion.Motion(robot, joints)
    start, end = m._endpoints(down)
    seen_hits = seen_clear = 0
    try:
        for t in np.linspace(0.0, 1.0, 41):
            m._put(start + t * (end - start))
            clearance, hits = m.scan()
            reference, expected = every_pair(m)
            assert [(h.mover, h.obstacle.name, h.depth) for h in hits] == expected
            if reference > motion.SPACING:
                assert clearance == reference
                seen_clear += 1
            else:
                assert clearance <= motion.SPACING
            seen_hits += bool(hits)
    finally:
        m._put(start)
    assert seen_hits and seen_clear  # the way passes free space and goes into the counter
