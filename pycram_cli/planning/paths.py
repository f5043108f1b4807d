"""Ways for an arm: straight in joint space when that is free, else around what is in the way — through a few poses
of the tool (up, back towards the base, down onto the goal), joint by joint, through the arm's named poses — and,
last, a search in the arm's joint space (`search_path`); every leg collision-checked (`motion.py`)."""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from ..failures import ManipulationFailure
from ..kinds import arm_words
from ..reasoning.ik import IKSolution
from ..robots import Robot
from ..world import Object
from . import motion
from .motion import Motion
from .reach import arm_configuration, middle_of_ranges, reach_from_middle, reach_solutions, solve_tool

# -- finding a way around: a small bidirectional search in joint space ---------------------------------------------

#: the longest step of the search (rad, or m for a prismatic joint, per joint), its budget of edges checked, its seed
SEARCH_STEP = 0.4
SEARCH_EDGES = 300
SEARCH_SEED = 20191028
#: a search is remembered for where the arm starts and ends to this many decimals (rad, m): IK's answers to one
#: question from configurations a rounding error apart differ in the 15th, as a location test's pull and the action's
KEY_DIGITS = 9


def search_path(robot: Robot, goal: Mapping[str, float], ignore: Iterable[Object] = (),
                edges: int = SEARCH_EDGES) -> list[dict[str, float]] | None:
    """Joint values to pass through, from the current ones to `goal`, every leg between them free (checked as `move`
    checks a path), or None when none is found within a budget of `edges` legs checked (a configuration checked where
    it is counts as POINT_COST of a leg).

    RRT-connect (Kuffner and LaValle, 2000), checked lazily: two trees, grown from the start and from the goal towards
    random configurations within the joints' limits (continuous joints within half a turn either way), each reaching
    for the other. A new configuration is checked only where it is (one check, a few hundredths of a leg's); the legs
    between configurations only once the trees meet, along the way they make, and a leg found blocked cuts the
    configurations beyond it from their tree (Bohlin and Kavraki's lazy checking, 2000): most configurations the
    trees grow never end up on a way, and their legs are never checked. The way found is then shortened by joining
    its waypoints directly wherever that is free. The random numbers come from a fixed seed, so the same world gives
    the same way; a search made again in the same situation (`Motion.situation`) is answered from memory.
    """
    names = [name for name in goal]
    motion = Motion(robot, names, ignore)
    start_values, end_values = motion._endpoints(goal)
    order = [j.name for j in motion.joints]
    if not order:
        return []
    situation = motion.situation(KEY_DIGITS)
    key = None if situation is None else (situation, "search", (np.round(start_values, KEY_DIGITS) + 0.0).tobytes(),
                                          (np.round(end_values, KEY_DIGITS) + 0.0).tobytes())
    known = motion.remembered(key)
    if known is not None and _answers(known, edges):
        motion._put(start_values)  # as a search leaves it
        return None if known[0] is None else [dict(values) for values in known[0]]
    search = _Search(motion, start_values, edges)
    way = search.run(end_values)
    found = None if way is None else [{n: float(v) for n, v in zip(order, values)} for values in way]
    motion.remember(key, (found, edges, search.starved))
    return None if found is None else [dict(values) for values in found]


def _answers(known: tuple[list[dict[str, float]] | None, int, bool], edges: int) -> bool:
    """Whether a search remembered (its way or None, its budget, whether a check was refused for want of budget)
    answers the same question with a budget of `edges`. The budget only stops a search: one that found a way
    without running short goes the same way with any larger budget, and one that found none within its budget finds
    none within a smaller one (the park after opening a drawer asks, with its larger budget, what the location's test
    of the way back found)."""
    way, budget, starved = known
    if edges == budget:
        return True
    return edges > budget and not starved if way is not None else edges < budget


#: what a configuration checked where it is costs of the search's budget, in legs (a check at one configuration is a
#: few hundredths of a leg's: a leg near things takes tens of them)
POINT_COST = 0.1


class _Search:
    """The lazy RRT-connect of `search_path` for one motion, from the joints' current values."""

    def __init__(self, motion: Motion, start: np.ndarray, edges: int) -> None:
        self.motion = motion
        self.start = start
        lows, highs = [], []
        for joint, value in zip(motion.joints, start):
            lows.append(joint.lower if joint.limited else value - math.pi)
            highs.append(joint.upper if joint.limited else value + math.pi)
        self.low, self.high = np.array(lows), np.array(highs)
        self.names = [joint.name for joint in motion.joints]
        self.budget = float(edges)
        self.legs: dict[tuple[bytes, bytes], bool] = {}  # legs checked: whether free
        self.starved = False  # whether a check was refused for want of budget

    def point_free(self, values: np.ndarray) -> bool:
        """Whether the moving part is inside nothing at `values` (one check; the joints stay there)."""
        if self.budget <= 0:
            self.starved = True
            return False
        self.budget -= POINT_COST
        self.motion._put(values)
        return not self.motion.scan()[1]

    def leg_free(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Whether the straight leg from `a` to `b` is free, checked as `move` checks a path (continuous joints
        turning the short way round, as `move` turns them), once."""
        key = (a.tobytes(), b.tobytes())
        if key not in self.legs:
            if self.budget <= 0:
                self.starved = True
                return False
            self.budget -= 1
            fraction, hits = self.motion._follow(a, motion.short_way(self.motion.body, self.names, a, b))
            self.legs[key] = not hits and fraction >= 1.0
        return self.legs[key]

    def run(self, end: np.ndarray) -> list[np.ndarray] | None:
        """The way's waypoints after the start (the last is `end`), or None."""
        motion = self.motion
        motion._prune(motion._levers())
        motion.allow_current()  # contacts where the arm starts may stay; none is made anywhere else
        try:
            path = self._connect(end)
            return None if path is None else self._shorten(path)[1:]
        finally:
            motion._put(self.start)

    def _connect(self, end: np.ndarray) -> list[np.ndarray] | None:
        """The trees grown until they meet along a way whose legs are all free: the way, or None."""
        rng = np.random.default_rng(SEARCH_SEED)
        low, high = self.low, self.high
        # each tree: configurations, the parent of each (-1: the root), whether each is still in the tree
        trees: list[_Tree] = [_Tree(self.start), _Tree(end)]
        start_tree = trees[0]  # (the two swap places as they take turns)
        while self.budget > 0:
            grow, other = trees
            # a random configuration, or (one time in five) the other tree's root
            sample = other.values[0] if rng.random() < 0.2 else low + rng.random(len(low)) * (high - low)
            new = _toward(grow.values[grow.nearest(sample)], sample)
            if not self.point_free(new):
                trees.reverse()
                continue
            grow.add(new, grow.nearest(sample))
            # the other tree reaches for the new configuration, step by step
            reach = other.nearest(new)
            met = False
            while self.budget > 0:
                nxt = _toward(other.values[reach], new)
                if not self.point_free(nxt):
                    break
                reach = other.add(nxt, reach)
                if np.max(np.abs(nxt - new)) < 1e-9:
                    met = True
                    break
            if met:
                first, second = (grow, other) if grow is start_tree else (other, grow)
                ends = (len(grow.values) - 1, reach) if grow is start_tree else (reach, len(grow.values) - 1)
                path = self._checked(first, second, *ends)
                if path is not None:
                    return path
            trees.reverse()
        return None

    def _checked(self, first: _Tree, second: _Tree, i: int, j: int) -> list[np.ndarray] | None:
        """The way from the start tree's root through its node `i` (= the other's `j`) to the goal tree's root when
        every leg is free; else None, the node beyond the first blocked leg cut from its tree (with what hangs on
        it)."""
        ours, theirs = first.chain(i)[::-1], second.chain(j)
        nodes = [(first, k) for k in ours] + [(second, k) for k in theirs[1:]]
        for (tree_a, a), (tree_b, b) in zip(nodes, nodes[1:]):
            if not self.leg_free(tree_a.values[a], tree_b.values[b]):
                if self.budget > 0:
                    tree, node = (tree_b, b) if tree_b is first else (tree_a, a)  # the one farther from its root
                    tree.cut(node)
                return None
        return [tree.values[k] for tree, k in nodes]

    def _shorten(self, path: list[np.ndarray]) -> list[np.ndarray]:
        """The way with waypoints joined directly wherever that leg is free (a few legs' budget of its own)."""
        self.budget = max(self.budget, len(path) * 2.0)
        short = [path[0]]
        i = 0
        while i < len(path) - 1:
            j = len(path) - 1
            while j > i + 1 and not self.leg_free(path[i], path[j]):
                j -= 1
            short.append(path[j])
            i = j
        return short


class _Tree:
    """One of the search's trees: configurations, each one's parent, and whether it is still in the tree."""

    def __init__(self, root: np.ndarray) -> None:
        self.values: list[np.ndarray] = [root]
        self.parents: list[int] = [-1]
        self.alive: list[bool] = [True]

    def add(self, values: np.ndarray, parent: int) -> int:
        self.values.append(values)
        self.parents.append(parent)
        self.alive.append(True)
        return len(self.values) - 1

    def nearest(self, target: np.ndarray) -> int:
        """The configuration in the tree nearest `target` (largest joint difference; the first of equals)."""
        return min((i for i in range(len(self.values)) if self.alive[i]),
                   key=lambda i: float(np.max(np.abs(self.values[i] - target))))

    def chain(self, index: int) -> list[int]:
        """The nodes from `index` up to the root."""
        found = []
        while index != -1:
            found.append(index)
            index = self.parents[index]
        return found

    def cut(self, index: int) -> None:
        """Take `index` and everything that hangs on it out of the tree (a parent always comes before its children)."""
        self.alive[index] = False
        for k in range(index + 1, len(self.values)):
            if self.alive[k] and not self.alive[self.parents[k]]:
                self.alive[k] = False


def _toward(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """`b`, or the configuration SEARCH_STEP from `a` towards it when it is farther (largest joint difference)."""
    step = np.max(np.abs(b - a))
    return b if step <= SEARCH_STEP else a + (b - a) * (SEARCH_STEP / step)


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
#: or the tool drawn straight back towards the base, this far (m), through LINE_STEPS poses on the line (a joint-space
#: leg between two poses far apart can swing what the hand holds down into the counter it was lifted from)
LINE_BACKS = (0.3, 0.45)
LINE_STEPS = 3


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
        found: dict[int, IKSolution] = {}
        for k, answer in reach_solutions(robot, arm, [(target, orientation, None),
                                                      (target, orientation, middle_of_ranges(robot, arm))],
                                         best_effort=False):  # only whether
            found[k] = answer
            if k == 0 and answer.success:
                break
        solution = found[0] if found[0].success else found.get(1)
    return solution.joint_positions if solution is not None and solution.success else None


# long: the ways are recipes tried in order in one loop, each solved when tried, sharing one start and pose table
def move_over(robot: Robot, arm: str, goal: Mapping[str, float], what: str, down_onto_goal: bool = True,
              around: bool = True, search: bool = True, ignore: Sequence[Object] = (),
              straight: ManipulationFailure | None = None, edges: int = SEARCH_EDGES) -> None:
    """Move an arm to joint values along a collision-free path: straight (in joint space) when it is free, else around
    what is in the way, through a few poses of the tool — up from where it is, or back towards the base and up, or
    straight back along a line —
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
    if motion.hits_at_goal(robot, goal, ignore):
        raise first  # the goal itself is inside something: every way ends there (the search's too), none is free
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
            elif kind == "line":  # the k-th of n poses on the line back, from the one before it
                length, k, n = key[1], key[2], key[3]
                solved[key] = _shifted(robot, arm, start if k == 1 else via(("line", length, k - 1, n)), 0.0,
                                       length / n)
        return solved[key]

    departures: list[list[Any]] = [[]]
    for h in VIA_HEIGHTS:
        departures.append([("up", h, 0.0)])
    departures.append([("up", 0.0, BACK)])
    for h in VIA_HEIGHTS:
        departures.append([("up", 0.0, BACK), ("back-up", h)])
    for h in VIA_HEIGHTS:  # up and back at once (where the arm cannot draw back at its height)
        departures.append([("up", h, BACK)])
    for length in LINE_BACKS:  # straight back, along a line
        departures.append([("line", length, k, LINE_STEPS) for k in range(1, LINE_STEPS + 1)])
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
            legs = [via(leg) if isinstance(leg, tuple) else leg for leg in plan]
            way_round = [leg for leg in legs if leg is not None]
            if len(way_round) < len(legs):
                continue
            try:
                for leg in way_round:
                    motion.move(robot, leg, what, ignore)
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
