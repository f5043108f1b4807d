"""The design's Python API (the 2019 thesis' PyCRAM, chapter 4), as thin wrappers over pycram's own.

Scripts written against the design port by their imports, module for module:

    import pycram.bullet_world_reasoning as btr      ->  import pycram_cli.design.bullet_world_reasoning as btr
    from pycram.bullet_world import BulletWorld, Object  ->  from pycram_cli.design.bullet_world import ...
    from pycram.designator import MotionDesignator   ->  from pycram_cli.design.designator import ...
    from pycram.process_module import ProcessModule  ->  from pycram_cli.design.process_module import ...

and then run as written: `BulletWorld()`, `BulletWorld("DIRECT")`, `world.set_gravity(...)`,
`Object(name, type, path, position, orientation, world, color)` (bare file names such as
"plane.urdf" are found as world files find them), `BulletWorld.robot = robot`,
`BulletWorld.current_bullet_world`, `world.get_attachment_event()` and its kin,
`ProcessModule.perform(MotionDesignator([("type", "moving"), ("target", [...])]))`,
`btr.stable(obj)`, `btr.contact(a, b, world)`, `btr.reachable_pose(...)`, `raise btr.ReasoningError`.

One difference stays: the design's `Object.get_pose()` was an alias of `get_position()`; pycram's
returns (position, orientation) — write `get_position()` for the design's meaning.
"""
from . import bullet_world, bullet_world_reasoning, designator, process_module  # noqa: F401  (the design's module names)
from .bullet_world import BulletWorld, Event, Object
from .designator import MotionDesignator
from .process_module import ProcessModule

# the design's modules (bullet_world, bullet_world_reasoning, designator, process_module) are submodules, imported
# above; what the package itself names is the objects
__all__ = ["BulletWorld", "Event", "Object", "MotionDesignator", "ProcessModule"]
