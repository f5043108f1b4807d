"""Robot descriptions: the robot-specific knowledge (arms, frames, poses) kept as data."""
from .description import ArmDescription, RobotDescription, description_for, load_description

__all__ = ["ArmDescription", "RobotDescription", "description_for", "load_description"]
