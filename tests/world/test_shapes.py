"""A link's collision shapes as boxes, one per shape: a cabinet of panels with a plinth set back and a handle bar out
front leaves room under the handle, where the link's one bounding box is solid from the handle to the wall."""
from __future__ import annotations

import numpy as np

from pycram_cli.world.shapes import shape_boxes


def inside(point, boxes):
    return any((np.asarray(point) >= lo).all() and (np.asarray(point) <= hi).all() for lo, hi in boxes)


def test_every_shape_of_a_compound_link_gets_a_box_within_the_links_own(kitchen):
    cabinet = kitchen.get_object_by_name("kitchen")
    link = cabinet.get_link_id("sink_area")
    boxes = shape_boxes(cabinet, link)
    lo, hi = (np.asarray(v) for v in cabinet.get_aabb(link))
    assert len(boxes) > 10  # panels, plinth, dish washer, its handle bar, ...
    assert all((b_lo >= lo - 0.01).all() and (b_hi <= hi + 0.01).all() for b_lo, b_hi in boxes)
    assert np.allclose(np.min([b[0] for b in boxes], axis=0), lo, atol=0.01)
    assert np.allclose(np.max([b[1] for b in boxes], axis=0), hi, atol=0.01)


def test_the_room_under_a_handle_bar_is_free_where_the_links_box_is_not(kitchen):
    cabinet = kitchen.get_object_by_name("kitchen")
    link = cabinet.get_link_id("sink_area")
    lo, hi = (np.asarray(v) for v in cabinet.get_aabb(link))
    boxes = shape_boxes(cabinet, link)
    handle_tip = min(b[0][0] for b in boxes)  # the cabinet faces -x: its handle sticks out farthest
    under = (handle_tip + 0.01, (lo[1] + hi[1]) / 2, 0.1)  # at a wheel's height, just behind the handle's front
    assert inside(under, [(lo, hi)]) and not inside(under, boxes)


def test_a_link_of_one_shape_keeps_its_own_box(kitchen):
    milk = kitchen.get_object_by_name("milk")
    lo, hi = milk.get_aabb(-1)
    [(b_lo, b_hi)] = shape_boxes(milk, -1)
    assert tuple(b_lo) == tuple(lo) and tuple(b_hi) == tuple(hi)
