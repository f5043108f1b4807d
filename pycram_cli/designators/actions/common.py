"""What several actions share: objects by name, resting poses of the arms, standing somewhere, trying choices."""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

from ...errors import InputError
from ...failures import Failure, LocationFailure, NavigationFailure
from ...kinds import KINDS, Robots, location_goals
from ...planning.reach import CARRY, PARK, rest_configuration, rest_pose  # noqa: F401 (re-exported to the actions)
from ...robots import Robot
from ...signature import Problem
from ...world import Object
from ..inference import object_in
from .actor import Actor, Finder, as_failure

#: how many poses (or spots) an action tries before it gives up
CHOICES = 3
#: the arm poses actions rest the arms in (robot descriptions name them): an empty arm parks, a full one carries


def object_of(actor: Actor, value: Any, slot: str) -> Object:
    """The object a slot names (or holds); an unknown name fails the action, naming it."""
    try:
        return object_in(actor.world, value, slot)
    except InputError as exc:
        raise as_failure(exc, slot) from None


def rest_of(robot: Robot, arm: str, holding: bool | None = None) -> str | list[float] | None:
    """What an arm rests in, as move-arm-joints takes it: its pose's name, or joint values when it carries something
    as it was grasped (`rest_configuration`); None when it has no resting pose."""
    pose = rest_pose(robot, arm, holding)
    config = rest_configuration(robot, arm, holding)
    if pose is None or config is None:
        return None
    desc = robot.description.arm(arm)
    if all(abs(_wrap(config[j] - v)) < 1e-9 for j, v in zip(desc.joints, desc.poses[pose])):
        return pose
    return [round(config[j], 6) for j in desc.joints]


def resting(robot: Robot, arms: list[str] | None = None) -> dict[str, str | list[float]]:
    """The resting pose of each arm (given, or every arm) that is not in it already."""
    moves: dict[str, str | list[float]] = {}
    for arm in arms if arms is not None else list(robot.description.arms):
        rest = rest_of(robot, arm)
        if rest is None:
            continue
        desc = robot.description.arm(arm)
        target = dict(zip(desc.joints, desc.poses[rest] if isinstance(rest, str) else rest))
        current = robot.body.get_joint_positions(list(target))
        if any(abs(_wrap(current[j] - v)) > 1e-3 for j, v in target.items()):
            moves[arm] = rest
    return moves


def _wrap(angle: float) -> float:
    return math.atan2(math.sin(angle), math.cos(angle))


def stands_at(robot: Robot, pose: Any) -> bool:
    """Whether the base already stands at a base pose (then there is nowhere to drive)."""
    x, y, _ = robot.body.get_position()
    here_yaw = _yaw(robot.body.get_orientation())
    return math.hypot(x - pose.position[0], y - pose.position[1]) < 1e-6 and abs(_wrap(here_yaw - pose.yaw)) < 1e-6


def _yaw(q: Any) -> float:
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def go(actor: Actor, pose: Any) -> None:
    """Drive to a base pose (`moving`), unless the robot stands there already; then raise or lower the torso to the
    height the pose was found with, when it says one (an arm that reaches the object only with the torso moved). The
    pose was found free with the torso at that height: when the robot cannot stand there with its torso where it is
    (its arm, lower or higher, against an open drawer's handle), the torso moves first, then the base."""
    torso, joint = getattr(pose, "torso", None), actor.robot.description.torso_joint
    to_move = torso is not None and joint is not None and \
        abs(actor.robot.body.get_joint_positions([joint])[joint] - torso) > 1e-6
    if not stands_at(actor.robot, pose):
        target = {"target": list(pose.position), "orientation": list(pose.orientation)}
        try:
            actor.motion("moving", target)
        except NavigationFailure:
            if not to_move:
                raise
            actor.motion("moving-torso", {"position": torso})
            actor.motion("moving", target)
            return
    if to_move:
        actor.motion("moving-torso", {"position": torso})


def try_choices(actor: Actor, finder: Finder, attempt: Callable[[Actor, Any], Any], what: str,
                retry_on: tuple[type[Failure], ...] = (Failure,), past_locations: bool = False) -> Any:
    """CPL-style: the next pose of a location, then `attempt(actor, pose)` in a child of its own; when it fails,
    the next pose, up to `CHOICES`. No pose left: the location's failure; all tried: the last failure. An attempt's
    own LocationFailure ends the choosing (what is in the way is the plan's to handle), unless `past_locations`:
    then it is one more choice that failed (a spot no place to stand reaches: the next spot)."""
    failures: list[Failure] = []
    for number in range(1, CHOICES + 1):
        try:
            choice = actor.locate(finder)
        except LocationFailure as exc:
            if not failures:
                raise
            raise _gave_up(what, failures, exc) from exc
        def run(child: Actor, chosen: Any = choice) -> Any:
            return attempt(child, chosen)

        try:
            return actor.attempt(number, run)
        except Failure as exc:
            if (isinstance(exc, LocationFailure) and not past_locations) or not isinstance(exc, retry_on):
                raise
            failures.append(exc)
    raise _gave_up(what, failures, None)


def _gave_up(what: str, failures: list[Failure], last: LocationFailure | None) -> Failure:
    tail = failures[-1]
    more = f"; {last.message}" if last is not None else f" ({len(failures)} choices tried)"
    error = type(tail)(f"{what}: {tail.message}{more}", **tail.details)
    error.failures = failures
    return error


# -- static checks of location slots ---------------------------------------------------------------------


def location_slot(slot: str, goals: tuple[str, ...], what: str) -> Callable[[Mapping[str, Any], Robots], list[Problem]]:
    """A check that a location slot asks for one of `goals` (e.g. a spot `on` a surface, not a base pose)."""
    def check(slots: Mapping[str, Any], robots: Robots) -> list[Problem]:
        value = slots.get(slot)
        if not isinstance(value, Mapping) or KINDS["location"].check(value, Robots()):
            return []
        if not any(goal in goals for goal in location_goals(value)):
            return [Problem(f"slot '{slot}': {what} (got {', '.join(location_goals(value))})", slot)]
        return []

    return check
