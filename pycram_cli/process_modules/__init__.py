"""Process modules: one per physical resource, chosen by designator type and robot."""
from . import accessing, arms, head, manipulation, navigation, perception, torso  # noqa: F401  (registration)
from .base import ProcessModule
from .registry import PROCESS_MODULES, choose, process_module

__all__ = ["PROCESS_MODULES", "ProcessModule", "choose", "process_module"]
