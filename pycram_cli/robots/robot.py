"""The robot: its body in a world together with its description (arms, frames, poses as data).

Every layer above `robots/` takes a `Robot` (reasoning, planning, the process modules, locations, designators),
so what the robot is and what it holds is answered in one place."""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError, Location
from ..world import BulletWorld, Object
from .description import ArmDescription, RobotDescription, description_for


@dataclass
class Robot:
    """The robot object together with its description."""

    world: BulletWorld
    body: Object
    description: RobotDescription

    @classmethod
    def of(cls, world: BulletWorld) -> Robot:
        """The world's robot with its description: the one the world loader gave it, kept by the world (else found for
        its model once, `description_for`); an input error when the world has no robot or it has no description."""
        body = world.robot
        if body is None:
            raise InputError("the world has no robot (an object of type 'robot')", Location("world"),
                             suggestion="add an object of type robot to the world file")
        description = description_for(body)
        if description is None:
            raise InputError(f"no robot description for '{body.name}' ({body.path.name})", Location(str(body.path)),
                             suggestion=f"write {body.path.with_suffix('.yaml').name} beside it, or name one with "
                                        "'description:' in the world file (see docs/robots.md)")
        return cls(world, body, description)

    def arm(self, name: str) -> ArmDescription:
        """The description of one arm (a KeyError naming the arms for an unknown one)."""
        return self.description.arm(name)

    def held_objects(self, arm: str | None = None) -> list[Object]:
        """Objects attached to a tool frame (of `arm`, or of any arm)."""
        arms = [self.description.arm(arm)] if arm else list(self.description.arms.values())
        tool_ids = {self.body.get_link_id(a.tool_frame) for a in arms}
        return sorted((child for child, att in self.body.attachments.items()
                       if att.parent is self.body and att.parent_link in tool_ids), key=lambda o: o.name)

    def arm_holding(self, obj: Object) -> str | None:
        """The arm whose tool holds `obj`, or None."""
        att = self.body.attachments.get(obj)
        if att is None or att.parent is not self.body:
            return None
        return self.description.arm_of_link(self.body.get_link_name(att.parent_link))

