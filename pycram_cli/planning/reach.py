"""Reaching: inverse kinematics for the tool frame (near the arm's configuration, in straight moves), the arms'
named and resting poses, grippers; every motion collision-checked along its path (`motion.py`), ways around
what is in the way in `paths.py`."""
from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from ..errors import did_you_mean
from ..failures import ManipulationFailure, ReachabilityFailure
from ..kinds import arm_words, gripper_words
from ..reasoning.ik import IKSolution, Query, Settings, solutions, solve
from ..robots import Robot
from ..world.pose import angle_between, quat_inverse, quat_multiply, quat_to_matrix
from . import motion
from .grasps import gripper_values, tool_axes

#: how close the arm must bring its tool to a pose it moves to: 1 cm, and 2° of the orientation (grasps are aligned
#: with objects' sides: a looser angle would hold a square carton askew)
REACH = 0.01
REACH_ANGLE = math.radians(2.0)
#: how reaching asks inverse kinematics, for a solution (the nearest configuration when none reaches) or only whether
REACHING = Settings(threshold=REACH, angle_threshold=REACH_ANGLE)
REACHING_VERDICT = replace(REACHING, best_effort=False)


def reach(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None,
          best_effort: bool = True) -> IKSolution:
    """The arm's joints that bring its tool within REACH (and REACH_ANGLE) of a pose. `best_effort=False`, for a caller
    that needs only whether: a pose out of the arm's reach by a distance bound fails at once, without the search for
    the nearest configuration (`ik.Settings`)."""
    return solve(robot, arm, position, orientation, settings=REACHING if best_effort else REACHING_VERDICT)


#: an IK solution that turns some joint of the arm farther than this from where it is (rad) is compared with one
#: solved from the middle of the arm's joint ranges, and the one nearer the arm's current configuration is taken
FAR = 1.5


def reach_near(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None) -> IKSolution:
    """`reach`, preferring a solution near the arm's current configuration: inverse kinematics starts from where the arm
    is, but may settle on a twisted solution far from it (an arm that would then have to sweep through everything in
    front of the robot to get there); then it is also solved from the middle of the joints' ranges (an arm held out in
    front, elbow out), and the solution that moves the arm least is taken. Both are searched at once."""
    for _, solution in near_solutions(robot, arm, [(position, orientation)]):
        return solution
    raise AssertionError("one target gives one solution")


#: `near_solutions` searches the targets of this many at a time (more cost a little more each while the first may do)
NEAR_BATCH = 4

Target = tuple[Sequence[float], "Sequence[float] | None"]


def near_solutions(robot: Robot, arm: str, targets: Sequence[Target]) -> Iterator[tuple[int, IKSolution]]:
    """`reach_near` for each target in turn, yielding `(k, solution)` in target order; the caller stops when it has the
    one it needs (break). The targets are searched NEAR_BATCH at a time in one batched search (`ik.solutions`), so
    that ways to hold an object that all fail cost about one search; each solution is exactly `reach_near`'s."""
    middle = middle_of_ranges(robot, arm)
    chooser = _Nearer(robot, arm)
    for first, batch in _near_batches(targets):
        answers: dict[int, IKSolution] = {}  # by query: target k from where the arm is (2k) and from the middle (2k+1)
        handed = 0  # how many of the batch's targets have been handed over
        queries = [(position, orientation, start) for position, orientation in batch for start in (None, middle)]
        for g, solution in reach_solutions(robot, arm, queries):
            answers[g] = solution
            while handed < len(batch) and (chosen := chooser.decided(answers, handed)) is not None:
                yield first + handed, chosen
                handed += 1
            if handed == len(batch):
                break


def _near_batches(targets: Sequence[Target]) -> list[tuple[int, Sequence[Target]]]:
    """The targets NEAR_BATCH at a time (with their first index), each batch with an orientation for every target or
    for none."""
    batches: list[tuple[int, Sequence[Target]]] = []
    first = 0
    while first < len(targets):
        end = first + 1
        while end < min(len(targets), first + NEAR_BATCH) and \
                (targets[end][1] is None) == (targets[first][1] is None):
            end += 1
        batches.append((first, targets[first:end]))
        first = end
    return batches


class _Nearer:
    """Which of a target's two solutions (from where the arm is, from the middle of its ranges) `reach_near` takes."""

    def __init__(self, robot: Robot, arm: str) -> None:
        self.names = list(robot.description.arm(arm).joints)
        self.current = robot.body.get_joint_positions(self.names)

    def spread(self, s: IKSolution) -> float:
        return max((abs(s.joint_positions[n] - self.current[n]) for n in self.names if n in s.joint_positions),
                   default=0.0)

    def moved(self, s: IKSolution) -> float:
        return sum(abs(s.joint_positions[n] - self.current[n]) for n in self.names)

    def decided(self, answers: Mapping[int, IKSolution], k: int) -> IKSolution | None:
        """Target k's solution once the answers found so far decide it, else None."""
        here, other = answers.get(2 * k), answers.get(2 * k + 1)
        if here is None:
            return None
        if here.success and self.spread(here) <= FAR:
            return here
        if other is None:
            return None
        if other.success and (not here.success or self.moved(other) < self.moved(here)):
            return other
        return here


def reach_solutions(robot: Robot, arm: str, queries: Sequence[Query],
                    best_effort: bool = True) -> Iterator[tuple[int, IKSolution]]:
    """`reach` for each query (target position, orientation, start configuration), searched at once, as they are found
    (`ik.solutions`)."""
    return solutions(robot, arm, queries, settings=REACHING if best_effort else REACHING_VERDICT)


def middle_of_ranges(robot: Robot, arm: str) -> dict[str, float]:
    """The middle of the arm's joint ranges (an arm held out in front, elbow out); a joint without limits as it is."""
    body = robot.body
    names = list(robot.description.arm(arm).joints)
    current = body.get_joint_positions(names)
    middle = {}
    for name in names:
        joint = body.joint(name)
        middle[name] = (joint.lower + joint.upper) / 2.0 if joint.limited else current[name]
    return middle


def reach_from_middle(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None) -> IKSolution:
    """`reach` solved from the middle of the arm's joint ranges (an arm held out in front, elbow out)."""
    return reach_from(robot, arm, middle_of_ranges(robot, arm), position, orientation)


#: a short straight move of the tool (`reach_from`) may stray this far from the straight line between its two poses
#: anywhere on its joint-space path (m, rad); it is checked at LINE_SAMPLES points, and when a solution strays (an
#: arm that was nearly stretched out flips its elbow or wrist to the other branch on the way) the move is solved
#: again in LINE_STEPS steps along the line, each from the last
LINE_SLACK = (0.03, math.radians(15.0))
LINE_SAMPLES = 4
LINE_STEPS = 5


def reach_from(robot: Robot, arm: str, joints: Mapping[str, float], position: Sequence[float],
               orientation: Sequence[float] | None) -> IKSolution:
    """`reach`, starting from the arm configuration `joints`, for a short straight move from there: the solution is on
    the same branch, so that the joint-space path between the two keeps the tool near the straight line between its
    poses (`strays`). When the first solution strays, the move is solved in steps along the line; when that strays
    too, the answer is a failure whose `position_error` is how far the tool would stray."""
    body = robot.body
    tool = robot.description.arm(arm).tool_frame
    with body.joints_kept(joints):
        body.reset_joints(joints)
        start = body.get_link_position(tool)
        solution = reach(robot, arm, position, orientation)
        if not solution.success:
            return solution
        off = strays(robot, arm, joints, solution.joint_positions, start, position, orientation)
        if off == 0.0:
            return solution
        current: Mapping[str, float] = joints
        for step in range(1, LINE_STEPS + 1):
            along = np.asarray(start) + (np.asarray(position, dtype=float) - np.asarray(start)) * step / LINE_STEPS
            body.reset_joints(current)
            stepped = reach(robot, arm, tuple(float(v) for v in along), orientation)
            if not stepped.success:
                break
            current = stepped.joint_positions
        else:
            if strays(robot, arm, joints, current, start, position, orientation) == 0.0:
                return stepped
        own = _on_branch(robot, arm, joints, position, orientation, REACHING)  # every answer strayed: the arm's own
        if own.success and strays(robot, arm, joints, own.joint_positions, start, position, orientation) == 0.0:
            return own
    return IKSolution(False, solution.joint_positions, off, solution.orientation_error)


def strays(robot: Robot, arm: str, start: Mapping[str, float], end: Mapping[str, float], line_start: Sequence[float],
           line_end: Sequence[float], orientation: Sequence[float] | None) -> float:
    """How far (m) the tool strays beyond LINE_SLACK from the straight line between two positions (holding
    `orientation`, when given) as the arm moves from `start` to `end` straight in joint space (continuous joints the
    short way); 0 when it keeps to the line. It moves the arm's joints: call it inside `joints_kept`."""
    body = robot.body
    tool = robot.description.arm(arm).tool_frame
    names = list(end)
    a = np.array([float(start.get(n, end[n])) for n in names])
    b = motion.short_way(body, names, a, np.array([float(end[n]) for n in names]))
    p0, p1 = np.asarray(line_start, dtype=float), np.asarray(line_end, dtype=float)
    span = p1 - p0
    length2 = float(span @ span)
    worst = 0.0
    for k in range(1, LINE_SAMPLES + 1):
        values = a + (b - a) * k / (LINE_SAMPLES + 1)
        body.reset_joints(dict(zip(names, (float(v) for v in values))))
        where, turned = body.get_link_position_and_orientation(tool)
        p = np.asarray(where)
        t = 0.0 if length2 == 0.0 else min(1.0, max(0.0, float((p - p0) @ span) / length2))
        off = float(np.linalg.norm(p - (p0 + t * span)))
        if off > LINE_SLACK[0]:
            worst = max(worst, off)
        elif orientation is not None and angle_between(turned, orientation) > LINE_SLACK[1]:
            worst = max(worst, LINE_SLACK[0])
    return worst


def solve_tool(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None,
               what: str, near: bool = False, start: Mapping[str, float] | None = None) -> IKSolution:
    """Joint values that bring the arm's tool frame to a pose, or raise ReachabilityFailure saying how far off it stays.
    `near`: prefer a solution near the arm's configuration (`reach_near`); `start`: solved from that configuration
    (`reach_from`, for a short straight move from it)."""
    if start is not None:
        solution = reach_from(robot, arm, start, position, orientation)
    elif near:
        solution = reach_near(robot, arm, position, orientation)
    else:
        solution = reach(robot, arm, position, orientation)
    if not solution.success:
        angle = ("" if solution.orientation_error is None
                 else f", {math.degrees(solution.orientation_error):.0f}° off in orientation")
        raise ReachabilityFailure(
            f"{arm_words(arm)} cannot reach {what}: the tool frame stays {solution.position_error * 100:.1f} cm away{angle}",
            arm=arm, position_error=solution.position_error)
    return solution


#: after letting go, the tool backs off along its approach this far, or, when the arm cannot, the shorter of these (m)
BACK_OFF = (0.08, 0.05, 0.03)


def back_off(robot: Robot, arm: str, what: str) -> float:
    """Back the (open) tool straight out along its approach after letting go of something: `BACK_OFF[0]`, or the
    longest of the shorter distances the arm reaches and the way to which is free. The distance backed off (0 when
    none: the hand stays where it let go, and the next motion starts from there)."""
    tool_frame = robot.description.arm(arm).tool_frame
    position, orientation = robot.body.get_link_position_and_orientation(tool_frame)
    approach = quat_to_matrix(orientation) @ tool_axes(robot, arm)[:, 0]
    for distance in BACK_OFF:
        target = tuple(float(v) for v in np.asarray(position) - approach * distance)
        solution = reach(robot, arm, target, orientation, best_effort=False)  # only whether
        if not solution.success:
            continue
        try:
            motion.move(robot, solution.joint_positions, f"the {arm_words(arm)}'s retreat from {what}")
        except ManipulationFailure:
            continue
        return distance
    return 0.0


#: the named poses an arm rests in (when its description has them): holding something, and empty
PARK, CARRY = "park", "carry"


def rest_pose(robot: Robot, arm: str, holding: bool | None = None) -> str | None:
    """The pose an arm rests in: `carry` when it holds something (or will: `holding`) and has one, else `park` (None:
    it has neither)."""
    poses = robot.description.arm(arm).poses
    full = bool(robot.held_objects(arm)) if holding is None else holding
    if full and CARRY in poses:
        return CARRY
    return PARK if PARK in poses else None


#: an arm that holds something and has no carry pose carries it as it was grasped: its tool where the park pose
#: puts it, raised by the first of these that the arm reaches (m), turned as it holds the object now
CARRY_RAISE = (0.1, 0.0, 0.2)


def rest_configuration(robot: Robot, arm: str, holding: bool | None = None) -> dict[str, float] | None:
    """The joint values an arm rests in (`rest_pose`'s, None when it has none). An arm that holds something (or will:
    `holding`) and has no `carry` pose keeps it as it was grasped — a milk carton taken from the front stays upright —
    its tool where `park` puts it (raised a little) and turned relative to the base as it is now; when the arm
    cannot hold it so, it parks."""
    pose = rest_pose(robot, arm, holding)
    if pose is None:
        return None
    config = arm_configuration(robot, arm, pose)
    full = bool(robot.held_objects(arm)) if holding is None else holding
    if pose != PARK or not full:
        return config
    body, tool = robot.body, robot.description.arm(arm).tool_frame
    turned = quat_multiply(quat_inverse(body.get_orientation()), body.get_link_orientation(tool))
    with body.joints_kept(list(config)):
        body.reset_joints(config)
        parked = body.get_link_position(tool)
    orientation = quat_multiply(body.get_orientation(), turned)
    for raise_ in CARRY_RAISE:
        target = (parked[0], parked[1], parked[2] + raise_)
        solution = reach(robot, arm, target, orientation, best_effort=False)
        if solution.success and _far_from(solution.joint_positions, config):
            # the winner lies on another branch (an arm turned over, its elbow through what stands in front): park's own
            own = _on_branch(robot, arm, config, target, orientation, REACHING_VERDICT)
            solution = own if own.success and not _far_from(own.joint_positions, config) else solution
        if solution.success:
            return {name: solution.joint_positions[name] for name in config}
    return config


def _on_branch(robot: Robot, arm: str, joints: Mapping[str, float], position: Sequence[float],
               orientation: Sequence[float] | None, settings: Settings) -> IKSolution:
    """The solution searched from the configuration `joints` alone (the joints put back). IK's seeds race and the
    first to converge wins, which may come from another branch although `joints` leads there too, a little slower:
    for a short move from `joints`, or a pose near it, this is the one on its branch."""
    body = robot.body
    with body.joints_kept(list(joints)):
        body.reset_joints(joints)
        return solve(robot, arm, position, orientation, settings=replace(settings, seeds=1))


def _far_from(joints: Mapping[str, float], config: Mapping[str, float]) -> bool:
    """Whether some joint of `joints` is more than FAR (rad, or m) from its value in `config`."""
    return any(abs(joints[name] - value) > FAR for name, value in config.items() if name in joints)


def set_gripper(robot: Robot, arm: str, opening: str) -> None:
    """Open the gripper fully (the fingers' path checked), or close it until the fingers touch something."""
    gripper = robot.description.arm(arm).gripper
    if not gripper.joints:
        return
    if opening == "open":
        motion.move(robot, gripper_values(robot, arm, "open"), f"opening the {gripper_words(arm)}")
    else:
        close_on(robot, arm)


def close_on(robot: Robot, arm: str) -> float:
    """Close the arm's gripper until its fingers touch something (never inside it), every joint by its coupling (so
    that the joints of a curling finger close together); the first joint's value reached."""
    gripper = robot.description.arm(arm).gripper
    motion.advance(robot, gripper_values(robot, arm, "closed"))
    return robot.body.get_joint_position(gripper.joints[0])


def arm_configuration(robot: Robot, arm: str, config: Any) -> dict[str, float]:
    """Joint values by name for a named pose, a list in joint order, or a mapping."""
    desc = robot.description.arm(arm)
    if isinstance(config, str):
        if config not in desc.poses:
            hint = did_you_mean(config, desc.poses)
            raise ManipulationFailure(f"{arm_words(arm)} has no pose '{config}'" + (f" ({hint})" if hint else "")
                                      + f"; poses: {', '.join(desc.poses)}")
        values: Sequence[float] = desc.poses[config]
        return dict(zip(desc.joints, values))
    if isinstance(config, Mapping):
        unknown = [j for j in config if j not in desc.joints]
        if unknown:
            hint = did_you_mean(unknown[0], desc.joints)
            raise ManipulationFailure(f"'{unknown[0]}' is not a joint of the {arm_words(arm)}" + (f" ({hint})" if hint else ""))
        return {str(k): float(v) for k, v in config.items()}
    if len(config) != len(desc.joints):
        raise ManipulationFailure(f"{arm_words(arm)} has {len(desc.joints)} joints ({', '.join(desc.joints)}), "
                                  f"got {len(config)} values")
    return dict(zip(desc.joints, (float(v) for v in config)))


def arm_configs(slots: Mapping[str, Any]) -> dict[str, Any]:
    """Configuration by arm name from `arms: {arm: config}` and the design's `<arm>-arm: config` slots."""
    configs: dict[str, Any] = dict(slots.get("arms") or {})
    for key, config in slots.items():
        if key.endswith("-arm") and config is not None:
            configs[key[: -len("-arm")]] = config
    return configs
