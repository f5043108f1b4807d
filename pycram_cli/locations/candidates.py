"""The candidates of a resolution and what it answers: outcome codes, the ranked arrays, `BasePose` and `Spot`.

Both kinds of resolution (`base_poses.py`, `spots.py`) keep every candidate as numpy arrays, so that the cheap
tests run vectorised over all of them, and mark each with the first test that ruled it out; `summary` turns the
marks into the failure text ("412 candidates: 380 collide, 32 out of reach"), the plot colours them by it.
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass
from typing import Any

import numpy as np

#: why a candidate was ruled out, in the order the tests run, and how the reasons read
REASONS = {
    "out of reach": "out of reach",
    "out of view": "out of view",
    "collides": "collide",
    "occupied": "occupied",
    "cannot hold": "cannot hold it",
    "blocked": "blocked",
    "not visible": "not visible",
    "unstable": "unstable",
    "not tried": "not tried",
}


#: outcome codes of candidates (`Candidates.outcome`): 0 not tested yet, 1 passed, then the reasons in order
OUTCOMES = ("", "ok", *REASONS)
CODE = {name: code for code, name in enumerate(OUTCOMES)}


class Candidates:
    """Every candidate of a resolution as arrays (positions, turns, scores, outcomes), and the order they are tried in."""

    def __init__(self, xs: np.ndarray, ys: np.ndarray, yaws: np.ndarray, scores: np.ndarray,
                 outcome: np.ndarray, first: np.ndarray | None = None) -> None:
        self.xs, self.ys, self.yaws, self.scores = xs, ys, yaws, scores
        self.outcome = outcome.astype(np.int8)
        self.first = np.zeros(len(xs), dtype=bool) if first is None else first.astype(bool)
        self.detail: dict[int, str] = {}
        # best first (those marked `first` before the rest); ties by position and turn, so that the order never
        # depends on arithmetic noise
        index = np.arange(len(xs))
        self.order = np.lexsort((index, np.round(ys, 6), np.round(xs, 6), np.round(scores, 9), ~self.first,
                                 outcome != 0))

    def extended(self, more: Candidates) -> Candidates:
        """These candidates (their outcomes and details kept) and `more` after them, ordered anew."""
        joined = Candidates(*(np.concatenate([a, b]) for a, b in
                              ((self.xs, more.xs), (self.ys, more.ys), (self.yaws, more.yaws),
                               (self.scores, more.scores), (self.outcome, more.outcome), (self.first, more.first))))
        joined.detail = dict(self.detail)
        return joined

    def __len__(self) -> int:
        return len(self.xs)

    def mark(self, i: int, reason: str, detail: str = "") -> None:
        self.outcome[i] = CODE[reason]
        if detail:
            self.detail[i] = detail

    def counts(self) -> Counter[str]:
        values, numbers = np.unique(self.outcome, return_counts=True)
        return Counter({OUTCOMES[v]: int(n) for v, n in zip(values, numbers) if v >= 2})

    def untested(self) -> int:
        return int((self.outcome == 0).sum())

    def details(self, reason: str) -> list[str]:
        code = CODE[reason]
        return [text for i, text in sorted(self.detail.items()) if self.outcome[i] == code]


@dataclass(frozen=True)
class BasePose:
    """Where the robot's base stands (and, for visible-for, where it looks; for reachable-for, which arm and grasp)."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    yaw: float
    score: float
    arm: str | None = None
    grasp: Any = None
    look_at: tuple[float, float, float] | None = None
    index: int = 0  # the how-manieth pose of its location (0: the first)
    torso: float | None = None  # the torso height the arm reaches from (None: the torso stays where it is)

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {"position": list(self.position), "orientation": list(self.orientation),
                                "yaw": self.yaw, "score": self.score}
        if self.arm is not None:
            data["arm"] = self.arm
        if self.grasp is not None:
            data["grasp"] = self.grasp if isinstance(self.grasp, str) else list(self.grasp)
        if self.look_at is not None:
            data["look-at"] = list(self.look_at)
        if self.torso is not None:
            data["torso"] = self.torso
        return data


@dataclass(frozen=True)
class Spot:
    """Where an object's origin (its bottom centre) goes on a surface, and how it is turned."""

    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    score: float
    surface: str = ""
    index: int = 0

    def to_json(self) -> dict[str, Any]:
        return {"position": list(self.position), "orientation": list(self.orientation), "score": self.score,
                "surface": self.surface}

def summary(counts: Counter[str], total: int) -> str:
    """`412 candidates: 380 collide, 32 out of reach`."""
    parts = [f"{counts[key]} {REASONS[key]}" for key in REASONS if counts.get(key)]
    return f"{total} candidate{'s' if total != 1 else ''}" + (": " + ", ".join(parts) if parts else "")

