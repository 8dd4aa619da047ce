"""A two-link arm reaching for a target, as a Gymnasium environment.

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


def joint_state(world: rebond.World) -> tuple[np.ndarray, np.ndarray]:
    """Joint angles (shoulder, elbow) and their rates, from the links' rotations."""
    rotations = world.rotations()
    heading = 2.0 * np.arctan2(rotations[:, 2], rotations[:, 3])  # each link's angle about z
    rates = world.angular_velocities()[:, 2]
    angles = wrap(np.array([heading[0], heading[1] - heading[0]]))
    return angles, np.array([rates[0], rates[1] - rates[0]])


def tip(world: rebond.World) -> np.ndarray:
    """Where the forearm's far end is, (x, y)."""
    q = world.rotations()[1]
    heading = 2.0 * math.atan2(q[2], q[3])
    centre = world.positions()[1, :2]
    return centre + LINK / 2 * np.array([math.cos(heading), math.sin(heading)])


class ReacherEnv(gym.Env):
    """Move the arm's tip onto a random target within reach."""

    metadata = {"render_modes": []}

    def __init__(self) -> None:
        self.template = rebond.World.from_scene(reacher_scene())
        self.action_space = spaces.Box(-MAX_SPEED, MAX_SPEED, shape=(2,), dtype=np.float32)
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(10,), dtype=np.float32)
        self.world: Optional[rebond.World] = None
        self.target = np.zeros(2)
        self.steps = 0

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        self.world = self.template.copy()
        radius = self.np_random.uniform(0.3, 0.95)
        bearing = self.np_random.uniform(-math.pi, math.pi)
        self.target = radius * np.array([math.cos(bearing), math.sin(bearing)])
        self.steps = 0
        return self._observation(), {}

    def step(self, action):
        assert self.world is not None, "call reset() first"
        action = np.clip(np.asarray(action, dtype=np.float32), -MAX_SPEED, MAX_SPEED)
        self.world.set_motor_targets(action)
        self.world.step()
        self.steps += 1
        distance = float(np.linalg.norm(tip(self.world) - self.target))
        reward = -distance - 0.01 * float(np.sum(action**2))
        return self._observation(), reward, False, self.steps >= MAX_STEPS, {"distance": distance}

    def _observation(self) -> np.ndarray:
        assert self.world is not None
        angles, rates = joint_state(self.world)
        return np.concatenate(
            [np.cos(angles), np.sin(angles), self.target, rates, tip(self.world) - self.target]
        ).astype(np.float32)


def reaching_policy(observation: np.ndarray, gain: float = 5.0) -> np.ndarray:
    """Drives the joints towards the elbow-down inverse-kinematics solution for the target."""
    cos, sin, target = observation[0:2], observation[2:4], observation[4:6]
    angles = np.arctan2(sin, cos)
    x, y = target
    elbow = math.acos(np.clip((x * x + y * y - 2 * LINK**2) / (2 * LINK**2), -1.0, 1.0))
    shoulder = math.atan2(y, x) - math.atan2(LINK * math.sin(elbow), LINK + LINK * math.cos(elbow))
    error = wrap(np.array([shoulder, elbow]) - angles)
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


if __name__ == "__main__":
    main()
