"""Typed stubs of the native module; everything here is re-exported by ``rebond``."""

import os
from typing import Any, Iterable, Literal, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

Vector = Union[Sequence[float], npt.ArrayLike]
Scene = Union[str, "os.PathLike[str]", Mapping[str, Any], "World"]
BodyRef = Union[str, int]
FloatArray = npt.NDArray[np.float32]

class SceneError(ValueError):
    """A scene, body or joint that is not valid; the message names the place of the bad value."""

class StateError(ValueError):
    """Bytes that are not a world saved by ``World.save`` of this build: the message says why."""

class StepError(RuntimeError):
    """The engine refused to step: ``step N failed: ...``, as the command line says."""

class RayHit:
    """Where a ray met a body."""

    @property
    def body(self) -> int:
        """The body's index in scene order."""
    @property
    def name(self) -> str:
        """The body's name."""
    @property
    def point(self) -> list[float]:
        """The point hit, world, m."""
    @property
    def normal(self) -> list[float]:
        """The unit normal there, facing the ray."""
    @property
    def distance(self) -> float:
        """Distance from the ray's origin, m."""

class World:
    """A simulated world: bodies, joints, and the scene's timestep."""

    def __init__(
        self,
        gravity: Optional[Vector] = None,
        timestep: Optional[float] = None,
        substeps: Optional[int] = None,
    ) -> None:
        """An empty world; defaults as in a scene file ((0, -9.81, 0), 1/60 s, 8)."""
    @staticmethod
    def from_scene(scene: Scene) -> "World":
        """The world of a scene file (path), a built-in scene's name, or a dict."""
    def add_body(
        self,
        shape: Mapping[str, Any],
        *,
        name: Optional[str] = ...,
        type: Literal["dynamic", "static", "kinematic"] = ...,
        position: Vector = ...,
        rotation: Vector = ...,
        linear_velocity: Vector = ...,
        angular_velocity: Vector = ...,
        density: float = ...,
        mass: float = ...,
        friction: float = ...,
        restitution: float = ...,
        rolling_resistance: float = ...,
        force: Vector = ...,
        force_point: Vector = ...,
        torque: Vector = ...,
        linear_damping: float = ...,
        angular_damping: float = ...,
        can_sleep: bool = ...,
        sensor: bool = ...,
        collision_groups: Mapping[str, int] = ...,
    ) -> int:
        """Adds a body (the fields of a scene body); returns its index."""
    def add_joint(
        self,
        type: Literal["fixed", "ball", "revolute", "prismatic", "distance"],
        *,
        body_b: BodyRef,
        body_a: Optional[BodyRef] = ...,
        name: Optional[str] = ...,
        anchor: Vector = ...,
        anchor_b: Vector = ...,
        axis: Vector = ...,
        limits: Sequence[float] = ...,
        swing_limit: float = ...,
        twist_limits: Sequence[float] = ...,
        motor: Mapping[str, float] = ...,
        length: float = ...,
        spring: Mapping[str, float] = ...,
        collide_connected: bool = ...,
        friction: float = ...,
        break_force: float = ...,
        break_torque: float = ...,
    ) -> int:
        """Adds a joint (the fields of a scene joint, bodies by name or index); returns its index."""
    def step(self, n: int = 1) -> None:
        """Advances the world by ``n`` steps, without the GIL."""
    def copy(self) -> "World":
        """A copy that steps on exactly as this world would."""
    def save(self) -> bytes:
        """The whole world as bytes, which ``World.load`` restores exactly."""
    @staticmethod
    def load(data: bytes) -> "World":
        """A world saved by ``save`` (or ``rebond run --save-state``); raises ``StateError``."""
    @property
    def timestep(self) -> float:
        """Seconds per step."""
    @property
    def body_count(self) -> int:
        """Number of bodies."""
    def __len__(self) -> int: ...
    def body_names(self) -> list[str]:
        """Body names in scene order, the order of every array."""
    def joint_names(self) -> list[str]:
        """Joint names in scene order."""
    def motor_names(self) -> list[str]:
        """Names of the joints with a motor, the order of ``set_motor_targets``."""
    def positions(self) -> FloatArray:
        """Body origins, m: (bodies, 3)."""
    def rotations(self) -> FloatArray:
        """Rotations as quaternions (x, y, z, w): (bodies, 4)."""
    def linear_velocities(self) -> FloatArray:
        """Velocities of the centres of mass, m/s: (bodies, 3)."""
    def angular_velocities(self) -> FloatArray:
        """Angular velocities, rad/s: (bodies, 3)."""
    def centers_of_mass(self) -> FloatArray:
        """Centres of mass, m: (bodies, 3)."""
    def inertias(self) -> FloatArray:
        """Inertias about the centres of mass in world axes, kg·m², ``R I Rᵀ`` as xx, yy, zz,
        xy, xz, yz: (bodies, 6); zeros for static and kinematic bodies."""
    def actuator_names(self) -> list[str]:
        """Actuator names in scene order, the order of ``set_controls``."""
    def ctrl_ranges(self) -> FloatArray:
        """Each actuator's control range ``[lo, hi]``: (actuators, 2); ``[-inf, inf]`` if none."""
    def set_controls(self, u: npt.ArrayLike) -> None:
        """Sets every actuator's control (actuators,), clamped to its range: a ``motor`` gives
        its joint ``gear * u``, a ``position`` actuator a position motor towards ``u / gear``, a
        ``velocity`` actuator a velocity motor towards ``u / gear``."""
    def set_linear_velocities(self, a: npt.ArrayLike) -> None:
        """Sets every body's linear velocity, m/s: (bodies, 3)."""
    def set_angular_velocities(self, a: npt.ArrayLike) -> None:
        """Sets every body's angular velocity, rad/s: (bodies, 3)."""
    def apply_forces(self, a: npt.ArrayLike, points: Optional[npt.ArrayLike] = None) -> None:
        """Adds forces, N, (bodies, 3), at the centres of mass or at world ``points`` (bodies, 3),
        acting on every step of the next ``step(n)``."""
    def set_motor_targets(self, a: npt.ArrayLike) -> None:
        """Sets each motor's target velocity or position: (motors,)."""
    def ray_cast(
        self, origin: Vector, direction: Vector, max_distance: float = ...
    ) -> Optional[RayHit]:
        """The nearest body the ray meets within ``max_distance`` m, or ``None``."""
    def apply_torques(self, a: npt.ArrayLike) -> None:
        """Adds torques, N·m, world axes, (bodies, 3), for every step of the next ``step(n)``."""
    def masses(self) -> FloatArray:
        """Body masses, kg, (bodies,); 0 for static and kinematic bodies."""
    def frictions(self) -> FloatArray:
        """Body friction coefficients, (bodies,)."""
    def restitutions(self) -> FloatArray:
        """Body restitutions, (bodies,)."""
    def set_masses(self, a: npt.ArrayLike) -> None:
        """Sets dynamic bodies' masses, kg, (bodies,); inertia scales with the mass."""
    def set_frictions(self, a: npt.ArrayLike) -> None:
        """Sets body friction coefficients (>= 0), (bodies,)."""
    def set_restitutions(self, a: npt.ArrayLike) -> None:
        """Sets body restitutions (0 to 1), (bodies,)."""
    def gravity(self) -> FloatArray:
        """The world's gravity, m/s², (3,)."""
    def set_gravity(self, a: npt.ArrayLike) -> None:
        """Sets the world's gravity, m/s², (3,)."""
    def motor_gains(self) -> FloatArray:
        """Stiffness and damping of every motor, (motors, 2); zeros unless a position motor."""
    def set_motor_gains(self, stiffness: npt.ArrayLike, damping: npt.ArrayLike) -> None:
        """Sets the stiffness and damping of position motors, (motors,) each."""
    def contact_forces(self) -> FloatArray:
        """Contact force on each body over the last step, N, (bodies, 3)."""
    def joint_forces(self) -> FloatArray:
        """Force of each joint on its ``body_b`` over the last step, N, (joints, 3)."""
    def joint_torques(self) -> FloatArray:
        """Torque of each joint on its ``body_b`` over the last step, N·m, (joints, 3)."""
    def contact_events(self) -> list[tuple[Literal["started", "stopped"], int, int]]:
        """``(kind, body_a, body_b)`` of every step of the last ``step(n)``."""
    def sensor_events(self) -> list[tuple[Literal["entered", "exited"], int, int]]:
        """``(kind, sensor, body)`` of every step of the last ``step(n)``."""
    def ray_casts(
        self, origins: npt.ArrayLike, directions: npt.ArrayLike, max_distance: float = ...
    ) -> FloatArray:
        """Distances along rays (rays, 3) to the nearest body, m, (rays,); inf for a miss."""
    def ray_hits(
        self, origins: npt.ArrayLike, directions: npt.ArrayLike, max_distance: float = ...
    ) -> tuple[FloatArray, npt.NDArray[np.int64], FloatArray]:
        """Distances (rays,), body indices (rays,) (-1 for a miss) and normals (rays, 3)."""
    def render(
        self, width: int, height: int, camera: Optional[Mapping[str, Any]] = None
    ) -> npt.NDArray[np.uint8]:
        """The world drawn on the CPU: uint8 (height, width, 3), top row first. ``camera``: a
        dict of ``position``, ``target`` (m), ``fov`` (degrees, default 45), ``up``; fields
        left out are the default camera's, which frames the moving bodies."""
    def render_camera(
        self, width: int, height: int, camera: Optional[Mapping[str, Any]] = None
    ) -> dict[str, Any]:
        """The camera ``render`` draws with, every field filled in."""
    def set_positions(self, a: npt.ArrayLike) -> None:
        """Teleports every body's origin, m: (bodies, 3); the bodies wake."""
    def set_rotations(self, a: npt.ArrayLike) -> None:
        """Turns each body about its origin to a quaternion x, y, z, w, normalised: (bodies, 4)."""
    def joint_positions(self) -> FloatArray:
        """Joint coordinates in ``joint_names()`` order, rad or m: (joints,); NaN: fixed, ball."""
    def joint_velocities(self) -> FloatArray:
        """Their rates, rad/s or m/s: (joints,); NaN for fixed and ball joints."""
    def set_joint_positions(self, a: npt.ArrayLike) -> None:
        """Places bodies along each joint tree so the joints read ``a``: (joints,), NaN at fixed
        and ball joints."""
    def set_joint_velocities(self, a: npt.ArrayLike) -> None:
        """Sets velocities along each joint tree so the rates read ``a``: (joints,)."""
    def rollout(self, controls: npt.ArrayLike) -> dict[str, FloatArray]:
        """For each t of controls (T, motors): set_motor_targets then step(1); states (T, ...)."""

class Batch:
    """``count`` copies of one world, stepped in parallel on every core without the GIL."""

    def __init__(self, scene: Scene, count: int) -> None:
        """Copies of a scene file (path), a built-in scene, a dict, or a ``World``."""
    @property
    def count(self) -> int:
        """Number of worlds."""
    @property
    def timestep(self) -> float:
        """Seconds per step."""
    @property
    def body_count(self) -> int:
        """Number of bodies in each world."""
    def __len__(self) -> int: ...
    def body_names(self) -> list[str]: ...
    def joint_names(self) -> list[str]: ...
    def motor_names(self) -> list[str]: ...
    def step(self, n: int = 1) -> None:
        """Advances every world by ``n`` steps, in parallel, without the GIL."""
    def reset(
        self,
        indices: Optional[Union[int, Iterable[int]]] = None,
        *,
        positions: Optional[npt.ArrayLike] = None,
        rotations: Optional[npt.ArrayLike] = None,
        linear_velocities: Optional[npt.ArrayLike] = None,
        angular_velocities: Optional[npt.ArrayLike] = None,
        joint_positions: Optional[npt.ArrayLike] = None,
        joint_velocities: Optional[npt.ArrayLike] = None,
    ) -> None:
        """Puts the worlds at ``indices`` (all when ``None``) back in their starting state, then
        sets the states given, each ``(len(indices), ...)``."""
    def world(self, index: int) -> World:
        """A copy of one world of the batch."""
    def positions(self) -> FloatArray:
        """(count, bodies, 3)."""
    def rotations(self) -> FloatArray:
        """(count, bodies, 4), x, y, z, w."""
    def linear_velocities(self) -> FloatArray:
        """(count, bodies, 3)."""
    def angular_velocities(self) -> FloatArray:
        """(count, bodies, 3)."""
    def centers_of_mass(self) -> FloatArray:
        """(count, bodies, 3)."""
    def inertias(self) -> FloatArray:
        """(count, bodies, 6): xx, yy, zz, xy, xz, yz in world axes."""
    def actuator_names(self) -> list[str]: ...
    def ctrl_ranges(self) -> FloatArray:
        """(actuators, 2), the same in every world."""
    def set_controls(self, u: npt.ArrayLike) -> None:
        """(count, actuators), each world as ``World.set_controls``."""
    def set_linear_velocities(self, a: npt.ArrayLike) -> None:
        """(count, bodies, 3)."""
    def set_angular_velocities(self, a: npt.ArrayLike) -> None:
        """(count, bodies, 3)."""
    def apply_forces(self, a: npt.ArrayLike, points: Optional[npt.ArrayLike] = None) -> None:
        """(count, bodies, 3), with ``points`` (count, bodies, 3); for every step of the next
        ``step(n)``."""
    def set_motor_targets(self, a: npt.ArrayLike) -> None:
        """(count, motors)."""
    def apply_torques(self, a: npt.ArrayLike) -> None:
        """(count, bodies, 3), N·m, for every step of the next ``step(n)``."""
    def masses(self) -> FloatArray:
        """(count, bodies), kg."""
    def frictions(self) -> FloatArray:
        """(count, bodies)."""
    def restitutions(self) -> FloatArray:
        """(count, bodies)."""
    def set_masses(self, a: npt.ArrayLike) -> None:
        """(count, bodies), kg."""
    def set_frictions(self, a: npt.ArrayLike) -> None:
        """(count, bodies)."""
    def set_restitutions(self, a: npt.ArrayLike) -> None:
        """(count, bodies)."""
    def gravity(self) -> FloatArray:
        """(count, 3), m/s²."""
    def set_gravity(self, a: npt.ArrayLike) -> None:
        """(count, 3), m/s²."""
    def motor_gains(self) -> FloatArray:
        """(count, motors, 2)."""
    def set_motor_gains(self, stiffness: npt.ArrayLike, damping: npt.ArrayLike) -> None:
        """(count, motors) each."""
    def contact_forces(self) -> FloatArray:
        """(count, bodies, 3), N."""
    def joint_forces(self) -> FloatArray:
        """(count, joints, 3), N."""
    def joint_torques(self) -> FloatArray:
        """(count, joints, 3), N·m."""
    def contact_events(self) -> list[list[tuple[Literal["started", "stopped"], int, int]]]:
        """One list a world."""
    def sensor_events(self) -> list[list[tuple[Literal["entered", "exited"], int, int]]]:
        """One list a world."""
    def ray_casts(
        self, origins: npt.ArrayLike, directions: npt.ArrayLike, max_distance: float = ...
    ) -> FloatArray:
        """Rays (count, rays, 3): distances (count, rays), inf for a miss."""
    def ray_hits(
        self, origins: npt.ArrayLike, directions: npt.ArrayLike, max_distance: float = ...
    ) -> tuple[FloatArray, npt.NDArray[np.int64], FloatArray]:
        """Distances (count, rays), body indices (count, rays), normals (count, rays, 3)."""
    def render(
        self,
        index: Union[int, Iterable[int]],
        width: int,
        height: int,
        camera: Optional[Mapping[str, Any]] = None,
    ) -> npt.NDArray[np.uint8]:
        """World ``index`` drawn as ``World.render``: (height, width, 3); for a list of indices,
        those worlds in parallel: (len(index), height, width, 3)."""
    def set_positions(self, a: npt.ArrayLike) -> None:
        """(count, bodies, 3), m: teleports."""
    def set_rotations(self, a: npt.ArrayLike) -> None:
        """(count, bodies, 4), x, y, z, w, normalised."""
    def joint_positions(self) -> FloatArray:
        """(count, joints); NaN for fixed and ball joints."""
    def joint_velocities(self) -> FloatArray:
        """(count, joints); NaN for fixed and ball joints."""
    def set_joint_positions(self, a: npt.ArrayLike) -> None:
        """(count, joints), NaN at fixed and ball joints."""
    def set_joint_velocities(self, a: npt.ArrayLike) -> None:
        """(count, joints), NaN at fixed and ball joints."""
    def rollout(self, controls: npt.ArrayLike) -> dict[str, FloatArray]:
        """For each t of controls (T, count, motors): set_motor_targets then step(1), in
        parallel without the GIL; states (T, count, ...)."""

def builtin_scenes() -> list[tuple[str, str]]:
    """The scenes built into rebond, (name, description), loadable by name from anywhere."""
