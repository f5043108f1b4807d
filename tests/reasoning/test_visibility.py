"""visible(obj, camera) and occluding(obj, camera): what the robot's camera (or any camera) sees of an object."""
from __future__ import annotations

import math

import numpy as np
import pybullet as p
import pytest
from scenes import fingerprint

from pycram_cli.reasoning import VisibleAnswer, occluding, visible
from pycram_cli.reasoning.visibility import look_at

CAMERA = "wide_stereo_optical_frame"
BREAKFAST = ["milk", "cereal", "bowl", "bottle"]


def camera_position(world):
    return np.array(world.robot.get_link_position(CAMERA))


def between(world, obj, fraction):
    """A point on the line from the robot's camera to the object's centre."""
    lo, hi = obj.get_aabb()
    centre = (np.array(lo) + np.array(hi)) / 2
    eye = camera_position(world)
    return eye + fraction * (centre - eye)


def full_frame_fraction(world, obj, eye, size=256):
    """The design's method, for reference: two full 256x256 frames looking at the object."""
    lo, hi = obj.get_aabb()
    centre = (np.array(lo) + np.array(hi)) / 2
    cid = world.client_id
    view = p.computeViewMatrix(eye.tolist(), centre.tolist(), [0, 0, 1], physicsClientId=cid)
    proj = p.computeProjectionMatrixFOV(20, 1, 0.01, 10, physicsClientId=cid)
    scene = np.asarray(p.getCameraImage(size, size, view, proj, renderer=p.ER_TINY_RENDERER, physicsClientId=cid)[4])
    saved = obj.get_pose()
    others = [o for o in world.objects if o is not obj]
    with world.snapshot():  # render it alone: everything else far away
        for other in others:
            if not other.fixed:
                other.set_position([50, 50, 50])
        hidden = []
        for other in others:
            if other.fixed:
                for shape in p.getVisualShapeData(other.id, physicsClientId=cid):
                    hidden.append((other.id, shape[1], shape[7]))
                    p.changeVisualShape(other.id, shape[1], rgbaColor=[1, 1, 1, 0], physicsClientId=cid)
        alone = np.asarray(p.getCameraImage(size, size, view, proj, renderer=p.ER_TINY_RENDERER, physicsClientId=cid)[4])
        for body, link, rgba in hidden:
            p.changeVisualShape(body, link, rgbaColor=rgba, physicsClientId=cid)
    assert obj.get_pose() == saved
    return float((scene == obj.id).sum()) / float((alone == obj.id).sum())


@pytest.mark.parametrize("name", BREAKFAST)
def test_the_breakfast_on_the_counter_is_in_full_view_of_the_robot(scene, name):
    answer = visible(scene.get_object_by_name(name))
    assert isinstance(answer, VisibleAnswer) and answer
    assert answer.fraction == 1.0 and answer.pixels == answer.total > 100
    assert occluding(scene.get_object_by_name(name)) == []


def test_the_spoon_in_the_closed_drawer_is_hidden_by_the_kitchen(scene):
    spoon = scene.get_object_by_name("spoon")
    answer = visible(spoon)
    assert not answer and answer.fraction == 0.0 and answer.total > 0
    assert scene.get_object_by_name("kitchen") in occluding(spoon)


def test_an_object_in_front_hides_the_object_and_is_named_as_occluder(scene):
    bottle, cereal = scene.get_object_by_name("bottle"), scene.get_object_by_name("cereal")
    cereal.set_position(between(scene, bottle, 0.8) - np.array([0, 0, 0.14]))  # the box's middle on the line
    answer = visible(bottle)
    assert not answer and answer.fraction < 0.2
    assert occluding(bottle) == [cereal]


def test_a_partly_covered_object_has_a_fraction_between_zero_and_one(scene):
    bottle, milk = scene.get_object_by_name("bottle"), scene.get_object_by_name("milk")
    milk.set_position(between(scene, bottle, 0.7) + np.array([0, 0.05, -0.18]))
    answer = visible(bottle)
    assert 0.05 < answer.fraction < 0.95
    assert answer.pixels == round(answer.fraction * answer.total)
    assert visible(bottle, threshold=answer.fraction - 0.01)
    assert not visible(bottle, threshold=answer.fraction + 0.01)
    assert occluding(bottle) == [milk]


def test_the_fraction_agrees_with_full_frame_rendering(scene):
    bottle, milk = scene.get_object_by_name("bottle"), scene.get_object_by_name("milk")
    milk.set_position(between(scene, bottle, 0.7) + np.array([0, 0.05, -0.18]))
    eye = camera_position(scene)
    assert visible(bottle, eye.tolist()).fraction == pytest.approx(full_frame_fraction(scene, bottle, eye), abs=0.05)


def test_several_occluders_are_sorted_by_name_and_never_include_the_object(scene):
    bottle, milk, cereal = (scene.get_object_by_name(n) for n in ("bottle", "milk", "cereal"))
    lo, hi = bottle.get_aabb()
    right = look_at(camera_position(scene), (np.array(lo) + np.array(hi)) / 2)[:, 0]
    right = right / np.linalg.norm(right[:2])
    # the milk covers a strip on the left of the bottle, the cereal box one on the right
    milk.set_position(between(scene, bottle, 0.7) - right * (0.035 + 0.7 * 0.0365 - 0.01) - [0, 0, 0.1])
    cereal.set_position(between(scene, bottle, 0.5) + right * (0.099 + 0.5 * 0.0365 - 0.01) - [0, 0, 0.14])
    answer = visible(bottle)
    assert 0.3 < answer.fraction < 0.9
    assert occluding(bottle) == [cereal, milk]


def test_an_object_outside_the_cameras_field_of_view_is_not_visible(scene):
    scene.robot.set_joint_positions({"head_pan_joint": 1.6})  # looking to the left
    milk = scene.get_object_by_name("milk")
    assert visible(milk) == VisibleAnswer(False, 0.0, 0, 0)
    assert occluding(milk) == []


def test_an_object_at_the_edge_of_the_view_is_partly_visible(scene):
    cereal = scene.get_object_by_name("cereal")
    pan_position = np.array(scene.robot.get_link_position("head_pan_link"))
    x, y, _ = np.array(cereal.get_position()) - pan_position
    half_fov = 0.995 / 2
    scene.robot.set_joint_positions({"head_pan_joint": math.atan2(y, x) + half_fov})  # its centre on the right edge
    answer = visible(cereal)
    assert not answer and 0.2 < answer.fraction < 0.8
    assert occluding(cereal) == []


def test_a_bare_position_camera_looks_straight_at_the_object(scene):
    bottle = scene.get_object_by_name("bottle")
    answer = visible(bottle, [1.35, 0.4, 1.8])  # right above it
    assert answer and answer.fraction == 1.0
    from_side = visible(bottle, (1.32, 2.0, 1.0))  # from the side, through the milk carton
    assert from_side.fraction < 0.5
    assert scene.get_object_by_name("milk") in occluding(bottle, (1.32, 2.0, 1.0))


def test_a_pose_camera_is_an_optical_frame(scene):
    milk = scene.get_object_by_name("milk")
    eye = [0.3, 1.0, 1.2]
    aimed = (eye, _quaternion(look_at(eye, [1.3, 1.0, 0.95])))
    away = (eye, _quaternion(look_at(eye, [-1.0, 1.0, 0.95])))
    assert visible(milk, aimed).fraction == 1.0
    assert visible(milk, away) == VisibleAnswer(False, 0.0, 0, 0)


def test_the_robot_camera_frame_by_name_or_pose_is_the_default_camera(scene):
    bottle = scene.get_object_by_name("bottle")
    robot = scene.robot
    default = visible(bottle)
    assert visible(bottle, CAMERA) == default
    assert visible(bottle, robot.get_link_position_and_orientation(CAMERA)) == default


def test_another_robot_link_is_a_position_looking_at_the_object(scene):
    answer = visible(scene.get_object_by_name("milk"), "head_tilt_link")
    assert answer and answer.fraction == 1.0


def test_unknown_camera_links_are_reported_with_a_suggestion(scene):
    with pytest.raises(KeyError, match="did you mean 'head_tilt_link'"):
        visible(scene.get_object_by_name("milk"), "head_tilt_lnk")


def test_visible_and_occluding_change_nothing_not_even_colours(scene):
    cid = scene.client_id
    colours = [p.getVisualShapeData(o.id, physicsClientId=cid) for o in scene.objects]
    before = fingerprint(scene)
    for name in BREAKFAST + ["spoon"]:
        obj = scene.get_object_by_name(name)
        visible(obj)
        occluding(obj)
        visible(obj, [1.0, 0.0, 1.5])
    assert fingerprint(scene) == before
    assert [p.getVisualShapeData(o.id, physicsClientId=cid) for o in scene.objects] == colours


def _quaternion(rotation):
    from pycram_cli.world.pose import matrix_to_quat

    return matrix_to_quat(rotation)
