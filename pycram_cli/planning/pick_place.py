"""Pick-up and place, with physics where it matters and every arm motion collision-checked (`motion.py`).

Pick-up: the grasp comes from the object's own frame (`grasps.py`); the gripper opens, the tool
goes to a pre-grasp pose `APPROACH` back along its approach, moves in until the fingers or the palm
touch something (never inside it: the object, the drawer's bottom), the fingers close until they
touch the object, the object is attached to the tool frame and lifted `LIFT` straight up. A hand whose
fingers curl towards its palm approaches palm-first, along the palm's normal, until the palm touches the
object, and curls every finger joint by its coupling until the fingers touch it (robots/tool.py `hand`).

Place: the object is stood upright (as held, turned about the vertical if the arm needs it) on the
surface under the target — its lowest point on the highest surface found below it, whatever its
mesh's origin — lowered onto it from `LIFT` above, let go; the tool backs off along its
approach, and physics settles the object (at most `SETTLE` seconds, less once it has come to
rest), so that what `stable` checks afterwards is the pose it really rests in.
"""
from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from ..failures import GripperFailure, ManipulationFailure, ReachabilityFailure
from ..kinds import arm_words, gripper_words
from ..reasoning.ik import IKSolution
from ..robots import Robot
from ..world import Object
from ..world.pose import Quat, Vec3, angle_between, compose, invert, quat_inverse, quat_multiply, quat_to_matrix, yaw_quaternion
from . import motion
from .grasps import Grasp, gripper_values, holdable_grasps, wanted_orientation
from .reach import close_on, near_solutions, reach_from, reach_near, set_gripper

#: the pre-grasp pose is this far back along the approach from where the tool enters the object's box (m)
APPROACH = 0.10
#: a picked-up object is lifted this far off its support first, then pulled back RETREAT towards the robot, then
#: lifted to LIFT, clear of what stands around it (m)
CLEAR = 0.02
LIFT = 0.10
#: a placed object is lowered from this far above its place (or from half that, when the arm cannot reach so high) (m)
LOWER = 0.05
#: after placing, the tool backs off this far along its approach (m)
RETREAT = 0.08
#: the longest a placed object is left to settle (s); it is checked every SETTLE_WINDOW
SETTLE = 1.0
SETTLE_WINDOW = 0.05
CALM = 2
#: a placed object moving less than this per window has settled (m, rad)
SETTLED = (1e-4, math.radians(0.05))
#: when closing fingers stop on something else, the tool backs off this far (m), at most GRIP_TRIES - 1 times
GRIP_BACKOFF = 0.005
GRIP_TRIES = 7
#: a place target's z names the surface at that height: the highest one from SURFACE above it to SURFACE_BELOW below
#: it (the design's targets give the height of the object's origin, up to half a tall object above its surface) (m)
SURFACE = 0.05
SURFACE_BELOW = 0.15
#: a placed object is lowered to this gap above its support before it is let go (m)
DROP = 0.0005
#: a grasp whose open gripper would be inside something is tried this much (m) short of that, see `_short_of`
SHORT_MARGIN = 0.002
#: a placed object keeps its heading, or is turned about the vertical by these (rad, in this order) if the arm needs it
PLACE_TURNS = (0.0, math.pi / 2, -math.pi / 2, math.pi, math.pi / 4, -math.pi / 4, 3 * math.pi / 4, -3 * math.pi / 4)


def grasp_orientation(robot: Robot, grasp: str | Sequence[float]) -> Quat:
    """The tool orientation a grasp names relative to the robot base (for move-tcp's orientation slot)."""
    return wanted_orientation(robot, grasp)


def offset_along(position: Sequence[float], direction: np.ndarray, distance: float) -> Vec3:
    p = np.asarray(position, dtype=float) + direction * distance
    return (float(p[0]), float(p[1]), float(p[2]))


# long: its attempt callback collects three kinds of failure the end turns into the one to report
def plan_grasp(robot: Robot, arm: str, obj: Object,
               grasp: str | Sequence[float]) -> tuple[Grasp, IKSolution, IKSolution]:
    """The first way to hold `obj` with `grasp` whose pre-grasp pose and grasp pose the arm reaches, the arm with its
    gripper open at the grasp pose inside nothing, with both IK solutions (pre-grasp, grasp); GripperFailure when the
    gripper cannot hold it so, ReachabilityFailure when the arm reaches none, ManipulationFailure when every way
    would be inside something."""
    candidates, why = holdable_grasps(robot, arm, obj, grasp)
    how = f"a {grasp} grasp" if isinstance(grasp, str) else "that grasp"
    if not candidates:
        raise GripperFailure(f"the {gripper_words(arm)} cannot hold {obj.name} with {how}: {why}", arm=arm, object=obj.name)
    best: tuple[float, IKSolution] | None = None
    blocked: list[motion.Hit] = []
    brushed: list[motion.Hit] = []  # what the open gripper's way in meets before the object
    refused: list[ManipulationFailure] = []  # the gripper could not open at the pre-grasp pose
    opened = gripper_values(robot, arm, "open")
    taken: list[tuple[Grasp, IKSolution, IKSolution]] = []

    def attempt(k: int, pre: IKSolution) -> bool:
        """The way `candidates[k]`, its pre-grasp pose solved near where the arm is (`pre`): whether it holds."""
        nonlocal best
        candidate = candidates[k]
        # the grasp from the pre-grasp pose (so that the approach is a short straight move)
        solution = reach_from(robot, arm, pre.joint_positions, candidate.position, candidate.orientation) \
            if pre.success else pre
        if solution.success:
            # the gripper free to open at the pre-grasp pose (where pick-up opens it)
            with robot.body.joints_kept([*pre.joint_positions, *opened]):
                robot.body.reset_joints(pre.joint_positions)
                try:
                    motion.move(robot, opened, f"opening the {gripper_words(arm)}")
                except ManipulationFailure as failure:
                    refused.append(failure)
                    return False
            # the open gripper at the grasp pose inside something else (a neighbour, the drawer)? The object itself
            # may be touched before: the approach stops there
            hits = motion.hits_at(robot, {**solution.joint_positions, **opened}, ignore=[obj])
            if not hits:
                brush = _approach_hits(robot, obj, pre, solution, opened)
                if not brush:
                    taken.append((candidate, pre, solution))
                    return True
                brushed.extend(brush)
                return False
            shifted = _short_of(robot, arm, obj, candidate, pre, hits, opened)
            if shifted is not None:
                taken.append(shifted)
                return True
            blocked.extend(hits)
            return False
        if best is None or solution.position_error < best[0]:
            best = (solution.position_error, solution)
        return False

    # every way's pre-grasp pose near where the arm is, searched a few at a time (`near_solutions`), until one holds
    for k, pre in near_solutions(robot, arm, [(offset_along(c.position, c.approach, -(c.depth + APPROACH)),
                                               c.orientation) for c in candidates]):
        if attempt(k, pre):
            break
    if taken:
        return taken[0]
    if blocked or brushed:
        why = f"{blocked[0]}" if blocked else f"on the way in from the pre-grasp pose, {brushed[0]}"
        raise ManipulationFailure(f"the {arm_words(arm)} cannot take {obj.name} with {how}: {why}", arm=arm,
                                  object=obj.name, colliding=sorted({h.obstacle.name for h in blocked + brushed}))
    if refused:
        raise ManipulationFailure(f"the {arm_words(arm)} cannot take {obj.name} with {how}: {refused[0]}", arm=arm,
                                  object=obj.name, colliding=sorted({n for f in refused for n in f.details.get("colliding", [])}))
    error = best[0] if best is not None else math.inf
    raise ReachabilityFailure(f"{arm_words(arm)} cannot reach {obj.name} with {how}: the tool frame stays "
                              f"{error * 100:.1f} cm away", arm=arm, position_error=error, object=obj.name)


def _approach_hits(robot: Robot, obj: Object, pre: IKSolution, solution: IKSolution,
                   opened: Mapping[str, float]) -> list[motion.Hit]:
    """What the open gripper meets on its way in from the pre-grasp pose before it touches `obj`: pick-up moves in
    until the first touch, so a neighbour the fingers brush on the way (a bottle beside a cereal box) stops them
    short of the object, and they close on nothing."""
    with robot.body.joints_kept([*solution.joint_positions, *opened]):
        robot.body.reset_joints({**pre.joint_positions, **opened})
        _, hits = motion.advance(robot, solution.joint_positions)
    return [hit for hit in hits if hit.obstacle is not obj]


def _short_of(robot: Robot, arm: str, obj: Object, candidate: Grasp, pre: IKSolution, hits: list[motion.Hit],
              opened: Mapping[str, float]) -> tuple[Grasp, IKSolution, IKSolution] | None:
    """The grasp stopped short by as far as the open gripper would be inside something (the bottom of a drawer under a
    flat spoon: the approach stops there anyway), if the gripper there is inside nothing and its closing fingers still
    meet the object; else None."""
    back = max(h.depth for h in hits) + SHORT_MARGIN
    position = offset_along(candidate.position, candidate.approach, -back)
    solution = reach_from(robot, arm, pre.joint_positions, position, candidate.orientation)
    if not solution.success or motion.hits_at(robot, {**solution.joint_positions, **opened}, ignore=[obj]):
        return None
    gripper = robot.description.arm(arm).gripper
    with robot.body.joints_kept([*solution.joint_positions, *gripper.joints]):  # as pick-up will: in from the
        robot.body.reset_joints({**pre.joint_positions, **opened})              # pre-grasp pose until a touch, close
        motion.advance(robot, solution.joint_positions)
        close_on(robot, arm)
        if not touches(robot, arm, obj):
            return None
    return replace(candidate, position=position), pre, solution


def finger_links(robot: Robot, arm: str) -> list[int]:
    """The links the arm's gripper joints move (the fingers)."""
    return motion.Motion(robot, robot.description.arm(arm).gripper.joints).links


def retreat(robot: Robot, arm: str, obj: Object) -> None:
    """Take a picked-up object away from where it stood: off its support (CLEAR up, a must), then clear of its
    neighbours (up to `LIFT`); when something overhangs it (a counter over an open drawer), out from under it first
    (`RETREAT` back towards the robot) and then up."""
    tool_frame = robot.description.arm(arm).tool_frame
    up = np.array([0.0, 0.0, 1.0])
    tool = robot.body.get_link_position_and_orientation(tool_frame)
    toward = np.subtract(robot.body.get_position(), tool[0])
    toward[2] = 0.0
    back = toward / (np.linalg.norm(toward) or 1.0)

    def leg(direction: np.ndarray, distance: float) -> bool:
        tool = robot.body.get_link_position_and_orientation(tool_frame)
        # a short straight move: solved on the arm's branch, so that the joint-space path keeps the object near the
        # line (a solution on another branch turns the arm through the counter the object stands on)
        here = robot.body.get_joint_positions(list(robot.description.arm(arm).joints))
        solution = reach_from(robot, arm, here, offset_along(tool[0], direction, distance), tool[1])
        if not solution.success:
            raise ReachabilityFailure(f"{arm_words(arm)} cannot lift {obj.name}: the tool frame stays "
                                      f"{solution.position_error * 100:.1f} cm away", arm=arm, object=obj.name)
        motion.move(robot, solution.joint_positions, f"lifting {obj.name}")
        return True

    leg(up, CLEAR)
    for way in ([(up, LIFT - CLEAR)], [(back, RETREAT), (up, LIFT - CLEAR)]):
        try:
            for direction, distance in way:
                leg(direction, distance)
            return
        except (ManipulationFailure, ReachabilityFailure):
            continue


def touches(robot: Robot, arm: str, obj: Object) -> bool:
    """Whether a finger of the arm's gripper touches `obj` (within twice the penetration tolerance)."""
    world = robot.world
    return any(world.distance(robot.body, obj, 2 * motion.PENETRATION, link_a=link) < math.inf
               for link in finger_links(robot, arm))


def grip(robot: Robot, arm: str, obj: Object, back: Mapping[str, float]) -> bool:
    """Close the gripper until the fingers touch; when they stop on something else first (closing fingers that swing
    forward meet the drawer's bottom under a spoon), open again, back off towards the `back` configuration in
    GRIP_BACKOFF steps and try again. Whether the fingers hold `obj`; if not, the gripper is left open."""
    gripper = robot.description.arm(arm).gripper
    body = robot.body
    if not gripper.joints:
        return True
    start = body.get_joint_positions(list(back))
    length = math.dist(body.get_link_position(robot.description.arm(arm).tool_frame),
                       _tool_at(robot, arm, back))
    for attempt in range(GRIP_TRIES):
        close_on(robot, arm)
        if touches(robot, arm, obj):
            return True
        set_gripper(robot, arm, "open")
        if length <= 0:
            break
        fraction = min(1.0, GRIP_BACKOFF * (attempt + 1) / length)
        goal = {name: start[name] + _turn(body, name, start[name], back[name]) * fraction for name in back}
        try:
            motion.move(robot, goal, f"the {arm_words(arm)} backing off from {obj.name}")
        except ManipulationFailure:
            break
    return False


def _turn(body: Object, joint: str, start: float, end: float) -> float:
    """How far a joint moves from `start` to `end`: a continuous joint the short way round (after a path of several
    legs it may stand a whole turn from where the goal's numbers say)."""
    if body.joint(joint).type == "continuous":
        return math.remainder(end - start, 2 * math.pi)
    return end - start


def _tool_at(robot: Robot, arm: str, joints: Mapping[str, float]) -> Vec3:
    tool = robot.description.arm(arm).tool_frame
    with robot.body.joints_kept(joints):
        robot.body.reset_joints(joints)
        return robot.body.get_link_position(tool)


def level(orientation: Sequence[float], upright: Sequence[float] = (0.0, 0.0, 0.0, 1.0)) -> Quat:
    """The object's orientation stood upright: `upright` (the object's own, `Object.upright`: its z axis up for most
    models, y for a Y-up mesh) turned to the heading it has (that of its upright frame's x axis, or of its y axis when
    x points up or down)."""
    rotation = quat_to_matrix(quat_multiply(orientation, quat_inverse(upright)))
    axis = rotation[:, 0] if math.hypot(rotation[0, 0], rotation[1, 0]) > 0.2 else rotation[:, 1]
    heading = math.atan2(axis[1], axis[0]) - (0.0 if axis is rotation[:, 0] else math.pi / 2)
    if tuple(upright) == (0.0, 0.0, 0.0, 1.0):
        return yaw_quaternion(heading)
    return quat_multiply(yaw_quaternion(heading), upright)


def support_height(robot: Robot, obj: Object, orientation: Quat, xy: Sequence[float], top: float,
                   depth: float = 3.0) -> tuple[float, Object | None]:
    """The height of the highest surface under the object's footprint (stood at `xy` with `orientation`) between `top`
    and `depth` below it: rays straight down from the footprint's middle and corners, through the robot and what it
    holds."""
    lo, hi = (np.asarray(v) for v in obj.get_local_aabb())
    rotation = quat_to_matrix(orientation)
    footprint = [(0.0, 0.0)] + [(sx * 0.8, sy * 0.8) for sx in (-1, 1) for sy in (-1, 1)]
    centre, half = (lo + hi) / 2.0, (hi - lo) / 2.0
    starts, ends = [], []
    for fx, fy in footprint:
        local = centre + np.array([fx * half[0], fy * half[1], 0.0])
        p = rotation @ local
        starts.append((xy[0] + p[0], xy[1] + p[1], top))
        ends.append((xy[0] + p[0], xy[1] + p[1], top - depth))
    ignore = [robot.body, *motion.followers(robot.body)]
    hits = [h for h in robot.world.cast_rays(starts, ends, ignore) if h is not None]
    if not hits:
        return -math.inf, None
    best = max(hits, key=lambda h: h.position[2])
    return best.position[2], best.object


def rest_pose(robot: Robot, obj: Object, orientation: Quat, target: Sequence[float], arm: str) -> tuple[Vec3, Object]:
    """Where `obj` rests, stood with `orientation` at the target's x, y on the surface under it: its lowest point on the
    support, DROP above (measured with closest points, so whatever the mesh's origin and the shapes' margins)."""
    if len(target) > 2:  # the surface at the target's height: from SURFACE above it to SURFACE_BELOW below it
        height, support = support_height(robot, obj, orientation, target, float(target[2]) + SURFACE,
                                         SURFACE + SURFACE_BELOW)
    else:  # the highest surface under it that the arm can come down on: below the arm's first joint
        top = robot.body.get_link_position(robot.body.joint(robot.description.arm(arm).joints[0]).index)[2]
        height, support = support_height(robot, obj, orientation, target, top)
    if support is None:
        where = ", ".join(f"{v:.3f}" for v in target)
        raise ManipulationFailure(f"there is nothing to place {obj.name} on at ({where})"
                                  + (f" (no surface from {SURFACE * 100:.0f} cm above to {SURFACE_BELOW * 100:.0f} cm "
                                     "below that height)" if len(target) > 2 else ""), object=obj.name)
    return resting_on(obj, orientation, target, height, support), support


def resting_on(obj: Object, orientation: Quat, xy: Sequence[float], height: float, support: Object,
               link: int | None = None) -> Vec3:
    """Where `obj`, stood with `orientation` (upright: a turn about z) at x, y over a surface `height` high, rests: its
    lowest point DROP above the support (or that link of it), measured with closest points, so whatever the mesh's
    origin (its bottom, its centre, anywhere) and the shapes' margins; the object is put back as it was."""
    with _trial_pose(obj):
        # its lowest point is its box's bottom (stood so): 2 mm above the surface, then lowered by the gap closest
        # points measure
        obj.set_position_and_orientation((float(xy[0]), float(xy[1]), height + 1.0), orientation)
        bottom = obj.get_aabb()[0][2] - (height + 1.0)
        position = (float(xy[0]), float(xy[1]), height - bottom + 0.002)
        obj.set_position_and_orientation(position, orientation)
        gap = obj.world.distance(obj, support, 0.02, link_b=link)
    if math.isfinite(gap):
        position = (position[0], position[1], position[2] - gap + DROP)
    return position


@contextlib.contextmanager
def _trial_pose(obj: Object) -> Iterator[None]:
    """`with _trial_pose(obj):` move a (held) object to try a pose; afterwards it is back, held as it was."""
    pose = obj.get_pose()
    attachments = dict(obj.attachments)
    try:
        yield
    finally:
        obj.set_position_and_orientation(*pose)
        for other, att in attachments.items():  # the offsets to what holds it, exactly as they were
            obj.attachments[other] = att
            other.attachments[obj] = att


def settle(obj: Object) -> float:
    """Let physics run until `obj` has come to rest — CALM consecutive windows in which it moves less than SETTLED (a
    rocking object is still at the turn of each rock) — or SETTLE seconds; the seconds simulated."""
    world = obj.world
    world.wake_free_objects()
    simulated, calm = 0.0, 0
    while simulated < SETTLE - 1e-9:
        before = obj.get_pose()
        world.simulate(SETTLE_WINDOW)
        simulated += SETTLE_WINDOW
        after = obj.get_pose()
        still = math.dist(before[0], after[0]) < SETTLED[0] and angle_between(before[1], after[1]) < SETTLED[1]
        calm = calm + 1 if still else 0
        if calm >= CALM:
            break
    return simulated


def plan_place(robot: Robot, arm: str, obj: Object,
               target: Sequence[float]) -> tuple[Vec3, Quat, IKSolution, IKSolution, Object]:
    """How the held `obj` is put down at `target`: where it will rest and how it stands (upright, its heading kept or
    turned about the vertical if that is what the arm needs), the arm's configuration there and above it (a short
    move down on one IK branch), and what it will rest on. ReachabilityFailure when the arm reaches no way,
    ManipulationFailure when there is nothing to put it on or the arm does not hold it."""
    if robot.arm_holding(obj) != arm:
        raise ManipulationFailure(f"{obj.name} is not held by the {gripper_words(arm)}", object=obj.name, arm=arm)
    att = robot.body.attachments[obj]
    held = invert(att.transform)  # the tool frame seen from the object
    upright = level(obj.get_orientation(), obj.upright)
    where = f"({', '.join(f'{v:.3f}' for v in target)})"
    best: tuple[float, Any] | None = None
    chosen = None
    for turn in PLACE_TURNS:
        orientation = quat_multiply(yaw_quaternion(turn), upright)
        position, support = rest_pose(robot, obj, orientation, target, arm)
        tool = compose((position, orientation), held)
        solution = reach_near(robot, arm, tool[0], tool[1])
        if solution.success:
            for height in (LOWER, LOWER / 2):  # above the place, from there down onto it: one branch
                above = reach_near(robot, arm, offset_along(tool[0], np.array([0.0, 0.0, 1.0]), height), tool[1])
                if above.success:
                    down = reach_from(robot, arm, above.joint_positions, tool[0], tool[1])
                    if down.success:
                        chosen = (position, orientation, down, above, support)
                        break
            if chosen is not None:
                break
            solution = above
        if best is None or solution.position_error < best[0]:
            best = (solution.position_error, solution)
    if chosen is None:
        error = best[0] if best is not None else math.inf
        raise ReachabilityFailure(f"{arm_words(arm)} cannot place {obj.name} at {where}: the tool frame stays "
                                  f"{error * 100:.1f} cm away", arm=arm, object=obj.name)
    return chosen
