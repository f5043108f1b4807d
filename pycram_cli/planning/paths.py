"""Ways for an arm: straight in joint space when that is free, else around what is in the way — through a few poses
of the tool (up, back towards the base, down onto the goal), joint by joint, through the arm's named poses — and,
last, a search in the arm's joint space (`search_path`); every leg collision-checked (`motion.py`)."""
from __future__ import annotations

import math
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from ..failures import ManipulationFailure
from ..kinds import arm_words
from ..reasoning.ik import IKSolution
from ..robots import Robot
from ..world import Object
from . import motion
from .motion import Motion
from .reach import arm_configuration, middle_of_ranges, reach_each, reach_from_middle, solve_tool


# -- finding a way around: a small bidirectional search in joint space ---------------------------------------------

#: the longest step of the search (rad, or m for a prismatic joint, per joint), its budget of edges checked, its seed
SEARCH_STEP = 0.4
SEARCH_EDGES = 300
SEARCH_SEED = 20191028


def search_path(robot: Robot, goal: Mapping[str, float], ignore: Iterable[Object] = (),
                edges: int = SEARCH_EDGES) -> list[dict[str, float]] | None:
    """Joint values to pass through, from the current ones to `goal`, every leg between them free (checked as `move`
    checks a path), or None when none is found within `edges` checks of a leg.

    RRT-connect (Kuffner and LaValle, 2000): two trees, grown from the start and from the goal towards random
    configurations within the joints' limits (continuous joints within half a turn either way), each reaching for the
    other; the way found is then shortened by joining its waypoints directly wherever that is free. The random
    numbers come from a fixed seed, so the same world gives the same way; a search made again in the same situation
    (`Motion.situation`) is answered from memory.
    """
    names = [name for name in goal]
    motion = Motion(robot, names, ignore)
    start_values, end_values = motion._endpoints(goal)
    order = [j.name for j in motion.joints]
    if not order:
        return []
    situation = motion.situation()
    key = None if situation is None else (situation, "search", start_values.tobytes(), end_values.tobytes(), edges)
    known = motion.remembered(key)
    if known is not None:
        motion._put(start_values)  # as a search leaves it
        return None if known[0] is None else [dict(values) for values in known[0]]
    way = _search(motion, start_values, end_values, order, edges)
    motion.remember(key, (None if way is None else [dict(values) for values in way],))
    return way


def _search(motion: Motion, start_values: np.ndarray, end_values: np.ndarray, order: list[str],
            edges: int) -> list[dict[str, float]] | None:
    """The search of `search_path` (RRT-connect, then shortened), from `start_values` to `end_values`."""
    lows, highs = [], []
    for joint, value in zip(motion.joints, start_values):
        if joint.limited:
            lows.append(joint.lower)
            highs.append(joint.upper)
        else:
            lows.append(value - math.pi)
            highs.append(value + math.pi)
    low, high = np.array(lows), np.array(highs)
    rng = np.random.default_rng(SEARCH_SEED)
    budget = [edges]

    motion._prune(motion._levers())
    motion.allow_current()  # contacts where the arm starts may stay; none is made anywhere else

    def free(a: np.ndarray, b: np.ndarray) -> bool:
        if budget[0] <= 0:
            return False
        budget[0] -= 1
        fraction, hits = motion._follow(a, b)
        return not hits and fraction >= 1.0

    def toward(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        step = np.max(np.abs(b - a))
        return b if step <= SEARCH_STEP else a + (b - a) * (SEARCH_STEP / step)

    trees: list[list[tuple[np.ndarray, int]]] = [[(start_values, -1)], [(end_values, -1)]]
    meeting: tuple[int, int] | None = None
    try:
        while budget[0] > 0 and meeting is None:
            grow, other = trees[0], trees[1]
            # a random configuration, or (one time in five) the other tree's root
            sample = other[0][0] if rng.random() < 0.2 else low + rng.random(len(low)) * (high - low)
            near = min(range(len(grow)), key=lambda i: float(np.max(np.abs(grow[i][0] - sample))))
            new = toward(grow[near][0], sample)
            if not free(grow[near][0], new):
                trees.reverse()
                continue
            grow.append((new, near))
            # the other tree reaches for the new node, step by step
            reach = min(range(len(other)), key=lambda i: float(np.max(np.abs(other[i][0] - new))))
            while budget[0] > 0:
                nxt = toward(other[reach][0], new)
                if not free(other[reach][0], nxt):
                    break
                other.append((nxt, reach))
                reach = len(other) - 1
                if np.max(np.abs(nxt - new)) < 1e-9:
                    meeting = (len(grow) - 1, reach) if grow is trees[0] else (reach, len(grow) - 1)
                    break
            if meeting is None:
                trees.reverse()
        if meeting is None:
            return None
        # the trees may have been swapped: the one holding the start comes first
        if not np.array_equal(trees[0][0][0], start_values):
            trees.reverse()
            meeting = (meeting[1], meeting[0])

        def chain(tree: list[tuple[np.ndarray, int]], index: int) -> list[np.ndarray]:
            found = []
            while index != -1:
                found.append(tree[index][0])
                index = tree[index][1]
            return found

        path = list(reversed(chain(trees[0], meeting[0]))) + chain(trees[1], meeting[1])[1:]
        budget[0] = max(budget[0], len(path) * 2)  # shortening gets a few checks of its own
        short = [path[0]]
        i = 0
        while i < len(path) - 1:
            j = len(path) - 1
            while j > i + 1 and not free(path[i], path[j]):
                j -= 1
            short.append(path[j])
            i = j
        return [{n: float(v) for n, v in zip(order, values)} for values in short[1:]]
    finally:
        motion._put(start_values)


# -- ways for an arm ------------------------------------------------------------------------------------------------

def move_tool(robot: Robot, arm: str, position: Sequence[float], orientation: Sequence[float] | None,
              what: str) -> IKSolution:
    """Bring the arm's tool frame to a pose along a collision-free path (straight in joint space, else around what is
    in the way: `move_over`): ReachabilityFailure when no arm configuration gets there, ManipulationFailure naming
    what the arm (or what it holds) would hit on the straight way when no way is free."""
    solution = solve_tool(robot, arm, position, orientation, what)
    if motion.hits_at(robot, solution.joint_positions):  # a configuration there inside nothing, if there is one
        other = reach_from_middle(robot, arm, position, orientation)
        if other.success and not motion.hits_at(robot, other.joint_positions):
            solution = other
    move_over(robot, arm, solution.joint_positions, f"the {arm_words(arm)}'s motion to {what}")
    return solution


#: when the straight path (in joint space) is blocked, the arm tries to go around what is in the way: up from where
#: it is (these heights, m), back towards the robot's base (BACK, m) and up, and down onto its goal from above it
VIA_HEIGHTS = (0.1, 0.2, 0.3)
BACK = 0.15


def _shifted(robot: Robot, arm: str, joints: Mapping[str, float] | None, up: float,
             back: float = 0.0) -> dict[str, float] | None:
    """Joint values that put the arm's tool `up` higher and `back` nearer the robot's base (horizontally) than `joints`
    put it, same orientation (None: out of reach); solved from `joints`, so that they are close to them."""
    if joints is None:
        return None
    body = robot.body
    with body.joints_kept(joints):
        body.reset_joints(joints)
        position, orientation = body.get_link_position_and_orientation(robot.description.arm(arm).tool_frame)
        toward = np.subtract(body.get_position(), position)[:2]
        toward = toward / (np.linalg.norm(toward) or 1.0) * back
        target = (position[0] + toward[0], position[1] + toward[1], position[2] + up)
        # inverse kinematics may stall from a folded arm: then from the middle of its ranges (searched at once)
        here, middle = reach_each(robot, arm, [(target, orientation, None),
                                               (target, orientation, middle_of_ranges(robot, arm))],
                                  enough=lambda k, s: k == 0 and s.success)
        assert here is not None
        solution = here if here.success else middle
    return solution.joint_positions if solution is not None and solution.success else None


def move_over(robot: Robot, arm: str, goal: Mapping[str, float], what: str, down_onto_goal: bool = True,
              around: bool = True, search: bool = True, ignore: Sequence[Object] = (),
              straight: ManipulationFailure | None = None, edges: int = SEARCH_EDGES) -> None:
    """Move an arm to joint values along a collision-free path: straight (in joint space) when it is free, else around
    what is in the way, through a few poses of the tool — up from where it is, or back towards the base and up —
    or joint by joint (the arm's outer joints first, folding it in, or its inner ones first), or through one of the
    arm's named poses (the description's park, carry, ...), and, for a goal that is
    a tool pose, down onto the goal from above it; last, a search through the arm's joint space
    (`search_path`). Each leg is checked. Raises the straight path's ManipulationFailure when no way is
    free; then nothing has moved. `around=False`: the straight path only (a cheap first test); `search=False`: no
    joint-space search (the dearest test: about 0.4 s when no way exists). `ignore`: what the arm may pass through.
    `straight`: the straight path's failure, when it is already known (from the same configuration): it is not
    walked again. `edges`: the search's budget (legs checked)."""
    if straight is not None:
        if not around:
            raise straight
        first = straight
    else:
        try:
            motion.move(robot, goal, what, ignore)
            return
        except ManipulationFailure as exc:
            if not around:
                raise
            first = exc
    body = robot.body
    start = body.get_joint_positions(list(goal))
    # the poses the ways go through are solved only when a way needs them (a way that works early saves the rest),
    # each once: a way is a list of keys of `_VIAS`-like recipes, looked up in `solved`
    solved: dict[tuple, dict[str, float] | None] = {}

    def via(key: tuple) -> dict[str, float] | None:
        if key not in solved:
            kind = key[0]
            if kind == "up":  # up from where it is (and back towards the base)
                solved[key] = _shifted(robot, arm, start, key[1], key[2])
            elif kind == "back-up":  # back, then up from there
                solved[key] = _shifted(robot, arm, via(("up", 0.0, BACK)), key[1])
            elif kind == "onto":  # above the goal
                solved[key] = _shifted(robot, arm, goal, key[1])
        return solved[key]

    departures: list[list[Any]] = [[]]
    for h in VIA_HEIGHTS:
        departures.append([("up", h, 0.0)])
    departures.append([("up", 0.0, BACK)])
    for h in VIA_HEIGHTS:
        departures.append([("up", 0.0, BACK), ("back-up", h)])
    for h in VIA_HEIGHTS:  # up and back at once (where the arm cannot draw back at its height)
        departures.append([("up", h, BACK)])
    # or joint by joint: the arm's outer half first (folding it in, out of the way), or its inner half first
    names = [n for n in robot.description.arm(arm).joints if n in goal]
    half = len(names) // 2
    outer_first = {n: (goal[n] if i >= half else start[n]) for i, n in enumerate(names)}
    inner_first = {n: (goal[n] if i < half else start[n]) for i, n in enumerate(names)}
    departures += [[outer_first], [("up", VIA_HEIGHTS[0], 0.0), outer_first], [inner_first]]
    # or through one of the arm's named poses (its description's park, carry, ...): folded in, away from things
    for pose in robot.description.arm(arm).poses:
        named = arm_configuration(robot, arm, pose)
        if any(abs(named[n] - goal[n]) > 1e-9 for n in named if n in goal):
            departures.append([named])
    arrivals: list[list[Any]] = [[]]
    if down_onto_goal:
        arrivals += [[("onto", h)] for h in VIA_HEIGHTS]
    for arrival in arrivals:
        for departure in departures:
            plan = departure + arrival
            if not plan:
                continue
            way = [via(leg) if isinstance(leg, tuple) else leg for leg in plan]
            if any(leg is None for leg in way):
                continue
            try:
                for leg in way:
                    motion.move(robot, leg, what, ignore)  # type: ignore[arg-type]
                motion.move(robot, goal, what, ignore)
                return
            except ManipulationFailure:
                body.reset_joints(start)  # back where it was, along legs that were free
                body.move_attached()
    way = search_path(robot, goal, ignore, edges) if search else None  # last: a search in the joint space
    if way:
        try:
            for leg in way:
                motion.move(robot, leg, what, ignore)
            return
        except ManipulationFailure:
            body.reset_joints(start)
            body.move_attached()
    raise first


def move_from_above(robot: Robot, arm: str, solution: IKSolution, what: str) -> None:
    """`move_over` to an IK solution."""
    move_over(robot, arm, solution.joint_positions, what)
