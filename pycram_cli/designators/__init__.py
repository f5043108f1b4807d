"""Motion designators: symbolic descriptions of motions, each declared once, checked, resolved and performed.

A designator is one `Designator` declaration (its slots as a `Signature` of `pycram_cli.signature`,
inference, the roles it drives, its default process module) in a module of its own family, imported here; plan
validation, the scheduler's resources, `pycram designators` and `perform` are generated from
`DESIGNATORS`. A new designator is a module with its `declare_designator(...)`, imported here.
"""
# the design's eleven designators, declared in this order (pycram designators lists them so), then ours
from . import navigation, manipulation, perception, arms, torso  # noqa: F401,I001  (registration, in this order)
from .declaration import (ANY_ARM, DESIGNATORS, Designator, check_designator, declare_designator, drives, drives_arm,
                          process_module_problems, robot_resources)
from .performing import perform
from .result import Performed
from . import actions  # noqa: F401,I001  (action designators, one level up, their own registry ACTIONS: imported last)

__all__ = ["ANY_ARM", "DESIGNATORS", "Designator", "Performed", "check_designator",
           "declare_designator", "drives", "drives_arm", "perform", "process_module_problems", "robot_resources"]
