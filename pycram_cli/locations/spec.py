"""A location mapping read against a world: its objects and links looked up, every problem an input error.

    {reachable-for: milk, arm: left, grasp: front}     base poses from which the arm reaches the milk
    {visible-for: milk}                                base (and head) poses from which the camera sees it
    {reachable-for: milk, visible-for: milk}           both at once
    {on: kitchen_island_surface, for: milk, near: P}   a free spot on a surface where the milk fits and stands
    {accessing: sink_area_left_upper_drawer_handle}    where to stand to open that drawer

The keys and their static checks are the `location` kind's (`pycram_cli.kinds`); here names
become objects and links of the world, with suggestions for typos.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..errors import InputError, Location, did_you_mean
from ..kinds import KINDS, Robots, location_mapping, parse_vector
from ..robots import description_for
from ..schema import is_vector
from ..world import BulletWorld, Object

WHERE = Location("location")


@dataclass(frozen=True)
class Surface:
    """A supporting surface: a link of an object (or the object's top, when the object is named)."""

    obj: Object
    link: str | None  # None: the object as a whole

    @property
    def name(self) -> str:
        """The link's name (`OBJECT/LINK` when another object has a link of that name too), or the object's."""
        if self.link is None:
            return self.obj.name
        shared = any(o is not self.obj and o is not o.world.robot and self.link in o.link_names
                     for o in self.obj.world.objects)
        return f"{self.obj.name}/{self.link}" if shared else self.link

    def box(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        return self.obj.get_aabb(self.link) if self.link is not None else self.obj.get_aabb()


@dataclass(frozen=True)
class Handle:
    """A handle link of an articulated object and the joint it opens."""

    obj: Object
    link: str
    joint: str


@dataclass(frozen=True)
class LocationSpec:
    """What a location asks for, with names resolved in one world."""

    reachable_for: Object | tuple[float, float, float] | None = None
    visible_for: Object | None = None
    arm: str | None = None
    grasp: Any = None
    on: Surface | None = None
    for_object: Object | None = None
    near: tuple[float, float, float] | None = None
    accessing: Handle | None = None
    #: how far the drawer or door opens (accessing; set by the open and close actions)
    distance: float | None = None
    #: placing: the held object whose origin must reach `reachable_for`, and the surface it goes on (set by the
    #: place action: the arm may touch that surface)
    placing: Object | None = None
    onto: Surface | None = None
    #: at most this many candidates get the expensive tests (None: the resolution's own patience, which grows while
    #: nothing is in the way). An action with a cheaper way to try next sets it (the open action's one stroke, before
    #: it tries strokes: an arm that follows no pull that long failed IK at 120 poses, 6 s, to learn it)
    patience: int | None = None

    @property
    def kind(self) -> str:
        if self.on is not None:
            return "on"
        if self.accessing is not None:
            return "accessing"
        if self.reachable_for is not None and self.visible_for is not None:
            return "reachable-for and visible-for"
        return "reachable-for" if self.reachable_for is not None else "visible-for"

    def describe(self) -> str:
        """The location in words: `reachable-for milk (left arm)`."""
        def name(value: Any) -> str:
            if isinstance(value, Object):
                return value.name
            if isinstance(value, (list, tuple)):
                return "(" + ", ".join(f"{v:.3g}" for v in value) + ")"
            return str(value)

        parts = []
        if self.reachable_for is not None:
            parts.append(f"reachable-for {name(self.reachable_for)}")
        if self.visible_for is not None:
            parts.append(f"visible-for {name(self.visible_for)}")
        if self.on is not None:
            parts.append(f"on {self.on.name}" + (f" for {self.for_object.name}" if self.for_object else ""))
        if self.accessing is not None:
            parts.append(f"accessing {self.accessing.link}")
        extra = [f"arm {self.arm}"] if self.arm else []
        if self.placing is not None:
            extra.append(f"placing {self.placing.name}")
        if self.grasp is not None:
            extra.append(f"grasp {name(self.grasp)}")
        if self.near is not None:
            extra.append(f"near {name(self.near)}")
        return " and ".join(parts) + (f" ({', '.join(extra)})" if extra else "")

    def to_json(self) -> dict[str, Any]:
        data: dict[str, Any] = {}
        if self.reachable_for is not None:
            target = self.reachable_for
            data["reachable-for"] = target.name if isinstance(target, Object) else list(target)
        if self.visible_for is not None:
            data["visible-for"] = self.visible_for.name
        if self.arm is not None:
            data["arm"] = self.arm
        if self.grasp is not None:
            data["grasp"] = self.grasp if isinstance(self.grasp, str) else list(self.grasp)
        if self.on is not None:
            data["on"] = self.on.name
        if self.for_object is not None:
            data["for"] = self.for_object.name
        if self.near is not None:
            data["near"] = list(self.near)
        if self.accessing is not None:
            data["accessing"] = self.accessing.link
        if self.placing is not None:  # set by the place action: the held object's origin goes to reachable-for
            data["placing"] = self.placing.name
        return data


def _error(key: str, message: str, suggestion: str | None = None) -> InputError:
    return InputError(message, WHERE, key=key, suggestion=suggestion)


def find_object(world: BulletWorld, value: Any, key: str) -> Object:
    if isinstance(value, Object):
        if value.world is not world:
            raise _error(key, f"object '{value.name}' is not in this world")
        return value
    found = world.get_object_by_name(str(value))
    if found is None:
        raise _error(key, f"no object '{value}'", did_you_mean(str(value), [o.name for o in world.objects]))
    return found


def _links(world: BulletWorld) -> dict[str, Object]:
    """Every link name of every object but the robot, to the (first) object that has it."""
    found: dict[str, Object] = {}
    for obj in world.objects:
        if obj is world.robot:
            continue
        for link in obj.link_names:
            found.setdefault(link, obj)
    return found


def find_surface(world: BulletWorld, value: Any) -> Surface:
    """An object (its top), a link of one (`kitchen_island_surface`), or `OBJECT/LINK` (`table_b/baseLink`): a link
    name that several objects have (two tables of one model) must say whose."""
    if isinstance(value, Object):
        return Surface(find_object(world, value, "on"), None)
    name = str(value)
    obj = world.get_object_by_name(name)
    if obj is not None and obj is not world.robot:
        return Surface(obj, None)
    owner, slash, link = name.partition("/")
    if slash:
        holder = world.get_object_by_name(owner)
        if holder is None or holder is world.robot:
            raise _error("on", f"no object '{owner}' (in '{name}')",
                         did_you_mean(owner, [o.name for o in world.objects if o is not world.robot]))
        if link not in holder.link_names:
            raise _error("on", f"'{owner}' has no link '{link}'", did_you_mean(link, holder.link_names))
        return Surface(holder, link)
    holders = [o for o in world.objects if o is not world.robot and name in o.link_names]
    if len(holders) > 1:
        raise _error("on", f"'{name}' is a link of {' and '.join(o.name for o in holders)}: say whose",
                     f"e.g. on: {holders[-1].name}/{name}")
    if holders:
        return Surface(holders[0], name)
    links = _links(world)
    candidates = [*links, *(o.name for o in world.objects if o is not world.robot)]
    raise _error("on", f"no surface '{name}': neither an object nor a link of one", did_you_mean(name, candidates))


def opening_joint(obj: Object, link: str) -> str | None:
    """The movable joint that carries a link (the first one up its chain): a handle's drawer or door joint."""
    index = obj.get_link_id(link)
    while index != -1:
        joint = obj.joints[index]
        if joint.movable:
            return joint.name
        index = joint.parent_index
    return None


def find_handle(world: BulletWorld, value: Any, key: str = "accessing") -> Handle:
    name = str(value)
    links = _links(world)
    if name not in links:
        raise _error(key, f"no link '{name}' in the world", did_you_mean(name, list(links)))
    obj = links[name]
    joint = opening_joint(obj, name)
    if joint is None:
        raise _error(key, f"'{name}' of '{obj.name}' moves with no joint: nothing to open or close there")
    return Handle(obj, name, joint)


def handle_of(obj: Object, joint: str) -> str | None:
    """The handle link a joint's drawer or door carries: a link named `*handle*` below the joint's link."""
    index = obj.joint(joint).index
    below = [j for j in obj.joints if obj.hangs_below(j.index, index)]
    handles = [j.child_link for j in below if "handle" in j.child_link]
    return sorted(handles)[0] if handles else None


def parse_location(world: BulletWorld, value: Any, for_object: Object | None = None) -> LocationSpec:
    """The location a mapping names in `world` (InputError for bad keys, unknown objects, links, arms, grasps).

    `for_object` fills `for` of an `on` location when the mapping leaves it out (the object being placed).
    """
    robot = world.robot
    desc = description_for(robot) if robot is not None else None
    robots = Robots((desc,), True) if desc is not None else Robots()
    value = location_mapping(value)
    if isinstance(value, Mapping):
        value = {k: v for k, v in value.items() if v is not None}
    problem = KINDS["location"].check(value, robots)
    if problem:
        key = next((k for k in (value if isinstance(value, Mapping) else ()) if problem.startswith(f"{k}: ")), None)
        raise InputError(problem[len(key) + 2:] if key else problem, WHERE, key=key)
    assert isinstance(value, Mapping)
    for key in ("reachable-for", "accessing"):
        if key in value and desc is not None and not desc.arms:
            raise _error(key, f"robot '{desc.name}' cannot reach: it has no arms (arms: {{}} in {desc.path.name})")
    reach: Any = None
    if "reachable-for" in value:
        target = value["reachable-for"]
        if isinstance(target, str) and parse_vector(target, 3) is not None:
            target = parse_vector(target, 3)
        if is_vector(target, 3):
            reach = (float(target[0]), float(target[1]), float(target[2]))
        else:
            reach = find_object(world, target, "reachable-for")
    visible = find_object(world, value["visible-for"], "visible-for") if "visible-for" in value else None
    surface = find_surface(world, value["on"]) if "on" in value else None
    obj_for = find_object(world, value["for"], "for") if "for" in value else (for_object if surface else None)
    if surface is not None and obj_for is None:
        raise _error("for", f"which object should fit on {surface.name}? give 'for: OBJECT'")
    near = None
    if "near" in value:
        near = tuple(float(v) for v in value["near"])
    handle = find_handle(world, value["accessing"]) if "accessing" in value else None
    if visible is not None and (desc is None or desc.camera is None):
        raise _error("visible-for", f"robot '{robot.name if robot else '?'}' has no camera to look with")
    for obj, key in ((reach, "reachable-for"), (visible, "visible-for"), (obj_for, "for")):
        if isinstance(obj, Object) and obj is robot:
            raise _error(key, f"'{obj.name}' is the robot itself")
    if surface is not None and obj_for is not None and surface.obj is obj_for:
        raise _error("on", f"'{obj_for.name}' cannot be placed on itself")
    return LocationSpec(reachable_for=reach, visible_for=visible, arm=value.get("arm"), grasp=value.get("grasp"),
                        on=surface, for_object=obj_for, near=near, accessing=handle)  # type: ignore[arg-type]  # checked above
