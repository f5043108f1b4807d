"""Things riding on a moving link, tried without attaching them: what a drawer holds, where a pull takes it.

An action that pulls a drawer attaches what rests in it for the pull (`process_modules/accessing.py`); a location test
that tries the pull first must see those things where the pull takes them (the arm's way back passes them), without
attaching anything (an attachment is an event, and the test leaves the world as it was). `carrying` puts them where
the attachment would, bitwise, so the test and the action ask the same questions (and a walk or search the test made
is the action's to reuse: `planning/motion.py`)."""
from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Sequence

import pybullet as p

from .object import Object, _relative
from .pose import compose


@contextlib.contextmanager
def carrying(part: Object, link: int, riders: Sequence[Object]) -> Iterator[Callable[[], None]]:
    """`with carrying(part, link, riders) as follow:` — `follow()` puts the riders where `part`'s link `link` carries
    them, as if attached to it where they are when the block begins; on leaving they are put back bitwise, keeping
    their versions (what was kept for them stays valid)."""
    cid = part.world.client_id
    carrier = part.get_link_position_and_orientation(link)
    offsets = [(obj, _relative(carrier, obj.get_link_position_and_orientation(-1))) for obj in riders]
    kept = [(obj, obj._version, obj._exact_state()) for obj in riders]

    def follow() -> None:
        where = part.get_link_position_and_orientation(link)
        for obj, offset in offsets:  # as Object._move_attached places an attached child
            target = compose(where, offset)
            p.resetBaseVelocity(obj.id, [0, 0, 0], [0, 0, 0], physicsClientId=cid)
            obj._reset_base(target[0], target[1])

    try:
        yield follow
    finally:
        for obj, version, before in kept:
            (position, orientation), (linear, angular) = before[0], before[1]
            p.resetBasePositionAndOrientation(obj.id, position, orientation, physicsClientId=cid)
            p.resetBaseVelocity(obj.id, linear, angular, physicsClientId=cid)
            part.world.mark_changed(obj)
            if obj._exact_state() == before:
                obj._version = version
