"""visible/occluding draw only what can be seen (issue 15); the answers must be those of drawing everything.

Over random kitchens (objects on the counter, in the air, tilted; the robot anywhere in front of the
counter with its head and arms anywhere) and random cameras, each object's answers are compared with
the full render the queries used before: the whole world in the world's own client (every body, every
link), in the same cropped window, the object alone counted as before. Same occluders, visible fraction
within 0.02. Also on the real PR2 in the real IAI kitchen when ../shared/models is present.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scenes import kitchen_world
from test_restore import arrange

from pycram_cli.reasoning import occluding, visible
from pycram_cli.reasoning import visibility as V
from pycram_cli.world.camera import projection_matrix, view_matrix

FREE = ["milk", "cereal", "bowl", "spoon", "bottle"]
SCENES = 12


def full_render(world, obj, camera):
    """(fraction, occluders) the way the queries rendered before issue 15: the whole world drawn."""
    cam = V.resolve_camera(obj, camera)
    window = V._window(obj, cam)
    if window is None:
        return 0.0, []
    umin, umax, vmin, vmax, near, far = window
    if cam.fov is not None:
        tu, tv = math.tan(cam.fov[0] / 2.0), math.tan(cam.fov[1] / 2.0)
        if umax < -tu or umin > tu or vmax < -tv or vmin > tv:
            return 0.0, []
    ratio = (umax - umin) / (vmax - vmin)
    width = int(min(V.MAX_SIDE, max(V.MIN_SIDE, round(math.sqrt(V.PIXEL_BUDGET * ratio)))))
    height = int(min(V.MAX_SIDE, max(V.MIN_SIDE, round(math.sqrt(V.PIXEL_BUDGET / ratio)))))
    eye, forward, down = cam.position, cam.rotation[:, 2], cam.rotation[:, 1]
    view = view_matrix(eye.tolist(), (eye + forward).tolist(), (-down).tolist())
    proj = projection_matrix(near * umin, near * umax, -near * vmax, -near * vmin, near, far)
    scene = world.segmentation(width, height, view, proj)  # the world's own client: everything
    alone = world.segmentation_alone(obj, width, height, view, proj)
    in_view = np.ones_like(alone)
    if cam.fov is not None:
        us = umin + (np.arange(width) + 0.5) / width * (umax - umin)
        vs = vmin + (np.arange(height) + 0.5) / height * (vmax - vmin)
        in_view = (np.abs(vs)[:, None] <= tv) & (np.abs(us)[None, :] <= tu)
    total = int(alone.sum())  # pixels outside the field of view are not seen
    fraction = int((alone & in_view & (scene == obj.id)).sum()) / total if total else 0.0
    ids = {int(i) for i in np.unique(scene[alone & in_view])} - {obj.id, -1}
    return fraction, sorted(world.get_object_by_id(i).name for i in ids)


def cameras(world, rng):
    yield None  # the robot's camera
    for _ in range(2):  # positions looking straight at the object
        yield [float(rng.uniform(-0.5, 1.0)), float(rng.uniform(-0.5, 2.0)), float(rng.uniform(0.9, 2.2))]


def check(world, rng, label):
    compared = 0
    for name in FREE:
        obj = world.get_object_by_name(name)
        for camera in cameras(world, rng):
            fraction, occluders = full_render(world, obj, camera)
            answer = visible(obj, camera)
            assert answer.fraction == pytest.approx(fraction, abs=0.02), f"{label}: {name} from {camera}"
            assert [o.name for o in occluding(obj, camera)] == occluders, f"{label}: {name} from {camera}"
            compared += 1
    return compared


@pytest.mark.parametrize("seed", range(SCENES))
def test_drawing_only_what_can_be_seen_answers_as_drawing_everything(scene, seed):
    rng = np.random.default_rng(100 + seed)
    arrange(scene, rng)
    scene.robot.set_joint_positions({"head_pan_joint": float(rng.uniform(-0.6, 0.6)),
                                     "head_tilt_joint": float(rng.uniform(0.1, 0.9))})
    assert check(scene, rng, f"scene {seed}") == 15


def test_the_robot_turned_to_look_at_the_breakfast_sees_what_a_full_render_sees():
    world = kitchen_world()
    try:
        world.robot.set_position_and_orientation((0.65, 0.7, 0.0), (0, 0, 0, 1))
        check(world, np.random.default_rng(0), "at the counter")
    finally:
        world.exit()


@pytest.mark.parametrize("seed", range(4))
def test_on_the_real_pr2_in_the_real_kitchen_too(real_kitchen, seed):
    rng = np.random.default_rng(200 + seed)
    world = real_kitchen
    if seed:
        world.robot.set_position_and_orientation((float(rng.uniform(0.3, 0.7)), float(rng.uniform(0.4, 1.0)), 0.0),
                                                 (0, 0, 0, 1))
        world.robot.set_joint_positions({"head_pan_joint": float(rng.uniform(-0.5, 0.5)),
                                         "head_tilt_joint": float(rng.uniform(0.2, 0.8))})
    check(world, rng, f"real kitchen {seed}")
