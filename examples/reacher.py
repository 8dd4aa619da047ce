"""A two-link arm reaching for a target, as a Gymnasium environment and a vector environment.

The arm lies in the xy plane without gravity: a 0.5 m upper link on a revolute joint to the
world at the origin (the shoulder), a 0.5 m forearm on a revolute joint at the upper link's end
(the elbow), both turning about z. Each joint has a velocity motor; an action is the two target
joint speeds (rad/s, ``World.set_motor_targets``). The reward is minus the distance from the
forearm's tip to the target, and an episode lasts 100 steps (2 s).

    python examples/reacher.py   # an episode with an inverse-kinematics policy
"""

from __future__ import annotations

import math
from typing import Any, Optional

import gymnasium as gym
import numpy as np
from gymnasium import spaces

import rebond
import rebond.gym

LINK = 0.5  # length of each link, m
MAX_SPEED = 3.0  # rad/s
MAX_TORQUE = 20.0  # N m
MAX_STEPS = 100


def reacher_scene() -> dict[str, Any]:
    """The arm, stretched along +x, as a scene dict."""
    link = {"type": "box", "half_extents": [LINK / 2, 0.02, 0.02]}
    motor = {"target_velocity": 0.0, "max_force": MAX_TORQUE}
    return {
        "gravity": [0.0, 0.0, 0.0],
        "timestep": 0.02,
        "substeps": 4,
        "bodies": [
            {"name": "upper", "shape": link, "position": [LINK / 2, 0.0, 0.0], "mass": 1.0,
             "can_sleep": False},
            {"name": "forearm", "shape": link, "position": [1.5 * LINK, 0.0, 0.0], "mass": 1.0,
             "can_sleep": False},
        ],
        "joints": [
            {"name": "shoulder", "type": "revolute", "body_b": "upper",
             "anchor": [0.0, 0.0, 0.0], "axis": [0.0, 0.0, 1.0], "motor": motor},
            {"name": "elbow", "type": "revolute", "body_a": "upper", "body_b": "forearm",
             "anchor": [LINK, 0.0, 0.0], "axis": [0.0, 0.0, 1.0], "motor": motor},
        ],
    }


def wrap(angle: np.ndarray) -> np.ndarray:
    return (angle + np.pi) % (2 * np.pi) - np.pi


def joint_state(
    rotations: np.ndarray, angular_velocities: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Joint angles (shoulder, elbow) and their rates from the links' rotations and angular
    velocities, with any leading batch axes: two arrays (..., 2)."""
    heading = 2.0 * np.arctan2(rotations[..., 2], rotations[..., 3])  # each link's angle about z
    rates = angular_velocities[..., 2]
    angles = wrap(np.stack([heading[..., 0], heading[..., 1] - heading[..., 0]], axis=-1))
    return angles, np.stack([rates[..., 0], rates[..., 1] - rates[..., 0]], axis=-1)


def tip(positions: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """Where the forearm's far end is, (..., 2) for (x, y), with any leading batch axes."""
    q = rotations[..., 1, :]
    heading = 2.0 * np.arctan2(q[..., 2], q[..., 3])
    centre = positions[..., 1, :2]
    return centre + LINK / 2 * np.stack([np.cos(heading), np.sin(heading)], axis=-1)


def arm_observation(
    positions: np.ndarray, rotations: np.ndarray, angular_velocities: np.ndarray,
    target: np.ndarray,
) -> np.ndarray:
    """cos and sin of the joint angles, the target, the joint rates and the tip's offset from
    the target: (..., 10)."""
    angles, rates = joint_state(rotations, angular_velocities)
    offset = tip(positions, rotations) - target
    return np.concatenate(
        [np.cos(angles), np.sin(angles), target, rates, offset], axis=-1
    ).astype(np.float32)


def random_target(rng: np.random.Generator, size: Optional[int] = None) -> np.ndarray:
    """A target within reach: 0.3 to 0.95 m from the shoulder, any bearing; (2,) or (size, 2)."""
    radius = rng.uniform(0.3, 0.95, size=size)
    bearing = rng.uniform(-math.pi, math.pi, size=size)
    return np.stack([radius * np.cos(bearing), radius * np.sin(bearing)], axis=-1)


class ReacherEnv(gym.Env):
    """Move the arm's tip onto a random target within reach."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 50}

    def __init__(self, render_mode: Optional[str] = None) -> None:
        assert render_mode is None or render_mode in self.metadata["render_modes"]
        self.render_mode = render_mode
        self.pictures = rebond.gym.Pictures()
        self.template = rebond.World.from_scene(reacher_scene())
        self.action_space = spaces.Box(-MAX_SPEED, MAX_SPEED, shape=(2,), dtype=np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(10,), dtype=np.float32)
        self.world: Optional[rebond.World] = None
        self.target = np.zeros(2)
        self.steps = 0

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        self.world = self.template.copy()
        self.target = random_target(self.np_random)
        self.steps = 0
        return self._observation(), {}

    def step(self, action):
        assert self.world is not None, "call reset() first"
        action = np.clip(np.asarray(action, dtype=np.float32), -MAX_SPEED, MAX_SPEED)
        self.world.set_motor_targets(action)
        self.world.step()
        self.steps += 1
        distance = float(np.linalg.norm(tip(self.world.positions(), self.world.rotations())
                                        - self.target))
        reward = -distance - 0.01 * float(np.sum(action**2))
        return self._observation(), reward, False, self.steps >= MAX_STEPS, {"distance": distance}

    def render(self) -> Optional[np.ndarray]:
        """With ``render_mode="rgb_array"``, the world drawn on the CPU, (240, 320, 3) ``uint8``."""
        if self.render_mode is None or self.world is None:
            return None
        return self.pictures.of_world(self.world)

    def _observation(self) -> np.ndarray:
        assert self.world is not None
        w = self.world
        return arm_observation(w.positions(), w.rotations(), w.angular_velocities(), self.target)


class ReacherVectorEnv(rebond.gym.VectorEnv):
    """``num_envs`` arms in one ``rebond.Batch``, each with its own target: the task written as
    a subclass of ``rebond.gym.VectorEnv``, the target being per-environment state that
    ``reset_noise`` draws and ``observe`` reads."""

    def __init__(self, num_envs: int, **options: Any) -> None:
        self.targets = np.zeros((num_envs, 2))
        super().__init__(
            reacher_scene(),
            num_envs,
            action_space=spaces.Box(-MAX_SPEED, MAX_SPEED, shape=(2,), dtype=np.float32),
            observation_space=spaces.Box(-np.inf, np.inf, shape=(10,), dtype=np.float32),
            max_episode_steps=MAX_STEPS,
            **options,
        )

    def act(self, actions: np.ndarray) -> None:
        self.batch.set_motor_targets(np.clip(actions, -MAX_SPEED, MAX_SPEED))

    def observe(self) -> np.ndarray:
        b = self.batch
        return arm_observation(b.positions(), b.rotations(), b.angular_velocities(), self.targets)

    def distances(self) -> np.ndarray:
        return np.linalg.norm(tip(self.batch.positions(), self.batch.rotations()) - self.targets,
                              axis=-1)

    def reward(self, actions: np.ndarray, observations: np.ndarray) -> np.ndarray:
        actions = np.clip(actions, -MAX_SPEED, MAX_SPEED)
        return -self.distances() - 0.01 * np.sum(actions**2, axis=-1)

    def reset_noise(self, indices: np.ndarray) -> None:
        self.targets[indices] = random_target(self.np_random, len(indices))

    def info(self, observations: np.ndarray) -> dict:
        return {"distance": self.distances()}


def reaching_policy(observation: np.ndarray, gain: float = 5.0) -> np.ndarray:
    """Drives the joints towards the elbow-down inverse-kinematics solution for the target;
    observations (10,) or a batch of them (..., 10)."""
    cos, sin, target = observation[..., 0:2], observation[..., 2:4], observation[..., 4:6]
    angles = np.arctan2(sin, cos)
    x, y = target[..., 0], target[..., 1]
    elbow = np.arccos(np.clip((x * x + y * y - 2 * LINK**2) / (2 * LINK**2), -1.0, 1.0))
    shoulder = np.arctan2(y, x) - np.arctan2(LINK * np.sin(elbow), LINK + LINK * np.cos(elbow))
    error = wrap(np.stack([shoulder, elbow], axis=-1) - angles)
    return np.clip(gain * error, -MAX_SPEED, MAX_SPEED).astype(np.float32)


def main() -> None:
    env = ReacherEnv()
    observation, _ = env.reset(seed=0)
    info: dict = {}
    for _ in range(MAX_STEPS):
        observation, _, _, truncated, info = env.step(reaching_policy(observation))
        if truncated:
            break
    print(f"target {env.target.round(3)}: tip within {info['distance'] * 1000:.1f} mm after 2 s")
    envs = ReacherVectorEnv(64)
    observations, _ = envs.reset(seed=0)
    for _ in range(MAX_STEPS):
        observations, _, _, truncated, infos = envs.step(reaching_policy(observations))
    distances = infos["final_info"]["distance"]
    print(f"64 arms at once: every tip within {distances.max() * 1000:.1f} mm after 2 s")

if __name__ == "__main__":
    main()
