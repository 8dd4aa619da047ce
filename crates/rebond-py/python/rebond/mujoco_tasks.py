"""Gymnasium's MuJoCo tasks (v5) on rebond: ``rebond/HalfCheetah-v0``, ``rebond/Hopper-v0``,
``rebond/Walker2d-v0``, ``rebond/Ant-v0``, ``rebond/Humanoid-v0``, ``rebond/InvertedPendulum-v0``,
``rebond/InvertedDoublePendulum-v0`` and ``rebond/Reacher-v0``, registered when ``rebond.gym``
is imported.

Each loads Gymnasium's own MJCF file from the installed ``gymnasium`` package and keeps v5's
spaces, rewards, terminations, reset noise, ``frame_skip`` and episode length, with MuJoCo's
``qpos``/``qvel`` read from rebond: a free root is the root body's origin and rotation turned
back from rebond's Y-up frame to the file's Z-up frame, and each hinge or slide is the rebond
joint of the same name. Where v5 reads ``cfrc_ext``, ``cinert`` or ``cvel``, the nearest rebond
quantities stand in (see "MuJoCo tasks" in docs/python.md).
"""

from __future__ import annotations

import importlib.util
import os
import xml.etree.ElementTree as ElementTree
from typing import Any, Optional

import gymnasium
import numpy as np
from gymnasium import spaces

from ._rebond import Batch
from .gym import Pictures, VectorEnv

__all__ = ["TASKS", "MujocoTaskEnv", "MujocoTaskVectorEnv", "assets_folder"]

# The rotation C from MJCF's Z-up frame to rebond's Y-up frame, -90° about X: (x, y, z) becomes
# (x, z, -y). ``_TO_MJCF`` is C⁻¹ as a matrix; quaternions are (x, y, z, w).
_TO_MJCF = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
_HALF = np.sqrt(0.5)
_C = np.array([-_HALF, 0.0, 0.0, _HALF])
_C_INVERSE = np.array([_HALF, 0.0, 0.0, _HALF])

# Each task: v5's file, frame skip, episode length, reset noise scale and whether the root is a
# free joint (qpos starts with 7 numbers, observations skip x and y) or slides (skip x).
TASKS: dict[str, dict[str, Any]] = {
    "HalfCheetah": {"xml": "half_cheetah.xml", "frame_skip": 5, "steps": 1000, "noise": 0.1},
    "Hopper": {"xml": "hopper.xml", "frame_skip": 4, "steps": 1000, "noise": 5e-3},
    "Walker2d": {"xml": "walker2d_v5.xml", "frame_skip": 4, "steps": 1000, "noise": 5e-3},
    "Ant": {"xml": "ant.xml", "frame_skip": 5, "steps": 1000, "noise": 0.1},
    "Humanoid": {"xml": "humanoid.xml", "frame_skip": 5, "steps": 1000, "noise": 1e-2},
    "InvertedPendulum": {
        "xml": "inverted_pendulum.xml", "frame_skip": 2, "steps": 1000, "noise": 0.01,
    },
    "InvertedDoublePendulum": {
        "xml": "inverted_double_pendulum.xml", "frame_skip": 5, "steps": 1000, "noise": 0.1,
    },
    "Reacher": {"xml": "reacher.xml", "frame_skip": 2, "steps": 50, "noise": 0.1},
}


def assets_folder() -> str:
    """The folder of Gymnasium's MuJoCo model files in the installed ``gymnasium`` package,
    beside ``gymnasium.envs.mujoco``'s ``__file__``, found without importing that package (which
    imports ``mujoco``)."""
    spec = importlib.util.find_spec("gymnasium.envs.mujoco")
    if spec is None or spec.origin is None:
        raise FileNotFoundError("gymnasium.envs.mujoco: not in the installed gymnasium package")
    return os.path.join(os.path.dirname(spec.origin), "assets")


def _multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Quaternion products ``a b``, (x, y, z, w) on the last axis, broadcast."""
    av, aw = a[..., :3], a[..., 3:]
    bv, bw = b[..., :3], b[..., 3:]
    vector = aw * bv + bw * av + np.cross(av, bv)
    scalar = aw * bw - np.sum(av * bv, axis=-1, keepdims=True)
    return np.concatenate([vector, scalar], axis=-1)


def _rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``v`` turned by the unit quaternions ``q`` (x, y, z, w), broadcast:
    ``v + 2w (u × v) + 2 u × (u × v)``."""
    u, w = q[..., :3], q[..., 3:]
    twice = 2.0 * np.cross(u, v)
    return v + w * twice + np.cross(u, twice)


def _conjugate(q: np.ndarray) -> np.ndarray:
    """The inverse rotations of the unit quaternions ``q`` (x, y, z, w)."""
    return q * np.array([-1.0, -1.0, -1.0, 1.0])


class _Model:
    """What a task needs of its MJCF file, and MuJoCo's ``qpos``/``qvel`` read from and written
    to a ``Batch`` of it.

    ``qpos`` of a hinge or slide is rebond's ``joint_position`` plus the offset that makes it
    MuJoCo's ``qpos0`` (the joint's ``ref``) in the file's pose, where both engines start.
    """

    def __init__(self, path: str, batch: Batch) -> None:
        root = ElementTree.parse(path).getroot()
        compiler = root.find("compiler")
        degrees = compiler is None or compiler.get("angle", "degree") == "degree"
        self.free_root: Optional[str] = None
        coordinates: list[tuple[str, float]] = []
        # Each joint's passive damping (its own, or the top-level default's), which rebond's joint
        # force holds and MuJoCo's constraint force does not.
        default_joint = root.find("default/joint")
        default_damping = 0.0 if default_joint is None else float(default_joint.get("damping", "0"))
        dampings: list[float] = []
        self.sites: dict[str, tuple[str, np.ndarray]] = {}
        self.mujoco_bodies: list[str] = []
        # The importer's names (docs/mjcf.md): an unnamed body is `body<k>` (its MuJoCo body id,
        # from 1 in file order), an unnamed joint `<body>/joint<k>` (from 1 among its body's).
        for number, body in enumerate(root.iter("body"), start=1):
            name = body.get("name", f"body{number}")
            self.mujoco_bodies.append(name)
            joints = [element for element in body if element.tag in ("joint", "freejoint")]
            for place, element in enumerate(joints, start=1):
                joint_name = element.get("name", f"{name}/joint{place}")
                if element.tag == "freejoint" or element.get("type") == "free":
                    self.free_root = name
                    continue
                reference = float(element.get("ref", "0"))
                if element.get("type", "hinge") == "hinge" and degrees:
                    reference = np.radians(reference)
                coordinates.append((joint_name, reference))
                dampings.append(float(element.get("damping", default_damping)))
            for element in body:
                if element.tag == "site":
                    position = np.array(element.get("pos", "0 0 0").split(), dtype=float)
                    self.sites[element.get("name", "")] = (name, position)
        joint_names = batch.joint_names()
        body_names = batch.body_names()
        missing = [name for name, _ in coordinates if name not in joint_names]
        if missing:
            raise ValueError(f"{path}: the rebond scene has no joint named {missing}")
        self.joints = np.array([joint_names.index(name) for name, _ in coordinates], dtype=int)
        self.joint_names = [name for name, _ in coordinates]
        self.dampings = np.array(dampings)
        self.body_index = {name: index for index, name in enumerate(body_names)}
        # Actuated joints in actuator order, for qfrc_actuator.
        self.actuated: list[tuple[int, float]] = []
        actuators = root.find("actuator")
        for actuator in [] if actuators is None else list(actuators):
            gear = float(actuator.get("gear", "1").split()[0])
            joint = actuator.get("joint", "")
            place = self.joint_names.index(joint) if joint in self.joint_names else -1
            self.actuated.append((place, gear))
        start_joints = np.asarray(batch.joint_positions()[0], dtype=np.float64)
        self.start_joint_positions = start_joints
        references = np.array([reference for _, reference in coordinates])
        self.offsets = references - start_joints[self.joints]
        self.start_positions = np.asarray(batch.positions()[0], dtype=np.float64)
        self.start_rotations = np.asarray(batch.rotations()[0], dtype=np.float64)
        self.masses = np.asarray(batch.masses()[0], dtype=np.float64)
        self.dynamic = self.masses > 0
        self.root = None if self.free_root is None else self.body_index[self.free_root]
        self.sign = 1.0
        if self.root is not None:
            # Both q and -q give a rotation: keep the sign that reads MuJoCo's starting quaternion
            # with w >= 0, and keep it after, so that the reading is continuous.
            start = _multiply(_C_INVERSE, self.start_rotations[self.root])
            self.sign = -1.0 if start[3] < 0 else 1.0
        self.nq = len(coordinates) + (7 if self.root is not None else 0)
        self.nv = len(coordinates) + (6 if self.root is not None else 0)
        self.init_qpos = self.qpos(batch)[0]
        self.init_qvel = np.zeros(self.nv)

    def body(self, name: str) -> int:
        """The rebond index of the body named ``name`` in the file."""
        return self.body_index[name]

    def qpos(self, batch: Batch) -> np.ndarray:
        """MuJoCo's ``qpos`` of every world, (count, nq)."""
        joints = np.asarray(batch.joint_positions(), dtype=np.float64)[:, self.joints]
        joints = joints + self.offsets
        if self.root is None:
            return joints
        position = np.asarray(batch.positions()[:, self.root], dtype=np.float64)
        rotation = np.asarray(batch.rotations()[:, self.root], dtype=np.float64)
        rotation = self.sign * _multiply(_C_INVERSE, rotation)
        quaternion = np.concatenate([rotation[:, 3:], rotation[:, :3]], axis=1)
        return np.concatenate([position @ _TO_MJCF.T, quaternion, joints], axis=1)

    def qvel(self, batch: Batch) -> np.ndarray:
        """MuJoCo's ``qvel`` of every world, (count, nv): a free root's origin velocity in world
        axes and its angular velocity in its own axes, then the joint rates."""
        joints = np.asarray(batch.joint_velocities(), dtype=np.float64)[:, self.joints]
        if self.root is None:
            return joints
        position = np.asarray(batch.positions()[:, self.root], dtype=np.float64)
        rotation = np.asarray(batch.rotations()[:, self.root], dtype=np.float64)
        center = np.asarray(batch.centers_of_mass()[:, self.root], dtype=np.float64)
        linear = np.asarray(batch.linear_velocities()[:, self.root], dtype=np.float64)
        angular = np.asarray(batch.angular_velocities()[:, self.root], dtype=np.float64)
        origin = linear + np.cross(angular, position - center)
        local = _rotate(_conjugate(rotation), angular)
        return np.concatenate([origin @ _TO_MJCF.T, local, joints], axis=1)

    def set_state(
        self, batch: Batch, indices: np.ndarray, qpos: np.ndarray, qvel: np.ndarray
    ) -> None:
        """Puts the worlds at ``indices`` back in the start, then in MuJoCo's state ``qpos``,
        ``qvel`` (one row per index) through ``Batch.reset``."""
        count = len(indices)
        joint_positions = np.tile(self.start_joint_positions, (count, 1))
        joint_positions[:, self.joints] = qpos[:, -len(self.joints) :] - self.offsets
        joint_velocities = np.where(np.isnan(joint_positions), np.nan, 0.0)
        joint_velocities[:, self.joints] = qvel[:, -len(self.joints) :]
        if self.root is None:
            batch.reset(
                indices, joint_positions=joint_positions, joint_velocities=joint_velocities
            )
            return
        # The root's new pose in rebond's frame, and the whole model carried there rigidly.
        root_position = qpos[:, 0:3] @ _TO_MJCF
        quaternion = qpos[:, 3:7] / np.linalg.norm(qpos[:, 3:7], axis=1, keepdims=True)
        root_rotation = _multiply(_C, np.concatenate([quaternion[:, 1:], quaternion[:, :1]], 1))
        turn = _multiply(root_rotation, _conjugate(self.start_rotations[self.root]))
        offsets = self.start_positions - self.start_positions[self.root]
        positions = root_position[:, None, :] + _rotate(turn[:, None, :], offsets[None])
        rotations = _multiply(turn[:, None, :], self.start_rotations[None])
        positions[:, ~self.dynamic] = self.start_positions[~self.dynamic]
        rotations[:, ~self.dynamic] = self.start_rotations[~self.dynamic]
        batch.reset(
            indices, positions=positions, rotations=rotations, joint_positions=joint_positions
        )
        # The velocities, once the joints have placed the bodies: every body moves rigidly with
        # the root (welded bodies keep that), then the joint rates are set along the tree.
        positions = np.asarray(batch.positions()[indices], dtype=np.float64)
        rotations = np.asarray(batch.rotations()[indices], dtype=np.float64)
        centers = np.asarray(batch.centers_of_mass()[indices], dtype=np.float64)
        spin = _rotate(root_rotation, qvel[:, 3:6])
        origin = qvel[:, 0:3] @ _TO_MJCF
        arms = centers - positions[:, self.root][:, None, :]
        linear = origin[:, None, :] + np.cross(spin[:, None, :], arms)
        angular = np.repeat(spin[:, None, :], len(self.masses), axis=1)
        linear[:, ~self.dynamic] = 0.0
        angular[:, ~self.dynamic] = 0.0
        batch.reset(
            indices,
            positions=positions,
            rotations=rotations,
            linear_velocities=linear,
            angular_velocities=angular,
            joint_velocities=joint_velocities,
        )

    def body_origins(self, batch: Batch, name: str) -> np.ndarray:
        """MuJoCo's ``xpos`` of the body ``name`` in every world, (count, 3)."""
        return np.asarray(batch.positions()[:, self.body(name)], dtype=np.float64) @ _TO_MJCF.T

    def site(self, batch: Batch, name: str) -> np.ndarray:
        """MuJoCo's ``site_xpos`` of the site ``name`` in every world, (count, 3)."""
        body, local = self.sites[name]
        index = self.body(body)
        position = np.asarray(batch.positions()[:, index], dtype=np.float64)
        rotation = np.asarray(batch.rotations()[:, index], dtype=np.float64)
        return (position + _rotate(rotation, local)) @ _TO_MJCF.T

    def mujoco_body_indices(self) -> np.ndarray:
        """The rebond index of each of MuJoCo's bodies but the world, in MuJoCo's order."""
        return np.array([self.body(name) for name in self.mujoco_bodies], dtype=int)

    def com_based(self, batch: Batch) -> dict[str, np.ndarray]:
        """The nearest rebond readings of MuJoCo's ``cinert``, ``cvel`` and ``cfrc_ext`` of
        MuJoCo's bodies but the world, each (count, bodies, 10 or 6), in the file's axes about
        the centre of mass of MuJoCo's bodies (MuJoCo's "com-based" frame):

        - ``cinert``: inertia about that point (xx, yy, zz, xy, xz, yz: each body's own inertia
          shifted by ``m (|r|² E − r rᵀ)``), ``m r``, ``m``; with ``r`` the body's centre of
          mass from that point;
        - ``cvel``: angular velocity, then the velocity of the body's point at that point;
        - ``cfrc_ext``: the torque of the body's contact force as if it acted at the body's
          centre of mass (rebond sums contact forces per body, not their points), then the
          force.
        """
        bodies = self.mujoco_body_indices()
        masses = self.masses[bodies]
        whole = self.mass_center(batch)
        centers = np.asarray(batch.centers_of_mass()[:, bodies], dtype=np.float64) @ _TO_MJCF.T
        r = centers - whole[:, None, :]
        inertia = np.asarray(batch.inertias()[:, bodies], dtype=np.float64)
        xx, yy, zz, xy, xz, yz = np.moveaxis(inertia, -1, 0)
        tensor = np.stack(
            [np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1), np.stack([xz, yz, zz], -1)],
            -2,
        )
        tensor = _TO_MJCF @ tensor @ _TO_MJCF.T
        shift = np.einsum("nbi,nbj->nbij", r, r)
        eye = np.eye(3) * np.sum(r * r, axis=-1)[..., None, None]
        tensor = tensor + masses[None, :, None, None] * (eye - shift)
        six = tensor[..., [0, 1, 2, 0, 0, 1], [0, 1, 2, 1, 2, 2]]
        weights = np.broadcast_to(masses[None, :, None], r.shape[:2] + (1,))
        cinert = np.concatenate([six, masses[None, :, None] * r, weights], axis=-1)
        angular = np.asarray(batch.angular_velocities()[:, bodies], dtype=np.float64) @ _TO_MJCF.T
        linear = np.asarray(batch.linear_velocities()[:, bodies], dtype=np.float64) @ _TO_MJCF.T
        cvel = np.concatenate([angular, linear - np.cross(angular, r)], axis=-1)
        force = np.asarray(batch.contact_forces()[:, bodies], dtype=np.float64) @ _TO_MJCF.T
        cfrc_ext = np.concatenate([np.cross(r, force), force], axis=-1)
        return {"cinert": cinert, "cvel": cvel, "cfrc_ext": cfrc_ext}

    def mass_center(self, batch: Batch) -> np.ndarray:
        """The centre of mass of MuJoCo's bodies in the file's axes, (count, 3) (Humanoid's
        ``mass_center``, the origin of MuJoCo's com-based frame); the importer's light link
        bodies, which MuJoCo has not, are left out."""
        bodies = self.mujoco_body_indices()
        masses = self.masses[bodies]
        centers = np.asarray(batch.centers_of_mass()[:, bodies], dtype=np.float64)
        whole = np.einsum("b,nbk->nk", masses, centers) / np.sum(masses)
        return whole @ _TO_MJCF.T

    def actuator_forces(self, controls: np.ndarray, ctrl_range: np.ndarray) -> np.ndarray:
        """MuJoCo's ``qfrc_actuator`` of the hinges and slides, (count, joints): each motor's
        ``gear · clamp(u)`` on its joint."""
        forces = np.zeros((len(controls), len(self.joints)))
        clamped = np.clip(controls, ctrl_range[:, 0], ctrl_range[:, 1])
        for column, (place, gear) in enumerate(self.actuated):
            if place >= 0:
                forces[:, place] += gear * clamped[:, column]
        return forces


class MujocoTaskVectorEnv(VectorEnv):
    """One of Gymnasium's MuJoCo tasks (``task``, a key of ``TASKS``) on ``num_envs`` worlds of
    a ``rebond.Batch``: v5's observations, actions, rewards, terminations and resets.

    ``reset_noise_scale`` overrides v5's (0 starts every episode exactly in the file's pose);
    ``max_episode_steps`` is v5's unless given (``None``: never truncate).
    """

    def __init__(
        self,
        task: str,
        num_envs: int = 1,
        *,
        max_episode_steps: Optional[int] = -1,
        reset_noise_scale: Optional[float] = None,
        render_mode: Optional[str] = None,
    ) -> None:
        if task not in TASKS:
            raise ValueError(f"task: {task!r} is not one of {sorted(TASKS)}")
        spec = TASKS[task]
        self.task = task
        self.path = os.path.join(assets_folder(), spec["xml"])
        self.noise = spec["noise"] if reset_noise_scale is None else reset_noise_scale
        first = Batch(self.path, 1)
        self.model = _Model(self.path, first)
        # v5's action space: a box of each actuator's control range.
        ranges = np.asarray(first.ctrl_ranges(), dtype=np.float32)
        action_space = spaces.Box(low=ranges[:, 0], high=ranges[:, 1], dtype=np.float32)
        self.controls: Optional[np.ndarray] = None
        self._before: Optional[np.ndarray] = None
        self._info: dict[str, np.ndarray] = {}
        super().__init__(
            self.path,
            num_envs,
            action_space=action_space,
            observation_space=None,
            max_episode_steps=spec["steps"] if max_episode_steps == -1 else max_episode_steps,
            frame_skip=spec["frame_skip"],
            render_mode=render_mode,
        )
        self.dt = self.batch.timestep * self.frame_skip
        self.metadata = dict(self.metadata, render_fps=int(np.round(1.0 / self.dt)))

    # The task, as VectorEnv calls it.

    def act(self, actions: np.ndarray) -> None:
        """The actions as the actuators' controls (``Batch.set_controls``), kept for
        Humanoid's ``qfrc_actuator``."""
        self.controls = np.asarray(actions, dtype=np.float64)
        self.batch.set_controls(actions)

    def _advance(self, actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
        """``VectorEnv._advance``, keeping the tracked positions from before the frames for the
        forward reward."""
        self._before = self._tracked()
        return super()._advance(actions)

    def _tracked(self) -> np.ndarray:
        """The positions whose rate is the forward reward: qpos[0] (x, y of the root for Ant,
        the centre of mass for Humanoid)."""
        if self.task == "Humanoid":
            return self.model.mass_center(self.batch)[:, :2]
        if self.task == "Ant":
            return self.model.qpos(self.batch)[:, :2]
        return self.model.qpos(self.batch)[:, :1]

    def observe(self) -> np.ndarray:
        """v5's observation of every world, (num_envs, size), float64."""
        qpos, qvel = self.model.qpos(self.batch), self.model.qvel(self.batch)
        task = self.task
        if task == "HalfCheetah":
            return np.concatenate([qpos[:, 1:], qvel], axis=1)
        if task in ("Hopper", "Walker2d"):
            return np.concatenate([qpos[:, 1:], np.clip(qvel, -10, 10)], axis=1)
        if task == "Ant":
            forces = self.model.com_based(self.batch)["cfrc_ext"]
            forces = np.clip(forces, -1.0, 1.0).reshape(len(qpos), -1)
            return np.concatenate([qpos[:, 2:], qvel, forces], axis=1)
        if task == "Humanoid":
            com = self.model.com_based(self.batch)
            count = len(qpos)
            return np.concatenate(
                [
                    qpos[:, 2:],
                    qvel,
                    com["cinert"].reshape(count, -1),
                    com["cvel"].reshape(count, -1),
                    self._actuator_forces(),
                    com["cfrc_ext"].reshape(count, -1),
                ],
                axis=1,
            )
        if task == "InvertedPendulum":
            return np.concatenate([qpos, qvel], axis=1)
        if task == "InvertedDoublePendulum":
            # The slider's force on the cart along the rail is its limit's, its motor's and its
            # damping's `-d v`: MuJoCo's constraint force is the limit's alone.
            column = self.model.joint_names.index("slider")
            slider = self.model.joints[column]
            force = np.asarray(self.batch.joint_forces()[:, slider], dtype=np.float64)
            passive = -self.model.dampings[column] * qvel[:, column]
            along = (force @ _TO_MJCF.T)[:, 0] - self._actuator_forces()[:, column] - passive
            constraint = along[:, None]
            return np.concatenate(
                [
                    qpos[:, :1],
                    np.sin(qpos[:, 1:]),
                    np.cos(qpos[:, 1:]),
                    np.clip(qvel, -10, 10),
                    np.clip(constraint, -10, 10),
                ],
                axis=1,
            )
        # Reacher.
        tip = self.model.body_origins(self.batch, "fingertip")
        target = self.model.body_origins(self.batch, "target")
        return np.concatenate(
            [np.cos(qpos[:, :2]), np.sin(qpos[:, :2]), qpos[:, 2:], qvel[:, :2], (tip - target)[:, :2]],
            axis=1,
        )

    def _actuator_forces(self) -> np.ndarray:
        """MuJoCo's ``qfrc_actuator`` of the hinges and slides from the controls last set
        (zero before any), (num_envs, joints)."""
        controls = self.controls
        if controls is None:
            controls = np.zeros((self.num_envs, self.single_action_space.shape[0]))
        space = self.single_action_space
        ranges = np.stack([space.low, space.high], axis=1).astype(np.float64)
        return self.model.actuator_forces(controls, ranges)

    def reward(self, actions: np.ndarray, observations: np.ndarray) -> np.ndarray:
        """v5's reward of every world, its terms kept for ``info``."""
        actions = np.asarray(actions, dtype=np.float64)
        square = np.sum(np.square(actions), axis=1)
        qpos = self.model.qpos(self.batch)
        task = self.task
        info: dict[str, np.ndarray] = {}
        if task in ("HalfCheetah", "Hopper", "Walker2d", "Ant", "Humanoid"):
            assert self._before is not None
            velocity = (self._tracked() - self._before) / self.dt
            weights = {"HalfCheetah": (1.0, 0.1), "Hopper": (1.0, 1e-3), "Walker2d": (1.0, 1e-3),
                       "Ant": (1.0, 0.5), "Humanoid": (1.25, 0.1)}
            forward_weight, ctrl_weight = weights[task]
            forward = forward_weight * velocity[:, 0]
            ctrl = ctrl_weight * square
            reward = forward - ctrl
            info = {"x_position": qpos[:, 0], "x_velocity": velocity[:, 0],
                    "reward_forward": forward, "reward_ctrl": -ctrl}
            if task != "HalfCheetah":
                survive = {"Hopper": 1.0, "Walker2d": 1.0, "Ant": 1.0, "Humanoid": 5.0}[task]
                healthy = survive * self._healthy(qpos)
                reward = reward + healthy
                info["reward_survive"] = healthy
            if task in ("Ant", "Humanoid"):
                forces = self.model.com_based(self.batch)["cfrc_ext"]
                if task == "Ant":
                    contact = 5e-4 * np.sum(np.square(np.clip(forces, -1, 1)), axis=(1, 2))
                else:
                    contact = np.minimum(5e-7 * np.sum(np.square(forces), axis=(1, 2)), 10.0)
                reward = reward - contact
                info["reward_contact"] = -contact
                info["y_position"] = qpos[:, 1]
                info["y_velocity"] = velocity[:, 1]
        elif task == "InvertedPendulum":
            reward = (~self._pendulum_fell(observations)).astype(np.float64)
            info = {"reward_survive": reward}
        elif task == "InvertedDoublePendulum":
            tip = self.model.site(self.batch, "tip")
            x, y = tip[:, 0], tip[:, 2]
            qvel = self.model.qvel(self.batch)
            distance = 0.01 * x**2 + (y - 2) ** 2
            velocity = 1e-3 * qvel[:, 1] ** 2 + 5e-3 * qvel[:, 2] ** 2
            alive = 10.0 * (y > 1)
            reward = alive - distance - velocity
            info = {"reward_survive": alive, "distance_penalty": -distance,
                    "velocity_penalty": -velocity}
        else:
            tip = self.model.body_origins(self.batch, "fingertip")
            target = self.model.body_origins(self.batch, "target")
            distance = -np.linalg.norm(tip - target, axis=1)
            ctrl = -square
            reward = distance + ctrl
            info = {"reward_dist": distance, "reward_ctrl": ctrl}
        self._info = info
        return reward

    def _healthy(self, qpos: np.ndarray) -> np.ndarray:
        """v5's ``is_healthy`` of every world."""
        qvel = self.model.qvel(self.batch)
        if self.task == "Hopper":
            state = np.concatenate([qpos, qvel], axis=1)[:, 2:]
            return (
                np.all((-100 < state) & (state < 100), axis=1)
                & (0.7 < qpos[:, 1])
                & (-0.2 < qpos[:, 2])
                & (qpos[:, 2] < 0.2)
            )
        if self.task == "Walker2d":
            return (0.8 < qpos[:, 1]) & (qpos[:, 1] < 2.0) & (-1 < qpos[:, 2]) & (qpos[:, 2] < 1)
        if self.task == "Ant":
            finite = np.all(np.isfinite(np.concatenate([qpos, qvel], axis=1)), axis=1)
            return finite & (0.2 <= qpos[:, 2]) & (qpos[:, 2] <= 1.0)
        return (1.0 < qpos[:, 2]) & (qpos[:, 2] < 2.0)

    @staticmethod
    def _pendulum_fell(observations: np.ndarray) -> np.ndarray:
        """InvertedPendulum v5's end: an observation not finite or the pole beyond 0.2 rad."""
        return ~np.all(np.isfinite(observations), axis=1) | (np.abs(observations[:, 1]) > 0.2)

    def terminated(self, observations: np.ndarray) -> np.ndarray:
        """v5's termination: unhealthy, a fallen pole, or never (HalfCheetah, Reacher)."""
        if self.task in ("Hopper", "Walker2d", "Ant", "Humanoid"):
            return ~self._healthy(self.model.qpos(self.batch))
        if self.task == "InvertedPendulum":
            return self._pendulum_fell(observations)
        if self.task == "InvertedDoublePendulum":
            return self.model.site(self.batch, "tip")[:, 2] <= 1
        return np.zeros(self.num_envs, dtype=bool)

    def info(self, observations: np.ndarray) -> dict:
        """v5's ``info`` terms of the step (``x_position``, ``reward_forward``, ...)."""
        return self._info

    def reset_noise(self, indices: np.ndarray) -> None:
        """v5's ``reset_model``: init_qpos and init_qvel plus noise of ``reset_noise_scale``,
        uniform, or normal for qvel where v5 draws it so (HalfCheetah, Ant,
        InvertedDoublePendulum). Reacher: the arm's angles within ±scale (v5: ±0.1), its rates
        within ±scale / 20 (v5: ±0.005), and the goal drawn in a disc of 0.2 m."""
        indices = np.asarray(indices)
        model, rng, scale, count = self.model, self.np_random, self.noise, len(indices)
        if self.task == "Reacher":
            qpos = model.init_qpos + rng.uniform(-scale, scale, size=(count, model.nq))
            for row in range(count):
                while True:
                    goal = rng.uniform(-0.2, 0.2, size=2)
                    if np.linalg.norm(goal) < 0.2:
                        break
                qpos[row, -2:] = goal
            qvel = model.init_qvel + rng.uniform(-0.05 * scale, 0.05 * scale, (count, model.nv))
            qvel[:, -2:] = 0.0
        else:
            qpos = model.init_qpos + rng.uniform(-scale, scale, size=(count, model.nq))
            if self.task in ("HalfCheetah", "Ant", "InvertedDoublePendulum"):
                qvel = model.init_qvel + scale * rng.standard_normal((count, model.nv))
            else:
                qvel = model.init_qvel + rng.uniform(-scale, scale, size=(count, model.nv))
        model.set_state(self.batch, indices, qpos, qvel)
        if self.controls is not None:
            self.controls[indices] = 0.0


class MujocoTaskEnv(gymnasium.Env):
    """One of Gymnasium's MuJoCo tasks on one rebond world (``gymnasium.make``): the same task
    as ``MujocoTaskVectorEnv`` with one environment, without automatic resets."""

    metadata: dict[str, Any] = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self,
        task: str,
        *,
        reset_noise_scale: Optional[float] = None,
        render_mode: Optional[str] = None,
        render_size: tuple[int, int] = (320, 240),
    ) -> None:
        self._vector = MujocoTaskVectorEnv(
            task, 1, max_episode_steps=None, reset_noise_scale=reset_noise_scale
        )
        self.task = task
        self.dt = self._vector.dt
        self.frame_skip = self._vector.frame_skip
        self.metadata = dict(self.metadata, render_fps=self._vector.metadata["render_fps"])
        self.action_space = self._vector.single_action_space
        self.observation_space = self._vector.single_observation_space
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode: {render_mode!r} is not one of ['rgb_array']")
        self.render_mode = render_mode
        self._pictures = Pictures(*render_size)

    @property
    def batch(self) -> Batch:
        """The one-world batch stepped."""
        return self._vector.batch

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[dict] = None
    ) -> tuple[np.ndarray, dict]:
        """A new episode from init_qpos and init_qvel plus v5's noise, drawn from the
        generator ``seed`` seeds."""
        super().reset(seed=seed)
        self._vector.np_random = self.np_random
        self._vector._restart(np.arange(1))
        observation = self._vector._observations()[0]
        qpos = self._vector.model.qpos(self.batch)[0]
        return observation, {"x_position": float(qpos[0])}

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict]:
        """``frame_skip`` steps with ``action`` as the controls; never truncates (``make``
        adds v5's TimeLimit)."""
        actions = np.asarray(action, dtype=np.float32).reshape(1, -1)
        observations, rewards, terminated, info = self._vector._advance(actions)
        info = {key: float(value[0]) for key, value in info.items()}
        return observations[0], float(rewards[0]), bool(terminated[0]), False, info

    def render(self) -> Optional[np.ndarray]:
        """A ``(height, width, 3)`` ``uint8`` picture for ``render_mode="rgb_array"``."""
        if self.render_mode is None:
            return None
        return self._pictures.of_world(self.batch.world(0))


def _register() -> None:
    """Registers every task as ``rebond/<Task>-v0``, with v5's episode length."""
    for task, spec in TASKS.items():
        env_id = f"rebond/{task}-v0"
        if env_id in gymnasium.registry:
            continue
        gymnasium.register(
            id=env_id,
            entry_point="rebond.mujoco_tasks:MujocoTaskEnv",
            vector_entry_point="rebond.mujoco_tasks:MujocoTaskVectorEnv",
            max_episode_steps=spec["steps"],
            kwargs={"task": task},
        )


_register()
