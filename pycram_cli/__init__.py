"""pycram: plans for mobile pick-and-place robots, run in a lightweight PyBullet world.

    from pycram_cli import BulletWorld, Object, load_world
"""
from .world import BulletWorld, Event, Object, WorldState, current_world
from .worldfile.loader import load_world

__version__ = "0.1.0"


__all__ = ["BulletWorld", "Object", "Event", "WorldState", "current_world", "load_world", "__version__"]
