"""How far each moving part of a robot can travel over a step of a straight joint-space path: the spacing of checks.

A path q(t) = q₀ + t·Δq (t from 0 to 1) is checked at some values of t; between two checks each moving part (a
mover: a link, or an object it holds) may travel at most its clearance T, so that it cannot pass into anything in
between (`motion.py`). This module bounds a mover's travel over a step of length h from where the step starts, in
two ways, and a step is as long as the better of the two allows (both hold, so the smaller bound does).

*The lever bound.* A point p of mover k moves at ‖ṗ‖ ≤ Σᵢ |Δqᵢ|·rᵢₖ per unit of t, summed over the moving joints
i above k, where rᵢₖ is p's distance from joint i's axis (1 for a prismatic joint). That distance changes only as
the joints below i move p, so by no more than p's own travel: while p travels at most T, rᵢₖ ≤ rᵢₖ(0) + T, where
rᵢₖ(0), the lever, is the farthest corner of k's box from the axis (the farthest point of a box from a line is a
corner). So travel(h) ≤ h·(base + T·weight) with base = Σᵢ |Δqᵢ|·rᵢₖ(0), weight = Σᵢ |Δqᵢ|.

*The pace bound.* The lever bound adds up every joint's contribution as if all pushed the same way; they seldom
do (a shoulder and an elbow turning against each other move the hand far less than either alone). The velocity
of p is ṗ = Σᵢ Δqᵢ·wᵢ(p), wᵢ = aᵢ × (p − oᵢ) for a revolute joint with unit axis aᵢ through oᵢ, wᵢ = aᵢ for a
prismatic one: the Jacobian of p times Δq. Where the step starts it is affine in p (a rigid motion), so its
length is convex in p and largest at a corner of k's box, which holds every point of k: `speed`, the largest
‖J(c)·Δq‖ over the 8 corners c, bounds ‖ṗ(0)‖ for every point of k. Over the step the Jacobian changes; in the
frame of joint i's child link aᵢ and oᵢ are fixed, so wᵢ changes only (1) as that frame turns, by an angle of at
most u·Θᵢ after u of the step, Θᵢ = Σ |Δqⱼ| over the revolute joints j at or above i (angles of composed
rotations add at most; a vector of length ‖wᵢ‖ ≤ rᵢₖ(0) turned by θ moves by at most θ·‖wᵢ‖), and (2) as p moves
in that frame, which only the joints below i do, at most u·Λᵢ far, Λᵢ = Σ |Δqⱼ|·(rⱼₖ(0) + T) over the moving
joints j below i and above k (‖a × d‖ ≤ ‖d‖; prismatic joints: wᵢ = aᵢ only turns). So ‖ṗ(u) − ṗ(0)‖ ≤ u·A,
A = Σᵢ |Δqᵢ|·(Θᵢ·rᵢₖ(0) + Λᵢ) = curve + T·bend, and travel(h) ≤ ∫₀ʰ (speed + u·A) du = h·speed + h²·A/2.

Both bounds assume that p has travelled at most T (the levers grown by T); the step h chosen makes the bound T at
h, and a bound that grows with h keeps the travel within T until h, so the assumption holds all the way (were
it broken first at some u < h, the bound there, below T, would contradict it). Nothing here reads the world:
`motion.Motion` gives the boxes, the joints' frames and which joints are above which mover.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the 8 corners of a box from its (lo, hi) pair: where each coordinate comes from the high corner
_CORNER_BITS = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=bool)


def corners(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The 8 corners of each box, (boxes, 8, 3), from the boxes' low and high corners, (boxes, 3) each."""
    return np.where(_CORNER_BITS[None, :, :], hi[:, None, :], lo[:, None, :])


def _farthest(points: np.ndarray, origins: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """(joints, movers): the farthest of each mover's corners from each joint's axis (few numpy calls: hot path)."""
    rel = points.reshape(1, -1, 3) - origins[:, None, :]  # (joints, movers · 8, 3)
    along = np.matmul(rel, axes[:, :, None])[:, :, 0]
    square = np.einsum("nkd,nkd->nk", rel, rel)
    return np.sqrt(np.maximum(square - along * along, 0.0).reshape(len(origins), -1, 8).max(axis=2))


def levers(points: np.ndarray, origins: np.ndarray, axes: np.ndarray, prismatic: np.ndarray,
           below: np.ndarray) -> np.ndarray:
    """rᵢₖ, (joints, movers): the farthest corner of mover k's box (`points`, from `corners`) from joint i's axis
    (through `origins[i]` along the unit `axes[i]`) where k hangs below joint i (`below[i, k]`), else 0; 1 for a
    prismatic joint above it."""
    return np.where(below, np.where(prismatic[:, None], 1.0, _farthest(points, origins, axes)), 0.0)


@dataclass(frozen=True)
class Pace:
    """For each mover, bounds of its travel over a step of h (a fraction of the path) from where it is now, given
    that it travels at most T: h·(base + T·weight) (levers) and h·speed + h²·(curve + T·bend)/2 (Jacobian)."""

    base: np.ndarray
    weight: np.ndarray
    speed: np.ndarray
    curve: np.ndarray
    bend: np.ndarray

    @staticmethod
    def of_levers(base: np.ndarray, weight: np.ndarray) -> Pace:
        """The lever bound alone (the pace bound never the better one)."""
        endless = np.full(len(base), math.inf)
        return Pace(base, weight, endless, endless, np.zeros(len(base)))

    def moving(self) -> np.ndarray:
        """Which movers move at all along the path."""
        return (self.base + self.weight) > 0.0

    def rates(self, travel: np.ndarray) -> np.ndarray:
        """The lever bound of each mover's speed (travel per unit of the path) while it travels at most `travel`."""
        return self.base + travel * self.weight

    def steps(self, travel: np.ndarray) -> np.ndarray:
        """The longest step (fraction of the path) after which each mover has travelled at most `travel` (inf for
        a mover that does not move)."""
        moving = self.moving()
        lever = np.divide(travel, self.rates(travel), out=np.full(len(travel), math.inf), where=moving)
        # h·speed + h²·bend/2 = travel, solved for h (written so that bend = 0 gives travel / speed; an endless speed,
        # the levers alone, gives 0)
        bend = self.curve + travel * self.bend
        below = self.speed + np.sqrt(self.speed * self.speed + 2.0 * bend * travel)
        jacobian = np.divide(2.0 * travel, below, out=np.full(len(travel), math.inf), where=below > 0.0)
        return np.where(moving, np.maximum(lever, jacobian), math.inf)

    def needed(self, step: float, k: int) -> float:
        """The travel mover k must be allowed for a step of `step` (inf: none is enough): `steps` inverted."""
        if not math.isfinite(step):  # no other mover limits the path (inf · 0 below would be NaN)
            return math.inf
        lever = math.inf
        if step * self.weight[k] < 1.0:
            lever = step * float(self.base[k]) / (1.0 - step * float(self.weight[k]))
        jacobian = math.inf
        if math.isfinite(self.speed[k]) and step * step * self.bend[k] < 2.0:
            jacobian = ((step * float(self.speed[k]) + step * step * float(self.curve[k]) / 2.0)
                        / (1.0 - step * step * float(self.bend[k]) / 2.0))
        return min(lever, jacobian)


#: [a]× = a @ _SKEW reshaped to 3×3: the matrix of the cross product a × ·
_SKEW = np.zeros((3, 9))
for _m, _j, _l, _sign in ((0, 1, 2, -1.0), (0, 2, 1, 1.0), (1, 0, 2, 1.0), (1, 2, 0, -1.0), (2, 0, 1, -1.0),
                          (2, 1, 0, 1.0)):
    _SKEW[_m, 3 * _j + _l] = _sign


class Pacer:
    """The bounds of a path q₀ + t·`delta` (see the module's text), what of them stays the same along it computed
    once: `at` then gives a step's `Pace` from where the movers are (a path's checks call it at each).

    `prismatic[i]`: moving joint i slides; `below[i, k]`: mover k hangs below joint i; `inner[i, j]`: joint i
    hangs below joint j (i ≠ j)."""

    def __init__(self, delta: np.ndarray, prismatic: np.ndarray, below: np.ndarray, inner: np.ndarray) -> None:
        size = np.abs(delta)
        self._turned = below & ~prismatic[:, None]  # the levers: the farthest corners where k turns about i,
        self._slid = (below & prismatic[:, None]).astype(float)  # 1 where it slides along i, else 0
        # Θᵢ: |Δq| summed over the revolute joints at or above i
        turning = np.where(prismatic, 0.0, size)
        theta = turning + inner.astype(float) @ turning
        # the pace bound's A = Σᵢ |Δqᵢ|·(Θᵢ·rᵢₖ + Λᵢ) over the joints above k, Λᵢ (revolute i only) =
        # Σⱼ |Δqⱼ|·(rⱼₖ + T) over the joints j below i and above k; summed by j instead, every joint i above j
        # being above k too: A = Σⱼ |Δqⱼ|·rⱼₖ·(Θⱼ + (Θⱼ − |Δqⱼ| if revolute)) + T·Σⱼ |Δqⱼ|·(Θⱼ − |Δqⱼ| if revolute)
        outer = theta - turning  # |Δq| of the revolute joints strictly above each joint
        self._rows = np.stack([size, size * (theta + outer)])  # base and curve: · levers
        self.weight = size @ below.astype(float)
        self.bend = (size * outer) @ below.astype(float)
        self._share = (below * delta[:, None]).T  # (movers, joints): each mover's Δq
        self._sliding = prismatic[:, None]

    def at(self, points: np.ndarray, origins: np.ndarray, axes: np.ndarray) -> Pace:
        """The bounds for a step from here: `points`, each mover's box corners (movers, 8, 3; `corners`); `origins`
        and `axes`, each moving joint's axis in the world (a point on it, its unit direction)."""
        lever = _farthest(points, origins, axes) * self._turned + self._slid  # `levers`, (joints, movers)
        base, curve = self._rows @ lever
        # ‖J(c)·Δq‖ at every corner c: Σᵢ Δqᵢ·(aᵢ × (c − oᵢ)), or Δqᵢ·aᵢ for a prismatic joint, over the joints above
        # k, = ω × c + b: mover k's rigid motion, ω = Σᵢ Δqᵢ·aᵢ over its revolute joints, b the rest
        skews = (axes @ _SKEW).reshape(-1, 3, 3)  # [aᵢ]×
        moments = np.where(self._sliding, axes, -np.matmul(skews, origins[:, :, None])[:, :, 0])
        omega = self._share @ np.where(self._sliding, 0.0, axes)
        turn = (omega @ _SKEW).reshape(-1, 3, 3)  # [ω]×
        velocity = np.matmul(points, turn.transpose(0, 2, 1)) + (self._share @ moments)[:, None, :]  # (movers, 8, 3)
        speed = np.sqrt(np.einsum("mcd,mcd->mc", velocity, velocity).max(axis=1))
        return Pace(base, self.weight, speed, curve, self.bend)
