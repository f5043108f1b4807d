"""An accessing location's drawer (or door): where its handle goes, the floor it opens into, whether an arm pulls it.

A pose for opening (or closing) something must do more than reach the handle: the robot must stand clear of the
drawer opened, and the arm holding the handle must follow it all the way. These tests read the location's handle
and distance (`LocationSpec.accessing`, `.distance`) and ask accessing's own planning (`planning/drawers.py`), so a
pose found here is one from which the accessing action succeeds.
"""
from __future__ import annotations

import numpy as np

from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..kinds import arm_words
from ..planning.drawers import DISTANCE, contents_of, follows_handle, handle_grasp, plan_handle_grasp, pull_beyond_reach
from ..planning.paths import move_over
from ..planning.reach import back_off, rest_configuration
from ..robots import Robot
from ..world import Object
from ..world.riders import carrying
from . import floor
from .spec import Handle, LocationSpec


def _handle(spec: LocationSpec) -> Handle:
    handle = spec.accessing
    assert handle is not None
    return handle


def goal(spec: LocationSpec, start: float) -> float:
    """Where the accessing process module takes the joint: `distance` above its lower limit (at most to its upper
    limit); the designator's default distance when the location names none."""
    handle = _handle(spec)
    joint = handle.obj.joint(handle.joint)
    distance = DISTANCE.default if spec.distance is None else spec.distance
    return min(joint.upper, joint.lower + distance) if joint.limited else start + distance


def handle_positions(spec: LocationSpec) -> list[np.ndarray]:
    """Where the handle is now and where accessing takes it (the location's distance; the drawer put back)."""
    handle = _handle(spec)
    obj = handle.obj
    start = obj.get_joint_position(handle.joint)
    end = goal(spec, start)
    positions = []
    with obj.joints_kept([handle.joint]):
        for value in (start, end):
            obj.reset_joints({handle.joint: value})
            positions.append(np.asarray(obj.get_link_position(handle.link)))
    return positions


def closing(spec: LocationSpec) -> bool:
    """Whether accessing pushes the handle towards the joint's lower limit (closes the drawer or door)."""
    handle = _handle(spec)
    start = handle.obj.get_joint_position(handle.joint)
    return goal(spec, start) < start


def opened_map(robot: Robot, spec: LocationSpec, held: list[Object]) -> floor.FloorMap:
    """The floor map with the drawer where accessing takes it (the drawer put back)."""
    handle = _handle(spec)
    obj = handle.obj
    with obj.joints_kept([handle.joint]):
        obj.reset_joints({handle.joint: goal(spec, obj.get_joint_position(handle.joint))})
        return floor.build(robot.body, held)


def opened_collisions(robot: Robot, spec: LocationSpec, held: list[Object], x: float, y: float,
                      yaw: float) -> list[str]:
    """What the robot's base pose (x, y, yaw) collides with once the drawer is where accessing takes it."""
    handle = _handle(spec)
    obj = handle.obj
    with obj.joints_kept([handle.joint]):
        obj.reset_joints({handle.joint: goal(spec, obj.get_joint_position(handle.joint))})
        return floor.exact_collisions(robot.body, held, x, y, yaw)


def takes_handle(robot: Robot, spec: LocationSpec, arm: str, search: bool = True) -> bool | None:
    """Accessing's own planning takes the handle from here and pulls it to the goal: its grasp (aligned with the handle's
    box, not turned with the base as the reach test's first IK) and its pre-grasp pose are reached, the arm holding
    the handle so follows it all the way, step by step (`follows_handle`: the drawer then inside no part of
    the robot but the hand, as a robot standing too close would open it into its own arm), the arm, its
    gripper open as accessing opens it, has a free way from where it is to the pre-grasp pose (`move_over`), and
    from the end of the pull, backed off the handle as accessing backs off, a free way to the pose it rests in (the
    open and close actions take it there next: an arm that pulled the drawer into its own way back would stay stuck
    at the handle). With `search` off, the way to the pre-grasp pose without `move_over`'s joint-space search: None
    when only that way is blocked, a search might find one."""
    handle = _handle(spec)
    obj = handle.obj
    gripper = robot.description.arm(arm).gripper
    names = list(robot.description.arm(arm).joints) + list(gripper.joints)
    with robot.body.joints_kept(names):
        try:
            robot.body.reset_joints({joint: gripper.open for joint in gripper.joints})
            end = goal(spec, obj.get_joint_position(handle.joint))
            grasp = handle_grasp(robot, arm, obj, handle.link)
            if grasp is not None and pull_beyond_reach(robot, arm, obj, handle.link, handle.joint, end, grasp):
                return False  # as `follows_handle` would find, without solving the grasp first
            _, pre, at = plan_handle_grasp(robot, arm, obj, handle.link, grasp)
            robot.body.reset_joints({joint: gripper.closed for joint in gripper.joints})  # holding the handle
            pulled = follows_handle(robot, arm, obj, handle.link, handle.joint, end, at)
            if pulled is None:
                return False
            robot.body.reset_joints({joint: gripper.open for joint in gripper.joints})
        except (GripperFailure, ReachabilityFailure, ManipulationFailure):
            return False
        try:
            move_over(robot, arm, pre.joint_positions, f"the {arm_words(arm)}'s motion to the handle", search=search)
        except ManipulationFailure:
            return None if not search else False
        try:
            _way_back(robot, spec, arm, end, pulled)
        except ManipulationFailure:
            return False
    return True


def _way_back(robot: Robot, spec: LocationSpec, arm: str, end: float, pulled: dict[str, float]) -> None:
    """The arm's way, as the open and close actions make it, from the end of the pull (`pulled`: its joint values
    there, the drawer at `end`, the gripper open) to the pose it rests in: backed off the handle (`back_off`), then
    `move_over`, its joint-space search included (an arm that has pulled the drawer has no other way than the one
    from where it holds the handle: a pose whose way back only a search finds is no worse than another);
    ManipulationFailure when it is blocked. The arm and the drawer are put back."""
    handle = _handle(spec)
    rest = rest_configuration(robot, arm, holding=False)
    if rest is None:
        return
    body, part = robot.body, handle.obj
    index = part.joint(handle.joint).index
    with (part.joints_kept([handle.joint]), body.joints_kept(list(pulled)),
          carrying(part, index, contents_of(part, index)) as follow):  # what the drawer holds, where it rides to
        part.reset_joints({handle.joint: end})
        follow()
        body.reset_joints(pulled)
        back_off(robot, arm, f"the handle {handle.link}")
        move_over(robot, arm, rest, f"the {arm_words(arm)}'s way back from the handle", down_onto_goal=False)
