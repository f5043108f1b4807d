"""Action steps: an action designator in a plan, and what it expands into as child steps of the trace.

    - action: transport                          the action's name, then its slots beside it
      object-type: milk                          (`pycram designators --actions` lists them)
      target: {on: kitchen_island_surface}       a location designator: a mapping
      as: milk                                   binds what the action gives (the object)

`action:` is a head of its own because two actions share a name with motion designators
(`pick-up`, `place`): `- pick-up: {object: milk, arm: left}` is the motion designator, as in
the design; `- action: pick-up` / `object: milk` is the action, which finds where to stand,
which arm and which grasp, and drives there first.

An action step runs its declaration's `run` with a `PlanActor`: every motion designator, query
and location resolution it performs is a leaf step of the trace below the action's node
(`0:action transport/1:action pick-up/0:locate`, `.../1:attempt 1/0:moving`), taking turns with
concurrent branches like any leaf; every action it performs in turn is a node of its own.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

from ..designators import robot_resources
from ..designators.actions import ACTIONS, Actor, check_action
from ..errors import Location, did_you_mean
from ..failures import Failure
from ..kinds import KINDS, Kind, Robots, location_mapping
from ..robots import description_for
from ..yamlsource import LMap
from .context import is_reference, jsonable, references
from .resources import ResourceAnalysis
from .runtime import Record, Runtime
from .syntax import Node, Parser, node_type, plain, yaml11_on

if TYPE_CHECKING:  # for annotations only: validate imports syntax, which the node classes extend
    from .validate import Validator


def _every_slot() -> tuple[str, ...]:
    names: list[str] = []
    for spec in ACTIONS.values():
        names.extend(n for n in spec.slot_names if n not in names)
    return tuple(names)


@node_type("action")
class ActionStep(Node):
    BINDS = True
    DOC = "perform an action designator (navigate, pick-up, transport, ...): its slots beside `action:`"

    def __init__(self, head: str, where: Location, name: str, slots: LMap) -> None:
        super().__init__(head, where)
        self.name = name
        self.slots = slots

    @classmethod
    def allowed_keys(cls, head: str) -> tuple[str, ...]:
        return _every_slot() + ("as",)

    @classmethod
    def parse(cls, head: str, step: LMap, parser: Parser) -> Node | None:
        name = parser.string(step[head], step.loc(head, True), head)
        if name is None:
            return None
        spec = ACTIONS.get(name)
        if spec is None:
            parser.error(f"unknown action '{name}'", step.loc(head, True), key=head,
                         suggestion=did_you_mean(name, ACTIONS) or f"actions: {', '.join(ACTIONS)}")
            return None
        slots = LMap()
        slots.where, slots.key_where, slots.value_where = step.where, {}, {}
        for key, value in step.items():
            if key in (head, "as"):
                continue
            if key not in spec.slot_names:
                if key in _every_slot():  # other keys the parser has reported already
                    parser.error(f"action '{name}' has no slot '{key}'", step.loc(key), key=str(key),
                                 suggestion=did_you_mean(str(key), spec.slot_names) or f"slots: {', '.join(spec.slot_names)}")
                continue
            slot = spec.slot(str(key))
            if slot is not None and slot.kind == "location" and isinstance(value, LMap) and True in value:
                value = yaml11_on(value)  # YAML 1.1 reads an unquoted `on` as true
            if slot is not None and slot.kind == "location" and isinstance(value, LMap):
                parser.names_only(value)
            slots[key] = value
            slots.key_where[key], slots.value_where[key] = step.loc(key), step.loc(key, True)
        return cls(head, step.loc(head), name, slots)

    def label(self) -> str:
        return f"action {self.name}"

    def resources(self, analysis: ResourceAnalysis) -> frozenset[str]:
        known = {k: (None if is_reference(v) else v) for k, v in plain(self.slots).items()}
        return robot_resources(ACTIONS[self.name].uses(known), analysis.description)

    def check(self, v: Validator) -> None:
        for problem in check_action(self.name, plain(self.slots), is_reference, v.robots):
            where = self.slots.loc(problem.param, True) if problem.param in self.slots else self.where
            v.error(problem.message, where, key=problem.param or self.head, suggestion=problem.suggestion)
        v.refs(self.slots, self.where)
        facts = v.facts
        if facts is None:
            return
        v.need_robot(self.name, self.slots)
        spec = ACTIONS[self.name]
        objects = list(facts.objects)
        for slot in spec.slots:
            value = self.slots.get(slot.name)
            if value is None:
                continue
            where = self.slots.loc(slot.name, True)
            v.known_values(slot.name, slot.kind, value, where)
            if slot.kind == "object-type":
                v.object_type(slot.name, value, where)
            for key, name, what, origin in _slot_names(v, slot.name, KINDS[slot.kind], value):
                self._known(v, key or slot.name, name, what, where, objects, origin)
        v.action_parts(self.slots, [(s.name, s.kind, s.of) for s in spec.slots])

    def _known(self, v: Validator, key: str, name: str, what: str, where: Location, objects: list[str],
               origin: str = "") -> None:
        facts = v.facts
        assert facts is not None
        links = {link for name, names in facts.links.items() if name != facts.robot for link in names}
        if what == "object" and name not in objects:
            v.error(f"'{key}': the world has no object '{name}'{origin}", where, key=key,
                    suggestion=did_you_mean(name, objects))
        elif what == "link" and links is not None and name not in links:
            v.error(f"'{key}': the world has no link '{name}'{origin}", where, key=key,
                    suggestion=did_you_mean(name, sorted(links)))
        elif what == "object or link" and name not in objects:
            owner, slash, link = name.partition("/")
            holders = [o for o, names in facts.links.items() if o != facts.robot and name in names]
            if slash and owner not in objects:
                v.error(f"'{key}': the world has no object '{owner}' (in '{name}'){origin}", where, key=key,
                        suggestion=did_you_mean(owner, objects))
            elif slash and owner in facts.links and link not in facts.links[owner]:
                v.error(f"'{key}': '{owner}' has no link '{link}'{origin}", where, key=key,
                        suggestion=did_you_mean(link, facts.links[owner]))
            elif not slash and name not in links:
                v.error(f"'{key}': the world has no object or link '{name}'{origin}", where, key=key,
                        suggestion=did_you_mean(name, [*objects, *sorted(links)]))
            elif not slash and len(holders) > 1:
                v.error(f"'{key}': '{name}' is a link of {' and '.join(holders)}: say whose{origin}", where, key=key,
                        suggestion=f"e.g. {holders[-1]}/{name}")

    def execute(self, ex: Runtime, tn: Record) -> Any:
        values = ex.evaluate(dict(self.slots))
        tn.info["action"] = {"type": self.name, "slots": jsonable(values)}
        robot = ex.world.robot
        description = description_for(robot) if robot is not None else None
        robots = Robots((description,), True) if description is not None else Robots()
        problems = check_action(self.name, values, None, robots)
        if problems:
            raise Failure(f"action {self.name}: " + "; ".join(str(p) for p in problems))
        return ACTIONS[self.name].perform(PlanActor(ex, tn, self.where), values)


def _slot_names(v: Validator, slot_name: str, kind: Kind, value: Any) -> list[tuple[str, str, str, str]]:
    """(key, name, what, origin) for every object or link name an action slot gives, literally or through a
    `$variable` whose values are known before the run (a parameter's, a `for_each` item); `origin` says which
    variable (` ($object)`), empty for a literal."""
    found: list[tuple[str, str, str, str]] = []
    if isinstance(value, Mapping) and kind.names_in is not None:  # a location: each key's values
        for key, item in location_mapping(value).items():
            for known, origin in _known_items(v, item):
                found.extend((k, name, what, origin) for k, name, what in kind.names_in({key: known}))
        return found
    for known, origin in _known_items(v, value):
        if kind.names_object and isinstance(known, str) and known:
            found.append((slot_name, known, "object", origin))
        elif kind.names_in is not None:
            found.extend((k, name, what, origin) for k, name, what in kind.names_in(known))
    return found


def _known_items(v: Validator, value: Any) -> list[tuple[Any, str]]:
    """The values `value` has before the run, each with where it came from (` ($object)`, or '' for a literal)."""
    if not isinstance(value, str) or not references(value):
        return [(value, "")]
    return [(item, f" ({value})") for item in v.possible(value) or []
            if not (isinstance(item, str) and references(item))]


class PlanActor(Actor):
    """Performs an action's parts as steps of the running plan, each a child of the action's trace node."""

    def __init__(self, ex: Runtime, tn: Record, where: Location) -> None:
        super().__init__(ex.world)
        self.ex, self.tn, self.where = ex, tn, where
        self.count = 0

    def _child(self, label: str, type: str) -> Record:
        child = self.tn.child(f"{self.count}:{label}", type, self.where)
        self.count += 1
        return child

    def leaf(self, label: str, type: str, run: Callable[[dict[str, Any]], Any]) -> Any:
        return self.ex.step(_Leaf(type, self.where, run), self._child(label, type))

    def group(self, label: str, type: str, run: Callable[[Actor], Any], info: dict[str, Any] | None = None) -> Any:
        return self.ex.step(_Group(type, self.where, run, info or {}), self._child(label, type))


class _Leaf(Node):
    """One part of an action that touches the world: a leaf step (it takes its turn among concurrent branches)."""

    LEAF = True

    def __init__(self, head: str, where: Location, run: Callable[[dict[str, Any]], Any]) -> None:
        super().__init__(head, where)
        self.run = run

    def execute(self, ex: Runtime, tn: Record) -> Any:
        info: dict[str, Any] = {}
        try:
            with ex.world_action():
                return self.run(info)
        finally:
            tn.info.update(info)


class _Group(Node):
    """Parts of an action under a node of their own: an action it performs, or one attempt of a choice."""

    def __init__(self, head: str, where: Location, run: Callable[[Actor], Any], info: dict[str, Any]) -> None:
        super().__init__(head, where)
        self.run, self.info = run, info

    def execute(self, ex: Runtime, tn: Record) -> Any:
        tn.info.update(self.info)
        return self.run(PlanActor(ex, tn, self.where))
