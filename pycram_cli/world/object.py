"""Object: anything in a world — a robot, a kitchen, a spoon — loaded from URDF, STL or OBJ."""
from __future__ import annotations

import contextlib
import math
import warnings
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pybullet as p

from ..errors import BadValue, UnknownName, did_you_mean
from ..quiet import silenced
from .bullet_world import BulletWorld, WorldError
from .meshes import read_mesh
from .model_files import MESH_SUFFIXES, JointInfo, describe_urdf, find_model_file, mesh_urdf, prepare_urdf
from .parts import JOINT_TYPES, SHAPE_KINDS, Attachment, Joint, JointLimitError, MissingMeshWarning, VisualShape
from .pose import UP_TURNS, Quat, Vec3, check_position, check_quaternion, compose, invert, quat_to_matrix, up_axis

KINEMATIC_TYPES = ("robot", "environment")
HOLD_FORCE = 1e5  # N or N·m: what holds a fixed object's joints (see parking.py)


class Object:
    """A body in a BulletWorld, addressed by name; links and joints by their URDF names."""

    # long: loading a model: find the file, load it into PyBullet, index it, colour and fix it, in that order
    def __init__(
        self,
        name: str,
        type: str,
        path: str | Path,
        position: Sequence[float] = (0.0, 0.0, 0.0),
        orientation: Sequence[float] = (0.0, 0.0, 0.0, 1.0),
        world: BulletWorld | None = None,
        color: Sequence[float] | None = None,
        fixed: bool | None = None,
        mass: float | None = None,
    ) -> None:
        world = world if world is not None else BulletWorld.current_world
        if world is None or not world.alive:
            raise WorldError(f"object '{name}': no world to load it into (create a BulletWorld first)")
        position = check_position(position, f"object '{name}' position")
        orientation = check_quaternion(orientation, f"object '{name}' orientation")
        rgba = _check_color(color, name)
        self.name = name
        self.type = type
        self.world = world
        self._placement: tuple[int, tuple[Any, ...]] | None = None
        self._version = 0  # the world's version at this object's last change (see BulletWorld.version)
        self._drawn: list[tuple[int, bool]] | None = None  # see drawn_links
        self._solid: frozenset[int] | None = None  # see solid_links
        self._boxes: tuple[int, Any, Any] | None = None  # see link_aabbs: (version, min corners, max corners)
        try:  # a bare name is searched for as world files do: here, the bundled resources, PyBullet's models
            self.path = find_model_file(path)
        except FileNotFoundError as exc:
            raise FileNotFoundError(f"object '{name}': {exc}") from None
        self.fixed = fixed if fixed is not None else type in KINEMATIC_TYPES
        self._color, self._mass = rgba, mass  # as given: a copy of the object is loaded alike
        #: the turn that stands the model upright (its axis that points most nearly up where it starts: a Y-up mesh
        #: stood on its feet keeps them down when it is placed again), applied before its heading
        self.upright: Quat = UP_TURNS[up_axis(orientation)]
        if self.path.suffix.lower() in MESH_SUFFIXES:
            load_path = mesh_urdf(self.path, rgba, mass)
        else:
            prepared = prepare_urdf(self.path)
            load_path = prepared.path
            if prepared.missing:
                warnings.warn(
                    f"{self.path}: {len(prepared.missing)} mesh file(s) missing, loaded without them: "
                    + ", ".join(prepared.missing),
                    MissingMeshWarning,
                    stacklevel=2,
                )
        cid = world.client_id
        with silenced():
            body = p.loadURDF(str(load_path), position, orientation, useFixedBase=self.fixed, physicsClientId=cid)
        if body < 0:
            raise ValueError(f"object '{name}': PyBullet could not load {self.path}")
        self.id: int = body
        # PyBullet's base pose is the base's centre-of-mass (inertial) frame; ours is its URDF link
        # frame (for meshes: the mesh origin, e.g. the bottom centre). Keep the offset between them.
        dyn = p.getDynamicsInfo(body, -1, physicsClientId=cid)
        self._inertial: tuple[Vec3, Quat] | None = None
        if tuple(dyn[3]) != (0.0, 0.0, 0.0) or tuple(dyn[4]) != (0.0, 0.0, 0.0, 1.0):
            self._inertial = (tuple(dyn[3]), tuple(dyn[4]))
        self._reset_base(position, orientation)
        self.attachments: dict[Object, Attachment] = {}
        self._local_box: tuple[Vec3, Vec3] | None = None  # a mesh's box in its own frame, read once
        self._index_model(describe_urdf(load_path).joints if load_path.suffix.lower() == ".urdf" else {})
        if rgba is not None and self.path.suffix.lower() not in MESH_SUFFIXES:
            for link in [-1, *range(len(self.joints))]:
                p.changeVisualShape(body, link, rgbaColor=rgba, physicsClientId=cid)
        if self.fixed and self.movable_joints:
            ids = [j.index for j in self.movable_joints]
            p.setJointMotorControlArray(body, ids, p.VELOCITY_CONTROL, targetVelocities=[0.0] * len(ids),
                                        forces=[HOLD_FORCE] * len(ids), physicsClientId=cid)
        world.register(self)

    # -- model ------------------------------------------------------------------
    def _index_model(self, declared: Mapping[str, JointInfo]) -> None:
        cid = self.world.client_id
        base_name, _ = p.getBodyInfo(self.id, physicsClientId=cid)
        self.base_link_name = base_name.decode()
        self.joints: list[Joint] = []
        self._joint_ids: dict[str, int] = {}
        self._link_ids: dict[str, int] = {self.base_link_name: -1}
        for index in range(p.getNumJoints(self.id, physicsClientId=cid)):
            info = p.getJointInfo(self.id, index, physicsClientId=cid)
            name, kind, lower, upper, link = info[1].decode(), info[2], info[8], info[9], info[12].decode()
            type_name = JOINT_TYPES.get(kind, "unknown")
            if type_name == "revolute" and (lower > upper or getattr(declared.get(name), "type", "") == "continuous"):
                type_name, lower, upper = "continuous", -math.inf, math.inf
            dyn = p.getDynamicsInfo(self.id, index, physicsClientId=cid)
            orn = info[15]  # getJointInfo reports this orientation inverted (checked against getLinkState)
            joint = Joint(index, name, type_name, float(lower), float(upper), link,
                          parent_index=info[16], axis=tuple(info[13]),
                          parent_frame=(tuple(info[14]), (-orn[0], -orn[1], -orn[2], orn[3])),
                          inertial_frame=(tuple(dyn[3]), tuple(dyn[4])))
            self.joints.append(joint)
            self._joint_ids[name] = index
            self._link_ids[link] = index
        self._link_names = {v: k for k, v in self._link_ids.items()}
        self.movable_joints = [j for j in self.joints if j.movable]

    @property
    def link_names(self) -> list[str]:
        return list(self._link_ids)

    @property
    def joint_names(self) -> list[str]:
        return list(self._joint_ids)

    def get_joint_id(self, name: str) -> int:
        try:
            return self._joint_ids[name]
        except KeyError:
            raise UnknownName(_unknown(f"object '{self.name}' has no joint", name, self._joint_ids)) from None

    def get_link_id(self, name: str) -> int:
        try:
            return self._link_ids[name]
        except KeyError:
            raise UnknownName(_unknown(f"object '{self.name}' has no link", name, self._link_ids)) from None

    def get_link_name(self, link_id: int) -> str:
        return self._link_names[link_id]

    def joint(self, name: str) -> Joint:
        return self.joints[self.get_joint_id(name)]

    def joint_axis(self, name: str) -> np.ndarray:
        """A joint's unit axis in the world as the object stands (PyBullet gives it in the child's centre-of-mass
        frame, turned like the child link's frame)."""
        joint = self.joint(name)
        local = quat_to_matrix(joint.inertial_frame[1]) @ np.asarray(joint.axis, dtype=float)
        return quat_to_matrix(self.get_link_orientation(joint.index)) @ (local / (np.linalg.norm(local) or 1.0))

    # -- pose -------------------------------------------------------------------
    def get_position(self) -> Vec3:
        return self.get_pose()[0]

    def get_orientation(self) -> Quat:
        return self.get_pose()[1]

    @property
    def version(self) -> int:
        """Changes whenever this object may have changed (its own changes and every simulation step)."""
        return self.world.version_of(self)

    def get_pose(self) -> tuple[Vec3, Quat]:
        """(position, orientation) of the base link's frame in the world frame."""
        pos, orn = p.getBasePositionAndOrientation(self.id, physicsClientId=self.world.client_id)
        if self._inertial is not None:
            return compose((pos, orn), invert(self._inertial))
        return tuple(pos), tuple(orn)

    def get_com_pose(self) -> tuple[Vec3, Quat]:
        """PyBullet's own base pose: the base's centre-of-mass (inertial) frame in the world frame.

        One call, no conversion: cheap enough to watch motion at every simulation step, and the
        frame PyBullet's joint frames start from. `get_pose` is the base link's URDF frame.
        """
        return p.getBasePositionAndOrientation(self.id, physicsClientId=self.world.client_id)

    def get_velocity(self) -> tuple[Vec3, Vec3]:
        """(linear, angular) velocity of the base's centre of mass in the world frame (m/s, rad/s)."""
        linear, angular = p.getBaseVelocity(self.id, physicsClientId=self.world.client_id)
        return tuple(linear), tuple(angular)

    def _reset_base(self, position: Sequence[float], orientation: Sequence[float]) -> None:
        """Put the base link's frame at a pose (PyBullet places the centre of mass)."""
        if self._inertial is not None:
            position, orientation = compose((position, orientation), self._inertial)
        p.resetBasePositionAndOrientation(self.id, position, orientation, physicsClientId=self.world.client_id)
        self.world.mark_changed(self)

    def set_position_and_orientation(self, position: Sequence[float], orientation: Sequence[float]) -> None:
        """Teleport the object; everything attached to it follows at once."""
        position = check_position(position, f"object '{self.name}' position")
        orientation = check_quaternion(orientation, f"object '{self.name}' orientation")
        with self.world.lock:
            self._reset_base(position, orientation)
            self._after_move()

    def set_position(self, position: Sequence[float]) -> None:
        self.set_position_and_orientation(position, self.get_orientation())

    def set_orientation(self, orientation: Sequence[float]) -> None:
        self.set_position_and_orientation(self.get_position(), orientation)

    set_pose = set_position_and_orientation

    def get_link_position_and_orientation(self, link: str | int) -> tuple[Vec3, Quat]:
        index = link if isinstance(link, int) else self.get_link_id(link)
        if index == -1:
            return self.get_pose()
        state = p.getLinkState(self.id, index, computeForwardKinematics=True, physicsClientId=self.world.client_id)
        return tuple(state[4]), tuple(state[5])

    def get_link_position(self, link: str | int) -> Vec3:
        return self.get_link_position_and_orientation(link)[0]

    def get_link_orientation(self, link: str | int) -> Quat:
        return self.get_link_position_and_orientation(link)[1]

    def link_poses(self, links: Iterable[int]) -> dict[int, tuple[Vec3, Quat]]:
        """The URDF frames of several links (by index, -1: the base) in the world frame, read at once."""
        wanted = sorted(set(links))
        poses: dict[int, tuple[Vec3, Quat]] = {}
        if -1 in wanted:
            poses[-1] = self.get_pose()
        indices = [i for i in wanted if i >= 0]
        if indices:
            states = p.getLinkStates(self.id, indices, computeForwardKinematics=True,
                                     physicsClientId=self.world.client_id)
            for index, state in zip(indices, states):
                poses[index] = (tuple(state[4]), tuple(state[5]))
        return poses

    def visual_shapes(self) -> list[VisualShape]:
        """What the object looks like: every visual shape of every link, in the links' URDF frames."""
        shapes = []
        for row in p.getVisualShapeData(self.id, physicsClientId=self.world.client_id):
            link, geometry, dimensions, file_name = row[1], row[2], tuple(row[3]), row[4]
            origin = (tuple(float(v) for v in row[5]), tuple(float(v) for v in row[6]))
            rgba = tuple(float(v) for v in row[7])
            kind = SHAPE_KINDS.get(geometry, "unknown")
            fields: dict[str, object] = {}
            if kind == "box":
                fields["size"] = tuple(float(v) for v in dimensions[:3])
            elif kind == "sphere":
                fields["radius"] = float(dimensions[0])
            elif kind in ("cylinder", "capsule"):
                fields["length"], fields["radius"] = float(dimensions[0]), float(dimensions[1])
            elif kind == "mesh":
                name = file_name.decode(errors="replace") if isinstance(file_name, bytes) else str(file_name)
                fields["mesh_file"] = Path(name) if name else None
                fields["scale"] = tuple(float(v) for v in dimensions[:3])
            shapes.append(VisualShape(link, kind, origin, rgba, **fields))  # type: ignore[arg-type]
        return shapes

    def drawn_links(self) -> list[tuple[int, bool]]:
        """The links a renderer draws (with visual shapes not fully transparent), each with whether it has
        collision shapes too (whose box then bounds what is drawn, give or take a mesh's finish); read once."""
        if self._drawn is None:
            cid = self.world.client_id
            links = sorted({shape.link for shape in self.visual_shapes() if shape.rgba[3] > 0.0})
            self._drawn = [(link, bool(p.getCollisionShapeData(self.id, link, physicsClientId=cid))) for link in links]
        return self._drawn

    def solid_links(self) -> frozenset[int]:
        """The links with collision shapes (-1: the base); read once. A frame-only link (a tool or camera frame,
        a `base_footprint`) has none, though PyBullet still gives it a box of a few millimetres."""
        if self._solid is None:
            cid = self.world.client_id
            self._solid = frozenset(link for link in range(-1, len(self.joints))
                                    if p.getCollisionShapeData(self.id, link, physicsClientId=cid))
        return self._solid

    def hangs_below(self, link: int, ancestor: int) -> bool:
        """Whether link `link` is link `ancestor` or hangs below it (moves with it); -1 is the base."""
        while link != -1:
            if link == ancestor:
                return True
            link = self.joints[link].parent_index
        return False

    def links_below(self, joints: Iterable[str]) -> frozenset[int]:
        """The links that move when any of these joints moves: each joint's child link and everything below it."""
        indices = {self.get_joint_id(name) for name in joints}
        found = set()
        for joint in self.joints:
            index = joint.index
            while index != -1:
                if index in indices:
                    found.add(joint.index)
                    break
                index = self.joints[index].parent_index
        return frozenset(found)

    def get_aabb(self, link: str | int | None = None) -> tuple[Vec3, Vec3]:
        """Axis-aligned bounding box (min corner, max corner) of a link or the whole object."""
        cid = self.world.client_id
        if link is not None:
            index = link if isinstance(link, int) else self.get_link_id(link)
            lo, hi = p.getAABB(self.id, index, physicsClientId=cid)
            return tuple(lo), tuple(hi)
        boxes = [p.getAABB(self.id, i, physicsClientId=cid) for i in [-1, *range(len(self.joints))]]
        lo = tuple(min(b[0][k] for b in boxes) for k in range(3))
        hi = tuple(max(b[1][k] for b in boxes) for k in range(3))
        return lo, hi

    def link_aabbs(self, links: Sequence[int] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The boxes of some links (default: every link, the base first, as -1) as two (n, 3) arrays (min corners,
        max corners): `get_aabb` for many links at once. Every link's boxes are kept while the object does not
        change (`BulletWorld.version_of`), so that asking again costs nothing."""
        if links is None:
            version = self.world.version_of(self)
            if self._boxes is None or self._boxes[0] != version:
                cid = self.world.client_id
                rows = [p.getAABB(self.id, i, physicsClientId=cid) for i in range(-1, len(self.joints))]
                self._boxes = (version, np.array([r[0] for r in rows], dtype=float).reshape(-1, 3),
                               np.array([r[1] for r in rows], dtype=float).reshape(-1, 3))
            return self._boxes[1], self._boxes[2]
        cid = self.world.client_id
        rows = [p.getAABB(self.id, i, physicsClientId=cid) for i in links]
        return (np.array([r[0] for r in rows], dtype=float).reshape(-1, 3),
                np.array([r[1] for r in rows], dtype=float).reshape(-1, 3))

    def aabb_rows(self, links: Iterable[int]) -> list[tuple[Any, Any]]:
        """PyBullet's boxes of some links as it gives them, a (min corner, max corner) pair per link: the rows
        `link_aabbs` makes arrays of, for a caller that adds rows of its own before making one array of them all."""
        cid = self.world.client_id
        return [p.getAABB(self.id, i, physicsClientId=cid) for i in links]

    def get_local_aabb(self) -> tuple[Vec3, Vec3]:
        """The box of the object's collision shapes in its own frame (min corner, max corner): for a mesh, its
        vertices' bounds (no collision margin); otherwise every link's box, turned into the object's frame (exact
        for links whose boxes are aligned with the object)."""
        if self._local_box is None:
            if self.path.suffix.lower() in MESH_SUFFIXES:
                lo, hi = read_mesh(self.path).bounds
                self._local_box = (tuple(float(v) for v in lo), tuple(float(v) for v in hi))  # type: ignore[assignment]
            else:
                return _box_in_frame(self.get_pose(), [self.get_aabb(link) for link in [-1, *range(len(self.joints))]])
        return self._local_box  # type: ignore[return-value]

    def get_link_local_aabb(self, link: str | int) -> tuple[Vec3, Vec3]:
        """The box of a link's collision shapes in the link's own frame (its world box turned into the link frame:
        exact for a link whose shapes are aligned with its frame, as a handle bar or a drawer usually is)."""
        index = link if isinstance(link, int) else self.get_link_id(link)
        return _box_in_frame(self.get_link_position_and_orientation(index), [self.get_aabb(index)])

    # -- joints -----------------------------------------------------------------
    def get_joint_position(self, name: str) -> float:
        return float(p.getJointState(self.id, self.get_joint_id(name), physicsClientId=self.world.client_id)[0])

    def get_joint_positions(self, names: Iterable[str] | None = None) -> dict[str, float]:
        joints = [self.joint(n) for n in names] if names is not None else self.movable_joints
        if not joints:
            return {}
        states = p.getJointStates(self.id, [j.index for j in joints], physicsClientId=self.world.client_id)
        return {j.name: float(s[0]) for j, s in zip(joints, states)}

    def configuration(self, joints: Sequence[int] | None = None) -> tuple[Any, ...]:
        """Where PyBullet holds the object's links now, exactly: its base's pose and every joint's position (or those
        of `joints`, indices), as PyBullet reports them. Equal configurations place every link alike (those
        below `joints` when given), bitwise: a key for results computed from where the object is (what `version`
        cannot be for an object re-placed to the same spot)."""
        cid = self.world.client_id
        pose = p.getBasePositionAndOrientation(self.id, physicsClientId=cid)
        indices = range(len(self.joints)) if joints is None else joints
        if not len(indices):
            return (pose,)
        states = p.getJointStates(self.id, indices, physicsClientId=cid)
        return pose, tuple(s[0] for s in states)

    def placement(self) -> tuple[Any, ...]:
        """`configuration()`, read once per version: a key for results computed from where the object is that two
        ways to the same place share (a location test that tried the drawer opened, then the action that opened
        it), where `version` tells them apart."""
        version = self.world.version_of(self)
        kept = self._placement
        if kept is not None and kept[0] == version:
            return kept[1]
        found = self.configuration()
        self._placement = (version, found)
        return found

    def set_joint_position(self, name: str, value: float) -> None:
        self.set_joint_positions({name: value})

    def set_joint_positions(self, values: Mapping[str, float]) -> None:
        """Set joints by name (checked against their limits); attached objects follow at once."""
        checked: list[tuple[Joint, float]] = []
        for name, value in values.items():
            joint = self.joint(name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
                raise JointLimitError(f"joint '{name}' of '{self.name}': expected a number, got {value!r}")
            if joint.limited and not (joint.lower - 1e-9 <= value <= joint.upper + 1e-9):
                raise JointLimitError(
                    f"joint '{name}' of '{self.name}': {value:g} is outside its limits "
                    f"[{joint.lower:g}, {joint.upper:g}]"
                )
            checked.append((joint, float(value)))
        with self.world.lock:
            old = self.get_joint_positions([j.name for j, _ in checked]) if self.type != "robot" else {}
            cid = self.world.client_id
            for joint, value in checked:
                p.resetJointState(self.id, joint.index, value, 0.0, physicsClientId=cid)
            self.world.mark_changed(self)
            self._after_move()
        if self.type != "robot":
            for joint, value in checked:
                if old.get(joint.name) != value:
                    self.world.manipulation_event(self, joint.name, old.get(joint.name), value)

    def reset_joints(self, positions: Mapping[str, float]) -> None:
        """Set joints (velocity 0) without limit checks or events; attached objects do not follow.

        For putting joints back (drift, trial configurations); `set_joint_positions` is the checked way.
        """
        if not positions:
            return
        ids = [self.get_joint_id(name) for name in positions]
        # one call for all of them (what collision-checked motions do at every step of a path)
        p.resetJointStatesMultiDof(self.id, ids, [[float(v)] for v in positions.values()], [[0.0]] * len(ids),
                                   physicsClientId=self.world.client_id)
        self.world.mark_changed(self)

    def reset_joint_indices(self, indices: Sequence[int], values: Iterable[float]) -> None:
        """`reset_joints` by joint index, in one call: for a caller that moves the same joints many times (every
        step of a collision-checked path), with the indices looked up once."""
        if not indices:
            return
        p.resetJointStatesMultiDof(self.id, indices, [[float(v)] for v in values], [[0.0]] * len(indices),
                                   physicsClientId=self.world.client_id)
        self.world.mark_changed(self)

    @contextlib.contextmanager
    def joints_kept(self, names: Iterable[str]) -> Iterator[None]:
        """`with obj.joints_kept(names):` — these joints' positions and velocities are put back bitwise on leaving.

        Cheaper than a world snapshot when a query only tries joint values; attached objects are
        not moved (use `world.snapshot()` when they follow). An object the block leaves exactly as it found it
        (pose, joints, velocities, attachments) keeps its version: what was kept for it stays valid (a location
        trying the drawer opened leaves the walks made before it to be found again).
        """
        ids = [self.get_joint_id(name) for name in names]
        cid = self.world.client_id
        saved = [(s[0], s[1]) for s in p.getJointStates(self.id, ids, physicsClientId=cid)] if ids else []
        version, before = self._version, self._exact_state()
        try:
            yield
        finally:
            for jid, (position, velocity) in zip(ids, saved):
                p.resetJointState(self.id, jid, position, velocity, physicsClientId=cid)
            self.world.mark_changed(self)
            if self._exact_state() == before:  # all put back, bitwise: the object is as it was at its version
                self._version = version

    def _exact_state(self) -> tuple[Any, ...]:
        """The object's pose, joint positions and velocities, base velocity and attachments, exactly as held now."""
        cid = self.world.client_id
        states = p.getJointStates(self.id, range(len(self.joints)), physicsClientId=cid) if self.joints else ()
        return (p.getBasePositionAndOrientation(self.id, physicsClientId=cid),
                p.getBaseVelocity(self.id, physicsClientId=cid), tuple((s[0], s[1]) for s in states),
                tuple((id(other), att.parent_link, att.child_link, tuple(att.transform))
                      for other, att in self.attachments.items()))

    # -- attachments -----------------------------------------------------------
    def attach(self, other: Object, parent_link: str | None = None, child_link: str | None = None) -> None:
        """Attach `other` to this object: from now on it follows this object's link rigidly.

        Attachments are bilateral (either side can detach); attaching an attached pair again changes nothing.
        """
        if other is self:
            raise BadValue(f"object '{self.name}' cannot be attached to itself")
        if other.world is not self.world:
            raise WorldError(f"'{self.name}' and '{other.name}' are in different worlds")
        if other in self.attachments:
            return
        plink = self.get_link_id(parent_link) if parent_link else -1
        clink = other.get_link_id(child_link) if child_link else -1
        transform = _relative(self.get_link_position_and_orientation(plink), other.get_link_position_and_orientation(clink))
        att = Attachment(self, other, plink, clink, transform)
        self.attachments[other] = att
        other.attachments[self] = att
        self.world.mark_changed(self)
        self.world.mark_changed(other)
        self.world.attachment_event(self, other)

    def detach(self, other: Object) -> None:
        att = self.attachments.pop(other, None)
        if att is None:
            raise BadValue(f"'{self.name}' and '{other.name}' are not attached")
        other.attachments.pop(self, None)
        self.world.mark_changed(self)
        self.world.mark_changed(other)
        self.world.detachment_event(att.parent, att.child)

    def _after_move(self) -> None:
        """This object was moved on purpose: children follow; as a child, it keeps its new offset."""
        for other, att in list(self.attachments.items()):
            if att.child is self:
                transform = _relative(att.parent.get_link_position_and_orientation(att.parent_link),
                                      self.get_link_position_and_orientation(att.child_link))
                new = Attachment(att.parent, self, att.parent_link, att.child_link, transform)
                self.attachments[other] = new
                other.attachments[self] = new
                self.world.mark_changed(other)  # the parent's record of the attachment changed too
        self.move_attached()

    def move_attached(self) -> None:
        """Move every object attached to this one (and theirs, recursively) to its kept offset.

        Moving this object through the Object methods does this by itself; the world calls it
        after each simulation step, when PyBullet has moved the parent.
        """
        self._move_attached({self.id})

    def _move_attached(self, visited: set[int]) -> None:
        cid = self.world.client_id
        for child, att in list(self.attachments.items()):
            if att.parent is not self or child.id in visited:
                continue
            visited.add(child.id)
            target = compose(self.get_link_position_and_orientation(att.parent_link), att.transform)
            if att.child_link != -1:
                base_to_link = _relative(child.get_pose(), child.get_link_position_and_orientation(att.child_link))
                target = compose(target, invert(base_to_link))
            p.resetBaseVelocity(child.id, [0, 0, 0], [0, 0, 0], physicsClientId=cid)
            child._reset_base(target[0], target[1])  # (marks the child changed)
            child._move_attached(visited)

    def remove(self) -> None:
        """Take the object out of its world (detaching it from everything)."""
        for other in list(self.attachments):
            self.detach(other)
        p.removeBody(self.id, physicsClientId=self.world.client_id)
        self.world.unregister(self)

    def __repr__(self) -> str:
        return f"Object({self.name!r}, type={self.type!r}, id={self.id})"

    __hash__ = object.__hash__


def _box_in_frame(frame: tuple[Sequence[float], Sequence[float]],
                  boxes: Sequence[tuple[Sequence[float], Sequence[float]]]) -> tuple[Vec3, Vec3]:
    """The box, in `frame`, around the corners of world-aligned boxes."""
    inverse = invert(frame)
    corners = [compose(inverse, ((x, y, z), (0.0, 0.0, 0.0, 1.0)))[0]
               for lo, hi in boxes for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    lo = tuple(min(c[k] for c in corners) for k in range(3))
    hi = tuple(max(c[k] for c in corners) for k in range(3))
    return lo, hi  # type: ignore[return-value]


def _relative(a: tuple[Sequence[float], Sequence[float]], b: tuple[Sequence[float], Sequence[float]]) -> tuple[Vec3, Quat]:
    """Pose b expressed in frame a."""
    return compose(invert(a), b)


def _check_color(color: Sequence[float] | None, name: str) -> tuple[float, float, float, float] | None:
    if color is None:
        return None
    values = list(color)
    if len(values) not in (3, 4) or not all(isinstance(v, (int, float)) and 0 <= v <= 1 for v in values):
        raise ValueError(f"object '{name}' color: expected 3 or 4 numbers in 0..1 (r, g, b[, a]), got {values!r}")
    if len(values) == 3:
        values.append(1.0)
    return (float(values[0]), float(values[1]), float(values[2]), float(values[3]))


def _unknown(prefix: str, name: str, known: Iterable[str]) -> str:
    hint = did_you_mean(name, known)
    return f"{prefix} '{name}'" + (f" ({hint})" if hint else "")
