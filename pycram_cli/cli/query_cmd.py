"""`pycram query QUERY ARGS`: ask a reasoning question about a world.

    pycram query visible bottle
    pycram query contact kitchen milk
    pycram query reachable 1.3,0.6,1.0 --arm left
    pycram query blocking milk --arm left --exclude-type environment --json

Arguments, options and help are generated from the query declarations (`reasoning.QUERIES`),
so a newly declared query is asked like any other. Exit 0 whatever the answer; 2 on bad input.
"""
from __future__ import annotations

import math
from typing import Any

import click
from click.shell_completion import CompletionItem

from .. import locations  # noqa: F401 - registers pick-up's planning, which reachable asks about objects
from ..errors import InputError, Location, did_you_mean
from ..jsonable import jsonable
from ..kinds import KINDS, POSITION_FORMS, looks_like_numbers, parse_vector
from ..limits import MAX_MAGNITUDE
from ..planning.contacts import collisions
from ..reasoning import QUERIES, QuerySpec, run_query
from ..reasoning.query import unknown_query
from ..signature import Param
from ..world import BulletWorld
from ..world.pose import yaw_quaternion
from . import console
from .complete import object_names
from .options import is_number, joined, open_world, world_option

FIXED_OPTIONS = ("--world", "--json", "--help", "--at")


def _queries_help() -> str:
    lines = []
    for spec in QUERIES.values():
        lines.append(f"  {spec.usage()}")
        lines.append(f"      {spec.doc}")
        for param in spec.params:
            default = f" (default: {param.default_text})" if param.default_text else ""
            name = param.name.upper() if param.positional else param.option
            lines.append(f"      {name}: {param.doc or KINDS[param.kind].doc}{default}")
    return "\n".join(lines)


class QueryCommand(click.Command):
    """Help generated from the query declarations at the moment it is shown."""

    def format_help_text(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        text = ("Ask a reasoning question about a world (default: the bundled kitchen).\n\n\b\nQueries:\n"
                + _queries_help()
                + "\n\n\b\nPositions: 1.3,0.6,1.0 or [1.3,0.6,1.0] or '1.3, 0.6, 1.0', or 1.3 0.6 1.0 (three"
                "\narguments) where that is unambiguous; quaternions the same with four numbers."
                "\n\n\b\n--at X,Y[,YAW]  (reachable, blocking, visible, occluding) stand the robot's base at x, y"
                "\n               (metres), turned to YAW degrees (as `pycram locate` shows it; default: as it"
                "\n               stands) before answering; the world file is not changed."
                "\n\n\b\nExamples:\n  pycram query visible bottle\n  pycram query contact kitchen milk\n"
                "  pycram query reachable milk --arm right --grasp front\n"
                "  pycram query reachable milk --at 0.8,0.95,6\n"
                "  pycram query blocking milk --arm left --exclude-type environment --json\n\n"
                "Exit status: 0 whatever the answer, 2 on bad input.")
        formatter.write_paragraph()
        with formatter.indentation():
            formatter.write_text(text)


#: the kinds whose values may be vectors, and the vector's size (a position, a quaternion)
VECTOR_SIZES = {"position": 3, "target": 3, "camera": 3, "quaternion": 4, "grasp": 4}


def _grouped(positional: list[str], params: list[Param]) -> list[str]:
    """`x y z` (three arguments) as one position where that is the only way the arguments fit the parameters."""
    values: list[str] = []
    index = 0
    for number, param in enumerate(params):
        size = VECTOR_SIZES.get(param.kind)
        rest = len(params) - number - 1
        words = positional[index:index + size] if size else []
        if size and len(positional) - index - size == rest and len(words) == size and all(map(is_number, words)):
            values.append(",".join(words))
            index += size
        elif index < len(positional):
            values.append(positional[index])
            index += 1
    return values + positional[index:]


def _value(param: Param, text: str, where: Location, name: str) -> Any:
    """A parameter's value from its text; text meant as numbers that is no vector of the kind says how one is written."""
    value = KINDS[param.kind].from_text(text)
    size = VECTOR_SIZES.get(param.kind)
    if size and isinstance(value, str) and (looks_like_numbers(text) or is_number(text)):
        what = "a position" if size == 3 else "a quaternion"
        forms = POSITION_FORMS if size == 3 else "0,0,0,1 or [0,0,0,1] or '0, 0, 0, 1' (or 0 0 0 1 after an option)"
        raise InputError(f"{name}: cannot read {text!r} as {what} ({size} numbers)", where, key=param.name,
                         suggestion=f"write {what} as {forms}")
    return value


#: the queries asked from the robot's pose, which `--at` places
PLACED_QUERIES = ("reachable", "blocking", "visible", "occluding")
AT_FORMS = "X,Y or X,Y,YAW (metres, yaw in degrees, as `pycram locate` shows it), e.g. --at 0.8,0.95,6"


def split_at(tokens: tuple[str, ...]) -> tuple[str | None, list[str]]:
    """`--at X,Y[,YAW]` (also `--at=...`, `--at X Y YAW`, `--at 'X, Y'`) taken out of the words; the rest."""
    words = joined(tokens)
    at: str | None = None
    rest: list[str] = []
    index = 0
    while index < len(words):
        word = words[index]
        index += 1
        name, eq, inline = word.partition("=")
        if name != "--at":
            rest.append(word)
            continue
        if at is not None:
            raise InputError("option --at is given twice", Location("--at"))
        if eq:
            at = inline
        elif index < len(words):
            at, index = words[index], index + 1
            if is_number(at):  # `--at 0.8 0.95 6`: up to two numbers that follow are its own
                count = 0
                while count < 2 and index + count < len(words) and is_number(words[index + count]):
                    count += 1
                at = ",".join([at, *words[index:index + count]])
                index += count
        else:
            raise InputError("option --at needs a value", Location("--at"), suggestion=f"give {AT_FORMS}")
    return at, rest


def base_pose(text: str) -> tuple[float, float, float | None]:
    """`X,Y[,YAW]` -> (x, y, yaw in radians or None); an InputError that shows the form otherwise."""
    values = parse_vector(text, 3) if text.count(",") == 2 else parse_vector(text, 2)
    if values is None or not all(abs(v) <= MAX_MAGNITUDE for v in values):
        raise InputError(f"cannot read {text!r} as a base pose", Location("--at"),
                         suggestion=f"give {AT_FORMS}")
    return values[0], values[1], math.radians(values[2]) if len(values) == 3 else None


def place_robot(world: BulletWorld, pose: tuple[float, float, float | None]) -> None:
    """Stand the world's robot at (x, y), turned to yaw (kept when None), its height kept; warn when it stands
    inside something there (the answer is then of little use)."""
    robot = world.robot
    if robot is None:
        raise InputError("--at places the robot, but the world has no robot", Location("--at"))
    x, y, yaw = pose
    orientation = yaw_quaternion(yaw) if yaw is not None else robot.get_orientation()
    robot.set_position_and_orientation((x, y, robot.get_position()[2]), orientation)
    hits = sorted(o.name for o in collisions(robot))
    if hits:
        console.warning(f"--at {x:g},{y:g}: {robot.name} stands inside {', '.join(hits)} there")


def build_args(query: str, tokens: tuple[str, ...]) -> dict[str, Any]:
    """The query's parameters from the command line: positional ARGS in declaration order, then options.

    A position may be written `1.3,0.6,1.0`, `[1.3,0.6,1.0]`, `1.3, 0.6, 1.0` (split by the shell or not) and,
    where nothing else fits, `1.3 0.6 1.0` (three arguments; after an option that takes one, the number and
    the next two).
    """
    spec = QUERIES.get(query)
    if spec is None:
        raise unknown_query(query)
    where = Location(f"query {query}")
    usage = f"usage: pycram query {spec.usage()}"
    options = {param.option: param for param in spec.options}
    positional: list[str] = []
    args: dict[str, Any] = {}
    words = joined(tokens)
    index = 0
    while index < len(words):
        token = words[index]
        index += 1
        if not token.startswith("--") or parse_vector(token, 3) is not None or parse_vector(token, 4) is not None:
            if token.startswith("-") and not is_number(token) and not looks_like_numbers(token):
                raise InputError(f"no such option: {token}", where, suggestion=_option_hint(token, spec))
            positional.append(token)
            continue
        name, eq, inline = token.partition("=")
        param = options.get(name)
        if param is None:
            applies_elsewhere = any(name in {p.option for p in other.options} for other in QUERIES.values())
            message = f"option {name} does not apply to '{query}'" if applies_elsewhere else f"no such option: {name}"
            raise InputError(message, where, suggestion=_option_hint(name, spec) or usage)
        if eq:
            text = inline
        elif index < len(words):
            text = words[index]
            index += 1
        else:
            raise InputError(f"option {name} needs a value ({KINDS[param.kind].doc})", where, key=param.name)
        size = VECTOR_SIZES.get(param.kind)
        following = words[index:index + size - 1] if size and is_number(text) else []
        if size and len(following) == size - 1 and all(map(is_number, following)):
            text = ",".join([text, *following])  # `--from 1 2 3`: a number alone is no value of the kind
            index += size - 1
        value = _value(param, text, where, name)
        if param.multiple:
            args.setdefault(param.name, []).append(value)
        elif param.name in args:
            raise InputError(f"option {name} is given twice", where, key=param.name)
        else:
            args[param.name] = value
    positional = _grouped(positional, spec.positional)
    names = [param.name for param in spec.positional]
    if len(positional) != len(names):
        what = "missing" if len(positional) < len(names) else "too many"
        takes_vector = any(param.kind in VECTOR_SIZES for param in spec.positional)
        raise InputError(f"{what} arguments: expected {len(names)} ({', '.join(names)}), got {len(positional)}",
                         where, suggestion=usage + (f"; a position is written {POSITION_FORMS}" if takes_vector else ""))
    for param, text in zip(spec.positional, positional):
        args[param.name] = _value(param, text, where, param.name.upper())
    return args


def query_names(ctx: click.Context, param: click.Parameter, incomplete: str) -> list[CompletionItem]:
    """QUERY: the declared queries, each with its one-line doc."""
    return [CompletionItem(name, help=spec.doc) for name, spec in QUERIES.items() if name.startswith(incomplete)]


def _option_hint(token: str, spec: QuerySpec) -> str | None:
    allowed = [p.option for p in spec.options]
    return did_you_mean(token, [*allowed, *FIXED_OPTIONS]) or (f"its options: {', '.join(allowed)}" if allowed else None)


@click.command("query", cls=QueryCommand, context_settings={"ignore_unknown_options": True},
               short_help="Ask a reasoning question (stable, visible, reachable, ...) about a world.")
@click.argument("query_name", metavar="QUERY", shell_complete=query_names)
@click.argument("tokens", metavar="ARGS...", nargs=-1, type=click.UNPROCESSED, shell_complete=object_names)
@world_option
@click.option("--json", "as_json", is_flag=True, help="Machine-readable output on stdout.")
def query(query_name: str, tokens: tuple[str, ...], world_file: str | None, as_json: bool) -> None:
    spec = QUERIES.get(query_name)
    if spec is None:
        raise unknown_query(query_name)
    at_text, tokens_left = split_at(tokens)
    if at_text is not None and query_name not in PLACED_QUERIES:
        raise InputError(f"option --at does not apply to '{query_name}' (it places the robot for "
                         f"{', '.join(PLACED_QUERIES)})", Location(f"query {query_name}"))
    at = base_pose(at_text) if at_text is not None else None
    args = build_args(query_name, tuple(tokens_left))
    with open_world(world_file) as (world, path):
        if at is not None:
            place_robot(world, at)
        answer = run_query(world, query_name, args)
    if as_json:
        payload = answer.to_json()
        payload["world"] = str(path)
        console.emit_json(jsonable(payload, nonfinite=None))
    else:
        console.plain(spec.describe(answer))
