"""Building a BulletWorld from a YAML world file."""
from __future__ import annotations

import contextlib
from collections.abc import Iterator
from pathlib import Path

from ..errors import InputError, Location, raise_if_any
from ..paths import default_world, find_world
from ..robots import assign_description
from ..world import BulletWorld, Object
from ..world.camera import frame_viewer_on_robot
from .spec import WorldSpec, parse_world


@contextlib.contextmanager
def _reported_at(where: Location) -> Iterator[None]:
    """Problems the simulation finds with an object become input errors at its place in the file."""
    try:
        yield
    except (ValueError, KeyError, FileNotFoundError) as exc:
        message = exc.args[0] if isinstance(exc, KeyError) and exc.args else str(exc)
        raise InputError(str(message), where) from None


#: an object that starts deeper than this inside another body is an input error (m); resting contact is about 0.01 mm
#: deep, and the design's meshes settled by physics rest up to about 1 mm in
START_DEPTH = 0.003


def load_spec(spec: WorldSpec, mode: str = "direct", check_start: bool = True) -> BulletWorld:
    """A BulletWorld with the spec's objects. `check_start`: an object that starts inside another body (a mesh whose
    origin is not its bottom, put "on" a counter) is an input error naming both, the depth and the height that frees
    it (sweeps that vary a world check their own scenarios)."""
    world = BulletWorld(mode=mode, gravity=spec.gravity)
    try:
        with world.rendering_paused():
            _load_objects(world, spec)
            if check_start:
                raise_if_any(starting_inside(world, spec))
            frame_viewer_on_robot(world)  # a window's first picture shows the robot, not the default view
        world.source = spec.path
    except BaseException:
        world.exit()
        raise
    return world


def _load_objects(world: BulletWorld, spec: WorldSpec) -> None:
    """The file's objects, their joints, robot description and attachments, into `world`."""
    objects: dict[str, Object] = {}
    for item in spec.objects:
        with _reported_at(item.where):
            objects[item.name] = Object(item.name, item.type, item.file, item.position, item.orientation,
                                        world=world, color=item.color, fixed=item.fixed, mass=item.mass)
            if item.joints:
                objects[item.name].set_joint_positions(item.joints)
            if item is spec.robot:
                assign_description(objects[item.name], spec.robot_description)
                if spec.robot_description is not None:  # its defaults (torso height) where the world sets none
                    defaults = {joint: value for joint, value in spec.robot_description.default_joints().items()
                                if joint not in item.joints}
                    objects[item.name].set_joint_positions(defaults)
    for item in spec.objects:
        for att in item.attach:
            with _reported_at(item.where):
                objects[att.to].attach(objects[item.name], att.parent_link, att.child_link)


def starting_inside(world: BulletWorld, spec: WorldSpec) -> list[InputError]:
    """Free objects (neither robots nor environments) that start more than START_DEPTH inside another body, each
    reported once at its place in the file; what holds an object (attach) may touch it."""
    errors: list[InputError] = []
    reported: set[frozenset[str]] = set()
    for item in spec.objects:
        obj = world.get_object_by_name(item.name)
        if obj is None or obj.fixed:
            continue
        for other in world.objects:
            pair = frozenset((obj.name, other.name))
            if other is obj or pair in reported or other in obj.attachments:
                continue
            points = world.closest_points(obj, other, 0.0)
            deepest = min(points, key=lambda point: point.distance, default=None)
            if deepest is None or deepest.distance >= -START_DEPTH:
                continue
            reported.add(pair)
            depth = -deepest.distance
            link = other.get_link_name(deepest.link_b)
            where = other.name + (f" ({link})" if other.joints and link != other.name else "")
            z = item.position[2] + depth + 0.001
            errors.append(InputError(
                f"{item.name} starts {depth * 1000:.0f} mm inside {where}", item.where, key="position",
                suggestion=f"raise it to z = {z:.3f} (its origin may not be its bottom), or turn it upright with "
                           "'up:' or 'orientation:'"))
    return errors


def load_world(path: str | Path | None = None, mode: str = "direct") -> BulletWorld:
    """A BulletWorld built from `path` (default: the bundled kitchen world): a world file, or a name as the command
    line takes it (`kitchen_fetch`: the working folder's `worlds/` first, then the bundled worlds)."""
    return load_spec(parse_world(find_world(str(path)) if path is not None else default_world()), mode=mode)
