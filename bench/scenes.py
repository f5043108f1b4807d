"""Benchmark worlds: the design's scene on the real models, and the bundled world crowded with small objects.

`design_world()` is the scene the design's figures come from (thesis listing 5.1): the real PR2 and the
real IAI kitchen (`../shared/models`), the design's object meshes at the listing's (x, y), each let down
onto what is under it (the meshes have their origin at their middle), the spoon in the left upper
drawer. The robot stands and looks as in the bundled world (`worlds/kitchen.yaml`), so the camera sees
the counter. `None` when `../shared/models` is absent: benchmarks then skip those rows.

`crowded_world(n)` is the bundled world with `n` extra small cubes (3-5 cm) resting on the counter, the
island and the floor, at seeded positions that keep them apart: a big scene whose extra bodies have
nothing to do with the queries.
"""
from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import numpy as np

REPO = Path(__file__).resolve().parents[1]
SHARED_MODELS = REPO.parent / "shared" / "models"

#: name: (type, mesh, x, y) as in the design's listing 5.1 (the spoon: in the drawer)
LISTING = {
    "milk": ("milk", "milk.stl", 1.3, 1.0),
    "spoon": ("spoon", "spoon.stl", 1.4, 0.8),
    "cereal": ("breakfast_cereal", "breakfast_cereal.stl", 1.3, 0.6),
    "bowl": ("bowl", "bowl.stl", 1.3, 0.8),
}
DRAWER_FLOOR = 0.7324  # the real drawer is hollow: its floor's top is here
#: free areas for extra objects: (x0, x1, y0, y1, surface z), and how many of every 10 go to each
AREAS = [((1.30, 1.78, 0.23, 1.28, 0.851), 3),  # the counter beside the sink (minus the breakfast's spots)
         ((-0.6, 1.1, -0.9, -0.15, 0.0), 4),  # the floor before the fridge and the sink
         ((-0.6, 1.1, 1.6, 2.9, 0.0), 3)]  # the floor before the oven
SPACING = 0.07  # m between centres: at least 2 cm between two 5 cm cubes
CLEARANCE = 0.03  # m from the world's own loose objects (the breakfast)


def design_world() -> Any | None:
    """The design's scene on the real models, or None without ../shared/models."""
    if not SHARED_MODELS.is_dir():
        return None
    from pycram_cli.paths import default_world
    from pycram_cli.worldfile.loader import load_world

    models = SHARED_MODELS
    text = default_world().read_text()
    head, _, _ = text.partition("  - name: milk")
    head = head.replace("file: environments/floor/floor.urdf", f"file: {models / 'objects' / 'plane.urdf'}")
    head = head.replace("file: robots/pr2/pr2.urdf", f"file: {models / 'pr2' / 'pr2.urdf'}")
    head = head.replace("file: environments/kitchen/kitchen.urdf", f"file: {models / 'kitchen' / 'kitchen.urdf'}")
    lines = [head.rstrip()]
    for name, (kind, mesh, x, y) in LISTING.items():
        z = DRAWER_FLOOR + 0.03 if name == "spoon" else 1.0
        lines.append(f"  - {{name: {name}, type: {kind}, file: {models / 'objects' / mesh}, position: [{x}, {y}, {z}]}}")
    path = Path(tempfile.mkdtemp(prefix="pycram-bench-")) / "design_kitchen.yaml"
    path.write_text("\n".join(lines) + "\n")
    world = load_world(path)
    kitchen = world.get_object_by_name("kitchen")
    for name in LISTING:  # let each down onto what is under it, touching it
        obj = world.get_object_by_name(name)
        x, y, z = obj.get_position()
        obj.set_position([x, y, z - world.distance(obj, kitchen, 1.0) + 0.0002])
    return world


def cube_mesh(size: float) -> Path:
    """An OBJ cube `size` m wide standing on its bottom face (origin at the bottom centre), in a temp folder."""
    folder = Path(tempfile.gettempdir()) / "pycram-bench-cubes"
    folder.mkdir(exist_ok=True)
    path = folder / f"cube_{size * 1000:.0f}mm.obj"
    if not path.exists():
        h = size / 2
        corners = [(x, y, z) for z in (0.0, size) for x, y in ((-h, -h), (h, -h), (h, h), (-h, h))]
        faces = [(1, 3, 2), (1, 4, 3), (5, 6, 7), (5, 7, 8), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6),
                 (3, 4, 8), (3, 8, 7), (4, 1, 5), (4, 5, 8)]
        text = "".join(f"v {x:.4f} {y:.4f} {z:.4f}\n" for x, y, z in corners)
        text += "".join(f"f {a} {b} {c}\n" for a, b, c in faces)
        path.write_text(text)
    return path


def add_small_objects(world: Any, n: int, seed: int = 0) -> list[Any]:
    """`n` small cubes (3-5 cm, 50 g) resting on the counter and the floor (see AREAS), `SPACING` apart
    or more (and from the world's own free objects), each touching what is under it and nothing else."""
    from pycram_cli import Object

    rng = np.random.default_rng(seed)
    taken: list[tuple[float, float]] = []
    loose = [o for o in world.objects if not o.fixed]  # kept CLEARANCE away from the cubes
    scenery = [o for o in world.objects if o.fixed]
    turns = [area for area, share in AREAS for _ in range(share)]
    added: list[Any] = []
    while len(added) < n:
        x0, x1, y0, y1, top = turns[len(added) % len(turns)]
        x, y = float(rng.uniform(x0, x1)), float(rng.uniform(y0, y1))
        if any((x - a) ** 2 + (y - b) ** 2 < SPACING ** 2 for a, b in taken):
            continue
        size = float(rng.choice([0.03, 0.04, 0.05]))
        cube = Object(f"cube{len(added)}", "cube", cube_mesh(size), (x, y, top + 0.01), world=world,
                      color=(0.3, 0.4, 0.8), mass=0.05)
        gaps = sorted(world.distance(cube, other, 0.05) for other in scenery)
        if (not 0.0 < gaps[0] < 0.03 or gaps[1] < 0.02  # over the surface (not a hole), clear of other scenery
                or any(world.distance(cube, other, CLEARANCE) < CLEARANCE for other in loose)):
            cube.remove()
            continue
        cube.set_position([x, y, top + 0.01 - gaps[0] + 0.0002])  # let down onto it, touching it
        taken.append((x, y))
        added.append(cube)
    return added


def crowded_world(n: int = 200, seed: int = 0) -> Any:
    """The bundled kitchen world with `n` extra small objects (see `add_small_objects`)."""
    from pycram_cli import load_world

    world = load_world(REPO / "worlds" / "kitchen.yaml")
    add_small_objects(world, n, seed)
    return world
