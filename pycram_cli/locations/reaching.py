"""The arm tests of a base pose: whether, from where the robot stands, an arm takes, places, pulls or reaches.

These are the expensive tests (inverse kinematics, contact queries, collision-free ways), run on the few candidates
the cheap ones let through. Each asks the planning the action itself will use (`plan_grasp`, `plan_place`,
accessing's `takes_handle`, `move_over`), so a pose that passes is one from which the action succeeds; a pose that
fails says why (`Miss`: out of reach, blocked by what, cannot hold it), which the resolution counts.
"""
from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..kinds import arm_phrase, arm_words
from ..planning.paths import move_over
from ..planning.pick_place import grasp_orientation, plan_grasp, plan_place
from ..planning.reach import back_off, reach, rest_configuration, rest_pose, set_gripper
from ..robots import Robot
from ..world import Object
from .accessing import takes_handle
from .spec import LocationSpec
from .touching import let_go_for_now, touching

#: how hard the ways of an arm and grasp are tried (`move_over`'s options), cheapest first: every arm and grasp is
#: tried straight before any goes around what is in the way, and that before any joint-space search
STRAIGHT = {"around": False, "search": False}
AROUND = {"around": True, "search": False}
SEARCH = {"around": True, "search": True}


@dataclass(frozen=True)
class Miss:
    """Why no arm passed at a pose: a reason of `candidates.REASONS` and its detail (what blocked it)."""

    reason: str
    detail: str = ""
    #: whether a joint-space search for the arm's way (not made: `ArmTests.searching` was off) might have passed it
    unsearched: bool = False


def _missed(blocked: list[str], holdable: bool, target: Any, unsearched: bool = False) -> Miss:
    """Blocked when something was in the way, else cannot hold (an object no grasp fits), else out of reach."""
    if blocked:
        return Miss("blocked", ", ".join(blocked), unsearched)
    if not holdable and isinstance(target, Object):
        return Miss("cannot hold", target.name, unsearched)
    return Miss("out of reach", "", unsearched)


class ArmTests:
    """The arm tests of one location's base poses (the robot already standing at the pose to test).

    It remembers what the last test found, for `take_here`'s answer: `taken` (the grasp's IK solution of the arm
    and grasp that take the object), `attempts` (what each arm and grasp ran into) and `shortfall` (how far the
    tool stayed from the nearest grasp out of reach, m)."""

    def __init__(self, robot: Robot, spec: LocationSpec, held: list[Object],
                 allowed: tuple[set[int], set[tuple[int, str]]], handle_path: Sequence[np.ndarray]) -> None:
        self.robot, self.spec, self.held = robot, spec, held
        self.allowed = allowed
        self.handle_path = handle_path
        self.attempts: list[tuple[str, Any, str]] = []
        self.taken: Any = None
        self.shortfall = math.inf
        #: whether the tests may search the arm's joint space for a way (`move_over`'s last resort: about 0.4 s when
        #: no way exists); a test that failed only for want of one says so (`Miss.unsearched`)
        self.searching = True

    def reach(self, arms: list[str]) -> tuple[str, Any] | Miss:
        """The first arm and grasp (arms in the order given, grasps in the description's order) that reach untouched."""
        robot, spec = self.robot, self.spec
        blocked: list[str] = []
        holdable = unsearched = False
        target = spec.reachable_for
        if isinstance(target, Object) and spec.placing is None and spec.accessing is None:
            return self._grasp(arms, target)
        if spec.placing is not None:
            return self._place(arms, spec.placing, target)
        for arm in arms:
            for grasp, position, orientation in self._reach_targets():
                if position is None:
                    continue
                holdable = True
                solution = reach(robot, arm, position, orientation, best_effort=False)  # only whether
                if not solution.success:
                    continue
                if spec.accessing is not None:
                    takes = takes_handle(robot, spec, arm, search=self.searching)
                    if not takes:
                        unsearched |= takes is None
                        continue
                if self._touches_at(solution.joint_positions, blocked):
                    continue
                return arm, grasp
        return _missed(blocked, holdable, spec.reachable_for, unsearched)

    def _grasp(self, arms: list[str], obj: Object) -> tuple[str, Any] | Miss:
        """The first arm and grasp with which pick-up itself would take `obj` from here: the test is the pick-up
        process module's own planning (pre-grasp and grasp reached, the open gripper inside nothing), so a pose found
        here is one from which the pick-up succeeds; the arm at the grasp then touches nothing but the object and
        what it stands on. An arm and grasp whose ways are straight come before one whose ways must go around
        something (finding that a way round does not exist costs a search: about 0.4 s)."""
        robot, spec = self.robot, self.spec
        blocked: list[str] = []
        holdable = False
        viable: list[tuple[str, Any, Any, Any, dict[str, Any]]] = []
        grasps = [spec.grasp] if spec.grasp is not None else list(robot.description.grasps)
        attempts: dict[tuple[str, Any], str] = {}  # what each arm and grasp ran into (for take_here's failure)
        for arm in arms:
            for grasp in grasps:
                try:
                    _, pre, solution = plan_grasp(robot, arm, obj, grasp)
                except GripperFailure as failure:
                    attempts[arm, grasp] = str(failure)
                    continue
                except ManipulationFailure as failure:
                    holdable = True
                    blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                    attempts[arm, grasp] = str(failure)
                    continue
                except ReachabilityFailure as failure:
                    holdable = True
                    attempts[arm, grasp] = str(failure)
                    self.shortfall = min(self.shortfall, float(failure.details.get("position_error", math.inf)))
                    continue
                holdable = True
                touched: list[str] = []
                if self._touches_at(solution.joint_positions, touched):
                    blocked.extend(n for n in touched if n not in blocked)
                    attempts[arm, grasp] = f"{arm_phrase(arm)} at the grasp would touch {', '.join(touched)}"
                    continue
                legs: dict[str, Any] = {}
                if self._ways_free(obj, arm, pre, solution, STRAIGHT, blocked, legs):
                    self.taken = solution
                    return arm, grasp
                viable.append((arm, grasp, pre, solution, legs))  # its ways may go around what is in the way
        for tier in ((AROUND, SEARCH) if self.searching else (AROUND,)):
            for arm, grasp, pre, solution, legs in viable:
                if self._ways_free(obj, arm, pre, solution, tier, blocked, legs):
                    self.taken = solution
                    return arm, grasp
        for arm, grasp, _, _, legs in viable:
            why = legs.get("pre") if legs.get("pre") is not True else legs.get("rest")
            attempts[arm, grasp] = str(why) if why is not None else "its ways are blocked"
        self.attempts = [(arm, grasp, attempts[arm, grasp]) for arm in arms for grasp in grasps
                         if (arm, grasp) in attempts]
        return _missed(blocked, holdable, obj, bool(viable) and not self.searching)

    def _touches_at(self, joints: Mapping[str, float], blocked: list[str]) -> bool:
        """Whether the arm at these joint values touches anything but what it may (the target, its support), what
        it touches added to `blocked`; the joints are put back."""
        body = self.robot.body
        saved = body.get_joint_positions(list(joints))
        body.set_joint_positions(joints)
        try:
            touched = touching(self.robot, self.held, *self.allowed, joints)
        finally:
            body.set_joint_positions(saved)
        blocked.extend(t for t in touched if t not in blocked)
        return bool(touched)

    def _ways_free(self, obj: Object, arm: str, pre: Any, solution: Any, tier: dict[str, bool],
                   blocked: list[str], legs: dict[str, Any]) -> bool:
        """Whether the arm's ways are free as pick-up will move it: from where it is to the pre-grasp pose, and from
        the grasp to the pose it will rest in holding the object (the object itself not counted), tried as `tier`
        says (`STRAIGHT`, `AROUND`, `SEARCH`: see `move_over`). What they would hit is added to `blocked`. `legs`
        remembers, across the tiers of one arm and grasp, which way was found free and which way's straight path
        is not (a dearer tier need not walk them again)."""
        robot = self.robot
        body = robot.body
        rest = rest_pose(robot, arm, holding=True)
        with body.joints_kept(list(pre.joint_positions)):
            try:
                if legs.get("pre") is not True:
                    move_over(robot, arm, pre.joint_positions, f"the {arm_words(arm)}'s motion to the pre-grasp pose",
                              straight=legs.get("pre"), around=tier["around"], search=tier["search"])
                    legs["pre"] = True
                if rest is not None and legs.get("rest") is not True:
                    body.reset_joints(solution.joint_positions)  # holding it as grasped: the way to rest holding it so
                    move_over(robot, arm, rest_configuration(robot, arm, holding=True) or {},
                              f"the {arm_words(arm)}'s motion to its {rest} pose", down_onto_goal=False, ignore=[obj],
                              straight=legs.get("rest"), around=tier["around"],
                              search=tier["search"])
                    legs["rest"] = True
            except ManipulationFailure as failure:  # move_over raises its straight path's failure
                legs["pre" if legs.get("pre") is not True else "rest"] = failure
                blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                return False
        return True

    def _place(self, arms: list[str], obj: Object, target: Any) -> tuple[str, Any] | Miss:
        """The arm with which place itself would put `obj` down at `target` from here (the place process module's own
        planning), the arm there touching nothing but the surface."""
        robot = self.robot
        body = robot.body
        blocked: list[str] = []
        unsearched = False
        for arm in arms:
            try:
                _, _, solution, above, _ = plan_place(robot, arm, obj, tuple(float(v) for v in target))
            except (ManipulationFailure, ReachabilityFailure):
                continue
            saved = body.get_joint_positions(list(solution.joint_positions))
            body.set_joint_positions(solution.joint_positions)
            body.move_attached()
            try:
                touched = touching(robot, self.held, *self.allowed, solution.joint_positions)
            finally:
                body.set_joint_positions(saved)
                body.move_attached()
            if touched:
                blocked.extend(t for t in touched if t not in blocked)
                continue
            # and the arm's way, with what it holds, from where it is to above the place, as place will move it
            free = True
            with body.joints_kept(list(above.joint_positions)):
                try:
                    move_over(robot, arm, above.joint_positions, f"the {arm_words(arm)}'s motion above the place",
                              search=self.searching)
                except ManipulationFailure as failure:
                    blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                    free = False
            body.move_attached()  # what it holds back with the arm (joints_kept puts only the joints back)
            if free and self._way_back_free(arm, obj, solution.joint_positions, blocked):
                return arm, None
            unsearched |= not self.searching
        return Miss("blocked", ", ".join(blocked), unsearched) if blocked else Miss("out of reach", "", unsearched)

    def _way_back_free(self, arm: str, obj: Object, placed: Mapping[str, float], blocked: list[str]) -> bool:
        """Whether the arm, having let `obj` go at the place (`placed`: its joint values there), gets back to the pose
        it rests in empty, as place and the park after it move it: the gripper opens, the hand backs off along its
        approach as far as the arm reaches (`back_off`; an elbow folded to its limit may not), and from there a way
        leads to rest; the object, where it was let go, is in the way only while the hand has not backed off it (an
        arm that cannot get away from the object or what stands around the place would be stuck there). What is in
        the way is added to `blocked`."""
        robot = self.robot
        body = robot.body
        rest = rest_configuration(robot, arm, holding=False)
        if rest is None:
            return True
        gripper = list(robot.description.arm(arm).gripper.joints)
        with body.joints_kept([*placed, *gripper]):
            body.reset_joints(placed)
            body.move_attached()  # the object where place lets it go
            free = True
            with let_go_for_now(obj):
                try:
                    set_gripper(robot, arm, "open")
                    backed = back_off(robot, arm, obj.name)
                    move_over(robot, arm, rest, f"the {arm_words(arm)}'s way back from the place", down_onto_goal=False,
                              ignore=[obj] if backed else [], search=self.searching)
                except ManipulationFailure as failure:
                    blocked.extend(n for n in failure.details.get("colliding", []) if n not in blocked)
                    free = False
        body.move_attached()  # what it holds back with the arm, either way
        return free

    def _reach_targets(self) -> Iterator[tuple[Any, Any, Any]]:
        """(grasp, tool position or None when the gripper cannot hold it so, tool orientation) to try, in order."""
        robot, spec = self.robot, self.spec
        target = spec.reachable_for
        if spec.accessing is not None:
            pull = next(iter(robot.description.grasps), None)
            yield pull, tuple(self.handle_path[0]), grasp_orientation(robot, pull) if pull is not None else None
            return
        grasps = [spec.grasp] if spec.grasp is not None else list(robot.description.grasps)
        for grasp in grasps:  # a position (an object is tested by `_grasp`)
            orientation = grasp_orientation(robot, grasp) if grasp is not None else None
            yield grasp, tuple(target), orientation  # type: ignore[arg-type]
            if spec.grasp is None:
                return  # a position in any orientation: one IK call answers for every grasp
