"""The URDF writer the bundled robots' generators and the zoo share: numbers spelt stably, joints and links written
as PyBullet reads them, broken trees refused, inertia from the shapes."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

from pycram_cli.robots.urdf_writer import (
    Joint,
    Limit,
    Numbers,
    Visual,
    check_tree,
    fixed,
    general,
    inertia_about,
    joint_xml,
    link_xml,
    urdf_text,
)

GENERAL = Numbers(general, 12, 6, 6, 6)


@dataclass(frozen=True)
class Box:
    kind: str = "box"
    dims: tuple[float, ...] = (0.2, 0.4, 0.6)
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)


def test_numbers_have_one_spelling_and_never_minus_zero():
    assert general(-0.0) == "0" and general(1 / 3, 6) == "0.333333" and general(2.0) == "2"
    assert fixed(-1e-9) == "0" and fixed(1 / 3) == "0.333333" and fixed(0.5, 2) == "0.5"


def test_a_joint_has_its_limit_and_mimic_only_when_it_has_them():
    fixed_joint = joint_xml(Joint("j", "fixed", "a", "b"), GENERAL)
    assert not any("<limit" in line or "<axis" in line for line in fixed_joint)
    continuous = joint_xml(Joint("w", "continuous", "a", "b", axis=(0, 0, 1), limit=Limit(None, None, 5, 2)), GENERAL)
    assert '    <limit effort="5" velocity="2"/>' in continuous
    finger = joint_xml(Joint("f", "prismatic", "a", "b", axis=(0, 1, 0), limit=Limit(0, 0.04, 10, 0.1), mimic="g"),
                       GENERAL)
    assert '    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/>' in finger
    assert '    <mimic joint="g" multiplier="1" offset="0"/>' in finger


def test_a_visual_only_shape_has_no_collision():
    lines = link_xml("l", (1.0, np.zeros(3), np.ones(3)), [Visual(Box(), "grey", (0.5, 0.5, 0.5, 1), collision=False)],
                     GENERAL)
    assert sum("<visual>" in line for line in lines) == 1 and not any("<collision>" in line for line in lines)
    assert '      <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>' in lines


def test_a_broken_tree_is_refused():
    check_tree("a", [Joint("j", "fixed", "a", "b")], ["a", "b"])
    with pytest.raises(ValueError, match="parent c not defined before use"):
        check_tree("a", [Joint("j", "fixed", "c", "b")], ["a", "b"])
    with pytest.raises(ValueError, match="links without joints"):
        check_tree("a", [Joint("j", "fixed", "a", "b")], ["a", "b", "lost"])


def test_the_inertia_of_a_box_is_the_textbook_one():
    com, diag = inertia_about([Box()], np.array([12.0]), 12.0)
    assert com.tolist() == [0, 0, 0]
    assert diag == pytest.approx([0.16 + 0.36, 0.04 + 0.36, 0.04 + 0.16])


def test_joints_and_their_child_links_are_written_in_table_order():
    joints = [Joint("j1", "fixed", "root", "b"), Joint("j2", "fixed", "b", "c")]
    text = urdf_text("bot", ["<!-- made here -->"], "root", joints, lambda name: [f"  <link {name}/>"], GENERAL)
    assert text.splitlines() == ['<?xml version="1.0"?>', "<!-- made here -->", '<robot name="bot">', "  <link root/>",
                                 *joint_xml(joints[0], GENERAL), "  <link b/>", *joint_xml(joints[1], GENERAL),
                                 "  <link c/>", "</robot>"]
