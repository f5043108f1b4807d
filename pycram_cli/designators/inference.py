"""What resolution infers for several designators: the object a slot names, and an arm and grasp that work."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from ..errors import InputError, Location, did_you_mean
from ..failures import GripperFailure, ReachabilityFailure
from ..kinds import arm_phrase
from ..planning.reach import reach
from ..robots import Robot
from ..world import BulletWorld, Object


def object_in(world: BulletWorld, value: Any, slot: str) -> Object:
    """The object of `world` a slot names (or holds); an unknown name is an input error naming the slot."""
    if isinstance(value, Object):
        return value
    found = world.get_object_by_name(str(value))
    if found is None:
        names = [o.name for o in world.objects]
        raise InputError(f"no object '{value}'", Location(f"slot {slot}"), key=slot,
                         suggestion=did_you_mean(str(value), names))
    return found


def the_object(robot: Robot, value: Any, slot: str) -> Object:
    """The object a slot names (or holds), in the robot's world."""
    return object_in(robot.world, value, slot)


def free_arms(robot: Robot, preferred: str | None) -> list[str]:
    """The arm asked for, or every arm whose gripper holds nothing (in the description's order)."""
    arms = [preferred] if preferred else list(robot.description.arms)
    return [a for a in arms if preferred or not robot.held_objects(a)]


Pose = tuple[Sequence[float], Sequence[float]]


def choose_arm_and_grasp(robot: Robot, pose_of: Callable[[str, Any], Pose | None], arm: str | None,
                         grasp: Any, what: str) -> tuple[str, Any]:
    """The first arm and grasp (both in the description's order) that can hold it and whose IK succeeds.

    `pose_of(arm, grasp)` gives the tool pose (position, orientation) for a grasp, or None when that arm cannot hold
    it that way.
    """
    grasps = [grasp] if grasp is not None else list(robot.description.grasps)
    best: tuple[float, str, Any] | None = None
    holdable = False
    for candidate_arm in free_arms(robot, arm):
        for candidate in grasps:
            pose = pose_of(candidate_arm, candidate)
            if pose is None:
                continue
            holdable = True
            solution = reach(robot, candidate_arm, pose[0], pose[1])
            if solution.success:
                return candidate_arm, candidate
            if best is None or solution.position_error < best[0]:
                best = (solution.position_error, candidate_arm, candidate)
    if best is None:
        if not free_arms(robot, arm):
            raise GripperFailure(f"no free gripper to take {what}: every gripper holds something")
        if not holdable:
            with_grasp = f"a {grasp} grasp" if isinstance(grasp, str) else "any grasp"
            raise GripperFailure(f"no gripper can hold {what} with {with_grasp} (too wide between the fingers)")
        raise ReachabilityFailure(f"no arm can reach {what}")
    grasp_text = f" with a {best[2]} grasp" if isinstance(best[2], str) else ""
    raise ReachabilityFailure(f"no arm can reach {what}: best is {arm_phrase(best[1])}{grasp_text}, "
                              f"{best[0] * 100:.1f} cm away", position_error=best[0])
