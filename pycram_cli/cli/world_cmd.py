"""`pycram world show|render`: look at a world file."""
from __future__ import annotations

from pathlib import Path

import click

from ..errors import InputError, Location
from ..files import check_writable
from ..world.camera import default_camera, parse_camera, render, write_png
from ..worldfile.loader import load_spec
from ..worldfile.spec import parse_world
from . import console
from .options import gui_option, json_option, resolve_world_path, wait_for_window


@click.group()
def world() -> None:
    """Inspect and render world files."""


def _fmt(values: tuple[float, ...] | list[float]) -> str:
    return "(" + ", ".join(f"{v:.3f}" for v in values) + ")"


@world.command("show")
@click.argument("world_file", metavar="[WORLD]", required=False)
@json_option
@gui_option
def show(world_file: str | None, as_json: bool, gui: bool) -> None:
    """List the objects of WORLD (default: the bundled kitchen) with their poses and joints."""
    path = resolve_world_path(world_file)
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
            wait_for_window(sim)
    finally:
        sim.exit()


def _joint_summary(joints: dict[str, float]) -> str:
    if not joints:
        return "-"
    opened = [f"{k}={v:.2f}" for k, v in joints.items() if abs(v) > 1e-9]
    return f"{len(joints)}" + (f" ({', '.join(opened[:3])}{', ...' if len(opened) > 3 else ''})" if opened else "")


@world.command("render")
@click.argument("world_file", metavar="[WORLD]", required=False)
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=Path("scene.png"),
              show_default=True, help="PNG file to write.")
@click.option("--camera", metavar="EYE:TARGET", help="Camera eye and target, each x,y,z, e.g. -1.5,-1.5,2.5:1,0.8,0.9.")
@click.option("--size", metavar="WxH", default="960x720", show_default=True, help="Image size in pixels.")
def render_cmd(world_file: str | None, output: Path, camera: str | None, size: str) -> None:
    """Render WORLD to a PNG (headless)."""
    try:
        width, height = (int(v) for v in size.lower().split("x"))
        if not (16 <= width <= 4096 and 16 <= height <= 4096):
            raise ValueError
    except ValueError:
        raise InputError(f"expected WIDTHxHEIGHT between 16 and 4096, e.g. 960x720, got '{size}'", Location("--size")) from None
    try:
        cam = parse_camera(camera) if camera else None
    except ValueError as exc:
        raise InputError(str(exc), Location("--camera")) from None
    check_writable(output, "--output")  # before anything is rendered
    path = resolve_world_path(world_file)
    sim = load_spec(parse_world(path))
    try:
        image = render(sim, cam or default_camera(sim), width, height)
    finally:
        sim.exit()
    write_png(output, image, key="--output")
    console.success(f"wrote {output} ({width}x{height})")


world.add_command(render_cmd, "render")


COMMANDS = [world]
