"""pycram: plans for mobile pick-and-place robots, run in a lightweight PyBullet world.

    from pycram_cli import BulletWorld, Object, load_world
"""
from .world import BulletWorld, Event, Object, WorldState, current_world

__version__ = "0.1.0"


def load_world(path=None, mode: str = "direct"):  # type: ignore[no-untyped-def]
    """Build a BulletWorld from a YAML world file (default: the bundled kitchen; the loader the CLI uses)."""
    from .worldfile.loader import load_world as _load

    return _load(path, mode=mode)


__all__ = ["BulletWorld", "Object", "Event", "WorldState", "current_world", "load_world", "__version__"]
