"""What both kinds of resolution share: candidates tried best first, lazily, and the report when none is left.

A resolution ranks its candidates once (`prepare`, inside a snapshot: the world is left as it was) and then tests
them one at a time as the caller asks (`next`), so a plan that takes the first pose pays for one; asking again
continues where it stopped. When none is left, `LocationFailure` carries the counts of what ruled them out.
"""
from __future__ import annotations

from collections import Counter
from collections.abc import Iterator
from typing import Any

from ..failures import LocationFailure
from ..robots import Robot
from .candidates import Candidates, summary
from .spec import LocationSpec


class Resolution:
    """What both kinds of resolution share: candidates tried in order, lazily, and the report when none is left."""

    candidates: Candidates
    spec: LocationSpec

    def __init__(self, robot: Robot, spec: LocationSpec, limit: int) -> None:
        self.robot = robot
        self.spec = spec
        self.limit = limit
        self.cursor = 0
        self.expensive = 0
        self._prepared = False
        self.found: list[Any] = []

    def _prepare(self) -> None:
        raise NotImplementedError

    @property
    def prepared(self) -> bool:
        return self._prepared

    def prepare(self) -> None:
        """The candidates, ranked (resolving does this first; the world is left as it was)."""
        if not self._prepared:
            world = self.robot.world
            with world.lock, world.snapshot():
                self._prepared_inside()

    def _prepared_inside(self) -> None:
        """Inside the caller's snapshot: the candidates, once."""
        if not self._prepared:
            self._prepare()
            self._prepared = True

    def __iter__(self) -> Iterator[Any]:
        while True:
            try:
                yield self.next()
            except LocationFailure:
                return

    def next(self) -> Any:
        raise NotImplementedError

    def counts(self) -> Counter[str]:
        """Why candidates were ruled out so far (those never tested count as `not tried`; none before there are any)."""
        if not self._prepared:
            return Counter()
        counts = self.candidates.counts()
        untested = self.candidates.untested()
        if untested:
            counts["not tried"] += untested
        return counts

    def summary(self) -> str:
        return summary(self.counts(), len(self.candidates) if self._prepared else 0)

    def _fail(self, text: str) -> LocationFailure:
        return LocationFailure(text, location=self.spec.describe(), counts=dict(self.counts()))
