"""Location designators: what they find holds when checked with the reasoning queries, what they cannot find
fails with the tests that ruled the candidates out, and the world is left exactly as it was."""
from __future__ import annotations

import math

import numpy as np
import pytest

from pycram_cli.errors import InputError
from pycram_cli.failures import LocationFailure
from pycram_cli.kinds import KINDS, Robots
from pycram_cli.locations import BasePose, Spot, floor, floor_map, locate, parse_location
from pycram_cli.designators import perform
from pycram_cli.paths import worlds_dir
from pycram_cli.robots import Robot
from pycram_cli.reasoning import blocking, reachable, stable, supporting, visible
from pycram_cli.robots import description_for
from pycram_cli.worldfile.loader import load_world

HANDLE = "sink_area_left_upper_drawer_handle"


@pytest.fixture(scope="module")
def fetch_kitchen():
    world = load_world(worlds_dir() / "kitchen_fetch.yaml")
    yield world
    world.exit()


@pytest.fixture
def world(kitchen):
    with kitchen.snapshot():
        yield kitchen


def state_of(world):
    """Every pose, joint position and attachment, to compare bitwise."""
    return [(o.name, o.get_pose(), tuple(o.get_joint_positions().items()), tuple(sorted(a.child.name for a in o.attachments.values())))
            for o in world.objects]


def stand(world, pose: BasePose) -> None:
    world.robot.set_position_and_orientation(pose.position, pose.orientation)


# -- the location kind: checked without a world ------------------------------------------------------------


@pytest.mark.parametrize("value, problem", [
    ({"reachable-for": "milk"}, None),
    ({"reachable-for": "milk", "visible-for": "milk", "arm": "left", "grasp": "front"}, None),
    ({"on": "kitchen_island_surface", "for": "milk", "near": [-1, 1, 0.9]}, None),
    ({True: "kitchen_island_surface"}, None),  # YAML 1.1 reads an unquoted `on` as true
    ({"accessing": HANDLE, "arm": "left"}, None),
    ("milk", "expected a location mapping"),
    ({}, "a location needs one of reachable-for, visible-for, on, accessing"),
    ({"reachable": "milk"}, "a location has no key 'reachable' (did you mean 'reachable-for'?)"),
    ({"on": "x", "accessing": "y"}, "on and accessing do not go together"),
    ({"visible-for": "milk", "grasp": "top"}, "'grasp' goes with reachable-for"),
    ({"reachable-for": [1, 2]}, "reachable-for: expected an object name or a position [x, y, z]"),
    ({"reachable-for": "milk", "arm": "middle"}, "reachable-for"),  # checked below with the robot known
])
def test_the_location_kind_checks_keys_and_values(value, problem):
    found = KINDS["location"].check(value, Robots())
    if problem is None or problem == "reachable-for":
        assert found is None
    else:
        assert found is not None and found.startswith(problem)


def test_the_location_kind_checks_arms_against_the_robot(kitchen):
    robots = Robots((description_for(kitchen.robot),), True)
    assert KINDS["location"].check({"reachable-for": "milk", "arm": "middle"}, robots) == \
        "arm: pr2 has no arm 'middle' (arms: left, right)"


def test_the_location_kind_names_the_objects_and_links_it_mentions():
    names = KINDS["location"].names_in({"reachable-for": "milk", "visible-for": "$obj", "on": "island"})
    assert names == [("reachable-for", "milk", "object"), ("on", "island", "object or link")]


# -- reading a location in a world: input errors -----------------------------------------------------------


@pytest.mark.parametrize("value, key, message, suggestion", [
    ({"reachable-for": "mlik"}, "reachable-for", "no object 'mlik'", "did you mean 'milk'?"),
    ({"on": "kitchen_island_surfac", "for": "milk"}, "on", "no surface 'kitchen_island_surfac'", "did you mean 'kitchen_island_surface'?"),
    ({"on": "kitchen_island_surface"}, "for", "which object should fit on kitchen_island_surface?", None),
    ({"accessing": "sink_area_left_upper_drawer_handel"}, "accessing", "no link", "did you mean"),
    ({"accessing": "sink_area_surface"}, "accessing", "'sink_area_surface' of 'kitchen' moves with no joint", None),
    ({"visible-for": "pr2"}, "visible-for", "'pr2' is the robot itself", None),
])
def test_unknown_objects_surfaces_and_handles_are_input_errors(kitchen, value, key, message, suggestion):
    with pytest.raises(InputError) as caught:
        parse_location(kitchen, value)
    assert caught.value.key == key and caught.value.message.startswith(message)
    if suggestion:
        assert caught.value.suggestion.startswith(suggestion)


def test_a_bad_value_is_reported_at_its_key_once(kitchen):
    with pytest.raises(InputError) as caught:
        parse_location(kitchen, {"reachable-for": "milk", "arm": "arm"})
    assert (caught.value.key, caught.value.message) == ("arm", "pr2 has no arm 'arm' (arms: left, right)")
    with pytest.raises(InputError) as caught:
        parse_location(kitchen, {"visible-for": "milk", "near": [1, 2, 3]})
    assert (caught.value.key, caught.value.message) == (None, "'near' goes with on")


def test_a_handle_is_found_with_the_joint_that_opens_it(kitchen):
    spec = parse_location(kitchen, {"accessing": HANDLE})
    assert spec.accessing.joint == "sink_area_left_upper_drawer_main_joint"


# -- what is found holds ---------------------------------------------------------------------------------


def test_reachable_for_an_object_gives_a_pose_an_arm_and_a_grasp_that_reach_it_untouched(world):
    before = state_of(world)
    pose = locate(world, {"reachable-for": "milk"}).next()
    assert state_of(world) == before  # resolving moved nothing
    milk = world.get_object_by_name("milk")
    stand(world, pose)
    tool = description_for(world.robot).arm(pose.arm).tool_frame
    assert reachable(milk, world.robot, tool, grasp=pose.grasp)
    assert [o.name for o in blocking(milk, world.robot, tool, grasp=pose.grasp, exclude_types=["environment"])] == []
    assert not perform_collisions(world)
    perform(world, "pick-up", {"object": "milk", "arm": pose.arm, "grasp": pose.grasp})
    assert Robot.of(world).arm_holding(milk) == pose.arm


def perform_collisions(world):
    return floor.exact_collisions(world.robot, [], *world.robot.get_position()[:2],
                                  2 * math.atan2(world.robot.get_orientation()[2], world.robot.get_orientation()[3]))


def test_visible_for_gives_a_pose_from_which_the_camera_sees_the_object(world):
    pose = locate(world, {"visible-for": "bottle"}).next()
    stand(world, pose)
    perform(world, "looking", {"target": list(pose.look_at)})
    assert visible(world.get_object_by_name("bottle"))


def test_both_at_once_hold_at_once(world):
    pose = locate(world, {"reachable-for": "milk", "visible-for": "milk"}).next()
    stand(world, pose)
    perform(world, "looking", {"object": "milk"})
    milk = world.get_object_by_name("milk")
    assert visible(milk)
    assert reachable(milk, world.robot, description_for(world.robot).arm(pose.arm).tool_frame, grasp=pose.grasp)


def test_reachable_for_a_position(world):
    target = [1.3, 0.2, 1.0]
    pose = locate(world, {"reachable-for": target, "arm": "right"}).next()
    assert pose.arm == "right"
    stand(world, pose)
    assert reachable(target, world.robot, "r_gripper_tool_frame")


def test_accessing_gives_a_pose_from_which_the_drawer_opens(world):
    pose = locate(world, {"accessing": HANDLE}).next()
    stand(world, pose)
    perform(world, "accessing", {"drawer-handle": HANDLE, "drawer-joint": "sink_area_left_upper_drawer_main_joint",
                                 "part-of": "kitchen", "arm": pose.arm})
    assert world.get_object_by_name("kitchen").get_joint_position("sink_area_left_upper_drawer_main_joint") == \
        pytest.approx(0.3)


@pytest.mark.parametrize("robot", ["pr2", "fetch"])
@pytest.mark.parametrize("opened", [0.0, 0.48], ids=["to open", "to close"])
def test_a_drawer_is_pulled_from_in_front_of_it_facing_into_it_found_at_once(world, fetch_kitchen, robot, opened):
    """Opening or closing a drawer, the robot stands in front of it facing into it (the hand takes the handle facing
    so), within reach of the handle all along the pull; such a pose is ranked first, so the location finds it after a
    few tests, not after a hundred poses from which the arm cannot turn its hand into the pull."""
    world = world if robot == "pr2" else fetch_kitchen
    joint = "sink_area_left_upper_drawer_main_joint"
    kitchen = world.get_object_by_name("kitchen")
    with world.snapshot():
        kitchen.set_joint_position(joint, opened)
        handle = np.asarray(kitchen.get_link_position(HANDLE))
        spec = parse_location(world, {"accessing": HANDLE})
        resolution = locate(world, spec if opened == 0.0 else type(spec)(**{**spec.__dict__, "distance": 0.0}))
        pose = resolution.next()
        into = 0.0  # this drawer opens towards -x: facing +x is facing into it
        assert abs(math.remainder(pose.yaw - into, 2 * math.pi)) < 0.1
        assert abs(pose.position[1] - handle[1]) < 0.15 and pose.position[0] < handle[0]
        assert resolution.expensive <= 3
        stand(world, pose)
        perform(world, "accessing", {"drawer-handle": HANDLE, "drawer-joint": joint, "part-of": "kitchen",
                                     "arm": pose.arm, "distance": 0.3 if opened == 0.0 else 0.0})
        assert kitchen.get_joint_position(joint) == pytest.approx(0.3 if opened == 0.0 else 0.0, abs=1e-3)


def test_on_gives_a_free_spot_where_the_object_stands(world):
    spots = locate(world, {"on": "kitchen_island_surface", "for": "milk", "near": [-1.0, 2.0, 0.9]})
    spot = spots.next()
    assert isinstance(spot, Spot) and spot.surface == "kitchen_island_surface"
    assert math.dist(spot.position[:2], (-1.0, 2.0)) < 0.1  # near what was asked
    milk, kitchen = world.get_object_by_name("milk"), world.get_object_by_name("kitchen")
    milk.set_position_and_orientation(spot.position, spot.orientation)
    assert stable(milk) and supporting(kitchen, milk, "kitchen_island_surface")


def test_on_keeps_clear_of_what_stands_there(world):
    bowl = world.get_object_by_name("bowl")
    bowl.set_position_and_orientation((-1.0, 2.0, 0.862), (0, 0, 0, 1))
    spot = locate(world, {"on": "kitchen_island_surface", "for": "milk", "near": [-1.0, 2.0, 0.9]}).next()
    assert math.dist(spot.position[:2], (-1.0, 2.0)) > 0.1


def test_the_sequence_is_lazy_ranked_and_the_same_every_time(world):
    first = locate(world, {"reachable-for": "milk"})
    poses = [first.next(), first.next(), first.next()]
    assert len({(p.position, p.yaw) for p in poses}) == 3
    assert [p.score for p in poses] == sorted(p.score for p in poses)
    again = locate(world, {"reachable-for": "milk"})
    assert [again.next() for _ in range(3)] == poses


def test_the_fetch_finds_where_to_stand_with_the_same_code(fetch_kitchen):
    with fetch_kitchen.snapshot():
        pose = locate(fetch_kitchen, {"reachable-for": "milk", "visible-for": "milk"}).next()
        assert pose.arm == "arm"
        stand(fetch_kitchen, pose)
        perform(fetch_kitchen, "looking", {"object": "milk"})
        assert visible(fetch_kitchen.get_object_by_name("milk"))


# -- what cannot be found --------------------------------------------------------------------------------


def test_an_unreachable_target_fails_saying_why(world):
    before = state_of(world)
    with pytest.raises(LocationFailure) as caught:
        locate(world, {"reachable-for": [1.3, 0.6, 2.5]}).next()
    assert caught.value.message.startswith("no pose for reachable-for (1.3, 0.6, 2.5): ")
    assert caught.value.message.endswith(" out of reach")
    assert state_of(world) == before


def test_an_object_in_a_closed_drawer_is_not_visible_from_anywhere(world):
    with pytest.raises(LocationFailure) as caught:
        locate(world, {"visible-for": "spoon"}).next()
    assert "not visible" in caught.value.message and "collide" in caught.value.message


def test_a_blocked_object_names_what_blocks_it(world):
    # the bowl boxed in: the milk and cereal beside it, the bottle in front
    for name, (x, y) in {"cereal": (1.3, 0.68), "milk": (1.3, 0.93), "bottle": (1.25, 0.8)}.items():
        world.get_object_by_name(name).set_position((x, y, 0.851))
    resolution = locate(world, {"reachable-for": "bowl", "arm": "left", "grasp": "top"})
    with pytest.raises(LocationFailure) as caught:
        resolution.next()
    assert "blocked" in caught.value.message and "(blocked by " in caught.value.message


def test_a_full_surface_has_no_spot(world):
    resolution = locate(world, {"on": "milk", "for": "bowl"})
    with pytest.raises(LocationFailure) as caught:
        resolution.next()
    assert caught.value.message.startswith("no spot on milk for bowl: the surface is smaller than the object")


# -- the floor map ----------------------------------------------------------------------------------------


def test_the_floor_map_never_calls_a_colliding_pose_free(kitchen):
    """Over random poses around the counter the map misses no collision the robot's shapes have (it is a prefilter:
    conservative by about a cell)."""
    with kitchen.snapshot():
        robot = kitchen.robot
        built = floor.build(robot)
        rng = np.random.default_rng(7)
        xs, ys, yaws = rng.uniform(-0.6, 1.2, 150), rng.uniform(-0.5, 2.3, 150), rng.uniform(-math.pi, math.pi, 150)
        said = built.collides(xs, ys, yaws)
        missed = [(x, y, a) for x, y, a, hit in zip(xs, ys, yaws, said)
                  if not hit and floor.exact_collisions(robot, [], x, y, a)]
    assert missed == []
    assert said.sum() > 20 and (~said).sum() > 20


def test_the_floor_map_leaves_the_room_under_a_cabinets_handle_bar(kitchen):
    """A cabinet of panels, its plinth set back and a handle bar out front, is as solid on the map as its shapes, not
    as its one bounding box: at the base's height the floor under the dish washer's handle is free (a robot whose
    wheels go under it stands as close to the counter as it really can)."""
    cabinet = kitchen.get_object_by_name("kitchen")
    lo, hi = cabinet.get_aabb("sink_area")
    built = floor.build(kitchen.robot)
    base = built.bands[0]  # the lowest: the base's
    ix, iy, _ = built.index(np.array([lo[0] + 0.03, (lo[1] + hi[1]) / 2]))
    assert not base.occupied[ix, iy]
    ix, iy, _ = built.index(np.array([lo[0] + 0.2, (lo[1] + hi[1]) / 2]))  # the cabinet itself
    assert base.occupied[ix, iy]


def test_a_footprint_is_the_same_whatever_was_sampled_before():
    """The robot's footprints are remembered across maps (a robot whose arms did not move has the same ones after
    every motion); boxes a rounding error apart (the robot read again elsewhere) give the footprint of the boxes as
    given, not of the ones sampled first: a sweep's scenario must not depend on what its worker ran before."""
    boxes = [(np.array([-0.3, -0.3, 0.0]), np.array([0.3, 0.3, 0.3])), (np.array([0.1, -0.1, 0.3]), np.array([0.45, 0.1, 0.9]))]
    fresh = floor._sampled_footprint(boxes, floor.RESOLUTION)
    floor._FOOTPRINTS.clear()
    nudged = [(lo + 1e-15, hi - 1e-15) for lo, hi in boxes]
    first = floor._footprint_samples(nudged, floor.RESOLUTION)
    again = floor._footprint_samples(boxes, floor.RESOLUTION)
    assert again is first and np.array_equal(first, fresh)
    assert len(floor._footprint_samples([(lo, hi + 0.1) for lo, hi in boxes], floor.RESOLUTION)) > len(fresh)  # others


def test_the_floor_map_is_cached_while_the_world_stands_still(kitchen):
    robot = Robot.of(kitchen)
    first = floor_map(robot, [])
    assert floor_map(robot, []) is first
    with kitchen.snapshot():
        robot.body.set_position((0.3, 1.5, 0.0))  # the robot's own pose is not in the map: still the same
        assert floor_map(robot, []) is first
        kitchen.get_object_by_name("bottle").set_position((0.3, 0.3, 0.0))
        moved = floor_map(robot, [])
        assert moved is not first and moved.any_occupied.sum() > first.any_occupied.sum()


def _same_map(a: floor.FloorMap, b: floor.FloorMap) -> bool:
    return (np.array_equal(a.origin, b.origin) and a.shape == b.shape and len(a.bands) == len(b.bands)
            and all(np.array_equal(x.occupied, y.occupied) and np.array_equal(x.samples, y.samples)
                    and (x.low, x.high, x.robot_links, x.obstacles) == (y.low, y.high, y.robot_links, y.obstacles)
                    for x, y in zip(a.bands, b.bands))
            and np.array_equal(a.any_occupied, b.any_occupied) and np.array_equal(a.core_occupied, b.core_occupied))


def test_a_map_built_again_after_things_moved_is_the_map_built_from_nothing(kitchen):
    """Maps rebuilt after a motion reuse what did not move (each object's boxes where it stands, the grids of the
    bands whose furniture is the same): the map they make is exactly the one built with nothing kept, whether the
    drawer was opened, the robot's arm moved or a bottle set elsewhere."""
    robot = Robot.of(kitchen)
    cabinet = kitchen.get_object_by_name("kitchen")
    drawer = cabinet.joint("sink_area_left_upper_drawer_main_joint")
    with kitchen.snapshot():
        floor.build(robot.body)  # what the next maps may reuse
        cabinet.reset_joints({drawer.name: drawer.upper})
        robot.body.reset_joints({robot.description.arm("left").joints[0]: 0.5})
        kitchen.get_object_by_name("bottle").set_position((0.3, 0.3, 0.0))
        again = floor.build(robot.body)
        floor.forget(kitchen)
        fresh = floor.build(robot.body)
        assert again.bands[0].occupied is not fresh.bands[0].occupied  # really built again, not the grids kept
        assert _same_map(again, fresh)
        assert not _same_map(fresh, floor.build(robot.body, ignore=[cabinet]))  # (the comparison sees a difference)
