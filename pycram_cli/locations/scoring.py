"""The cheap geometry that ranks base-pose candidates: scores, arm order, and the first two tests, vectorised.

Every candidate gets a score from how far its arm's shoulder is from the target compared with a comfortable reach,
how far its camera is from what it should see, how much it turns away and how far the robot would drive; a shoulder
farther than the arm's length rules it `out of reach`, a camera too near or too far `out of view`. A pull (accessing
a drawer or door) is scored from the middle of the handle's path, both ends within reach, and by how far the robot
turns from facing along it: the hand takes the handle facing into the drawer, and an arm comfortable at one end of a
long pull is stretched or cramped at the other. All of it is
numpy over every candidate at once (thousands), so the expensive tests see only the best few. The additions keep
one order: scores are compared to the last bit, and the same world must give the same ranking.
"""
from __future__ import annotations

import math

import numpy as np

from ..planning.head import camera_pitch
from ..robots import Robot
from .candidates import CODE
from .geometry import ArmGeometry

#: the comfortable distance from the shoulder to the target, as a fraction of the arm's length
REACH_FRACTION = 0.6
#: an arm reaches no farther from its shoulder than its length and this (m): beyond, no candidate tests it
REACH_SLACK = 0.02
#: a tool held level (taken along a reach line, `lattice.InLine`): the comfortable distance from the shoulder to the
#: wrist, as a fraction of the arm's length less the hand's; a level hand folds the arm less far than a free one, and
#: 0.75 lies inside the range IK reaches for every 5-joint arm of the robot zoo (0.46-0.63 to 0.89-1.0)
LEVEL_REACH_FRACTION = 0.75
#: visible-for: horizontal distances from the camera to the object (m): comfortable, least, most
VIEW_DISTANCE = (1.0, 0.45, 2.5)
#: a camera fixed on the body: how much of half its vertical view the target may be off its axis
VIEW_FILL = 0.8
#: score weights: per radian turned away, per metre driven, per metre off the comfortable view distance
TURN_WEIGHT = 0.15
TRAVEL_WEIGHT = 0.02
VIEW_WEIGHT = 0.3


def travel_scores(xs: np.ndarray, ys: np.ndarray, turns: np.ndarray, here: np.ndarray) -> np.ndarray:
    """The score of turning away from the target and of driving from where the robot stands (`here`, x and y)."""
    return TURN_WEIGHT * np.abs(turns) + TRAVEL_WEIGHT * np.hypot(xs - here[0], ys - here[1])


def _distance(point: np.ndarray, shoulder: tuple[np.ndarray, np.ndarray, float]) -> np.ndarray:
    """Each candidate's distance from its shoulder (x, y arrays and the height) to a point."""
    sx, sy, sz = shoulder
    return np.sqrt((point[0] - sx) ** 2 + (point[1] - sy) ** 2 + (point[2] - sz) ** 2)


def add_reach(scores: np.ndarray, outcome: np.ndarray, xs: np.ndarray, ys: np.ndarray, yaws: np.ndarray,
              arms: dict[str, ArmGeometry], target: np.ndarray, floor_z: float,
              also: np.ndarray | None = None,
              level: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The scores with the best arm's reach cost added, and each candidate's arms nearest first (indices into
    `arms`, -1 for an arm that cannot reach); candidates no arm reaches are marked `out of reach` in `outcome`.
    `also`: a second point the arm must reach from the same pose (where a pull takes a handle): the cost is the middle
    point's, and an arm must reach both. `level`: each candidate's arm index, wrist position and hand length where it
    stands on a reach line that takes the target with the tool held level (`lattice.Poses.level`; -1 elsewhere): for
    that arm, the cost is the wrist's distance off LEVEL_REACH_FRACTION of the arm less the hand."""
    c, s = np.cos(yaws), np.sin(yaws)
    ends = [target] if also is None else [target, also]
    scored = target if also is None else (np.asarray(target) + np.asarray(also)) / 2.0
    costs = []
    for k, geo in enumerate(arms.values()):
        sx = xs + c * geo.shoulder[0] - s * geo.shoulder[1]
        sy = ys + s * geo.shoulder[0] + c * geo.shoulder[1]
        shoulder = (sx, sy, floor_z + geo.shoulder[2])
        beyond = np.any([_distance(end, shoulder) > geo.length + REACH_SLACK for end in ends], axis=0)
        cost = np.abs(_distance(scored, shoulder) - REACH_FRACTION * geo.length)
        if level is not None and (level[0] == k).any():
            on, wrist, hand = level[0] == k, level[1], level[2]
            wrist_distance = np.sqrt((wrist[:, 0] - sx) ** 2 + (wrist[:, 1] - sy) ** 2 + (wrist[:, 2] - shoulder[2]) ** 2)
            cost = np.where(on, np.abs(wrist_distance - LEVEL_REACH_FRACTION * (geo.length - hand)), cost)
        costs.append(np.where(beyond, np.inf, cost))
    stacked = np.stack(costs, axis=1)  # candidates x arms
    best = stacked.min(axis=1)
    order = np.argsort(stacked, axis=1, kind="stable")
    arm_order = np.where(np.isfinite(np.take_along_axis(stacked, order, axis=1)), order, -1).astype(np.int8)
    outcome[~np.isfinite(best)] = CODE["out of reach"]
    return scores + np.where(np.isfinite(best), best, 0.0), arm_order


def add_pull_heading(scores: np.ndarray, yaws: np.ndarray, closed: np.ndarray, opened: np.ndarray) -> np.ndarray:
    """The scores with the cost of facing away from the drawer or door a handle pulls (from its `opened` end towards
    its `closed` one): the hand takes the handle facing into it, which an arm does best with the robot facing so too
    (TURN_WEIGHT per radian off it). Poses facing the handle from its side reach it, but seldom turn the hand into
    the pull."""
    into = np.asarray(closed[:2], dtype=float) - np.asarray(opened[:2], dtype=float)
    if float(np.hypot(*into)) < 1e-6:
        return scores
    heading = math.atan2(float(into[1]), float(into[0]))
    return scores + TURN_WEIGHT * np.abs(np.angle(np.exp(1j * (yaws - heading))))


def add_view(robot: Robot, scores: np.ndarray, outcome: np.ndarray, xs: np.ndarray, ys: np.ndarray,
             yaws: np.ndarray, camera: np.ndarray | None, target: np.ndarray, floor_z: float,
             fixed_camera: bool) -> np.ndarray:
    """The scores with the view cost added (distance off the comfortable one; for a camera fixed on the body, also
    how far the target is off its axis); candidates whose camera is too near, too far or cannot see the target's
    height are marked `out of view` in `outcome` (unless already ruled out)."""
    c, s = np.cos(yaws), np.sin(yaws)
    cx = xs + c * camera[0] - s * camera[1] if camera is not None else xs
    cy = ys + s * camera[0] + c * camera[1] if camera is not None else ys
    distance = np.hypot(target[0] - cx, target[1] - cy)
    out = (distance < VIEW_DISTANCE[1]) | (distance > VIEW_DISTANCE[2])
    if fixed_camera and camera is not None and robot.description.camera is not None:
        # a camera that cannot tilt sees the target only from the distances that put it in its view's height
        off = np.abs(np.arctan2(target[2] - (floor_z + camera[2]), distance) - camera_pitch(robot))
        out |= off > VIEW_FILL * robot.description.camera.vertical_fov / 2
        scores = scores + VIEW_WEIGHT * off
    outcome[(outcome == 0) & out] = CODE["out of view"]
    return scores + VIEW_WEIGHT * np.abs(distance - VIEW_DISTANCE[0])


def here_arm_order(arms: dict[str, ArmGeometry], target: np.ndarray | None, x: float, y: float, yaw: float,
                   floor_z: float, also: np.ndarray | None = None, bounded: bool = False) -> np.ndarray:
    """The arms to try from the robot's own pose (x, y, yaw): nearest shoulder first (one row of arm indices).
    `bounded`: an arm whose shoulder is farther from the target (or from `also`, where a pull takes the handle) than
    the arm is long is -1, as `add_reach` rules it out for every other candidate (the pose the robot stands at after
    taking something at the counter is tried first for the place on the island: without the bound, inverse
    kinematics spent 50-100 ms finding each arm short)."""
    if target is None or not arms:
        return np.zeros((1, len(arms)), dtype=np.int8)
    c, s = math.cos(yaw), math.sin(yaw)
    shoulders = [(x + c * g.shoulder[0] - s * g.shoulder[1], y + s * g.shoulder[0] + c * g.shoulder[1],
                  floor_z + g.shoulder[2]) for g in arms.values()]
    distance = [math.dist(target, shoulder) for shoulder in shoulders]
    order = sorted(range(len(arms)), key=lambda k: (distance[k], k))
    if bounded:
        ends = [target] if also is None else [target, also]
        lengths = [g.length for g in arms.values()]
        order = [k if all(math.dist(end, shoulders[k]) <= lengths[k] + REACH_SLACK for end in ends) else -1
                 for k in order]
    return np.array([order], dtype=np.int8)
