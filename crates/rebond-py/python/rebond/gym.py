"""Gymnasium vector environments over a ``rebond.Batch``: ``rebond.gym.VectorEnv``.

Importing ``rebond`` does not import this module, so rebond needs Gymnasium only when it is used
(``pip install gymnasium``, or ``pip install "rebond[gym]"``). See "Vector environments" in
docs/python.md.
"""

from __future__ import annotations

import types
from typing import Any, Callable, Iterable, Optional, Sequence

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector.utils import batch_space

from ._rebond import Batch, World

try:
    from gymnasium.vector import AutoresetMode

    _SAME_STEP: Any = AutoresetMode.SAME_STEP
except ImportError:  # Gymnasium 1.0 names the modes by their values only.
    _SAME_STEP = "SameStep"

__all__ = ["Pictures", "VectorEnv"]

Observe = Callable[["VectorEnv"], np.ndarray]
Act = Callable[["VectorEnv", np.ndarray], None]
Reward = Callable[["VectorEnv", np.ndarray, np.ndarray], np.ndarray]
Terminated = Callable[["VectorEnv", np.ndarray], np.ndarray]
ResetNoise = Callable[["VectorEnv", np.ndarray], None]
Info = Callable[["VectorEnv", np.ndarray], dict]


class Pictures:
    """Pictures of worlds, ``(height, width, 3)`` ``uint8`` (``World.render``), all from one camera:
    the one ``World.render_camera`` chooses for the first world drawn, kept after so that a
    video's view stays still. For a Gymnasium environment's ``render_mode="rgb_array"``."""

    def __init__(self, width: int = 320, height: int = 240) -> None:
        self.width, self.height = width, height
        self.camera: Optional[dict[str, Any]] = None

    def of_world(self, world: World) -> np.ndarray:
        """``world`` drawn from the kept camera."""
        if self.camera is None:
            self.camera = world.render_camera(self.width, self.height)
        return world.render(self.width, self.height, self.camera)

    def of_batch(self, batch: Batch, indices: Iterable[int]) -> np.ndarray:
        """The worlds of ``batch`` at ``indices``, drawn in parallel: ``(len, height, width, 3)``."""
        indices = list(indices)
        if self.camera is None:
            self.camera = batch.world(indices[0]).render_camera(self.width, self.height)
        return batch.render(indices, self.width, self.height, self.camera)


class VectorEnv(gymnasium.vector.VectorEnv):
    """``num_envs`` copies of a scene stepped together in one ``rebond.Batch``, as a Gymnasium
    vector environment.

    The task is given as functions, each called with this environment first (``env.batch`` is
    the ``Batch``, ``env.np_random`` the generator seeded by ``reset(seed=...)``,
    ``env.episode_steps`` the steps of each current episode), or by overriding the methods of
    the same names in a subclass:

    - ``observe(env)`` -> observations ``(num_envs, *obs_shape)``, from the batch's getters;
    - ``act(env, actions)`` applies ``actions`` ``(num_envs, *action_shape)`` before a step, with
      ``Batch.set_motor_targets``, ``Batch.apply_forces``, ...; by default the actions are the
      motor targets (``motor_names()`` order);
    - ``reward(env, actions, observations)`` -> ``(num_envs,)``; zero by default;
    - ``terminated(env, observations)`` -> ``(num_envs,)`` booleans; never by default;
    - ``reset_noise(env, indices)`` randomises the worlds at ``indices`` (an integer array) just
      after they were put back in the scene's starting state, drawing from ``env.np_random``;
      by default they start exactly as the scene does;
    - ``info(env, observations)`` -> a dict of ``(num_envs, ...)`` arrays; empty by default.

    ``max_episode_steps`` truncates episodes (``None``: never); ``frame_skip`` steps the batch
    that many times per ``step`` with ``act`` called before each, so that forces, which last one
    step, push through the whole frame. ``observation_space`` (one environment's) is by default
    an unbounded ``Box`` of the shape and dtype ``observe`` returns for the starting state.

    Episodes reset automatically in the step that ends them (Gymnasium's ``SAME_STEP`` autoreset,
    ``metadata["autoreset_mode"]``): the observation returned for a finished environment is the
    first of its next episode; the last of the finished one is in ``info["final_obs"]`` (an
    object array, ``None`` for the others, mask ``info["_final_obs"]``), its info in
    ``info["final_info"]`` (mask ``info["_final_info"]``).

    ``render_mode="rgb_array"`` makes ``render()`` return one ``(height, width, 3)`` ``uint8``
    picture per environment of size ``render_size`` ``(width, height)`` (``Batch.render``), all
    seen from the camera ``World.render_camera`` chooses for the first environment at the first
    ``render()``, kept so that a video's view stays still.
    """

    metadata: dict[str, Any] = {"autoreset_mode": _SAME_STEP, "render_modes": ["rgb_array"]}

    def __init__(
        self,
        scene: Any,
        num_envs: int,
        *,
        action_space: Optional[spaces.Space] = None,
        observation_space: Optional[spaces.Space] = None,
        observe: Optional[Observe] = None,
        act: Optional[Act] = None,
        reward: Optional[Reward] = None,
        terminated: Optional[Terminated] = None,
        reset_noise: Optional[ResetNoise] = None,
        info: Optional[Info] = None,
        max_episode_steps: Optional[int] = None,
        frame_skip: int = 1,
        render_mode: Optional[str] = None,
        render_size: Sequence[int] = (320, 240),
    ) -> None:
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"render_mode: {render_mode!r} is not one of {self.metadata['render_modes']}"
            )
        if max_episode_steps is not None and max_episode_steps < 1:
            raise ValueError(f"max_episode_steps: must be at least 1, got {max_episode_steps}")
        if frame_skip < 1:
            raise ValueError(f"frame_skip: must be at least 1, got {frame_skip}")
        self.batch = Batch(scene, num_envs)
        self.num_envs = self.batch.count
        self.render_mode = render_mode
        self.render_size = tuple(render_size)
        self._pictures = Pictures(*self.render_size)
        self.max_episode_steps = max_episode_steps
        self.frame_skip = frame_skip
        self.episode_steps = np.zeros(self.num_envs, dtype=np.int64)
        for name, function in [
            ("observe", observe),
            ("act", act),
            ("reward", reward),
            ("terminated", terminated),
            ("reset_noise", reset_noise),
            ("info", info),
        ]:
            if function is not None:
                setattr(self, name, types.MethodType(function, self))
        if action_space is None:
            motors = len(self.batch.motor_names())
            action_space = spaces.Box(-np.inf, np.inf, shape=(motors,), dtype=np.float32)
        self.single_action_space = action_space
        self.action_space = batch_space(action_space, self.num_envs)
        if observation_space is None:
            sample = np.asarray(self.observe())
            observation_space = spaces.Box(
                -np.inf, np.inf, shape=sample.shape[1:], dtype=sample.dtype
            )
        self.single_observation_space = observation_space
        self.observation_space = batch_space(observation_space, self.num_envs)
        self._started = False

    # The task: override in a subclass, or give functions to the constructor.

    def observe(self) -> np.ndarray:
        """Observations of every environment, ``(num_envs, *obs_shape)``."""
        raise NotImplementedError("VectorEnv: give observe=... or override observe()")

    def act(self, actions: np.ndarray) -> None:
        """Applies ``actions`` before a step; by default as the motor targets."""
        self.batch.set_motor_targets(actions)

    def reward(self, actions: np.ndarray, observations: np.ndarray) -> np.ndarray:
        """Rewards of the step just taken, ``(num_envs,)``; zero by default."""
        return np.zeros(self.num_envs)

    def terminated(self, observations: np.ndarray) -> np.ndarray:
        """Which episodes have ended, ``(num_envs,)`` booleans; none by default."""
        return np.zeros(self.num_envs, dtype=bool)

    def reset_noise(self, indices: np.ndarray) -> None:
        """Randomises the worlds at ``indices``, just reset to the scene's start; nothing by
        default."""

    def info(self, observations: np.ndarray) -> dict:
        """Extra information of the step just taken: arrays with a leading ``num_envs`` axis."""
        return {}

    # Gymnasium's interface.

    def reset(
        self, *, seed: Optional[int] = None, options: Optional[dict] = None
    ) -> tuple[np.ndarray, dict]:
        """Starts a new episode in every environment: the scene's starting state, then
        ``reset_noise`` from ``np_random`` (seeded by ``seed``)."""
        super().reset(seed=seed, options=options)
        self._restart(np.arange(self.num_envs))
        self._started = True
        return self._observations(), {}

    def step(
        self, actions: Any
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict]:
        """One step of every environment; finished episodes restart in the same step."""
        if not self._started:
            raise RuntimeError("VectorEnv: call reset() before step()")
        actions = np.asarray(actions)
        if actions.shape != self.action_space.shape:
            raise ValueError(
                f"actions: got an array of shape {actions.shape}, expected "
                f"{self.action_space.shape} (num_envs, *action_shape)"
            )
        observations, rewards, terminated, infos = self._advance(actions)
        if self.max_episode_steps is None:
            truncated = np.zeros(self.num_envs, dtype=bool)
        else:
            truncated = self.episode_steps >= self.max_episode_steps
        done = terminated | truncated
        if done.any():
            finished = np.flatnonzero(done)
            final_obs = np.full(self.num_envs, None, dtype=object)
            for index in finished:
                final_obs[index] = observations[index].copy()
            final_info: dict[str, Any] = {}
            for key, value in infos.items():
                final_info[key] = value
                final_info[f"_{key}"] = done.copy()
            self._restart(finished)
            observations[finished] = self._observations()[finished]
            infos["final_obs"], infos["_final_obs"] = final_obs, done.copy()
            infos["final_info"], infos["_final_info"] = final_info, done.copy()
        return observations, rewards, terminated, truncated, infos

    def render(self) -> Optional[tuple[np.ndarray, ...]]:
        """One picture per environment for ``render_mode="rgb_array"``; ``None`` otherwise."""
        if self.render_mode is None:
            return None
        return tuple(self._pictures.of_batch(self.batch, range(self.num_envs)))

    def _advance(self, actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict]:
        """``frame_skip`` steps with ``act`` before each, one more step in every episode, then
        the observations, rewards, terminations and info of every environment, without
        restarting any."""
        for _ in range(self.frame_skip):
            self.act(actions)
            self.batch.step(1)
        self.episode_steps += 1
        observations = self._observations()
        rewards = np.asarray(self.reward(actions, observations), dtype=np.float64)
        terminated = np.asarray(self.terminated(observations), dtype=bool)
        return observations, rewards, terminated, dict(self.info(observations))

    def _restart(self, indices: np.ndarray) -> None:
        """Puts the worlds at ``indices`` back in the starting state, with reset noise."""
        self.batch.reset(indices)
        self.episode_steps[indices] = 0
        self.reset_noise(indices)

    def _observations(self) -> np.ndarray:
        """``observe()`` as a fresh array of the observation space's dtype."""
        return np.array(self.observe(), dtype=self.single_observation_space.dtype)

    def __repr__(self) -> str:
        return (
            f"rebond.gym.VectorEnv(num_envs={self.num_envs}, bodies={self.batch.body_count}, "
            f"timestep={self.batch.timestep})"
        )


# Gymnasium's MuJoCo tasks, registered as ``rebond/<Task>-v0`` (after VectorEnv, which they use).
from . import mujoco_tasks  # noqa: E402,F401
