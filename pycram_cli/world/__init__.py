"""The simulation layer: worlds, objects, attachments, events and saved states."""
from ..quiet import silenced

with silenced():  # PyBullet prints its build banner from C when first imported
    import pybullet  # noqa: F401  (imported here, silenced, before anything else imports it)
from .bullet_world import BulletWorld, ClosestPoint, RayHit, WorldError, current_world
from .display import NoDisplayError
from .events import Event
from .object import Object
from .parts import Attachment, JointLimitError, MissingMeshWarning, VisualShape
from .state import StateError, WorldState

__all__ = ["BulletWorld", "ClosestPoint", "RayHit", "Object", "Attachment", "Event", "WorldState", "WorldError", "StateError",
           "JointLimitError", "MissingMeshWarning", "NoDisplayError", "VisualShape", "current_world"]
