"""Accessing, planned: grasp a drawer handle and pull the drawer open, the gripper following the handle.

The handle is grasped like an object (`grasps.py`), from its link's box: the tool approaches
the way the description's first grasp points (the one `accessing` pulls handles with), the
fingers close across the handle's thin side (a bar along y is taken across its height). The
tool comes in from `APPROACH` back until it touches, the fingers close until they touch the
handle, and the drawer is pulled in steps, the arm following the handle; every arm motion is
collision-checked (`motion.py`). What rests in the drawer rides along.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from ..failures import GripperFailure, ManipulationFailure
from ..kinds import gripper_words
from ..reasoning.ik import IKSolution, beyond_reach
from ..robots import Robot
from ..signature import Param
from ..world import Object
from ..world.pose import Quat, Vec3, compose, invert
from ..world.riders import carrying
from . import motion
from .grasps import Grasp, grasps_of_box, holdable
from .reach import REACHING_VERDICT, reach, solve_tool

#: how far accessing opens a drawer or door: the `accessing` designator's `distance` slot (the `open` action's, with its
#: own kind and wording); a location `{accessing: HANDLE}` names no distance and plans for this default
DISTANCE = Param("distance", "number", doc="how far to open, in metres", default=0.3,
                 default_doc="0.3, or the joint's upper limit if smaller")
#: how many steps the drawer is pulled in (the arm's path between two is checked)
STEPS = 6
#: the pre-grasp pose is this far back along the approach (m)
APPROACH = 0.10


def contents_of(part: Object, link: int) -> list[Object]:
    """Free objects resting on (touching, above) a link of `part` — they ride along when it moves."""
    link_top = part.get_aabb(link)[0][2]
    inside = []
    for obj in part.world.objects:
        if obj is part or obj.fixed or obj.attachments:
            continue
        points = part.world.closest_points(part, obj, 0.005, link_a=link)
        if points and obj.get_aabb()[0][2] >= link_top - 0.005:
            inside.append(obj)
    return inside


def handle_grasp(robot: Robot, arm: str, part: Object, handle: str) -> Grasp | None:
    """How the arm holds a handle (a link of `part`) with the description's first grasp, or None if it cannot."""
    pull = next(iter(robot.description.grasps), None)
    if pull is None:
        return None
    lo, hi = (np.asarray(v, dtype=float) for v in part.get_link_local_aabb(handle))
    pose = part.get_link_position_and_orientation(handle)
    return next((g for g in grasps_of_box(robot, arm, pose, lo, hi, pull) if holdable(robot, arm, g) is None), None)


def handle_pose(robot: Robot, arm: str, part: Object, handle: str) -> tuple[Vec3, Quat] | None:
    grasp = handle_grasp(robot, arm, part, handle)
    return None if grasp is None else (grasp.position, grasp.orientation)


def plan_handle_grasp(robot: Robot, arm: str, part: Object, handle: str,
                      grasp: Grasp | None = None) -> tuple[Grasp, IKSolution, IKSolution]:
    """How accessing takes the handle from where the robot stands: the grasp (`handle_grasp`'s, unless the caller
    has it already), and the arm's configurations at the pre-grasp pose (APPROACH back, near the arm's
    configuration) and at the handle. GripperFailure when the gripper cannot hold it, ReachabilityFailure when the
    arm reaches either pose not (the location test asks this too)."""
    grasp = grasp or handle_grasp(robot, arm, part, handle)
    if grasp is None:
        raise GripperFailure(f"the {gripper_words(arm)} cannot hold the handle {handle}", arm=arm)
    what = f"the handle {handle}"
    pre = solve_tool(robot, arm, _offset(grasp.position, grasp.approach, -(grasp.depth + APPROACH)), grasp.orientation,
                     f"the pre-grasp pose for {what}", near=True)
    at = solve_tool(robot, arm, grasp.position, grasp.orientation, what, start=pre.joint_positions)
    return grasp, pre, at


def pull_values(start: float, goal: float) -> list[float]:
    """The joint values accessing pulls (or pushes) the drawer through, one per step, the last one `goal`."""
    return [start + (goal - start) * k / STEPS for k in range(1, STEPS + 1)]


def held_pose(robot: Robot, arm: str, part: Object, handle: str) -> tuple[Vec3, Quat]:
    """The arm's tool frame in the handle's frame, as the arm stands now: the hand keeps it as the drawer moves."""
    tool_frame = robot.description.arm(arm).tool_frame
    return compose(invert(part.get_link_position_and_orientation(handle)),
                   robot.body.get_link_position_and_orientation(tool_frame))


def follows_handle(robot: Robot, arm: str, part: Object, handle: str, joint: str, goal: float,
                   at: IKSolution) -> dict[str, float] | None:
    """Whether the arm, holding the handle at `at` (from `plan_handle_grasp`), follows it to `goal` as accessing pulls
    it: every step's tool pose (the hand keeping its hold, `held_pose`) reached from the step before, the arm's way
    there free (the drawer's moving links not counted, as the pull counts them not), and the drawer then inside no
    part of the robot but the hand. Accessing's own plan of the pull, tried without moving: the
    location test asks this, so that a pose it finds is one the pull succeeds from. Joints are put back; the arm's
    joint values at the end of the pull, or None when it does not follow."""
    body = robot.body
    names = list(robot.description.arm(arm).joints)
    index = part.joint(joint).index
    moving = [(part, link) for link in range(len(part.joints)) if part.hangs_below(link, index)]
    hand = motion.Motion(robot, robot.description.arm(arm).joints[-1:]).links
    with part.joints_kept([joint]), body.joints_kept(names):
        body.reset_joints(at.joint_positions)
        tools = pull_tools(part, handle, joint, goal, held_pose(robot, arm, part, handle))
        if beyond_reach(robot, arm, [tool for _, tool in tools], REACHING_VERDICT) is not None:
            return None  # a step the walk would fail at: the drawer pushed (or pulled) out of the arm's reach
        with carrying(part, index, contents_of(part, index)) as follow:  # what the drawer holds rides along
            return _follows(robot, arm, part, joint, tools, moving, hand, follow)


def _follows(robot: Robot, arm: str, part: Object, joint: str, tools: list[tuple[float, tuple[Vec3, Quat]]],
             moving: list[tuple[Object, int]], hand: list[int], follow: Callable[[], None]) -> dict[str, float] | None:
    """`follows_handle`'s walk along the pull's steps (`tools`), what the drawer holds following it (`follow`)."""
    body = robot.body
    names = list(robot.description.arm(arm).joints)
    for value, tool in tools:
        part.reset_joints({joint: value})
        follow()
        solution = reach(robot, arm, tool[0], tool[1], best_effort=False)  # only whether (and the joints then)
        if not solution.success or motion.hits_on_way(robot, solution.joint_positions, ignore_links=moving):
            return None
        body.reset_joints(solution.joint_positions)
        try:
            drawer_pushes_into(robot, part, moving, hand)
        except ManipulationFailure:
            return None
    return body.get_joint_positions(names)


def pull_tools(part: Object, handle: str, joint: str, goal: float,
               held: tuple[Vec3, Quat]) -> list[tuple[float, tuple[Vec3, Quat]]]:
    """Each step's joint value and the tool pose there (the hand keeping `held`, its pose in the handle's frame), as
    accessing pulls the handle to `goal`; the joint is put back."""
    tools = []
    with part.joints_kept([joint]):
        for value in pull_values(part.get_joint_position(joint), goal):
            part.reset_joints({joint: value})
            tools.append((value, compose(part.get_link_position_and_orientation(handle), held)))
    return tools


#: the reach bound of a pull planned from the grasp pose, before the arm is solved for it: the hand holds the handle
#: within REACH and REACH_ANGLE of that pose, and the hand's pose in the handle's frame moves rigidly with it, so a
#: step beyond the bound by twice the thresholds is beyond it whatever the hand's solution
LOOSE_VERDICT = replace(REACHING_VERDICT, threshold=2 * REACHING_VERDICT.threshold,
                        angle_threshold=2 * REACHING_VERDICT.angle_threshold)


def pull_beyond_reach(robot: Robot, arm: str, part: Object, handle: str, joint: str, goal: float,
                      grasp: Grasp) -> bool:
    """Whether the pull to `goal`, the hand holding the handle at `grasp`, takes it out of the arm's reach by the
    distance bound whatever the arm's solution at the grasp (`LOOSE_VERDICT`): `follows_handle` would then fail, and
    the grasp's inverse kinematics need not be solved to know it."""
    held = compose(invert(part.get_link_position_and_orientation(handle)), (grasp.position, grasp.orientation))
    tools = pull_tools(part, handle, joint, goal, held)
    return beyond_reach(robot, arm, [tool for _, tool in tools], LOOSE_VERDICT) is not None


def _offset(position: Sequence[float], direction: np.ndarray, distance: float) -> Vec3:
    p = np.asarray(position, dtype=float) + direction * distance
    return (float(p[0]), float(p[1]), float(p[2]))


def drawer_pushes_into(robot: Robot, part: Object, moving: list[tuple[Object, int]], hand: list[int]) -> None:
    """The drawer's moving links may touch the hand that pulls them, nothing else of the robot: ManipulationFailure
    naming the link the drawer would be inside (a robot standing too close opens the drawer into its own arm)."""
    links = {link for _, link in moving}
    for point in robot.world.closest_points(robot.body, part, 0.0):
        if point.link_b in links and point.link_a not in hand and point.distance < -motion.PENETRATION:
            raise ManipulationFailure(f"{part.get_link_name(point.link_b)} would be {-point.distance * 1000:.0f} mm "
                                      f"inside {robot.body.get_link_name(point.link_a)}",
                                      colliding=[part.name], link=part.get_link_name(point.link_b))
