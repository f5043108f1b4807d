"""JSON Schemas (draft 2020-12) of world, plan and variation files, for editors, generated from the declarations.

    pycram schema plan                                             # print one (world, plan, vary)
    python -m pycram_cli.cli.editor_schema --write resources/schemas   # the shipped copies (from the checkout's top)

One source of truth: everything a user can name comes from what validation itself uses —
the plan language's node types (`plan/syntax.py` NODE_TYPES and node families, each node's
allowed and required keys, PLAN_KEYS, SUBPLAN_KEYS), the motion designators, action
designators and reasoning queries with their slots and parameters and their descriptions,
the parameter kinds (`kinds.py`: each kind's `schema`, the location keys), the world file's
keys (`worldfile/spec.py`) and the variation file's keys (`scenario/variations.py`), the
failure types (`failures.py`) and the variable syntax (`plan/context.py`).

What the parsers check in code, value by value (a `retry` count is a whole number, `then`
holds steps), is said here once per key in the `*_VALUES` tables below. A key of a declared
list that has no entry there is allowed with any value and listed in `Schemas.missing`
(tests keep that list empty); an entry for a key no list declares is an error.

The schema is looser than validation where validation needs a world or a robot (object
names, arms, grasps) or reads a value (unit quaternions, whether a subplan exists); a value
that holds a `$variable` anywhere passes the kind check of its slot, as it does in
validation, which checks it when the step runs.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from ..designators import DESIGNATORS
from ..designators.actions import ACTIONS
from ..failures import ALIASES, FAILURES
from ..kinds import KINDS
from ..limits import MAX_MAGNITUDE, MAX_PROJECTED, MAX_RETRIES, MAX_SCENARIO_TIMEOUT, MAX_WAIT
from ..plan import projecting, scoring
from ..plan.context import IDENTIFIER, NAME, REFERENCE
from ..plan.language import NODE_TYPES
from ..plan.leaves import CONDITION_FORMS
from ..plan.syntax import FAMILIES, PLAN_KEYS, PLAN_REQUIRED, SCOPES, SUBPLAN_KEYS, SUBPLAN_REQUIRED, all_heads
from ..reasoning import QUERIES
from ..scenario import variation_files as vary
from ..signature import Param
from ..worldfile import spec as world

Schema = dict[str, Any]

DIALECT = "https://json-schema.org/draft/2020-12/schema"
#: the file kinds `pycram schema` knows, and what each describes
FILE_KINDS = {"world": "a world file (worlds/*.yaml)", "plan": "a plan file (plans/*.yaml)",
              "vary": "a variation file of a sweep (plans/*.vary.yaml)"}


def ref(name: str) -> Schema:
    return {"$ref": f"#/$defs/{name}"}


def _text(description: str) -> Schema:
    return {"type": "string", "description": description}


def _number(low: float = -MAX_MAGNITUDE, high: float = MAX_MAGNITUDE, description: str = "") -> Schema:
    schema: Schema = {"type": "number", "minimum": low, "maximum": high}
    return {**schema, "description": description} if description else schema


def _numbers(sizes: tuple[int, ...], item: Schema, description: str) -> Schema:
    return {"type": "array", "items": item, "minItems": min(sizes), "maxItems": max(sizes), "description": description}


def _with(schema: Schema, description: str) -> Schema:
    return {**schema, "description": description}


# -- value shapes of the keys the parsers read in code ---------------------------------------------------------
#: what each variation of a node's head takes (`seq: [steps]`, `retry: 2`); `steps`, `condition`, ... name $defs
HEAD_VALUES: dict[str, Schema] = {
    "seq": ref("steps"), "par": ref("steps"), "pursue": ref("steps"), "try_all": ref("steps"),
    "try_in_order": ref("steps"), "try": ref("steps"),
    "retry": {"type": "integer", "minimum": 0, "maximum": MAX_RETRIES},
    "if": ref("condition"), "unless": ref("condition"), "assert": ref("condition"),
    "for_each": {"anyOf": [{"type": "array"}, ref("reference")]},
    "call": _text("the name of a subplan under plans:"),
    "fail": {"anyOf": [ref("failure-type"), ref("variable")]},
    "log": {},
    "set": {"type": "object", "propertyNames": ref("name")},
    "wait": {"anyOf": [_number(0, MAX_WAIT, "seconds"), ref("dynamic")]},
    "project": {
        "type": "object", "required": ["alternatives"], "additionalProperties": False,
        "properties": {
            "alternatives": {"type": "object", "minProperties": 1, "additionalProperties": ref("steps"),
                             "description": "named alternatives, each a list of steps"},
            "runs": {"type": "integer", "minimum": 1, "maximum": MAX_PROJECTED,
                     "description": f"projected runs per alternative (default {projecting.DEFAULT_RUNS})"},
            "vary": {"type": "object", "description": "how each projected run's world differs from the world now",
                     "additionalProperties": {
                         "type": "object", "additionalProperties": False, "properties": {
                             "noise": {"anyOf": [_number(0), {"type": "array", "items": _number(0),
                                                              "minItems": 3, "maxItems": 3}],
                                       "description": "uniform in ± per axis (m): a number (x and y) or [x, y, z]"},
                             "yaw": _number(0, math.pi, "turned by a uniform angle in ±yaw (rad) about z")}}},
            "choose": {"anyOf": [
                {"enum": list(projecting.CHOICES)},
                {"type": "object", "minProperties": 1, "maxProperties": 1,
                 "properties": {sense: {"type": ["string", "number"]} for sense in scoring.SENSES},
                 "additionalProperties": False,
                 "description": "the alternative with the highest (max) or lowest (min) value of an arithmetic "
                                "expression over its outcomes: " + ", ".join(scoring.OUTCOMES)}],
                "description": "how the alternative to run is chosen"},
            "at-least": _number(0, 1, "the success rate the chosen alternative needs (else a ProjectionFailure)"),
            "seed": {"type": "integer", "minimum": 0, "maximum": 2**32 - 1,
                     "description": "the projected runs' draws come from it"},
            "timeout": {"type": "number", "exclusiveMinimum": 0, "maximum": MAX_SCENARIO_TIMEOUT,
                        "description": "seconds a projected run may take; one past it is recorded as a Timeout"},
            "as": _with(ref("name"), "the variable bound to {name, value, table}"),
        }},
}
#: what the keys beside a head take
NODE_KEY_VALUES: dict[str, Schema] = {
    "as": _with(ref("name"), "the variable the step binds: its value (for_each: each item); a name, without $"),
    "scope": _with({"enum": list(SCOPES)}, "where `as` (or `set`) binds inside a branch of par, pursue or try_all: "
                   "branch (the default: the binding stays in the branch) or plan (seen after the step)"),
    "on": _with({"anyOf": [ref("failure-type"), {"type": "array", "items": ref("failure-type")}]},
                "the failure types that trigger a retry (default: any failure)"),
    "recover": _with(ref("steps"), "steps run before each new attempt"),
    "body": _with(ref("steps"), "the steps to run"),
    "catch": {"type": "object", "minProperties": 1, "propertyNames": ref("failure-type"),
              "additionalProperties": ref("steps"),
              "description": "handlers keyed by failure type, tried in order (Failure catches every failure)"},
    "then": _with(ref("steps"), "steps run when the condition holds (for unless: when it does not)"),
    "else": _with(ref("steps"), "steps run otherwise"),
    "do": _with(ref("steps"), "steps run for each item"),
    "args": {"type": ["array", "object"], "description": "the subplan's arguments: a list (in order) or a mapping"},
    "message": _text("the failure's message ($variables are filled in)"),
    "failure": _with(ref("failure-type"), "the failure raised when the condition does not hold"),
}
PLAN_VALUES: dict[str, Schema] = {
    "description": _text("what the plan does"),
    "world": _text("a bundled world's name (kitchen) or a world file's path relative to this file"),
    "params": _with(ref("params"), "the plan's parameters: {name: default}, or a list of names (required) and "
                                   "{name: default}; -p NAME=VALUE sets them"),
    "plans": {"type": "object", "description": "subplans by name, run with call: (a name that is no node type)",
              "propertyNames": ref("subplan-name"),
              "additionalProperties": {"anyOf": [ref("subplan"), {"type": "array", "minItems": 1,
                                                                   "items": ref("step")}]}},
    "body": _with(ref("steps"), "the steps pycram run runs"),
}
SUBPLAN_VALUES: dict[str, Schema] = {
    "description": _text("what the subplan does"),
    "params": _with(ref("params"), "the subplan's parameters: a list of names (required) and {name: default}"),
    "body": _with(ref("steps"), "the subplan's steps"),
    "returns": {"description": "the value of a call ($variables are filled in)"},
}
_COLOR = _numbers((3, 4), _number(0, 1), "r, g, b[, a], each from 0 to 1")
_VECTOR3 = _numbers((3,), _number(), "[x, y, z]")
_NONBLANK = {"type": "string", "pattern": r"\S"}
WORLD_VALUES: dict[str, Schema] = {
    "description": _text("what the world holds"),
    "extends": _with(_NONBLANK, "the world this one is made from: a world's name (pycram worlds) or a file relative "
                                "to this one; `objects` then add new objects and change its own (by name)"),
    "gravity": _with(_VECTOR3, "gravity [x, y, z] in m/s² (default [0, 0, -9.81])"),
    "objects": {"type": "array", "description": "the bodies of the world (of a world that extends another: "
                                                "the objects it adds or changes)"},
}
OBJECT_VALUES: dict[str, Schema] = {
    "name": _with(_NONBLANK, "the object's name, unique in the world"),
    "type": _with(_NONBLANK, "its type (milk, robot, environment, ...): detecting finds objects by type"),
    "file": _with(_NONBLANK, "its model: a URDF, OBJ or STL file, found beside this file, in the bundled "
                             "resources, then in pybullet_data"),
    "position": _with(_VECTOR3, "[x, y, z] in metres, world frame"),
    "orientation": _numbers((4,), _number(), "a unit quaternion [x, y, z, w]"),
    "up": {"enum": ["z", "y", "x", "-z", "-y", "-x"], "description": "the model's own axis that points up (default z; "
                                                                  "y for a Y-up mesh), turned upright before orientation"},
    "color": _with(_COLOR, "its colour (meshes)"),
    "joints": {"type": "object", "additionalProperties": _number(), "description": "initial joint positions: "
                                                                                   "{joint: value}"},
    "attach": {"anyOf": [_NONBLANK, ref("attach"), {"type": "array", "items": {"anyOf": [_NONBLANK, ref("attach")]}}],
               "description": "the objects this one follows: a name, {to, parent_link, child_link}, or a list"},
    "fixed": {"type": "boolean", "description": "fixed in place (robots and environments are by default)"},
    "mass": _number(0, MAX_MAGNITUDE, "kg (meshes)") | {"exclusiveMinimum": 0},
    "description": _text("robots: the robot description file (default: beside the URDF, or bundled)"),
}
ATTACH_VALUES: dict[str, Schema] = {
    "to": _text("the object this one follows"),
    "parent_link": _text("the link of that object it follows (default: its base)"),
    "child_link": _text("this object's link that is held (default: its base)"),
}
VARY_VALUES: dict[str, Schema] = {
    "description": _text("what the variations do"),
    "plan": _text("the plan they are made for (pycram validate checks the parameters against it)"),
    "separation": _number(0, MAX_MAGNITUDE, "varied objects start at least this far apart (m, x-y)"),
    "objects": {"type": "object", "additionalProperties": ref("varied-object"),
                "description": "how each object of the world varies, by its name"},
    "robot": _with(ref("varied-robot"), "where the robot starts"),
    "params": {"type": "object", "additionalProperties": ref("param-draw"),
               "description": "the plan's parameters: a list of values to choose from, or {range: [lo, hi]}"},
}
_NOT_NEGATIVE = _number(0, MAX_MAGNITUDE)
VARIED_VALUES: dict[str, Schema] = {
    "noise": {"anyOf": [_NOT_NEGATIVE, _numbers((3,), _NOT_NEGATIVE, "[x, y, z]")],
              "description": "uniform in ± this around its position (m): [x, y, z], or one number for x and y"},
    "region": _with(ref("region"), "anywhere in a box, or on a surface link"),
    "yaw": _number(0, math.pi + 1e-3, "turned by a uniform angle in ± this about z (rad)"),
    "present": _number(0, 1, "the probability that it is in the scenario"),
    "swap": {"type": "array", "minItems": 1, "items": {"anyOf": [{"const": vary.KEEP}, ref("swap")]},
             "description": "equally likely models: keep (the world's) or {type, file, color, mass}"},
}
REGION_VALUES: dict[str, Schema] = {
    "box": {"type": "array", "items": _VECTOR3, "minItems": 2, "maxItems": 2,
            "description": "two corners [[x, y, z], [x, y, z]]"},
    "on": {"type": "string", "pattern": "^[^/]+/.+", "description": "object/link: x-y uniform on the link's top"},
    "margin": _number(0, MAX_MAGNITUDE, "keep this far from the surface's edges (m)"),
}
SWAP_VALUES: dict[str, Schema] = {
    "type": _with(_NONBLANK, "the swapped object's type"),
    "file": _with(_NONBLANK, "its model file"),
    "color": _with(_COLOR, "its colour"),
    "mass": _number(0, MAX_MAGNITUDE, "kg"),
}
PARAM_VALUES: dict[str, Schema] = {
    "range": _numbers((2,), _number(), "[lo, hi]: uniform (whole numbers when both ends are whole)"),
    "choose": {"type": "array", "minItems": 1, "description": "values to choose from, equally likely"},
}


class Schemas:
    """Builds the schemas; `missing` lists the declared keys whose value shape is unknown here (any value)."""

    def __init__(self) -> None:
        self.missing: list[str] = []

    # -- helpers ----------------------------------------------------------------------------------------------
    def mapping(self, what: str, keys: tuple[str, ...], required: tuple[str, ...], values: Mapping[str, Schema],
                description: str = "") -> Schema:
        """An object with exactly the declared keys; each key's value from `values`."""
        extra = [key for key in values if key not in keys]
        if extra:
            raise ValueError(f"{what}: value shapes for keys that are not declared: {', '.join(extra)}")
        properties: Schema = {}
        for key in keys:
            if key not in values:
                self.missing.append(f"{what}: {key}")
            properties[key] = values.get(key, {})
        schema: Schema = {"type": "object", "properties": properties, "additionalProperties": False}
        if required:
            schema["required"] = list(required)
        return {"description": description, **schema} if description else schema

    @staticmethod
    def document(kind: str, root: Schema, defs: Schema) -> Schema:
        return {"$schema": DIALECT, "title": f"pycram {kind} file",
                "description": f"{FILE_KINDS[kind]}; generated by `pycram schema {kind}` from pycram's declarations",
                **root, "$defs": defs}

    # -- plans ------------------------------------------------------------------------------------------------
    def plan(self) -> Schema:
        defs: Schema = {
            "variable": {"type": "string", "pattern": rf"(^|[^$])(\$\$)*\$\{{?{NAME}",
                         "$comment": "text holding a $variable: known when the step runs"},
            "dynamic": {"$comment": "a value that holds a $variable (checked when the step runs)",
                        "anyOf": [ref("variable"), {"type": "array", "contains": ref("dynamic")},
                                  {"type": "object", "not": {"additionalProperties": {"not": ref("dynamic")}}}]},
            "reference": {"type": "string", "pattern": REFERENCE.pattern, "$comment": "a $variable ($name.attr)"},
            "name": {"type": "string", "pattern": IDENTIFIER.pattern,
                     "$comment": "a variable name (letters, digits, _ and -), without $"},
            "failure-type": {"enum": [*FAILURES, *ALIASES], "$comment": "a failure type"},
            "params": {"anyOf": [
                {"type": "null"},
                {"type": "object", "propertyNames": ref("name")},
                {"type": "array", "items": {"anyOf": [ref("name"), {"type": "object", "minProperties": 1,
                                                                      "maxProperties": 1,
                                                                      "propertyNames": ref("name")}]}}]},
            "subplan-name": {"allOf": [ref("name"), {"not": {"enum": sorted(all_heads())}}]},
            "subplan": self.mapping("subplan", SUBPLAN_KEYS, SUBPLAN_REQUIRED, SUBPLAN_VALUES),
            "steps": {"$comment": "a list of steps (or one step)",
                      "anyOf": [ref("step"), {"type": "array", "minItems": 1, "items": ref("step")}]},
        }
        for name, kind in KINDS.items():
            defs[f"kind.{name}"] = {"$comment": kind.doc, **(kind.schema or {})}
        variants: list[Schema] = []
        for head, cls in NODE_TYPES.items():
            if head == "action":
                variants.extend(self._action(name, defs) for name in ACTIONS)
                continue
            if head not in HEAD_VALUES:
                self.missing.append(f"node type {head}")
            keys = tuple(k for k in cls.allowed_keys(head) if k != head)
            extra = [k for k in keys if k not in NODE_KEY_VALUES]
            self.missing.extend(f"node type {head}: {k}" for k in extra)
            properties = {head: {**HEAD_VALUES.get(head, {}), "description": cls.DOC},
                          **{k: NODE_KEY_VALUES.get(k, {}) for k in keys}}
            variants.append({"title": head, "type": "object", "description": cls.DOC, "properties": properties,
                             "required": [head, *cls.REQUIRED], "additionalProperties": False})
        for family, heads, cls in FAMILIES:
            for head in heads():
                variants.append(self._family_step(family, head, cls.allowed_keys(head), defs))
        defs["step"] = {"type": "object", "$comment": "a step: one node type (its head key) and the keys it takes",
                        "anyOf": variants}
        defs["condition"] = {"$comment": "a condition: a $variable, true/false, a query, {equal: [a, b]} or "
                                         "{not: condition}",
                             "anyOf": [{"type": "boolean"}, ref("reference"), *self._condition_forms(),
                                       *({"title": name, "type": "object", "properties": {name: ref(f"query.{name}")},
                                          "required": [name], "additionalProperties": False}
                                         for name in QUERIES)]}
        root = self.mapping("the plan", PLAN_KEYS, PLAN_REQUIRED, PLAN_VALUES)
        return self.document("plan", root, defs)

    def _condition_forms(self) -> list[Schema]:
        values = {"not": ref("condition"), "equal": {"type": "array", "minItems": 2, "maxItems": 2}}
        forms = []
        for form, doc in CONDITION_FORMS.items():
            if form not in values:
                self.missing.append(f"condition {form}")
            forms.append({"title": form, "type": "object",
                          "properties": {form: {**values.get(form, {}), "description": doc}},
                          "required": [form], "additionalProperties": False})
        return forms

    def _family_step(self, family: str, head: str, keys: tuple[str, ...], defs: Schema) -> Schema:
        """A step whose head is a motion designator or a query: its slots or parameters as a mapping."""
        if family == "designator":
            spec = DESIGNATORS[head]
            defs[f"designator.{head}"] = self._slots(head, spec.doc, spec.slots, spec.one_of, whole_only=False)
            value, doc = ref(f"designator.{head}"), spec.doc
        elif family == "query":
            query = QUERIES[head]
            defs[f"query.{head}"] = self._query(head)
            value, doc = ref(f"query.{head}"), query.doc
        else:
            self.missing.append(f"node family {family}")
            value, doc = {}, ""
        properties = {head: {**value, "description": doc}, **{k: NODE_KEY_VALUES.get(k, {}) for k in keys}}
        return {"title": head, "type": "object", "description": doc, "properties": properties, "required": [head],
                "additionalProperties": False}

    def _slot(self, slot: Param, whole_only: bool) -> Schema:
        """A slot's value: of its kind, or holding a $variable (a location only as a whole: validation checks it
        key by key)."""
        need = "required" if slot.required else "optional"
        default = f"; default: {slot.default_text}" if slot.default_text else ""
        dynamic = ref("variable") if whole_only and slot.kind == "location" else ref("dynamic")
        return {"description": f"{slot.doc} ({need}{default}) — {KINDS[slot.kind].doc}",
                "anyOf": [ref(f"kind.{slot.kind}"), dynamic]}

    def _slots(self, title: str, doc: str, slots: tuple[Param, ...], one_of: tuple[str, ...],
               whole_only: bool) -> Schema:
        required = [s.name for s in slots if s.required]
        schema: Schema = {"title": title, "type": "object" if required or one_of else ["object", "null"], "description": doc,
                          "properties": {s.name: self._slot(s, whole_only) for s in slots},
                          "additionalProperties": False}
        if required:
            schema["required"] = required
        if one_of:
            schema["anyOf"] = [{"required": [name]} for name in one_of]
        return schema

    def _query(self, name: str) -> Schema:
        query = QUERIES[name]
        properties: Schema = {}
        for param in query.params:
            default = param.default_text
            need = "required" if param.required else "optional"
            values = [ref(f"kind.{param.kind}"), ref("dynamic")] + ([] if param.required else [{"type": "null"}])
            properties[param.name] = {"description": f"{param.doc} ({need}{f'; default: {default}' if default else ''})"
                                                     f" — {KINDS[param.kind].doc}", "anyOf": values}
        required = [p.name for p in query.params if p.required]
        schema: Schema = {"title": name, "type": "object" if required else ["object", "null"], "description": query.doc,
                          "properties": properties, "additionalProperties": False}
        return {**schema, "required": required} if required else schema

    def _action(self, name: str, defs: Schema) -> Schema:
        """`- action: NAME` with the action's slots beside it.

        The required slots are asked for only once `action` holds a string (always, in a valid file): an
        editor completing `action: ` (no value yet) then finds every action's variant usable and offers every
        name, and once a name is there it completes that action's slots alone.
        """
        spec = ACTIONS[name]
        gives = f" Gives: {spec.returns}." if spec.returns else ""
        properties: Schema = {"action": {"const": name, "description": f"{spec.doc}{gives}"},
                              **{s.name: self._slot(s, whole_only=True) for s in spec.slots},
                              "as": NODE_KEY_VALUES["as"], "scope": NODE_KEY_VALUES["scope"]}
        schema: Schema = {"title": f"action {name}", "type": "object", "description": spec.doc,
                          "properties": properties, "required": ["action"], "additionalProperties": False}
        then: Schema = {}
        if any(s.required for s in spec.slots):
            then["required"] = [s.name for s in spec.slots if s.required]
        if spec.one_of:
            then["anyOf"] = [{"required": [slot]} for slot in spec.one_of]
        if then:
            schema["if"] = {"properties": {"action": {"type": "string"}}}
            schema["then"] = then
        return schema

    # -- worlds -----------------------------------------------------------------------------------------------
    def world(self) -> Schema:
        defs = {"object": self.mapping("a world object", world.OBJECT_KEYS, world.OBJECT_REQUIRED, OBJECT_VALUES,
                                       "a body: its name, type and model file, where it starts"),
                "attach": self.mapping("attach", world.ATTACH_KEYS, world.ATTACH_REQUIRED, ATTACH_VALUES)}
        defs["object-change"] = {**self.mapping("a change to an object of the world it extends", world.OBJECT_KEYS,
                                                ("name",), OBJECT_VALUES,
                                                "an object the extended world has (the keys given replace its own), "
                                                "or a new one (name, type and file)")}
        root = self.mapping("the world", world.WORLD_KEYS, (), WORLD_VALUES)
        # a world that extends another may leave `objects` out, and names its objects' changes by name alone
        root["if"] = {"required": ["extends"]}
        root["then"] = {"properties": {"objects": {"items": ref("object-change")}}}
        root["else"] = {"required": list(world.WORLD_REQUIRED), "properties": {"objects": {"items": ref("object")}}}
        return self.document("world", root, defs)

    # -- variations -------------------------------------------------------------------------------------------
    def vary(self) -> Schema:
        both = {"not": {"required": ["noise", "region"]}}  # one or the other
        defs = {
            "varied-object": {**self.mapping("the variations of an object", vary.OBJECT_KEYS, (), VARIED_VALUES),
                              **both},
            "varied-robot": {**self.mapping("the variations of the robot", vary.ROBOT_KEYS, (),
                                            {k: v for k, v in VARIED_VALUES.items() if k in vary.ROBOT_KEYS}), **both},
            "region": {**self.mapping("region", vary.REGION_KEYS, (), REGION_VALUES),
                       "oneOf": [{"required": ["box"]}, {"required": ["on"]}]},
            "swap": self.mapping("swap", vary.SWAP_KEYS, vary.SWAP_REQUIRED, SWAP_VALUES),
            "param-draw": {"anyOf": [{"type": "array", "minItems": 1, "description": "values to choose from"},
                                     {**self.mapping("a parameter's draw", vary.PARAM_KEYS, (), PARAM_VALUES),
                                      "oneOf": [{"required": [key]} for key in vary.PARAM_KEYS]}]},
        }
        root = self.mapping("the variations", vary.TOP_KEYS, (), VARY_VALUES)
        return self.document("vary", root, defs)


BUILDERS: dict[str, Callable[[Schemas], Schema]] = {"world": Schemas.world, "plan": Schemas.plan,
                                                    "vary": Schemas.vary}


def build(kind: str) -> Schema:
    """The JSON Schema of a file kind (`world`, `plan`, `vary`)."""
    return BUILDERS[kind](Schemas())


def render(kind: str) -> str:
    """The schema as the text `pycram schema` prints (`console.emit_json`) and the shipped files hold."""
    return json.dumps(build(kind), indent=2, allow_nan=False) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m pycram_cli.cli.editor_schema",
                                     description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--write", type=Path, metavar="FOLDER", help="write KIND.schema.json for every kind to FOLDER")
    args = parser.parse_args(argv)
    if args.write is None:
        for kind in FILE_KINDS:
            sys.stdout.write(render(kind))
        return 0
    args.write.mkdir(parents=True, exist_ok=True)
    for kind in FILE_KINDS:
        (args.write / f"{kind}.schema.json").write_text(render(kind))
        print(f"wrote {args.write / f'{kind}.schema.json'}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
