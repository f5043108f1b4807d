"""`pycram world show|render`: look at a world file."""
from __future__ import annotations

from pathlib import Path

import click

from ..world.camera import IMAGE_FORMATS, encode_image, image_format, movable_objects, render, robot_camera
from ..worldfile.loader import load_spec
from ..worldfile.spec import parse_world
from . import console
from .complete import world_names
from ..paths import find_world
from .files import check_output, write_output
from .options import (camera_option, gui_option, image_camera, json_option, parse_size, parse_view, size_option,
                      wait_for_window)


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
    """List the objects of WORLD (default: the bundled kitchen) with their poses and joints."""
    path = find_world(world_file)
    spec = parse_world(path)
    sim = load_spec(spec, mode="gui" if gui else "direct")
    try:
        rows = []
        for item, obj in zip(spec.objects, sim.objects):
            joints = obj.get_joint_positions()
            rows.append({
                "name": obj.name, "type": obj.type, "file": item.file_text,
                "position": [round(v, 6) for v in obj.get_position()],
                "orientation": [round(v, 6) for v in obj.get_orientation()],
                "fixed": obj.fixed,
                "movable_joints": {k: round(v, 6) for k, v in joints.items()},
                "attached_to": sorted(a.parent.name for a in obj.attachments.values() if a.child is obj),
            })
        if as_json:
            console.emit_json({"world": str(path), "gravity": list(spec.gravity),
                               "robot": sim.robot.name if sim.robot else None, "objects": rows})
        else:
            console.table(f"{path.name}: {len(rows)} objects", ["name", "type", "file", "position", "movable joints"],
                          [(r["name"], r["type"], r["file"], _fmt(r["position"]), _joint_summary(r["movable_joints"]))
                           for r in rows])
        if gui:
            viewer = sim.viewer_camera()
            if viewer is not None:  # the robot and what it may work on, not the outside of the walls
                centres = [tuple((a + b) / 2 for a, b in zip(*o.get_aabb())) for o in movable_objects(sim)]
                sim.set_viewer_camera(robot_camera(sim, centres, viewer.vertical_fov_deg, sim.viewer_aspect()))
            wait_for_window(sim)
    finally:
        sim.exit()


def _joint_summary(joints: dict[str, float]) -> str:
    if not joints:
        return "-"
    opened = [f"{k}={v:.2f}" for k, v in joints.items() if abs(v) > 1e-9]
    return f"{len(joints)}" + (f" ({', '.join(opened[:3])}{', ...' if len(opened) > 3 else ''})" if opened else "")


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
