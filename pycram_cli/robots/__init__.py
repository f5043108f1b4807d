"""Robot descriptions (arms, frames, poses, resources: robot knowledge as data), object knowledge, and the Robot
(`robot.py`: a robot body with its description) that every floor above takes."""
from .description import (
                          ArmDescription,
                          CameraDescription,
                          GripperDescription,
                          HeadDescription,
                          RobotDescription,
                          assign_description,
                          bundled_descriptions,
                          check_description,
                          description_for,
                          find_description,
                          load_description,
)
from .robot import Robot

__all__ = ["ArmDescription", "CameraDescription", "GripperDescription", "HeadDescription", "RobotDescription",
           "assign_description", "bundled_descriptions", "check_description", "description_for", "find_description",
           "load_description", "Robot"]
