"""A cart-pole built from joints, as a Gymnasium environment and as a vector environment.

The cart slides along x on a prismatic joint to the world; the pole turns on a revolute joint
about z at the cart's centre. Actions push the cart with +-10 N (``World.apply_forces``), as
Gymnasium's classic ``CartPole-v1``; an episode ends when the cart leaves +-2.4 m or the pole
leans more than 12 degrees, and is cut at 500 steps.

    python examples/cartpole.py   # an episode with a balancing policy, then 1000 cart-poles
"""

from __future__ import annotations

import math
from typing import Any, Optional

import gymnasium as gym
import numpy as np
from gymnasium import spaces

import rebond
import rebond.gym

TIMESTEP = 0.02
SUBSTEPS = 4
CART_MASS = 1.0
POLE_MASS = 0.1
POLE_HALF_LENGTH = 0.5  # pivot to the pole's centre of mass, m
POLE_RADIUS = 0.05
PUSH = 10.0  # N
X_LIMIT = 2.4
ANGLE_LIMIT = 12 * 2 * math.pi / 360
MAX_STEPS = 500


def cartpole_scene(
    x: float = 0.0, x_dot: float = 0.0, theta: float = 0.0, theta_dot: float = 0.0
) -> dict[str, Any]:
    """The cart-pole as a scene dict: cart at ``x`` moving at ``x_dot``, the pole leaning
    ``theta`` radians towards +x and turning at ``theta_dot``."""
    com = (x + POLE_HALF_LENGTH * math.sin(theta), POLE_HALF_LENGTH * math.cos(theta), 0.0)
    pole_velocity = (
        x_dot + theta_dot * POLE_HALF_LENGTH * math.cos(theta),
        -theta_dot * POLE_HALF_LENGTH * math.sin(theta),
        0.0,
    )
    return {
        "timestep": TIMESTEP,
        "substeps": SUBSTEPS,
        "bodies": [
            {
                "name": "cart",
                "shape": {"type": "box", "half_extents": [0.25, 0.125, 0.15]},
                "position": [x, 0.0, 0.0],
                "linear_velocity": [x_dot, 0.0, 0.0],
                "mass": CART_MASS,
                "can_sleep": False,
            },
            {
                "name": "pole",
                "shape": {
                    "type": "capsule",
                    "radius": POLE_RADIUS,
                    "half_height": POLE_HALF_LENGTH - POLE_RADIUS,
                },
                "position": list(com),
                # A turn of -theta about z leans the pole's +y axis towards +x.
                "rotation": [0.0, 0.0, math.sin(-theta / 2), math.cos(-theta / 2)],
                "linear_velocity": list(pole_velocity),
                "angular_velocity": [0.0, 0.0, -theta_dot],
                "mass": POLE_MASS,
                "can_sleep": False,
            },
        ],
        "joints": [
            {"name": "rail", "type": "prismatic", "body_b": "cart",
             "anchor": [x, 0.0, 0.0], "axis": [1.0, 0.0, 0.0]},
            {"name": "hinge", "type": "revolute", "body_a": "cart", "body_b": "pole",
             "anchor": [x, 0.0, 0.0], "axis": [0.0, 0.0, 1.0]},
        ],
    }


def observe(
    positions: np.ndarray, rotations: np.ndarray,
    linear_velocities: np.ndarray, angular_velocities: np.ndarray,
) -> np.ndarray:
    """(x, x_dot, theta, theta_dot) from the getters' arrays, with any leading batch axes."""
    x = positions[..., 0, 0]
    x_dot = linear_velocities[..., 0, 0]
    theta = -2.0 * np.arctan2(rotations[..., 1, 2], rotations[..., 1, 3])
    theta = (theta + np.pi) % (2 * np.pi) - np.pi
    theta_dot = -angular_velocities[..., 1, 2]
    return np.stack([x, x_dot, theta, theta_dot], axis=-1).astype(np.float32)


def pushes(actions: np.ndarray, bodies: int = 2) -> np.ndarray:
    """The forces for ``World.apply_forces``/``Batch.apply_forces``: +-PUSH on the cart along x."""
    actions = np.asarray(actions)
    forces = np.zeros(actions.shape + (bodies, 3), dtype=np.float32)
    forces[..., 0, 0] = np.where(actions == 1, PUSH, -PUSH)
    return forces


class CartPoleEnv(gym.Env):
    """Gymnasium's CartPole task on a rebond world. Action 1 pushes right, 0 left."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 50}

    def __init__(self, render_mode: Optional[str] = None) -> None:
        assert render_mode is None or render_mode in self.metadata["render_modes"]
        self.render_mode = render_mode
        self.pictures = rebond.gym.Pictures()
        high = np.array([2 * X_LIMIT, np.inf, 2 * ANGLE_LIMIT, np.inf], dtype=np.float32)
        self.observation_space = spaces.Box(-high, high, dtype=np.float32)
        self.action_space = spaces.Discrete(2)
        self.world: Optional[rebond.World] = None
        self.steps = 0

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        start = self.np_random.uniform(-0.05, 0.05, size=4)
        self.world = rebond.World.from_scene(cartpole_scene(*map(float, start)))
        self.steps = 0
        return self._observation(), {}

    def step(self, action):
        assert self.world is not None, "call reset() first"
        self.world.apply_forces(pushes(np.asarray(action)))
        self.world.step()
        self.steps += 1
        observation = self._observation()
        x, _, theta, _ = observation
        terminated = bool(abs(x) > X_LIMIT or abs(theta) > ANGLE_LIMIT)
        truncated = self.steps >= MAX_STEPS
        return observation, 1.0, terminated, truncated, {}

    def render(self) -> Optional[np.ndarray]:
        """With ``render_mode="rgb_array"``, the world drawn on the CPU, (240, 320, 3) ``uint8``."""
        if self.render_mode is None or self.world is None:
            return None
        return self.pictures.of_world(self.world)

    def _observation(self) -> np.ndarray:
        assert self.world is not None
        w = self.world
        return observe(w.positions(), w.rotations(), w.linear_velocities(), w.angular_velocities())


def cartpole_observation(env: rebond.gym.VectorEnv) -> np.ndarray:
    """(x, x_dot, theta, theta_dot) of every cart-pole of a vector environment, (num_envs, 4)."""
    b = env.batch
    return observe(b.positions(), b.rotations(), b.linear_velocities(), b.angular_velocities())


def push_the_carts(env: rebond.gym.VectorEnv, actions: np.ndarray) -> None:
    env.batch.apply_forces(pushes(actions))


def one_a_step(
    env: rebond.gym.VectorEnv, actions: np.ndarray, observations: np.ndarray
) -> np.ndarray:
    return np.ones(env.num_envs)


def fallen(env: rebond.gym.VectorEnv, observations: np.ndarray) -> np.ndarray:
    """The cart off the track or the pole past 12 degrees."""
    return (np.abs(observations[:, 0]) > X_LIMIT) | (np.abs(observations[:, 2]) > ANGLE_LIMIT)


def random_starts(env: rebond.gym.VectorEnv, indices: np.ndarray) -> None:
    """Starts the cart-poles at ``indices`` as Gymnasium's CartPole does: cart position and
    speed, pole angle and rate each uniform within +-0.05, from the environment's seeded
    generator, set as the joints' coordinates (the rail's slide, the hinge's angle, which turns
    about +z: a pole leaning towards +x is a negative angle)."""
    x, x_dot, theta, theta_dot = env.np_random.uniform(-0.05, 0.05, size=(4, len(indices)))
    env.batch.reset(
        indices,
        joint_positions=np.stack([x, -theta], axis=1),
        joint_velocities=np.stack([x_dot, -theta_dot], axis=1),
    )


def make_vector_env(num_envs: int, **options: Any) -> rebond.gym.VectorEnv:
    """``num_envs`` cart-poles in one ``rebond.Batch``, as a Gymnasium vector environment: each
    resets on its own when its episode ends, its last observation in ``info["final_obs"]``.
    ``options`` replace the task's arguments to ``rebond.gym.VectorEnv`` or add others."""
    high = np.array([2 * X_LIMIT, np.inf, 2 * ANGLE_LIMIT, np.inf], dtype=np.float32)
    task: dict[str, Any] = {
        "action_space": spaces.Discrete(2),
        "observation_space": spaces.Box(-high, high, dtype=np.float32),
        "observe": cartpole_observation,
        "act": push_the_carts,
        "reward": one_a_step,
        "terminated": fallen,
        "reset_noise": random_starts,
        "max_episode_steps": MAX_STEPS,
    }
    task.update(options)
    return rebond.gym.VectorEnv(cartpole_scene(), num_envs, **task)


def balancing_policy(observation: np.ndarray) -> np.ndarray:
    """Pushes towards where the pole leans, ahead of its swing: keeps it up for 500 steps."""
    x, x_dot, theta, theta_dot = np.moveaxis(np.asarray(observation), -1, 0)
    return (theta + 0.5 * theta_dot + 0.01 * x + 0.1 * x_dot > 0).astype(np.int64)


def main() -> None:
    env = CartPoleEnv()
    observation, _ = env.reset(seed=0)
    length = 0
    while True:
        observation, _, terminated, truncated, _ = env.step(int(balancing_policy(observation)))
        length += 1
        if terminated or truncated:
            break
    print(f"balancing policy: episode of {length} steps (the most is {MAX_STEPS})")
    envs = make_vector_env(1000)
    envs.reset(seed=0)
    rng = np.random.default_rng(1)
    episodes = 0
    for _ in range(100):
        _, _, terminated, truncated, _ = envs.step(rng.integers(0, 2, size=1000))
        episodes += int(np.sum(terminated | truncated))
    print(
        f"1000 cart-poles, 100 steps of random pushes: {episodes} episodes ended "
        f"(one lasts about 20 steps)"
    )

if __name__ == "__main__":
    main()
