"""`pycram world show|render`: look at a world file."""
from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

import click
from rich.text import Text

from ..paths import find_world
from ..world import Object
from ..world.camera import IMAGE_FORMATS, encode_image, image_format, movable_objects, render, robot_camera
from ..worldfile.loader import load_spec
from ..worldfile.spec import parse_world
from . import console
from .complete import world_names
from .files import check_output, write_output
from .options import camera_option, gui_option, image_camera, json_option, parse_size, parse_view, size_option, wait_for_window


@click.group()
def world() -> None:
    """Inspect and render world files."""


def _fmt(values: tuple[float, ...] | list[float]) -> str:
    return "(" + ", ".join(f"{v:.3f}" for v in values) + ")"


@world.command("show")
@click.argument("world_file", metavar="[WORLD]", required=False, shell_complete=world_names)
@json_option
@gui_option
def show(world_file: str | None, as_json: bool, gui: bool) -> None:
    """List the objects of WORLD (default: the bundled kitchen): type, file, pose, movable joints with their
    limits, and link names."""
    path = find_world(world_file)
    spec = parse_world(path)
    sim = load_spec(spec, mode="gui" if gui else "direct")
    try:
        rows = [_describe(item, obj) for item, obj in zip(spec.objects, sim.objects)]
        robot = sim.robot.name if sim.robot else None
        if as_json:
            console.emit_json({"world": str(path), "gravity": list(spec.gravity), "robot": robot, "objects": rows})
        else:
            _print_world(path, robot, rows)
        if gui:
            viewer = sim.viewer_camera()
            if viewer is not None:  # the robot and what it may work on, not the outside of the walls
                centres = [tuple((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(sim)]
                sim.set_viewer_camera(robot_camera(sim, centres, viewer.vertical_fov_deg, sim.viewer_aspect()))
            wait_for_window(sim)
    finally:
        sim.exit()


def _describe(item: Any, obj: Object) -> dict[str, Any]:
    """One object as `world show --json` gives it."""
    values = obj.get_joint_positions()
    return {
        "name": obj.name, "type": obj.type, "file": item.file_text,
        "position": [round(v, 6) for v in obj.get_position()],
        "orientation": [round(v, 6) for v in obj.get_orientation()],
        "fixed": obj.fixed,
        "movable_joints": {k: round(v, 6) for k, v in values.items()},
        "joints": [{"name": j.name, "type": j.type, "value": round(values[j.name], 6),
                    "lower": j.lower if j.limited else None, "upper": j.upper if j.limited else None}
                   for j in obj.movable_joints],
        "links": obj.link_names,
        "attached_to": sorted(a.parent.name for a in obj.attachments.values() if a.child is obj),
    }


UNITS = {"prismatic": "m", "revolute": "rad", "continuous": "rad"}


def _print_world(path: Path, robot: str | None, rows: list[dict[str, Any]]) -> None:
    """One block per object, folded to the terminal's width (at most 100 columns)."""
    width = console.text_width()
    console.plain(_fold(f"{path.name}: {len(rows)} object{'s' if len(rows) != 1 else ''}"
                        + (f", robot {robot}" if robot else "") + f" ({path})", width, "  "))
    for row in rows:
        console.plain("")
        kind = row["type"] + (", fixed" if row["fixed"] else "")
        console.out.print(Text.assemble((row["name"], "bold" if console.out.is_terminal else ""), f"  {kind}"),
                          highlight=False)
        for label, text in _fields(row):
            console.plain(_fold(f"  {label:9} {text}", width, " " * 12))
        joints = row["joints"]
        if joints:
            console.plain(f"  {'joints':9} {len(joints)} movable: value, limits")
            name_width = min(max(len(j["name"]) for j in joints), width - 40)
            for joint in joints:
                console.plain(_fold(f"    {joint['name']:{name_width}}  {_joint(joint)}", width, " " * 8))
        links = row["links"]
        console.plain(_fold(f"  {'links':9} " + (f"{len(links)}: " if len(links) > 1 else "") + ", ".join(links),
                            width, " " * 12))


def _fields(row: dict[str, Any]) -> list[tuple[str, str]]:
    fields = [("file", row["file"]), ("position", _fmt(row["position"]))]
    if any(abs(a - b) > 1e-9 for a, b in zip(row["orientation"], (0.0, 0.0, 0.0, 1.0))):
        fields.append(("turned", _fmt(row["orientation"]) + " (quaternion x, y, z, w)"))
    if row["attached_to"]:
        fields.append(("attached", "to " + ", ".join(row["attached_to"])))
    return fields


def _joint(joint: dict[str, Any]) -> str:
    value = f"{joint['value']:7.3f} {UNITS.get(joint['type'], ''):3}"
    if joint["lower"] is None:
        return f"{value}  {joint['type']}"
    return f"{value}  [{joint['lower']:.3f}, {joint['upper']:.3f}]"


def _fold(text: str, width: int, indent: str) -> str:
    """`text` folded at `width` (between words; a word longer than a line is cut), later lines indented."""
    if len(text) <= width:
        return text
    return textwrap.fill(text, width, subsequent_indent=indent, break_long_words=True, break_on_hyphens=False,
                         drop_whitespace=True)


@world.command("render")
@click.argument("world_file", metavar="[WORLD]", required=False, shell_complete=world_names)
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=Path("scene.png"),
              show_default=True, help="Image file to write; its extension sets the format (.png, .jpg, ...).")
@camera_option
@size_option
def render_cmd(world_file: str | None, output: Path, camera: str | None, size: str) -> None:
    """Render WORLD to an image (headless): PNG, JPEG, WebP or BMP, by the file's extension."""
    width, height = parse_size(size)
    view = parse_view(camera)
    check_output(output, IMAGE_FORMATS, "image")
    path = find_world(world_file)
    sim = load_spec(parse_world(path))
    try:
        image = render(sim, image_camera(sim, view, (width, height)), width, height)
    finally:
        sim.exit()
    write_output(output, encode_image(image, output.suffix), f"{width}x{height} {image_format(output.suffix)}")


world.add_command(render_cmd, "render")
