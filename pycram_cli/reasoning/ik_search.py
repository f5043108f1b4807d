"""The search behind reasoning/ik.py: Levenberg–Marquardt on our own kinematic chain, every seed at once.

    (JᵀJ + (½‖e‖² + λ₀) I) Δq = Jᵀe

with joint limits enforced by clamping. `Problem` is the chain's forward kinematics and Jacobian over the joints
that move (batched over configurations); `search_groups` runs the search for several groups of seeds together and
yields each group's answer as the group finishes, so that the caller (ik.py, which judges the answers with
PyBullet's forward kinematics and keeps them) stops it when it has what it needs. Split from ik.py by job: this
module only computes, ik.py asks and remembers.
"""
from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING

import numpy as np

from .kinematics import Chain, kinematics_of, transform

if TYPE_CHECKING:
    from ..world import Object

#: weight of one radian of orientation error against one metre of position error
ORIENTATION_WEIGHT = 0.25
#: stop iterating once the tool is this close (much tighter than any success threshold)
CONVERGED_POSITION = 2e-5
CONVERGED_ANGLE = 2e-4
#: what the reach bound leaves to spare (m): PyBullet's forward kinematics, which judge an answer, and ours differ by
#: about 1e-7 m
REACH_SLACK = 1e-4
SEED = 20190923

class Problem:
    """Forward kinematics and Jacobian of the tool frame over the variable joints only.

    Everything is batched over a set of configurations (one per restart), so all the
    restarts advance together for the price of about one. Arrays of every joint's frames
    are laid out joint-major ((n, S, ...)), so that each joint's slice is contiguous.
    """

    def __init__(self, robot: Object, chain: Chain, variable: Sequence[str]) -> None:
        kin = kinematics_of(chain, variable)
        base_pos, base_orn = robot.get_com_pose()  # the chain starts at the base's centre of mass
        current = robot.get_joint_positions(kin.read) if kin.read else {}
        layout = self.layout = kin.layout(current)
        lead, self._after, self._turned, self._turned2 = layout.lead, layout.after, layout.turned, layout.turned2
        #: what of the robot's state the answers depend on, besides the base's pose: the chain's joint values (an
        #: answer is the same for the same question asked in the chain's own frame, `in_chain_frame`)
        self.state = tuple(current[name] for name in kin.read)
        start = transform(base_pos, base_orn)
        for factor in lead:
            start = start @ factor
        self.start = start  # the first variable joint's frame in the world, before its motion
        self.names = kin.names
        self.revolute = [bool(r) for r in kin.rev]
        self.current = np.array([current[n] for n in self.names])
        self.lo, self.hi, self.rev = kin.lo, kin.hi, kin.rev
        self._axes = kin.axes
        self._axes_col = kin.axes[:, None, :, None]  # (n,1,3,1): each joint's axis, for every configuration
        self._prismatic = kin.prismatic
        self._all_revolute = kin.all_revolute
        self._buffers: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # per number of configurations

    def in_chain_frame(self, target: np.ndarray, rotation: np.ndarray | None) -> tuple[bytes, bytes | None]:
        """A target (position, rotation matrix) in the first variable joint's frame before its motion, rounded to
        1e-6 (m, and of the matrix's entries), as bytes: the search and its answer depend on the target only so, so
        that the same question asked with the base somewhere else (a location's next candidate pose: the arm's ways
        from where it is) is the same question. The rounding makes one key of the same target reached through two
        base poses: PyBullet's link poses, from which such targets are computed, agree there to about 1e-7 only."""
        turn, origin = self.start[:3, :3], self.start[:3, 3]
        local = np.round(turn.T @ (target - origin), 6) + 0.0  # + 0.0: no -0.0, whose bytes differ
        if rotation is None:
            return local.tobytes(), None
        return local.tobytes(), (np.round(turn.T @ rotation, 6) + 0.0).tobytes()

    def beyond_reach(self, target: np.ndarray, rotation: np.ndarray | None, threshold: float,
                     angle_threshold: float) -> float:
        """How far (m) the target lies beyond anything the joints can reach within the thresholds (≤ 0: it may be
        reachable). Without an orientation, the tool can come no nearer the first variable joint's origin than
        `reach`; with one, the tool's pose fixes where the last variable joint's origin must be (within the
        thresholds), which can be no farther from the first's than `wrist_reach`. A necessary condition only, with
        REACH_SLACK to spare for PyBullet's forward kinematics (which decide success) against ours."""
        origin = self.start[:3, 3]
        layout = self.layout
        if rotation is None:
            return float(np.linalg.norm(target - origin)) - layout.reach - threshold - REACH_SLACK
        wrist = target + rotation @ layout.wrist
        return float(np.linalg.norm(wrist - origin)) - layout.wrist_reach - threshold \
            - angle_threshold * layout.lever - REACH_SLACK

    def _buffers_for(self, count: int) -> tuple[np.ndarray, np.ndarray]:
        found = self._buffers.get(count)
        if found is None:
            n = len(self.names)
            steps = np.zeros((n, count, 4, 4))
            steps[:, :, 3, 3] = 1.0
            frames = np.empty((n + 1, count, 4, 4))
            frames[0] = self.start
            found = self._buffers[count] = (steps, frames)
        return found

    def forward(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Tool poses (S,4,4) for configurations q (S,n), with the world origin and axis of every joint (n,S,3)."""
        count, n = q.shape
        steps, frames = self._buffers_for(count)
        # each joint's motion times the constant transform after it, all at once: R·A = A + sin·K·A + (1 - cos)·K²·A
        qt = q.T[:, :, None, None]
        if self._all_revolute:
            sin, versin = np.sin(qt), 1.0 - np.cos(qt)
        else:
            rev = self.rev[:, None, None, None]
            sin, versin = np.where(rev, np.sin(qt), 0.0), np.where(rev, 1.0 - np.cos(qt), 0.0)
        top = steps[:, :, :3, :]
        np.multiply(sin, self._turned[:, None], out=top)
        top += versin * self._turned2[:, None]
        top += self._after[:, None, :3, :]
        for i in self._prismatic:  # a shift along the axis: the transform after it moves with it
            steps[i, :, :3, 3] += q[:, i:i + 1] * self._axes[i]
        for i in range(n):
            np.matmul(frames[i], steps[i], out=frames[i + 1])
        joints = frames[:n]
        axes = (joints[:, :, :3, :3] @ self._axes_col)[..., 0]
        return frames[n].copy(), joints[:, :, :3, 3], axes

    def jacobian_t(self, tool: np.ndarray, origins: np.ndarray, axes: np.ndarray, weight: float | None) -> np.ndarray:
        """The transposed Jacobian (S,n,3) or, with an orientation `weight`, (S,n,6): per joint, the tool's linear
        velocity (axis × lever for a revolute joint, the axis for a prismatic one), then its weighted angular one."""
        n, count, _ = origins.shape
        lever = tool[None, :, :3, 3] - origins
        out = np.empty((count, n, 3 if weight is None else 6))
        joint_major = out.transpose(1, 0, 2)
        linear = joint_major[:, :, :3]
        np.subtract(axes[:, :, _NEXT] * lever[:, :, _AFTER], axes[:, :, _AFTER] * lever[:, :, _NEXT], out=linear)
        if weight is not None:
            np.multiply(axes, weight, out=joint_major[:, :, 3:])
        for i in self._prismatic:
            linear[i] = axes[i]
            if weight is not None:
                joint_major[i, :, 3:] = 0.0
        return out


_NEXT = np.array([1, 2, 0])
_AFTER = np.array([2, 0, 1])
_V_PLUS = np.array([7, 2, 3])  # r21, r02, r10 of a flattened 3×3
_V_MINUS = np.array([5, 6, 1])  # r12, r20, r01
_DIAGONAL = np.array([0, 4, 8])


def rotation_errors(target: np.ndarray, current: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotation vectors (S,3), world frame, that turn each `current` (S,3,3) into `target` (3,3) (or (S,3,3)), and
    their angles (S,): the vectors' lengths."""
    r = target @ current.transpose(0, 2, 1)
    flat = r.reshape(len(r), 9)
    cos = np.minimum(np.maximum((flat[:, _DIAGONAL].sum(axis=1) - 1.0) / 2.0, -1.0), 1.0)  # from the trace
    angle = np.arccos(cos)
    v = flat[:, _V_PLUS] - flat[:, _V_MINUS]  # (r21 - r12, r02 - r20, r10 - r01): 2 sin(angle) times the axis
    sin = np.sin(angle)
    if sin.min() > 1e-6:  # every angle well inside (0, pi)
        return v * (angle / (2.0 * sin))[:, None], angle
    small = angle < 1e-9
    regular = ~small & (sin > 1e-6)
    scale = np.where(small, 0.5, angle / (2.0 * np.where(regular, sin, 1.0)))
    out = v * scale[:, None]
    for k in np.flatnonzero(~small & ~regular):  # angle close to pi: the axis is the column of (r + I) with the largest norm
        m = r[k] + np.eye(3)
        col = m[:, int(np.argmax(np.linalg.norm(m, axis=0)))]
        out[k] = col / np.linalg.norm(col) * angle[k]
    return out, angle


def rotation_angle(target: np.ndarray, current: np.ndarray) -> float:
    """The angle (rad) between two rotation matrices (3,3)."""
    r = target @ current.T
    return math.acos(max(-1.0, min(1.0, (r[0, 0] + r[1, 1] + r[2, 2] - 1.0) / 2.0)))


def initial_seeds(problem: Problem, count: int, current: np.ndarray | None, fixed: dict[tuple, np.ndarray]) -> np.ndarray:
    """Deterministic starting points: where the arm is (or `current`), the middle of its range, then fixed
    pseudo-random ones. Those after the first are the same for every search of the same joint ranges, so they are made
    once and kept in `fixed` (the robot's table in the world's cache: drawing them cost as much as an iteration)."""
    first = np.clip((problem.current if current is None else current)[None, :], problem.lo, problem.hi)
    if count <= 1:
        return first
    key = (problem.lo.tobytes(), problem.hi.tobytes(), count)
    rest = fixed.get(key)
    if rest is None:
        lo = np.where(np.isfinite(problem.lo), problem.lo, -math.pi)
        hi = np.where(np.isfinite(problem.hi), problem.hi, math.pi)
        seeds = [(lo + hi) / 2.0]
        rng = np.random.default_rng(SEED)
        while len(seeds) < count - 1:
            seeds.append(lo + rng.random(len(lo)) * (hi - lo))
        rest = fixed[key] = np.clip(np.array(seeds), problem.lo, problem.hi)
        rest.flags.writeable = False
    return np.concatenate([first, rest])


#: a group's answer: its joint values, position error and angle error (None without an orientation)
Found = tuple[np.ndarray, float, "float | None"]


class _GroupSearch:
    """The state of one batched search: every seed's configuration, its best so far and whether it still improves,
    which group each seed belongs to and which groups are still pending. Seeds only finished groups had are dropped
    (`drop_finished`); the others' steps are unchanged by that, so each group's answer is what a search of its seeds
    alone gives."""

    def __init__(self, problem: Problem, seeds: np.ndarray, groups: Sequence[np.ndarray], target_pos: np.ndarray,
                 target_rot: np.ndarray | None, threshold: float, angle_threshold: float) -> None:
        self.problem = problem
        self.q = seeds.copy()
        self.count, self.n = self.q.shape
        self.best = np.full((self.count, 3), np.inf)  # per seed, the best so far: weighted cost, position, angle error
        self.best_q = self.q.copy()
        self.history: list[np.ndarray] = []  # the best costs, per iteration
        self.active = np.ones(self.count, dtype=bool)
        self.todo = list(range(len(groups)))
        self.groups = [np.asarray(idx) for idx in groups]  # renumbered as the seeds of finished groups are dropped
        self.member = np.zeros((len(groups), self.count), dtype=bool)  # member[g, s]: seed s is one of group g's
        for g, idx in enumerate(self.groups):
            self.member[g, idx] = True
        self.pending = np.ones(len(groups), dtype=bool)
        self.target_pos, self.target_rot = target_pos, target_rot
        self.per_seed_target = target_pos.ndim == 2
        self.oriented = target_rot is not None
        self.threshold, self.angle_threshold = threshold, angle_threshold
        self.converged_below = np.array([CONVERGED_POSITION, CONVERGED_ANGLE])
        self.good_below = np.array([threshold * 0.5, angle_threshold * 0.5])
        self.rows = 6 if self.oriented else 3

    def measure(self) -> None:
        """Every seed's tool pose and weighted error (`e`: position, then ORIENTATION_WEIGHT × rotation vector) and
        `now`: cost, position error, angle error."""
        self.tool, self.origins, self.axes = self.problem.forward(self.q)
        e = self.e = np.empty((self.count, self.rows))
        dp = np.subtract(self.target_pos, self.tool[:, :3, 3], out=e[:, :3])
        now = self.now = np.zeros((self.count, 3))
        np.sqrt(np.einsum("ij,ij->i", dp, dp), out=now[:, 1])
        if self.target_rot is not None:
            dr, now[:, 2] = rotation_errors(self.target_rot, self.tool[:, :3, :3])
            np.multiply(dr, ORIENTATION_WEIGHT, out=e[:, 3:])
        np.einsum("ij,ij->i", e, e, out=now[:, 0])

    def finished(self) -> np.ndarray:
        """Keep each seed's best; the pending groups done now: one of their seeds converged, or (after 8 iterations,
        stalled) one is good enough or none still improves."""
        better = self.now[:, 0] < self.best[:, 0]
        self.best = best = np.where(better[:, None], self.now, self.best)  # a new array: `history` keeps its costs
        np.copyto(self.best_q, self.q, where=better[:, None])
        converged = (best[:, 1:] < self.converged_below).all(axis=1)
        history = self.history
        history.append(best[:, 0])
        done = (self.member & converged).any(axis=1)
        if len(history) > 8:
            self.active &= history[-1] < 0.98 * history[-9]
            # a seed already within the thresholds that stopped improving is good enough
            good = (best[:, 1:] <= self.good_below).all(axis=1) & ~self.active
            done |= (self.member & good).any(axis=1) | ~(self.member & self.active).any(axis=1)
        return np.flatnonzero(done & self.pending)

    def finish(self, g: int) -> Found:
        """Group g's answer: the first of its seeds (in seed order) that converged, else the best within the
        thresholds, else the one with the smallest weighted error."""
        idx = self.groups[g]
        cost, pos, ang = self.best[idx, 0], self.best[idx, 1], self.best[idx, 2]
        converged = (pos < CONVERGED_POSITION) & (ang < CONVERGED_ANGLE)
        within = (pos <= self.threshold) & (ang <= (self.angle_threshold if self.oriented else np.inf))
        if converged.any():
            pick = int(np.argmax(converged))
        else:
            pick = int(np.argmin(np.where(within, cost, np.inf))) if within.any() else int(np.argmin(cost))
        self.todo.remove(g)
        self.pending[g] = False
        return self.best_q[idx[pick]].copy(), float(pos[pick]), float(ang[pick]) if self.oriented else None

    def drop_finished(self) -> None:
        """Search the seeds only finished groups had no further (the others' steps are the same without them)."""
        keep = np.flatnonzero(self.member[self.pending].any(axis=0))
        if len(keep) == self.count:
            return
        renumber = np.full(self.count, -1)
        renumber[keep] = np.arange(len(keep))
        self.groups = [renumber[idx] if self.pending[g] else idx for g, idx in enumerate(self.groups)]
        self.member = self.member[:, keep]
        self.q, self.best_q, self.best, self.active = self.q[keep], self.best_q[keep], self.best[keep], self.active[keep]
        self.now, self.e = self.now[keep], self.e[keep]
        self.tool, self.origins, self.axes = self.tool[keep], self.origins[:, keep], self.axes[:, keep]
        self.history = [h[keep] for h in self.history]
        if self.per_seed_target:
            self.target_pos = self.target_pos[keep]
            self.target_rot = self.target_rot[keep] if self.target_rot is not None else None
        self.count = len(keep)

    def step(self) -> None:
        """One damped least-squares step of every seed, clamped to the joint limits."""
        count, n = self.count, self.n
        jt = self.problem.jacobian_t(self.tool, self.origins, self.axes,
                                     ORIENTATION_WEIGHT if self.oriented else None)  # (S,n,rows)
        lhs = jt @ jt.transpose(0, 2, 1)
        lhs.reshape(count, n * n)[:, slice(None, None, n + 1)] += (0.5 * self.now[:, 0] + 1e-4)[:, None]  # damping
        step = np.linalg.solve(lhs, jt @ self.e[:, :, None])[:, :, 0]
        self.q = np.minimum(np.maximum(self.q + step, self.problem.lo), self.problem.hi)


def search_groups(problem: Problem, seeds: np.ndarray, groups: Sequence[np.ndarray], target_pos: np.ndarray,
                  target_rot: np.ndarray | None, threshold: float, angle_threshold: float,
                  iterations: int) -> Iterator[tuple[int, Found]]:
    """Levenberg–Marquardt from every seed at once, for several groups of seeds (rows of `seeds`), yielding `(g,
    found)` as each group g finishes: when one of its seeds converged or all stalled (`_GroupSearch.finish` says which
    answer). Every seed's iterations are independent of the others' (only when to stop depends on the group), so each
    group's answer is exactly what a search of its seeds alone gives, for the price of about one search. The targets
    may be one for all (`target_pos` (3,), `target_rot` (3,3)) or one per seed ((S,3), (S,3,3)). The caller stops the
    search by no longer asking (break)."""
    search = _GroupSearch(problem, seeds, groups, target_pos, target_rot, threshold, angle_threshold)
    for _ in range(iterations + 1):
        search.measure()
        finished = search.finished()
        for row in finished:
            yield int(row), search.finish(int(row))
        if not search.todo:
            return
        if len(finished):
            search.drop_finished()
        search.step()
    for g in list(search.todo):
        yield g, search.finish(g)
