"""Building a BulletWorld from a YAML world file."""
from __future__ import annotations

import contextlib
from pathlib import Path
from typing import Iterator

from ..errors import InputError, Location
from ..paths import default_world, find_world
from ..robots import assign_description
from ..world import BulletWorld, Object
from .spec import WorldSpec, parse_world


@contextlib.contextmanager
def _reported_at(where: Location) -> Iterator[None]:
    """Problems the simulation finds with an object become input errors at its place in the file."""
    try:
        yield
    except (ValueError, KeyError, FileNotFoundError) as exc:
        message = exc.args[0] if isinstance(exc, KeyError) and exc.args else str(exc)
        raise InputError(str(message), where) from None


def load_spec(spec: WorldSpec, mode: str = "direct") -> BulletWorld:
    world = BulletWorld(mode=mode, gravity=spec.gravity)
    try:
        with world.rendering_paused():
            _load_objects(world, spec)
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


def load_world(path: str | Path | None = None, mode: str = "direct") -> BulletWorld:
    """A BulletWorld built from `path` (default: the bundled kitchen world): a world file, or a name as the command
    line takes it (`kitchen_fetch`: the working folder's `worlds/` first, then the bundled worlds)."""
    return load_spec(parse_world(find_world(str(path)) if path is not None else default_world()), mode=mode)
