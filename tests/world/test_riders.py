"""What a moving link carries, tried without attaching it: where an attachment would take it, and put back as it was
(a location test tries a drawer's pull with what the drawer holds riding along)."""
from __future__ import annotations

import pytest

from pycram_cli.world.riders import carrying


def test_carrying_puts_riders_where_an_attachment_would_take_them(arm_scene):
    _, arm, cube = arm_scene
    with arm.joints_kept(["slide"]), carrying(arm, arm.get_link_id("hand"), [cube]) as follow:
        arm.reset_joints({"slide": 0.2})
        follow()
        carried = cube.get_pose()
    arm.attach(cube, parent_link="hand")
    arm.set_joint_position("slide", 0.2)
    assert cube.get_pose() == carried  # bitwise: what a location test tries is what the action then does


def test_carrying_puts_riders_back_bitwise_keeping_their_versions(arm_scene):
    _, arm, cube = arm_scene
    pose, version = cube.get_pose(), cube.version
    with arm.joints_kept(["slide"]), carrying(arm, arm.get_link_id("hand"), [cube]) as follow:
        arm.reset_joints({"slide": 0.2})
        follow()
        assert cube.get_pose()[0][0] == pytest.approx(pose[0][0] + 0.2)
    assert cube.get_pose() == pose and cube.version == version
