"""Augmented random search (Mania, Guy and Recht 2018, "Simple random search provides a
competitive approach to reinforcement learning", version V1-t) training a linear policy on
``rebond/InvertedPendulum-v0`` or any other ``rebond/<Task>-v0``, with NumPy only.

The policy is ``a = clip(M s)``, ``M`` a (actions, observations) matrix starting at zero. Each
iteration draws ``N`` directions ``δ_k`` with standard normal entries, runs one episode of each
policy ``M ± ν δ_k``, keeps the ``b`` directions whose better return ``max(r⁺, r⁻)`` is highest,
and steps

    M ← M + α / (b σ_R) · Σ_{top b} (r⁺_k − r⁻_k) δ_k,

with ``σ_R`` the standard deviation of the ``2b`` returns kept (V1: no state normalisation; -t:
the top ``b`` directions only). The ``2N`` perturbed policies and ``M`` itself run side by side as
the ``2N + 1`` worlds of one ``rebond.Batch`` (``gymnasium.make_vec``), each until its first
episode ends; the return of ``M`` is printed every iteration.

    python examples/ars.py                                        # InvertedPendulum, 20 iterations
    python examples/ars.py --env rebond/HalfCheetah-v0 --minutes 10
"""

from __future__ import annotations

import argparse
import time
from typing import Optional

import gymnasium
import numpy as np

import rebond.gym  # noqa: F401  (registers the rebond/<Task>-v0 environments)


# Defaults (α, ν, N, b) per task: InvertedPendulum's reach the 100-step horizon within 6
# iterations (the test); the others' are smaller steps among more directions, of the order the
# paper uses for the locomotion tasks.
SETTINGS = {
    "rebond/InvertedPendulum-v0": {"step_size": 0.1, "noise": 0.1, "directions": 4, "top": 2},
    "other": {"step_size": 0.02, "noise": 0.03, "directions": 8, "top": 4},
}


def episode_returns(envs: gymnasium.vector.VectorEnv, policies: np.ndarray, seed: int,
                    horizon: int) -> np.ndarray:
    """The return of each environment's first episode (at most ``horizon`` steps), environment
    ``i`` acting with the linear policy ``policies[i]`` (actions, observations)."""
    observations, _ = envs.reset(seed=seed)
    low, high = envs.single_action_space.low, envs.single_action_space.high
    returns = np.zeros(envs.num_envs)
    running = np.ones(envs.num_envs, dtype=bool)
    for _ in range(horizon):
        actions = np.clip(np.einsum("nao,no->na", policies, observations), low, high)
        observations, rewards, terminated, truncated, _ = envs.step(actions.astype(np.float32))
        returns += np.where(running, rewards, 0.0)
        running &= ~(terminated | truncated)
        if not running.any():
            break
    return returns


def train(env_id: str, iterations: Optional[int], minutes: Optional[float], directions: int,
          top: int, step_size: float, noise: float, horizon: int, seed: int,
          log=print) -> list[float]:
    """Runs ARS V1-t; returns the return of the unperturbed policy after each iteration."""
    envs = gymnasium.make_vec(env_id, num_envs=2 * directions + 1,
                              vectorization_mode="vector_entry_point",
                              max_episode_steps=horizon)
    shape = (envs.single_action_space.shape[0], envs.single_observation_space.shape[0])
    rng = np.random.default_rng(seed)
    policy = np.zeros(shape)
    history: list[float] = []
    deadline = None if minutes is None else time.monotonic() + 60.0 * minutes
    iteration = 0
    while (iterations is None or iteration < iterations) and (
        deadline is None or time.monotonic() < deadline
    ):
        deltas = rng.standard_normal((directions,) + shape)
        policies = np.concatenate(
            [policy + noise * deltas, policy - noise * deltas, policy[None]], axis=0
        )
        returns = episode_returns(envs, policies, seed + iteration, horizon)
        plus, minus = returns[:directions], returns[directions:2 * directions]
        best = np.argsort(-np.maximum(plus, minus))[:top]
        spread = np.std(np.concatenate([plus[best], minus[best]]))
        if spread > 0:
            step = np.einsum("k,kao->ao", plus[best] - minus[best], deltas[best])
            policy = policy + step_size / (top * spread) * step
        history.append(float(returns[-1]))
        log(f"iteration {iteration + 1:4d}  return {returns[-1]:10.2f}  "
            f"perturbed mean {returns[:-1].mean():10.2f}")
        iteration += 1
    envs.close()
    return history


def main() -> None:
    parser = argparse.ArgumentParser(description="augmented random search (ARS V1-t) on rebond")
    parser.add_argument("--env", default="rebond/InvertedPendulum-v0")
    parser.add_argument("--iterations", type=int, default=None,
                        help="iterations to run (default 20, or as many as --minutes allow)")
    parser.add_argument("--minutes", type=float, default=None, help="stop after this long")
    parser.add_argument("--directions", type=int, default=None,
                        help="N, directions per iteration")
    parser.add_argument("--top", type=int, default=None, help="b, directions kept")
    parser.add_argument("--step-size", type=float, default=None, help="alpha")
    parser.add_argument("--noise", type=float, default=None, help="nu, exploration noise")
    parser.add_argument("--horizon", type=int, default=1000, help="steps per episode at most")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    iterations = args.iterations
    if iterations is None and args.minutes is None:
        iterations = 20
    defaults = SETTINGS.get(args.env, SETTINGS["other"])
    directions = args.directions or defaults["directions"]
    top = min(args.top or defaults["top"], directions)
    step_size = args.step_size or defaults["step_size"]
    noise = args.noise or defaults["noise"]
    train(args.env, iterations, args.minutes, directions, top, step_size, noise, args.horizon,
          args.seed)


if __name__ == "__main__":
    main()
