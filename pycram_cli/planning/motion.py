"""Collision-checked motions of a robot's joints: an arm, its gripper, several arms at once.

A motion goes from the joints' current values to goal values along a straight line in joint space
(continuous joints the short way round). Before anything is applied, the path is checked against
everything in the world but the robot itself and what it holds: the moving part is every link
downstream of a moving joint, with the objects those links hold; a part more than 1 mm inside
anything (`PENETRATION`; resting contact sits at about 1e-5 m) fails the motion with a
ManipulationFailure that names the link or held object and what it would be inside (what the robot
holds elsewhere, in its other hand, counts as an obstacle like anything else). Contacts that
already exist where the motion starts may stay (a hand on a handle, a carton on the counter
while it is lifted off), as long as they get no deeper.

How densely the path is checked — conservative advancement, for each moving part, with a floor.
Each mover's (a link's, or a held object's) clearance (the gap between its box and every obstacle's
box, measured exactly where the boxes are near) is how far it may move before the next check, never
less than `SPACING`, 1 cm; the next check comes when the first mover may have used up its own (a
gripper far from everything does not slow the check of an upper arm brushing the counter, nor the
other way round). How far a mover can move over a step is bounded in `pace.py`: by the velocity of
its box's corners where the step starts (the Jacobian times the joints' change) plus a bound of how
much that velocity can change over the step, or by its levers (Σᵢ rᵢₖ·|Δqᵢ|, rᵢₖ the farthest corner
of k's box from joint i's axis), whichever allows the longer step (an approach that stops at contact
keeps the levers alone, measured afresh every `LEVER_REFRESH` of travel). A collision can then only
be missed where a link passes wholly through an obstacle within 1 cm of travel, i.e. where link and
obstacle together are thinner than 1.1 cm along the motion. Nothing the robots and worlds here move
or hit is that thin: the PR2's finger links are 1.5–2 cm across, the bundled kitchen's thinnest
boxes (drawer bottom and walls) 1.2 cm, the real IAI kitchen's drawer walls 1.8 cm; a link and an
obstacle are also never both at their thinnest along the direction of travel. In free space the
checks are far apart (a park motion takes a handful), near the kitchen 1–3 cm of the nearest part's
travel apart. Before a walk, obstacles farther from the outermost moving joint than the moving part
reaches (`_levers`) are set aside.

Robot-specific knowledge (which joints an arm or a gripper has) comes from the description; the
geometry comes from the world (`closest_points`, boxes); nothing here calls PyBullet.
"""
from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..failures import ManipulationFailure
from ..robots import Robot
from ..world import Object
from ..world.pose import quat_to_matrix, quats_to_matrices
from .pace import Pace, Pacer, corners
from .pace import levers as levers_of

#: deeper than this inside something is a collision (m); resting contact sits at about 1e-5 m
PENETRATION = 0.001
#: the farthest any point of the moving part travels between two checks near obstacles (m)
SPACING = 0.01
#: boxes closer than this are measured exactly (closest points), so that a check near big boxes (a counter, a
#: cabinet) steps as far as the parts' true distance allows, not only as far as their boxes' gap (m)
NEAR = 0.03
#: an approach's levers (see `_follow`) are measured afresh after this much travel (m)
LEVER_REFRESH = 0.1
#: approaches stop this close to the first contact (m of travel)
PRECISION = 0.001
#: an approach that stops at contact lets a contact that exists where it starts get this much deeper (m: numeric noise)
STILL = 1e-5
#: how many walks and searches each world remembers (the newest; see `Motion.situation`)
MEMO_SIZE = 512
#: the world's cache table of them (world/cache.py)
MEMO = "motion checks"
#: walks are remembered by where the robot is to this many decimals: PyBullet normalises a base orientation given
#: again (a snapshot put back) a rounding error apart, and a pick-up missed every way its location had found
WALK_DIGITS = 12


@dataclass(frozen=True)
class Hit:
    """A part of the robot (a link, or an object it holds) inside something."""

    mover: str  # "l_forearm_link", or "the held milk"
    obstacle: Object
    link: str  # the obstacle's link
    depth: float  # how far inside (m)

    def __str__(self) -> str:
        where = f"{self.obstacle.name}" + (f" ({self.link})" if self.link != self.obstacle.name else "")
        return f"{self.mover} would be {self.depth * 1000:.0f} mm inside {where}"


def followers(body: Object) -> list[Object]:
    """Everything that follows the robot (attached to it, and what is attached to that)."""
    found: list[Object] = []
    frontier = [body]
    while frontier:
        parent = frontier.pop()
        for child, att in parent.attachments.items():
            if att.parent is parent and child is not body and child not in found:
                found.append(child)
                frontier.append(child)
    return found


def _rounded(value: Any, digits: int | None) -> Any:
    """Every float in nested tuples rounded to `digits` decimals, -0.0 as 0.0 (None: as it is)."""
    if digits is None or not isinstance(value, (float, tuple)):
        return value
    return round(value, digits) + 0.0 if isinstance(value, float) else tuple(_rounded(v, digits) for v in value)


class Motion:
    """The moving part of a robot for some joints (their links and what those hold) and the obstacles around it."""

    def __init__(self, robot: Robot, joints: Iterable[str], ignore: Iterable[Object] = (),
                 ignore_links: Iterable[tuple[Object, int]] = ()) -> None:
        self.robot = robot
        body = self.body = robot.body
        self.world = body.world
        self.joints = [body.joint(name) for name in joints if body.joint(name).movable]
        self._indices = [j.index for j in self.joints]
        self.links = sorted(body.links_below(j.name for j in self.joints))
        # what the moving links hold moves with them; what the robot holds elsewhere (in the other hand, or in
        # this gripper's palm while its fingers move) is something to avoid like anything else
        self.held = [obj for obj in followers(body) if self._holder(obj) in self.links]
        skip = {body, *self.held, *ignore}
        self.obstacles = [obj for obj in self.world.objects if obj not in skip]
        skip_links = set((obj.id, link) for obj, link in ignore_links)
        self._skip_links = frozenset(skip_links)
        # every obstacle link's box (kept by the objects while they do not change), but the links to ignore
        self._obstacle_boxes = [(obj, link) for obj in self.obstacles for link in range(-1, len(obj.joints))
                                if (obj.id, link) not in skip_links]
        los, his = zip(*(obj.link_aabbs() for obj in self.obstacles)) if self.obstacles else ((), ())
        keep = np.array([(obj.id, link) not in skip_links for obj in self.obstacles
                         for link in range(-1, len(obj.joints))], dtype=bool)
        self._o_lo = (np.concatenate(los) if los else np.zeros((0, 3)))[keep].reshape(-1, 3)
        self._o_hi = (np.concatenate(his) if his else np.zeros((0, 3)))[keep].reshape(-1, 3)
        self.allowed: dict[tuple[str, int, int], float] = {}
        #: how much deeper an existing contact may get: PENETRATION along a motion, next to nothing for an approach
        #: that stops at contact (fingers closing on an object they already touch stop there, not 1 mm further in)
        self.deepen = PENETRATION
        # each joint's axis in its link's frame (PyBullet gives it in the link's centre-of-mass frame)
        self._joint_axes = np.array([quat_to_matrix(j.inertial_frame[1]) @ np.asarray(j.axis, dtype=float)
                                     / (np.linalg.norm(j.axis) or 1.0) for j in self.joints]).reshape(-1, 3)
        self._prismatic = np.array([j.type == "prismatic" for j in self.joints], dtype=bool)
        self._parts_found: list[tuple[int, ...]] | None = None
        self._chain: list[int] | None = None  # the joints `_configuration` reads

    def situation(self, digits: int | None = None) -> tuple | None:
        """Everything a walk or search of this motion depends on, exactly: where the moving part is (the robot's base
        and the joints it hangs below, `_configuration`), what follows it (re-placed by its links at every step of a
        path: by configuration and how it is held), where every other object is (`Object.placement`: the same place
        however it got there), the moving joints and what may be touched. Equal situations give equal walks and
        searches, bitwise, so each is made once (`remembered`): a way tried again — a departure re-tried for each
        arrival in `paths.move_over`, the way a location test found, then moved along — costs a look-up. With
        `digits`, where the robot and what it holds are is rounded to that many decimals (a search's way, which the
        mover walks checked, serves a start a rounding error away). None where versions do not see every change (a
        GUI, real time) or in a private copy: nothing is remembered there."""
        world = self.world
        if not world.tracks_changes or world.is_copy:
            return None
        body = self.body
        attached = followers(body)
        placed = set(attached)
        return (body.id, _rounded(self._configuration(), digits), tuple(j.index for j in self.joints),
                tuple((obj.id, _rounded(obj.configuration(), digits),
                       tuple((other.id, att.parent_link, att.child_link, att.transform)
                             for other, att in obj.attachments.items()))
                      for obj in attached),
                tuple((obj.id, obj.placement()) for obj in self.obstacles if obj not in placed),
                self._skip_links)

    def _configuration(self) -> tuple:
        """What of the robot's configuration places the moving part, exactly: its base's pose and the joints the
        moving links hang below (their own, and those above them up to the base). The robot's other links are no
        obstacle (a motion checks against the world), so the head turned or the other arm moved since leaves a walk
        what it was: the pick-up's own test finds what the location test found at that pose before the look."""
        body = self.body
        if self._chain is None:
            chain: set[int] = set(self.links)
            for link in self.links:
                index = body.joints[link].parent_index
                while index != -1 and index not in chain:
                    chain.add(index)
                    index = body.joints[index].parent_index
            self._chain = sorted(chain)
        return tuple(self._chain), body.configuration(self._chain)

    def remembered(self, key: tuple | None) -> Any:
        """What was found for `key` (a situation and the question asked in it) in this world, or None."""
        if key is None:
            return None
        return self.world.cache.memo(MEMO, self.world, MEMO_SIZE).recall(key)

    def remember(self, key: tuple | None, answer: Any) -> None:
        if key is None:
            return
        self.world.cache.memo(MEMO, self.world, MEMO_SIZE).remember(key, answer)

    def _holder(self, obj: Object) -> int | None:
        """The robot link `obj` hangs from (through other held objects, if need be)."""
        seen = set()
        while obj not in seen:
            seen.add(obj)
            for parent, att in obj.attachments.items():
                if att.child is obj:
                    if parent is self.body:
                        return att.parent_link
                    obj = parent
                    break
            else:
                return None
        return None

    # -- where the moving part is -----------------------------------------------------------------
    def _mover_boxes(self) -> tuple[np.ndarray, np.ndarray]:
        rows = self.body.aabb_rows(self.links)
        if self.held:
            rows += [obj.get_aabb() for obj in self.held]
        boxes = np.array(rows, dtype=float).reshape(-1, 2, 3)  # one array for all (a check's hot path)
        return boxes[:, 0], boxes[:, 1]

    def _distance(self, k: int, o: int, within: float) -> float:
        """The distance between mover k and obstacle box o (negative: inside), inf when farther than `within`."""
        obj, link = self._obstacle_boxes[o]
        if k < len(self.links):
            return self.world.distance(self.body, obj, within, link_a=self.links[k], link_b=link)
        return self.world.distance(self.held[k - len(self.links)], obj, within, link_b=link)

    def _mover_name(self, k: int) -> str:
        if k < len(self.links):
            return self.body.get_link_name(self.links[k])
        return f"the held {self.held[k - len(self.links)].name}"

    def scan(self, boxes: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[float, list[Hit]]:
        """At the current configuration: a lower bound of the gap between the moving part and the obstacles (exact
        above SPACING; at or below it, some value at or below SPACING: all a path's checks need), and what the
        moving part is inside of (beyond PENETRATION and the allowed). `clearances` for each mover."""
        clear, hits = self.clearances(boxes)
        return (float(clear.min()) if len(clear) else math.inf), hits

    def clearances(self, boxes: tuple[np.ndarray, np.ndarray] | None = None,
                   rates: Pace | None = None) -> tuple[np.ndarray, list[Hit]]:
        """`scan` for each mover (the links, then the held objects): a lower bound of its gap to the obstacles, and
        what the moving part is inside of.

        Only boxes that overlap can hold parts inside each other (PyBullet's boxes enclose the shapes), so only
        their pairs are measured for hits. A pair whose boxes are apart (but nearer than NEAR) is measured only
        while it can still matter (the distance between two parts is never below the gap between their boxes, so
        a mover's bound is the smaller of what was measured and its nearest unmeasured pair's box gap):
        - without `rates`, for every mover, nearest boxes first, until its bound is at SPACING or exact;
        - with `rates` (a path's check: how far each mover's travel lets the path step, see `_follow` and
          `pace.py`), only the mover that limits the next step is measured further, until its bound is at SPACING
          or exact: the step the bounds allow is then the one exact clearances would allow, with fewer queries."""
        count = len(self.links) + len(self.held)
        if not count:
            return np.zeros(0), []
        m_lo, m_hi = boxes if boxes is not None else self._mover_boxes()
        if not len(self._o_lo):
            return np.full(count, math.inf), []
        # the gaps between the boxes, (movers, obstacle links), computed in place (a check's hot path)
        gap = np.subtract(self._o_lo[None, :, :], m_hi[:, None, :])
        np.maximum(gap, np.subtract(m_lo[:, None, :], self._o_hi[None, :, :]), out=gap)
        np.maximum(gap, 0.0, out=gap)
        np.multiply(gap, gap, out=gap)
        gaps = np.sqrt(np.sum(gap, axis=2))
        near = gaps < NEAR
        clear = np.min(gaps, axis=1, where=~near, initial=math.inf)
        if not near.any():
            return clear, []
        hits: dict[tuple[int, int, int], Hit] = {}
        lows = clear.tolist()  # plain floats for the loops below (numpy's scalars are slow one by one)
        for k, o in np.argwhere(gaps == 0.0).tolist():
            distance = self._distance(k, o, NEAR)
            lows[k] = min(lows[k], max(distance, 0.0) if distance < NEAR else NEAR)
            if distance >= 0.0:
                continue
            depth = -distance
            obj, link = self._obstacle_boxes[o]
            key = (self._mover_name(k), obj.id, link)
            if depth > max(PENETRATION, self.allowed.get(key, -math.inf) + self.deepen):
                hits[(k, obj.id, link)] = Hit(key[0], obj, obj.get_link_name(link), depth)
        found = sorted(hits.values(), key=lambda h: -h.depth)
        apart = np.where(near & (gaps > 0.0), gaps, math.inf)  # the near pairs whose boxes are apart
        return self._refined(np.array(lows), apart, rates), found

    def _refined(self, lows: np.ndarray, apart: np.ndarray, rates: Pace | None) -> np.ndarray:
        """Each mover's bound (see `clearances`): the smaller of what is known of it (`lows`) and its nearest
        unmeasured pair's box gap (`apart`, inf where there is none), pairs measured as far as they matter."""
        nearest = apart.min(axis=1)
        bound = np.minimum(lows, nearest)
        if rates is None:
            for k in range(len(lows)):
                while nearest[k] < lows[k] and lows[k] > SPACING:
                    self._measure(k, lows, apart, nearest, bound)
            return bound
        moving = rates.moving()
        while True:
            step = rates.steps(np.maximum(np.minimum(bound, 1.0), SPACING))
            k = int(np.argmin(step))
            if not moving[k] or nearest[k] >= lows[k] or lows[k] <= SPACING:
                return bound  # the mover that limits the step is measured as far as it matters
            # the clearance k needs to step as far as the next mover lets the path step: no farther is asked
            following = float(np.partition(step, 1)[1]) if len(step) > 1 else math.inf
            enough = max(rates.needed(following, k), SPACING)
            self._measure(k, lows, apart, nearest, bound, enough)

    def _measure(self, k: int, lows: np.ndarray, apart: np.ndarray, nearest: np.ndarray, bound: np.ndarray,
                 enough: float = math.inf) -> None:
        """Mover k's nearest unmeasured pair measured (`_refined`'s arrays updated), up to `enough`: farther than
        that it counts as `enough` (PyBullet's queries cost more the farther they look)."""
        o = int(np.argmin(apart[k]))
        apart[k, o] = math.inf
        within = min(float(lows[k]), NEAR, enough)
        distance = self._distance(k, o, within)  # inf: not nearer than `within`
        lows[k] = min(float(lows[k]), within if distance == math.inf else max(distance, 0.0))
        nearest[k] = apart[k].min()
        bound[k] = min(lows[k], nearest[k])

    def allow_current(self) -> None:
        """Contacts as they are now may stay (no deeper) along the motion."""
        self.allowed = {}
        if not len(self._o_lo) or (not self.links and not self.held):
            return
        m_lo, m_hi = self._mover_boxes()
        overlap = np.all((m_lo[:, None, :] <= self._o_hi[None, :, :] + PENETRATION)
                         & (self._o_lo[None, :, :] <= m_hi[:, None, :] + PENETRATION), axis=2)
        for k, o in np.argwhere(overlap):
            obj, link = self._obstacle_boxes[o][0], self._obstacle_boxes[o][1]
            if k < len(self.links):
                distance = self.world.distance(self.body, obj, 0.0, link_a=self.links[k], link_b=link)
            else:
                distance = self.world.distance(self.held[k - len(self.links)], obj, 0.0, link_b=link)
            if distance < 0.0:
                self.allowed[(self._mover_name(k), obj.id, link)] = -distance

    # -- paths --------------------------------------------------------------------------------------
    def _parts(self) -> list[tuple[int, ...]]:
        """For each mover (links, then held objects): the indices of the moving joints above it, outermost first
        (found once: the movers and their joints stay what they are for a motion)."""
        if self._parts_found is None:
            self._parts_found = self._find_parts()
        return self._parts_found

    def _find_parts(self) -> list[tuple[int, ...]]:
        body = self.body
        index_of = {j.index: i for i, j in enumerate(self.joints)}
        found = []
        for link in [*self.links, *(self._holder(obj) or -1 for obj in self.held)]:
            ancestors = []
            index = link
            while index != -1:
                if index in index_of:
                    ancestors.append(index_of[index])
                index = body.joints[index].parent_index
            found.append(tuple(reversed(ancestors)))
        return found

    def _axes(self) -> tuple[np.ndarray, np.ndarray]:
        """Each moving joint's axis in the world now: a point on it (its link's frame) and its unit direction."""
        poses = self.body.link_poses(self._indices)  # read at once (the same numbers as one by one)
        frames = [poses[index] for index in self._indices]
        origins = np.array([f[0] for f in frames], dtype=float).reshape(-1, 3)
        axes = np.einsum("nij,nj->ni", quats_to_matrices(np.array([f[1] for f in frames], dtype=float).reshape(-1, 4)),
                         self._joint_axes)
        return origins, axes

    def _local_levers(self, m_lo: np.ndarray, m_hi: np.ndarray, below: np.ndarray) -> np.ndarray:
        """rᵢₖ now, (joints, movers): the farthest corner of mover k's box from joint i's axis where k hangs below
        joint i (`below[i, k]`), else 0; 1 for a prismatic joint above it (`pace.levers`)."""
        return levers_of(corners(m_lo, m_hi), *self._axes(), self._prismatic, below)

    def _nesting(self) -> tuple[np.ndarray, np.ndarray]:
        """`below[i, k]`: mover k hangs below moving joint i; `inner[i, j]`: moving joint i hangs below joint j."""
        parts = self._parts()
        below = np.array([[i in ancestors for ancestors in parts] for i in range(len(self.joints))], dtype=bool)
        pairs = {(i, j) for ancestors in set(parts) for position, i in enumerate(ancestors) for j in ancestors[:position]}
        inner = np.zeros((len(self.joints), len(self.joints)), dtype=bool)
        if pairs:
            rows, columns = zip(*pairs)
            inner[list(rows), list(columns)] = True
        return below.reshape(len(self.joints), len(parts)), inner

    def _levers(self) -> np.ndarray:
        """rᵢ for each moving joint: how far a point of the moving part can be from joint i (1 for a prismatic joint)."""
        body = self.body
        origins = np.array([body.get_link_position(j.index) for j in self.joints], dtype=float).reshape(-1, 3)
        levers = np.zeros(len(self.joints))
        parts = self._parts()
        if not any(parts):
            return levers
        points = corners(*self._mover_boxes())  # (movers, 8, 3)
        # the farthest corner of each mover from each joint's origin, and the joints' origins from each other
        far = np.sqrt(np.sum((points[:, None, :, :] - origins[None, :, None, :]) ** 2, axis=3)).max(axis=2).tolist()
        apart = np.sqrt(np.sum((origins[:, None, :] - origins[None, :, :]) ** 2, axis=2)).tolist()
        prismatic = self._prismatic.tolist()
        for k, ancestors in enumerate(parts):  # the moving joints above mover k, outermost first
            if not ancestors:
                continue
            reach = far[k][ancestors[-1]]
            for position in range(len(ancestors) - 1, -1, -1):
                i = ancestors[position]
                if position < len(ancestors) - 1:
                    reach += apart[ancestors[position + 1]][i]
                levers[i] = max(levers[i], 1.0 if prismatic[i] else reach)
        return levers

    def _prune(self, levers: np.ndarray) -> None:
        """Forget obstacle boxes the moving part cannot come near: farther from each outermost moving joint than the
        part reaches from it."""
        if not len(self._o_lo) or not self.joints:
            return
        roots = {ancestors[0] for ancestors in self._parts() if ancestors}
        keep = np.zeros(len(self._o_lo), dtype=bool)
        for i in roots:
            centre = np.asarray(self.body.get_link_position(self.joints[i].index))
            gap = np.maximum(0.0, np.maximum(self._o_lo - centre, centre - self._o_hi))
            keep |= np.sqrt(np.sum(gap * gap, axis=1)) <= levers[i] + SPACING
        self._obstacle_boxes = [b for b, k in zip(self._obstacle_boxes, keep) if k]
        self._o_lo, self._o_hi = self._o_lo[keep], self._o_hi[keep]

    def _endpoints(self, goal: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
        names = [j.name for j in self.joints]
        current = self.body.get_joint_positions(names)
        start = np.array([current[n] for n in names])
        end = np.array([float(goal.get(n, current[n])) for n in names])
        return start, short_way(self.body, names, start, end)

    def _put(self, values: np.ndarray) -> None:
        self.body.reset_joint_indices(self._indices, values)
        self.body.move_attached()

    def walk(self, goal: Mapping[str, float], stop_at_contact: bool = False) -> tuple[float, list[Hit], dict[str, float]]:
        """Follow the path from the current values to `goal`, checking as described above, and put the joints back.

        Returns the fraction of the path that is free (1.0: all of it), the hits where it ends otherwise, and the
        joint values at its free end (with `stop_at_contact`, found within PRECISION of the first hit).
        """
        start, end = self._endpoints(goal)
        names = [j.name for j in self.joints]
        if not len(start):
            return 1.0, [], {}
        situation = self.situation(WALK_DIGITS)
        key = None if situation is None else (situation, "walk", start.tobytes(), end.tobytes(), stop_at_contact)
        known = self.remembered(key)
        if known is not None:
            self._put(start)  # as a walk leaves it: the joints put back, what they hold placed by them
            return known[0], list(known[1]), dict(known[2])
        self._prune(self._levers())
        self.allow_current()
        self.deepen = STILL if stop_at_contact else PENETRATION
        last_free, hits = self._follow(start, end, stop_at_contact)
        reached = start + last_free * (end - start)
        answer = (1.0 if not hits else last_free), hits, {n: float(v) for n, v in zip(names, reached)}
        self.remember(key, (answer[0], list(hits), dict(answer[2])))
        return answer

    def _follow(self, start: np.ndarray, end: np.ndarray, stop_at_contact: bool = False) -> tuple[float, list[Hit]]:
        """The checks of `walk` along the straight path from `start` to `end` (the joints are put back at `start`):
        how far it is free (a fraction) and what ends it."""
        below, inner = self._nesting()
        delta = end - start
        size = np.abs(delta)
        # how much of each mover's lever bound each joint's change adds per unit of travel of the mover (see below)
        weights = (below * size[:, None]).sum(axis=0)
        t, last_free = 0.0, 0.0
        hits: list[Hit] = []
        total = 0.0
        levers, since = None, np.zeros(below.shape[1])
        pacer = Pacer(delta, self._prismatic, below, inner)
        try:
            while True:
                self._put(start + t * delta)
                boxes = self._mover_boxes()
                if stop_at_contact:
                    # an approach keeps the lever bound alone (pace.py): its levers are inflated by each mover's
                    # travel since they were measured (`since`) and measured afresh every LEVER_REFRESH of travel
                    if levers is None or since.max() > LEVER_REFRESH:
                        levers, since = self._local_levers(*boxes, below), np.zeros(below.shape[1])
                    rates = Pace.of_levers(size @ levers + since * weights, weights)
                else:  # no part travels farther than the better of the lever and the Jacobian bound (pace.py)
                    rates = pacer.at(corners(*boxes), *self._axes())
                clear, hits = self.clearances(boxes, rates)
                if hits:
                    break
                last_free = t
                if t >= 1.0:
                    break
                travel = np.maximum(np.minimum(clear, 1.0), SPACING)
                step = float(rates.steps(travel).min())
                if not math.isfinite(step):  # nothing moves
                    t = 1.0
                    continue
                speeds = rates.rates(travel)
                total = max(total, float(speeds.max()))
                since += speeds * min(step, 1.0 - t)
                t = min(1.0, t + step)
            if hits and stop_at_contact:
                last_free = self._contact(start, delta, last_free, t, total)
        finally:
            self._put(start)
        return last_free, hits

    def _contact(self, start: np.ndarray, delta: np.ndarray, low: float, high: float, rate: float) -> float:
        """The last free point of the path before its first contact, which lies between `low` (free) and `high`
        (not), found within PRECISION of travel (no part moves faster than `rate` per unit of the path)."""
        while (high - low) * rate > PRECISION:
            mid = (low + high) / 2.0
            self._put(start + mid * delta)
            if self.scan()[1]:
                high = mid
            else:
                low = mid
        return low


def short_way(body: Object, names: Sequence[str], start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """`end` with each continuous joint's value moved by whole turns to within half a turn of `start`: a path from
    `start` to it turns the short way."""
    end = np.array(end, dtype=float)
    for i, name in enumerate(names):
        if body.joint(name).type == "continuous":
            end[i] = start[i] + math.remainder(end[i] - start[i], 2 * math.pi)
    return end


def joints_of(robot: Robot, arms: Iterable[str], gripper: bool = False) -> list[str]:
    """The joints of some arms (or of their grippers) as the description names them."""
    names: list[str] = []
    for arm in arms:
        desc = robot.description.arm(arm)
        names += list(desc.gripper.joints if gripper else desc.joints)
    return names


def _moving(robot: Robot, goal: Mapping[str, float]) -> list[str]:
    """The joints of `goal` that are not already there (an arm that stays put is no part of the motion)."""
    current = robot.body.get_joint_positions(list(goal))
    return [name for name, value in goal.items() if abs(math.remainder(value - current[name], 2 * math.pi)
                                                         if robot.body.joint(name).type == "continuous"
                                                         else value - current[name]) > 1e-12]


def hits_at(robot: Robot, joints: Mapping[str, float], ignore: Iterable[Object] = ()) -> list[Hit]:
    """What the part of the robot below these joints (and what it holds) would be inside with the joints at these
    values (then put back): a quick check of a goal before the path to it."""
    motion = Motion(robot, joints, ignore)
    start, end = motion._endpoints(joints)
    try:
        motion._put(end)
        return motion.scan()[1]
    finally:
        motion._put(start)


def hits_at_goal(robot: Robot, goal: Mapping[str, float], ignore: Iterable[Object] = ()) -> list[Hit]:
    """What the moving part would be inside at `goal` (then put back), contacts that exist now allowed as a motion
    allows them: a goal with hits is reached by no path, so no search for one is worth its time."""
    motion = Motion(robot, _moving(robot, goal), ignore)
    start, end = motion._endpoints(goal)
    motion.allow_current()
    try:
        motion._put(end)
        return motion.scan()[1]
    finally:
        motion._put(start)


def move(robot: Robot, goal: Mapping[str, float], what: str, ignore: Iterable[Object] = (),
         ignore_links: Iterable[tuple[Object, int]] = ()) -> None:
    """Move joints to `goal` if the path is free (held objects follow); else raise a ManipulationFailure naming the
    first thing in the way, and leave everything where it was. `ignore`/`ignore_links`: what the motion may touch
    (a drawer's moving part while the hand pulls it)."""
    motion = Motion(robot, _moving(robot, goal), ignore, ignore_links)
    fraction, hits, reached = motion.walk(goal)
    if hits:
        raise collision_failure(what, hits, fraction)
    robot.body.set_joint_positions({**goal, **reached})  # continuous joints as turned (the short way)


def hits_on_way(robot: Robot, goal: Mapping[str, float], ignore: Iterable[Object] = (),
                ignore_links: Iterable[tuple[Object, int]] = ()) -> list[Hit]:
    """What `move` to `goal` would run into (nothing: the path is free), without moving: for planners that must
    know a motion will succeed before it is made."""
    return Motion(robot, _moving(robot, goal), ignore, ignore_links).walk(goal)[1]


def advance(robot: Robot, goal: Mapping[str, float], ignore: Iterable[Object] = ()) -> tuple[float, list[Hit]]:
    """Move joints towards `goal` until just before the first contact (or all the way); returns the fraction of the
    path travelled and what stopped it."""
    motion = Motion(robot, _moving(robot, goal), ignore)
    fraction, hits, reached = motion.walk(goal, stop_at_contact=True)
    robot.body.set_joint_positions(reached)
    return fraction, hits


def collision_failure(what: str, hits: Sequence[Hit], fraction: float, at_goal: bool = False) -> ManipulationFailure:
    """The failure of a motion whose path is blocked `fraction` of the way (`at_goal`: whose goal itself is)."""
    hit = hits[0]
    others = sorted({h.obstacle.name for h in hits[1:]} - {hit.obstacle.name})
    also = f" (and {', '.join(others)})" if others else ""
    where = "at its goal: no way leads there" if at_goal else f"{fraction:.0%} of the way"
    return ManipulationFailure(f"{what} would collide: {hit}{also}, {where}",
                               colliding=[hit.obstacle.name, *others], link=hit.link, part=hit.mover,
                               depth=round(hit.depth, 4))
