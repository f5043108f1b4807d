#!/usr/bin/env python3
"""Generate the project's own kitchen model (``kitchen.urdf``) and floor (``floor.urdf``).

The kitchen is a primitive-only (boxes and cylinders) re-creation of the IAI kitchen
used by CRAM's BulletWorld demo.  Link and joint names, the kinematic tree and the
joint origins follow the IAI ``iai_kitchen`` description; the geometry is a simplified
box model whose dimensions were measured from that description.  All numbers are
written below as data -- this script reads no external file.

Conventions
-----------
* World frame: x points from the room centre towards the sink counter, z is up,
  the floor is z = 0 (the floor itself is a separate model, ``floor.urdf``).
* Every piece of geometry is written below as an axis-aligned box (or a cylinder)
  in *world* coordinates with all joints at zero.  The script composes the joint
  origins from the root ``room_link`` and converts the geometry into each link's
  own frame, so the numbers stay readable although many IAI frames are rotated by
  180 degrees about z.
* Every link gets an ``<inertial>`` element (PyBullet otherwise warns).  Its origin
  is the link origin, so ``p.getLinkState(...)[0]`` equals the URDF link frame.

Main facts (world frame, joints at zero)
----------------------------------------
* ``sink_area_surface`` (counter top): x 1.2475..1.8225, y -0.285..1.315, top z 0.85.
* ``sink_area_left_upper_drawer_main``: origin (1.525, 0.89, 0.755); prismatic joint
  ``sink_area_left_upper_drawer_main_joint``, axis +x of the (180 deg rotated)
  ``sink_area`` frame, limits 0..0.48 -> opening moves the drawer towards -x.
  Open-topped box; interior floor at z = DRAWER_FLOOR_Z (0.70), interior
  x 1.275..1.785, y 0.515..1.275, walls up to z 0.815.
* ``sink_area_left_upper_drawer_handle``: origin (1.1925, 0.89, 0.7725) = the axis
  of a horizontal bar (radius 1 cm, 0.60 m long along y) on two stand-offs; the
  gap between bar and front panel (x 1.245) is 4.25 cm.
* ``kitchen_island_surface``: x -1.4675..-0.6675, y 0.4942..2.9442, top z 0.861.
* Kept free for the robot: floor region x -0.6..0.95, y -0.3..2.0 (up to 2 m),
  and the space above both counter tops up to z 1.5.

Usage::

    python resources/environments/kitchen/generate.py            # writes the defaults
    python resources/environments/kitchen/generate.py --kitchen /tmp/k.urdf --floor /tmp/f.urdf
"""
from __future__ import annotations

import argparse
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Sequence

import numpy as np

from pycram_cli.robots.urdf_writer import fixed

HERE = Path(__file__).resolve().parent
DEFAULT_KITCHEN = HERE / "kitchen.urdf"
DEFAULT_FLOOR = HERE.parent / "floor" / "floor.urdf"

PI = 3.14159265359  # the value written in the IAI description

Vec3 = tuple[float, float, float]

# --------------------------------------------------------------------------------------
# Colours (name -> RGBA)
# --------------------------------------------------------------------------------------
COLOURS: dict[str, tuple[float, float, float, float]] = {
    "cabinet_white": (0.93, 0.92, 0.89, 1.0),
    "wood": (0.74, 0.55, 0.36, 1.0),
    "counter_top": (0.24, 0.24, 0.26, 1.0),
    "wall": (0.90, 0.88, 0.82, 1.0),
    "steel": (0.72, 0.74, 0.77, 1.0),
    "handle": (0.55, 0.56, 0.58, 1.0),
    "black_glass": (0.08, 0.08, 0.09, 1.0),
    "fridge_white": (0.97, 0.97, 0.97, 1.0),
    "table_wood": (0.52, 0.36, 0.21, 1.0),
    "plinth": (0.30, 0.30, 0.30, 1.0),
}

# --------------------------------------------------------------------------------------
# Key dimensions (world frame, metres)
# --------------------------------------------------------------------------------------
SINK_FRONT_X = 1.2475        # front face of the sink-area carcass / counter top
SINK_BACK_X = 1.8225         # back edge of the counter top
SINK_CARCASS_BACK_X = 1.8025  # inner face of the carcass back panel
SINK_TOP_Z = 0.85            # top of sink_area_surface
SINK_SLAB_Z = 0.83           # underside of the counter top
SINK_Y_MIN = -0.74           # right end of the sink-area unit (incl. trash column)
SINK_Y_MAX = 1.32            # left end of the sink-area unit
SURFACE_Y_MIN = -0.285       # extent of the sink_area_surface link (IAI collision box)
SURFACE_Y_MAX = 1.315

BASIN_X = (1.32, 1.74)       # sink basin opening
BASIN_Y = (-0.55, 0.20)
BASIN_FLOOR_Z = 0.70

DRAWER_FRONT_X = 1.245       # front face of the drawer front panels (closed)
DRAWER_PANEL_T = 0.02        # front panel thickness
DRAWER_BOX_BACK_X = 1.795    # back face of the drawer boxes (closed)
DRAWER_WALL_T = 0.01         # drawer side/back/bottom wall thickness
DRAWER_FLOOR_Z = 0.70        # interior floor of sink_area_left_upper_drawer_main

ISLAND_X = (-1.4675, -0.6675)
ISLAND_Y = (0.4942, 2.9442)
ISLAND_TOP_Z = 0.861
ISLAND_SLAB_Z = 0.821
ISLAND_BODY_FRONT_X = -0.805  # the island carcass; the top overhangs to -0.6675
STOVE_X = (-1.3175, -0.8175)
STOVE_Y = (2.1992, 2.7708)


# Drawers of the sink counter: name -> (joint origin in the sink_area frame as in the
# IAI model, front panel extent (y0, y1, z0, z1) in the world, handle joint origin in
# the drawer frame as in the IAI model, handle bar length).
SINK_DRAWERS: dict[str, tuple[Vec3, tuple[float, float, float, float], Vec3, float]] = {
    "sink_area_left_upper_drawer": ((0.01, -0.6, 0.345), (0.495, 1.295, 0.688, 0.826), (0.3325, 0.0, 0.0175), 0.60),
    "sink_area_left_middle_drawer": ((0.01, -0.6, 0.12), (0.495, 1.295, 0.388, 0.672), (0.3325, 0.0, 0.11), 0.60),
    "sink_area_left_bottom_drawer": ((0.01, -0.6, -0.18), (0.495, 1.295, 0.088, 0.372), (0.3325, 0.0, 0.11), 0.60),
    "sink_area_trash_drawer": ((0.01, 0.7, -0.015), (-0.715, -0.105, 0.088, 0.680), (0.3325, 0.0, 0.2375), 0.45),
}


# --------------------------------------------------------------------------------------
# Geometry primitives (world frame at zero joint positions)
# --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Box:
    """Axis-aligned box given by its world-frame min and max corners."""

    name: str
    lo: Vec3
    hi: Vec3
    colour: str

    def centre(self) -> np.ndarray:
        return (np.array(self.lo) + np.array(self.hi)) / 2.0

    def size(self) -> np.ndarray:
        return np.array(self.hi) - np.array(self.lo)


@dataclass(frozen=True)
class Cylinder:
    """Cylinder with a world-frame centre, its axis along world 'x', 'y' or 'z'."""

    name: str
    centre_xyz: Vec3
    radius: float
    length: float
    axis: str
    colour: str

    def centre(self) -> np.ndarray:
        return np.array(self.centre_xyz, dtype=float)

    def size(self) -> np.ndarray:
        half = [self.radius] * 3
        half["xyz".index(self.axis)] = self.length / 2.0
        return 2.0 * np.array(half)


Shape = Box | Cylinder


@dataclass
class Link:
    name: str
    shapes: list[Shape] = field(default_factory=list)
    mass: float = 1.0


@dataclass(frozen=True)
class Joint:
    name: str
    type: str  # fixed | prismatic | revolute
    parent: str
    child: str
    xyz: Vec3
    yaw: float = 0.0
    axis: Vec3 | None = None
    lower: float | None = None
    upper: float | None = None
    effort: float = 300.0
    velocity: float = 10.0


def box(name: str, lo: Vec3, hi: Vec3, colour: str) -> Box:
    assert all(h > l for l, h in zip(lo, hi)), f"degenerate box {name}: {lo} {hi}"
    return Box(name, tuple(float(v) for v in lo), tuple(float(v) for v in hi), colour)


# --------------------------------------------------------------------------------------
# Building blocks
# --------------------------------------------------------------------------------------
def handle_bar(prefix: str, centre: Vec3, length: float, panel_x: float,
               direction: float = -1.0, axis: str = "y", radius: float = 0.01) -> list[Shape]:
    """A grasping bar parallel to a front panel plus two stand-offs.

    ``centre`` is the bar axis; ``panel_x`` the x of the panel face the stand-offs
    reach; ``direction`` is -1 for fronts facing -x and +1 for fronts facing +x.
    """
    cx, cy, cz = centre
    shapes: list[Shape] = [Cylinder(f"{prefix}_bar", centre, radius, length, axis, "handle")]
    x_near = cx - direction * radius * 0.5  # the stand-off starts inside the bar
    xs = sorted((x_near, panel_x))
    s = 0.0075  # half cross-section of a stand-off
    offset = length / 2.0 - 0.03
    for k, sign in enumerate((-1.0, 1.0)):
        if axis == "y":
            lo, hi = (xs[0], cy + sign * offset - s, cz - s), (xs[1], cy + sign * offset + s, cz + s)
        else:  # vertical bar
            lo, hi = (xs[0], cy - s, cz + sign * offset - s), (xs[1], cy + s, cz + sign * offset + s)
        shapes.append(box(f"{prefix}_standoff_{k}", lo, hi, "handle"))
    return shapes


def drawer_box(y_lo: float, y_hi: float, z_lo: float, z_hi: float,
               front_x: float = DRAWER_FRONT_X, back_x: float = DRAWER_BOX_BACK_X,
               inner_top_margin: float = 0.011) -> list[Shape]:
    """An open-topped drawer whose front panel faces -x.

    The front panel covers y_lo..y_hi, z_lo..z_hi; the box behind it is 5 mm narrower
    on each side, has a bottom plate, four thin walls and is open at the top.
    """
    t = DRAWER_WALL_T
    px = front_x + DRAWER_PANEL_T          # rear face of the front panel
    by0, by1 = y_lo + 0.01, y_hi - 0.01     # box outer extent in y
    bottom_lo = z_lo + 0.002
    floor = bottom_lo + t
    wall_top = z_hi - inner_top_margin
    return [
        box("front_panel", (front_x, y_lo, z_lo), (px, y_hi, z_hi), "wood"),
        box("bottom", (px, by0, bottom_lo), (back_x, by1, floor), "cabinet_white"),
        box("front_wall", (px, by0, floor), (px + t, by1, wall_top), "cabinet_white"),
        box("back_wall", (back_x - t, by0, floor), (back_x, by1, wall_top), "cabinet_white"),
        box("right_wall", (px + t, by0, floor), (back_x - t, by0 + t, wall_top), "cabinet_white"),
        box("left_wall", (px + t, by1 - t, floor), (back_x - t, by1, wall_top), "cabinet_white"),
    ]


# --------------------------------------------------------------------------------------
# The kitchen
# --------------------------------------------------------------------------------------
def sink_area() -> tuple[list[Link], list[Joint]]:
    """Sink counter: carcass, counter top, basin, three left drawers, trash drawer."""
    fx, bx, cbx = SINK_FRONT_X, SINK_BACK_X, SINK_CARCASS_BACK_X
    carcass = Link("sink_area", [
        # carcass shell
        box("plinth", (fx + 0.04, SINK_Y_MIN + 0.02, 0.0), (cbx, SINK_Y_MAX - 0.02, 0.07), "plinth"),
        box("bottom_board", (fx, SINK_Y_MIN + 0.02, 0.07), (cbx, SINK_Y_MAX - 0.02, 0.08), "cabinet_white"),
        box("back_panel", (cbx, SINK_Y_MIN, 0.0), (bx, SINK_Y_MAX, SINK_SLAB_Z), "cabinet_white"),
        box("right_end_panel", (fx, SINK_Y_MIN, 0.0), (cbx, SINK_Y_MIN + 0.02, SINK_SLAB_Z), "cabinet_white"),
        box("left_end_panel", (fx, SINK_Y_MAX - 0.02, 0.0), (cbx, SINK_Y_MAX, SINK_SLAB_Z), "cabinet_white"),
        # trash column | dish-washer column | drawer column
        box("divider_trash", (fx, -0.10, 0.08), (cbx, -0.08, 0.685), "cabinet_white"),
        box("dish_washer_body", (fx + 0.02, -0.08, 0.08), (cbx, 0.47, 0.685), "steel"),
        box("dish_washer_front", (fx, -0.075, 0.084), (fx + 0.02, 0.465, 0.826), "wood"),
        *handle_bar("dish_washer_handle", (1.1925, 0.195, 0.7615), 0.45, fx),
        box("divider_drawers", (fx, 0.47, 0.08), (cbx, 0.49, SINK_SLAB_Z), "cabinet_white"),
        box("shelf_upper", (fx + 0.02, 0.49, 0.676), (cbx, SINK_Y_MAX - 0.02, 0.684), "cabinet_white"),
        box("shelf_lower", (fx + 0.02, 0.49, 0.376), (cbx, SINK_Y_MAX - 0.02, 0.384), "cabinet_white"),
        # counter top pieces around the basin that lie outside sink_area_surface
        box("top_right_end", (fx, SINK_Y_MIN, SINK_SLAB_Z), (bx, BASIN_Y[0], SINK_TOP_Z), "counter_top"),
        box("top_right_front", (fx, BASIN_Y[0], SINK_SLAB_Z), (BASIN_X[0], SURFACE_Y_MIN, SINK_TOP_Z), "counter_top"),
        box("top_right_back", (BASIN_X[1], BASIN_Y[0], SINK_SLAB_Z), (bx, SURFACE_Y_MIN, SINK_TOP_Z), "counter_top"),
        box("top_left_cap", (fx, SURFACE_Y_MAX, SINK_SLAB_Z), (bx, SINK_Y_MAX, SINK_TOP_Z), "counter_top"),
    ], mass=1.0)

    surface = Link("sink_area_surface", [
        box("top_main", (fx, BASIN_Y[1], SINK_SLAB_Z), (bx, SURFACE_Y_MAX, SINK_TOP_Z), "counter_top"),
        box("top_front_of_basin", (fx, SURFACE_Y_MIN, SINK_SLAB_Z), (BASIN_X[0], BASIN_Y[1], SINK_TOP_Z), "counter_top"),
        box("top_behind_basin", (BASIN_X[1], SURFACE_Y_MIN, SINK_SLAB_Z), (bx, BASIN_Y[1], SINK_TOP_Z), "counter_top"),
    ])

    (x0, x1), (y0, y1), t = BASIN_X, BASIN_Y, 0.01
    sink = Link("sink_area_sink", [
        box("basin_floor", (x0, y0, BASIN_FLOOR_Z - t), (x1, y1, BASIN_FLOOR_Z), "steel"),
        box("basin_front", (x0, y0, BASIN_FLOOR_Z), (x0 + t, y1, SINK_TOP_Z), "steel"),
        box("basin_back", (x1 - t, y0, BASIN_FLOOR_Z), (x1, y1, SINK_TOP_Z), "steel"),
        box("basin_right", (x0 + t, y0, BASIN_FLOOR_Z), (x1 - t, y0 + t, SINK_TOP_Z), "steel"),
        box("basin_left", (x0 + t, y1 - t, BASIN_FLOOR_Z), (x1 - t, y1, SINK_TOP_Z), "steel"),
        # the faucet stands behind the basin, outside the free region y > -0.29
        Cylinder("faucet_column", (1.78, -0.42, 1.0), 0.015, 0.30, "z", "steel"),
        Cylinder("faucet_spout", (1.69, -0.42, 1.135), 0.012, 0.18, "x", "steel"),
    ])

    right_panel = Link("sink_area_right_panel", [
        box("panel", (DRAWER_FRONT_X, -0.708, 0.697), (DRAWER_FRONT_X + DRAWER_PANEL_T, -0.112, 0.826), "wood"),
    ])

    links = [carcass, surface, sink, right_panel]
    joints = [
        Joint("sink_area_footprint_joint", "fixed", "room_link", "sink_area_footprint", (1.825, 1.32, 0.0), PI),
        Joint("sink_area_main_joint", "fixed", "sink_area_footprint", "sink_area", (0.29, 1.03, 0.41)),
        Joint("sink_area_surface_joint", "fixed", "sink_area", "sink_area_surface", (0.0, 0.0, 0.43)),
        Joint("sink_area_sink_joint", "fixed", "sink_area", "sink_area_sink", (0.005, 0.47, 0.4414)),
        Joint("sink_area_right_panel_joint", "fixed", "sink_area", "sink_area_right_panel", (0.28, 0.7, 0.355)),
    ]
    links.insert(0, Link("sink_area_footprint", [], mass=1.0))

    for name, (origin, (fy0, fy1, fz0, fz1), handle_off, _) in SINK_DRAWERS.items():
        main, handle = f"{name}_main", f"{name}_handle"
        links.append(Link(main, drawer_box(fy0, fy1, fz0, fz1), mass=2.0))
        joints.append(Joint(f"{main}_joint", "prismatic", "sink_area", main, origin,
                            axis=(1.0, 0.0, 0.0), lower=0.0, upper=0.48))
        joints.append(Joint(f"{handle}_joint", "fixed", main, handle, handle_off))
        links.append(Link(handle, [], mass=0.2))  # bar added by fill_handles (needs world pose)
    return links, joints


def fill_handles(links: dict[str, Link], world: dict[str, np.ndarray]) -> None:
    """Give every sink drawer's handle link a bar centred on its (world) origin."""
    for name, (_, _, _, length) in SINK_DRAWERS.items():
        c = world[f"{name}_handle"][:3, 3]
        links[f"{name}_handle"].shapes.extend(
            handle_bar("handle", (float(c[0]), float(c[1]), float(c[2])), length, DRAWER_FRONT_X))


def oven_area() -> tuple[list[Link], list[Joint]]:
    """The tall oven unit left of the sink counter (y 1.325..2.52)."""
    fx, bx = 1.2475, 1.8085
    y0, y1 = 1.325, 2.52
    area = Link("oven_area_area", [
        box("plinth", (fx + 0.04, y0, 0.0), (bx, y1, 0.07), "plinth"),
        box("body", (fx + 0.02, y0, 0.07), (bx, y1, 1.51), "cabinet_white"),
        box("right_tall_front", (fx, y0 + 0.005, 0.08), (fx + 0.02, 1.625, 1.505), "wood"),
        box("left_tall_front", (fx, 2.225, 0.08), (fx + 0.02, y1 - 0.005, 1.505), "wood"),
        box("lower_drawer_front", (fx, 1.63, 0.08), (fx + 0.02, 2.22, 0.495), "wood"),
        box("upper_drawer_front", (fx, 1.63, 0.50), (fx + 0.02, 2.22, 0.86), "wood"),
        *handle_bar("right_tall_handle", (1.1925, 1.48, 0.805), 1.0, fx, axis="z"),
        *handle_bar("left_tall_handle", (1.1925, 2.37, 0.815), 1.0, fx, axis="z"),
        *handle_bar("lower_drawer_handle", (1.1925, 1.92, 0.44), 0.45, fx),
        *handle_bar("upper_drawer_handle", (1.1925, 1.92, 0.80), 0.45, fx),
    ], mass=1.0)
    oven = Link("oven_area_oven_main", [
        box("door_glass", (fx - 0.01, 1.64, 0.87), (fx + 0.02, 2.21, 1.38), "black_glass"),
        box("control_panel", (fx, 1.64, 1.385), (fx + 0.02, 2.21, 1.47), "steel"),
        *handle_bar("door_handle", (1.1925, 1.92, 1.33), 0.50, fx - 0.01),
    ])
    links = [Link("oven_area_area_footprint", [], mass=1.0), area, oven]
    joints = [
        Joint("oven_area_footprint_joint", "fixed", "room_link", "oven_area_area_footprint", (1.805, 2.52, 0.0), PI),
        Joint("oven_area_main_joint", "fixed", "oven_area_area_footprint", "oven_area_area", (0.29, 0.6, 0.755)),
        Joint("oven_area_oven_main_joint", "fixed", "oven_area_area", "oven_area_oven_main", (0.0, 0.0, 0.415)),
    ]
    return links, joints


def fridge_area() -> tuple[list[Link], list[Joint]]:
    """Fridge unit right of the sink counter (y -1.345..-0.735) with an opening door."""
    fx, bx = 1.2475, 1.8285
    y0, y1 = -1.345, -0.735
    area = Link("fridge_area", [
        box("plinth", (fx + 0.04, y0, 0.0), (bx, y1, 0.07), "plinth"),
        box("lower_body", (fx + 0.02, y0, 0.07), (bx, y1, 0.49), "cabinet_white"),
        box("lower_drawer_front", (fx, y0 + 0.005, 0.08), (fx + 0.02, y1 - 0.005, 0.485), "wood"),
        *handle_bar("lower_drawer_handle", (1.2025, -1.04, 0.4325), 0.45, fx),
        box("top_body", (fx, y0, 1.47), (bx, y1, 1.51), "cabinet_white"),
    ], mass=1.0)
    t = 0.02
    fridge = Link("iai_fridge_main", [
        box("bottom", (fx, y0, 0.49), (bx, y1, 0.51), "fridge_white"),
        box("top", (fx, y0, 1.45), (bx, y1, 1.47), "fridge_white"),
        box("back", (1.78, y0 + t, 0.51), (bx, y1 - t, 1.45), "fridge_white"),
        box("right_side", (fx, y0, 0.51), (bx, y0 + t, 1.45), "fridge_white"),
        box("left_side", (fx, y1 - t, 0.51), (bx, y1, 1.45), "fridge_white"),
        box("shelf", (1.29, y0 + t, 0.95), (1.78, y1 - t, 0.96), "steel"),
    ])
    door = Link("iai_fridge_door", [
        box("door", (1.2255, -1.335, 0.495), (1.2455, -0.745, 1.465), "fridge_white"),
    ], mass=5.0)
    handle = Link("iai_fridge_door_handle", handle_bar("handle", (1.19, -0.77, 0.985), 0.60, 1.2255, axis="z"),
                  mass=0.2)
    links = [Link("fridge_area_footprint", [], mass=1.0), area, fridge, door, handle]
    joints = [
        Joint("fridge_area_footprint_joint", "fixed", "room_link", "fridge_area_footprint", (1.825, -0.74, 0.0), PI),
        Joint("fridge_area_main_joint", "fixed", "fridge_area_footprint", "fridge_area", (0.29, 0.3, 0.74)),
        Joint("iai_fridge_main_joint", "fixed", "fridge_area", "iai_fridge_main", (0.0, 0.0, 0.0)),
        Joint("iai_fridge_door_joint", "revolute", "iai_fridge_main", "iai_fridge_door", (0.29, 0.3, 0.245),
              axis=(0.0, 0.0, 1.0), lower=0.0, upper=1.57079632679),
        Joint("iai_fridge_door_handle_joint", "fixed", "iai_fridge_door", "iai_fridge_door_handle", (0.06, -0.57, 0.0)),
    ]
    return links, joints


def kitchen_island() -> tuple[list[Link], list[Joint]]:
    """Kitchen island (the 'table' the robot places on) with a flush cook-top."""
    (x0, x1), (y0, y1) = ISLAND_X, ISLAND_Y
    fx = ISLAND_BODY_FRONT_X
    body: list[Shape] = [
        box("plinth", (x0 + 0.02, y0 + 0.02, 0.0), (fx - 0.04, y1 - 0.02, 0.07), "plinth"),
        box("body", (x0, y0, 0.07), (fx, y1, ISLAND_SLAB_Z), "cabinet_white"),
    ]
    # decorative fronts facing +x: (column centre y, column width) as in the IAI model
    for col, (cy, width) in {"left": (0.9192, 0.6), "middle": (1.7192, 1.0), "right": (2.5192, 0.6)}.items():
        ya, yb = cy - width / 2 + 0.003, cy + width / 2 - 0.003
        for part, (za, zb) in {"panel": (0.685, 0.815), "upper_drawer": (0.395, 0.68),
                               "lower_drawer": (0.08, 0.39)}.items():
            body.append(box(f"{col}_{part}_front", (fx, ya, za), (fx + 0.02, yb, zb), "wood"))
        for part, hz in {"upper_drawer": 0.645, "lower_drawer": 0.355}.items():
            body.extend(handle_bar(f"{col}_{part}_handle", (-0.7425, cy, hz), width - 0.15, fx + 0.02,
                                   direction=1.0))
    island = Link("kitchen_island", body, mass=1.0)

    sx, sy = STOVE_X, STOVE_Y
    surface = Link("kitchen_island_surface", [
        box("top_main", (x0, y0, ISLAND_SLAB_Z), (x1, sy[0], ISLAND_TOP_Z), "counter_top"),
        box("top_end", (x0, sy[1], ISLAND_SLAB_Z), (x1, y1, ISLAND_TOP_Z), "counter_top"),
        box("top_behind_stove", (x0, sy[0], ISLAND_SLAB_Z), (sx[0], sy[1], ISLAND_TOP_Z), "counter_top"),
        box("top_before_stove", (sx[1], sy[0], ISLAND_SLAB_Z), (x1, sy[1], ISLAND_TOP_Z), "counter_top"),
    ])
    stove = Link("kitchen_island_stove", [
        box("cook_top", (sx[0], sy[0], ISLAND_TOP_Z - 0.01), (sx[1], sy[1], ISLAND_TOP_Z), "black_glass"),
    ])
    links = [Link("kitchen_island_footprint", [], mass=1.0), island, surface, stove]
    joints = [
        Joint("kitchen_island_footprint_joint", "fixed", "room_link", "kitchen_island_footprint", (-1.365, 0.59, 0.0)),
        Joint("kitchen_island_joint", "fixed", "kitchen_island_footprint", "kitchen_island", (0.2975, 1.1292, 0.421)),
        Joint("kitchen_island_surface_joint", "fixed", "kitchen_island", "kitchen_island_surface", (0.0, 0.0, 0.42)),
        Joint("kitchen_island_stove_joint", "fixed", "kitchen_island", "kitchen_island_stove", (0.0, 0.7658, 0.4315)),
    ]
    return links, joints


def dining_table() -> tuple[list[Link], list[Joint]]:
    """A small dining table west of the island.

    The IAI model puts ``table_area_main`` at (-1.4, -1.05); here it stands at
    (-2.7, 1.3) so that it blocks neither the low walls nor the robot's paths.
    """
    cx, cy, hx, hy, top = -2.7, 1.3, 0.4, 0.8, 0.76
    shapes: list[Shape] = [box("top", (cx - hx, cy - hy, top - 0.04), (cx + hx, cy + hy, top), "table_wood")]
    for k, (sx, sy) in enumerate(((-1, -1), (-1, 1), (1, -1), (1, 1))):
        lx, ly = cx + sx * (hx - 0.06), cy + sy * (hy - 0.06)
        shapes.append(box(f"leg_{k}", (lx - 0.025, ly - 0.025, 0.0), (lx + 0.025, ly + 0.025, top - 0.04),
                          "table_wood"))
    return ([Link("table_area_main", shapes, mass=1.0)],
            [Joint("table_area_main_joint", "fixed", "room_link", "table_area_main", (cx, cy, 0.0), PI)])


def walls() -> tuple[list[Link], list[Joint]]:
    """Room walls as in the IAI model (walls 4-6 are 0.7 m high partitions there).

    ``kitchen_wall_2`` (behind the counters) is moved 2.8 cm back so that its face is
    flush with the back of the counter tops (x 1.8285).
    """
    walls_spec = [
        # name, joint origin (in kitchen_walls frame), joint yaw, world box lo, hi
        ("kitchen_wall_1", "wall_1_joint", (2.38151, -2.516, 0.0), 3.14159,
         (0.8127, -2.0288, 0.0), (1.9503, -1.8788, 2.5)),
        ("kitchen_wall_2", "wall_2_joint", (2.87551, 0.0, 0.0), 1.5708,
         (1.8285, -2.0288, 0.0), (1.9785, 3.1532, 2.5)),
        ("kitchen_wall_3", "wall_3_joint", (0.0, 2.516, 0.0), 3.14159,
         (-3.9505, 3.0032, 0.0), (1.9505, 3.1532, 2.5)),
        ("kitchen_wall_4", "wall_4_joint", (-2.87549, 0.466, 0.0), -1.5708,
         (-3.9505, -1.0968, 0.0), (-3.8005, 3.1532, 0.7)),
        ("kitchen_wall_5", "wall_5_joint", (-1.31385, -1.58376, 0.0), 0.000157,
         (-3.9505, -1.0966, 0.0), (-0.6771, -0.9466, 0.7)),
        ("kitchen_wall_6", "wall_6_joint", (0.247785, -2.00851, 0.0), -1.5708,
         (-0.8272, -1.9463, 0.0), (-0.6772, -0.9463, 0.7)),
    ]
    links = [Link("kitchen_walls", [], mass=1.0)]
    joints = [Joint("walls_main_joint", "fixed", "room_link", "kitchen_walls", (-1.0, 0.562175, 0.0))]
    for name, jname, xyz, yaw, lo, hi in walls_spec:
        links.append(Link(name, [box("wall", lo, hi, "wall")], mass=1.0))
        joints.append(Joint(jname, "fixed", "kitchen_walls", name, xyz, yaw))
    # Upper wall cabinets above the sink counter (not in the IAI model); they start at
    # z 1.60 so the space above the counter stays free up to 1.5 m.
    fx, bx = 1.4785, 1.8285
    cabinet: list[Shape] = [box("body", (fx, -0.72, 1.60), (bx, 1.30, 2.30), "cabinet_white")]
    for k, (ya, yb) in enumerate(((-0.72, -0.05), (-0.045, 0.625), (0.63, 1.30))):
        cabinet.append(box(f"door_{k}", (fx - 0.02, ya + 0.003, 1.603), (fx, yb - 0.003, 2.297), "wood"))
    links.append(Link("wall_cabinet", cabinet, mass=1.0))
    joints.append(Joint("wall_cabinet_joint", "fixed", "room_link", "wall_cabinet", (1.65, 0.29, 1.6)))
    return links, joints


def build_kitchen() -> tuple[list[Link], list[Joint]]:
    links: list[Link] = [Link("room_link", [], mass=1.0)]
    joints: list[Joint] = []
    for part in (sink_area, oven_area, fridge_area, kitchen_island, dining_table, walls):
        part_links, part_joints = part()
        links += part_links
        joints += part_joints
    return links, joints


# --------------------------------------------------------------------------------------
# Kinematics and URDF writing
# --------------------------------------------------------------------------------------
def transform(xyz: Sequence[float], yaw: float) -> np.ndarray:
    c, s = math.cos(yaw), math.sin(yaw)
    m = np.eye(4)
    m[:2, :2] = [[c, -s], [s, c]]
    m[:3, 3] = xyz
    return m


def world_poses(joints: Iterable[Joint]) -> dict[str, np.ndarray]:
    """World transform of every link at zero joint positions."""
    by_child = {j.child: j for j in joints}
    poses: dict[str, np.ndarray] = {"room_link": np.eye(4)}

    def pose(link: str) -> np.ndarray:
        if link not in poses:
            j = by_child[link]
            poses[link] = pose(j.parent) @ transform(j.xyz, j.yaw)
        return poses[link]

    for child in by_child:
        pose(child)
    return poses


def fmt(value: float) -> str:
    """Deterministic, compact number formatting: six digits after the point, as the robots' generators spell them."""
    return fixed(value)


def fmt3(values: Iterable[float]) -> str:
    return " ".join(fmt(v) for v in values)


def local_shape(shape: Shape, link_pose: np.ndarray) -> tuple[np.ndarray, np.ndarray, str]:
    """Centre, size (along the link axes) and cylinder axis of a shape in its link frame.

    Link frames are only rotated about z by multiples of 90 degrees (to within 0.01
    rad), so world-aligned boxes stay axis-aligned in the link frame.
    """
    rot = link_pose[:3, :3]
    centre = rot.T @ (shape.centre() - link_pose[:3, 3])
    yaw = math.atan2(rot[1, 0], rot[0, 0])
    quarter = round(yaw / (math.pi / 2))
    assert abs(yaw - quarter * math.pi / 2) < 1e-2, "link frames must be axis aligned"
    size = shape.size()
    axis = shape.axis if isinstance(shape, Cylinder) else ""
    if quarter % 2:
        size = size[[1, 0, 2]]
        axis = {"x": "y", "y": "x"}.get(axis, axis)
    return centre, size, axis


def box_inertia(mass: float, size: np.ndarray) -> tuple[float, float, float]:
    sx, sy, sz = (max(float(s), 0.05) for s in size)
    return (mass * (sy ** 2 + sz ** 2) / 12.0, mass * (sx ** 2 + sz ** 2) / 12.0,
            mass * (sx ** 2 + sy ** 2) / 12.0)


CYLINDER_RPY = {"x": "0 1.570796 0", "y": "1.570796 0 0", "z": "0 0 0"}


def geometry_lines(shape: Shape, centre: np.ndarray, size: np.ndarray, axis: str, indent: str) -> list[str]:
    rpy = CYLINDER_RPY[axis] if isinstance(shape, Cylinder) else "0 0 0"
    lines = [f'{indent}<origin xyz="{fmt3(centre)}" rpy="{rpy}"/>', f"{indent}<geometry>"]
    if isinstance(shape, Cylinder):
        lines.append(f'{indent}  <cylinder radius="{fmt(shape.radius)}" length="{fmt(shape.length)}"/>')
    else:
        lines.append(f'{indent}  <box size="{fmt3(size)}"/>')
    lines.append(f"{indent}</geometry>")
    return lines


def link_lines(link: Link, pose: np.ndarray) -> list[str]:
    lines = [f'  <link name="{link.name}">']
    local = [local_shape(s, pose) for s in link.shapes]
    if local:
        lo = np.min([c - s / 2 for c, s, _ in local], axis=0)
        hi = np.max([c + s / 2 for c, s, _ in local], axis=0)
        extent = hi - lo
    else:
        extent = np.full(3, 0.1)
    ixx, iyy, izz = box_inertia(link.mass, extent)
    lines += [
        "    <inertial>",
        '      <origin xyz="0 0 0" rpy="0 0 0"/>',
        f'      <mass value="{fmt(link.mass)}"/>',
        f'      <inertia ixx="{fmt(ixx)}" ixy="0" ixz="0" iyy="{fmt(iyy)}" iyz="0" izz="{fmt(izz)}"/>',
        "    </inertial>",
    ]
    for shape, (centre, size, axis) in zip(link.shapes, local):
        lines.append(f'    <visual name="{shape.name}">')
        lines += geometry_lines(shape, centre, size, axis, "      ")
        lines.append(f'      <material name="{shape.colour}"/>')
        lines.append("    </visual>")
    for shape, (centre, size, axis) in zip(link.shapes, local):
        lines.append(f'    <collision name="{shape.name}">')
        lines += geometry_lines(shape, centre, size, axis, "      ")
        lines.append("    </collision>")
    lines.append("  </link>")
    return lines


def joint_lines(joint: Joint) -> list[str]:
    lines = [
        f'  <joint name="{joint.name}" type="{joint.type}">',
        f'    <parent link="{joint.parent}"/>',
        f'    <child link="{joint.child}"/>',
        f'    <origin xyz="{fmt3(joint.xyz)}" rpy="0 0 {fmt(joint.yaw)}"/>',
    ]
    if joint.type != "fixed":
        assert joint.axis is not None and joint.lower is not None and joint.upper is not None
        lines.append(f'    <axis xyz="{fmt3(joint.axis)}"/>')
        lines.append(f'    <limit lower="{fmt(joint.lower)}" upper="{fmt(joint.upper)}" '
                     f'effort="{fmt(joint.effort)}" velocity="{fmt(joint.velocity)}"/>')
        lines.append('    <dynamics damping="1.0" friction="0.0"/>')
    lines.append("  </joint>")
    return lines


def kitchen_urdf() -> str:
    links, joints = build_kitchen()
    by_name = {link.name: link for link in links}
    assert len(by_name) == len(links), "duplicate link names"
    assert len({j.name for j in joints}) == len(joints), "duplicate joint names"
    poses = world_poses(joints)
    fill_handles(by_name, poses)
    out = [
        '<?xml version="1.0"?>',
        "<!-- Generated by resources/environments/kitchen/generate.py - do not edit by hand. -->",
        "<!-- Primitive re-creation of the IAI kitchen; names and frames follow iai_kitchen. -->",
        '<robot name="iai_kitchen">',
    ]
    for name, rgba in COLOURS.items():
        out += [f'  <material name="{name}">', f'    <color rgba="{fmt3(rgba)}"/>', "  </material>"]
    for link in links:
        out += link_lines(link, poses[link.name])
    for joint in joints:
        out += joint_lines(joint)
    out.append("</robot>")
    return "\n".join(out) + "\n"


def floor_urdf() -> str:
    return "\n".join([
        '<?xml version="1.0"?>',
        "<!-- Generated by resources/environments/kitchen/generate.py - do not edit by hand. -->",
        "<!-- A static 20 x 20 m floor slab whose top face is z = 0. -->",
        '<robot name="floor">',
        '  <link name="floor">',
        "    <contact>",
        '      <lateral_friction value="1"/>',
        "    </contact>",
        "    <inertial>",
        '      <origin xyz="0 0 0" rpy="0 0 0"/>',
        '      <mass value="0"/>',
        '      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>',
        "    </inertial>",
        '    <visual name="slab">',
        '      <origin xyz="0 0 -0.01" rpy="0 0 0"/>',
        "      <geometry>",
        '        <box size="20 20 0.02"/>',
        "      </geometry>",
        '      <material name="floor_grey">',
        '        <color rgba="0.62 0.62 0.6 1"/>',
        "      </material>",
        "    </visual>",
        '    <collision name="slab">',
        '      <origin xyz="0 0 -0.01" rpy="0 0 0"/>',
        "      <geometry>",
        '        <box size="20 20 0.02"/>',
        "      </geometry>",
        "    </collision>",
        "  </link>",
        "</robot>",
    ]) + "\n"


def write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kitchen", type=Path, default=DEFAULT_KITCHEN, help="output kitchen URDF")
    parser.add_argument("--floor", type=Path, default=DEFAULT_FLOOR, help="output floor URDF")
    args = parser.parse_args(argv)
    write(args.kitchen, kitchen_urdf())
    write(args.floor, floor_urdf())
    print(f"wrote {args.kitchen} and {args.floor}")


if __name__ == "__main__":
    main()
