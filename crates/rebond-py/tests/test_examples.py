"""The examples: Gymnasium environments (cart-pole, reaching arm) and the Ray scale-out."""

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import cartpole
import reacher


def test_cartpole_passes_the_gymnasium_checks():
    check_env(cartpole.CartPoleEnv(), skip_render_check=True)


def test_cartpole_follows_the_classic_cartpole_equations():
    """Gymnasium's CartPole-v1 integrates the textbook equations of the same cart and pole; the
    joint-built one tracks it to within a few millimetres and milliradians over 20 steps."""
    import gymnasium as gym

    classic = gym.make("CartPole-v1").unwrapped
    classic.reset(seed=0)
    start = np.array([0.01, 0.02, 0.03, -0.02])
    classic.state = start.copy()
    env = cartpole.CartPoleEnv()
    env.reset(seed=0)
    env.world = cartpole.rebond.World.from_scene(cartpole.cartpole_scene(*start))
    actions = [1, 0, 0, 1, 1, 1, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0]
    for action in actions:
        expected, *_ = classic.step(action)
        observed, *_ = env.step(action)
        assert observed[0] == pytest.approx(expected[0], abs=0.01)
        assert observed[2] == pytest.approx(expected[2], abs=0.02)


def test_a_balancing_policy_keeps_the_pole_up_and_pushing_one_way_drops_it():
    env = cartpole.CartPoleEnv()
    observation, _ = env.reset(seed=3)
    for length in range(1, cartpole.MAX_STEPS + 1):
        observation, reward, terminated, truncated, _ = env.step(
            int(cartpole.balancing_policy(observation))
        )
        assert reward == 1.0
        if terminated or truncated:
            break
    assert (length, terminated, truncated) == (cartpole.MAX_STEPS, False, True)
    env.reset(seed=3)
    for length in range(1, cartpole.MAX_STEPS + 1):
        _, _, terminated, _, _ = env.step(1)
        if terminated:
            break
    assert terminated and length < 40


def test_the_cartpole_batch_resets_finished_episodes():
    envs = cartpole.CartPoleBatch(200, seed=1)
    rng = np.random.default_rng(2)
    for _ in range(100):
        observation, rewards, terminated, truncated = envs.step(rng.integers(0, 2, size=200))
        assert observation.shape == (200, 4) and rewards.shape == (200,)
        assert np.all(np.abs(observation[:, 2]) <= cartpole.ANGLE_LIMIT + 1e-6)
    # Random pushes end an episode after about 20 steps.
    mean_length = 200 * 100 / envs.episodes
    assert 12 < mean_length < 40


def test_reacher_passes_the_gymnasium_checks():
    check_env(reacher.ReacherEnv(), skip_render_check=True)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_reacher_policy_brings_the_tip_onto_the_target(seed):
    env = reacher.ReacherEnv()
    observation, _ = env.reset(seed=seed)
    start = float(np.linalg.norm(observation[8:10]))
    for _ in range(reacher.MAX_STEPS):
        observation, reward, terminated, truncated, info = env.step(
            reacher.reaching_policy(observation)
        )
        assert not terminated
    assert truncated
    assert start > 0.05
    assert info["distance"] < 0.01
    assert reward > -0.02


def test_ray_actors_each_step_a_batch():
    import ray
    import ray_scaleout
    from conftest import EXAMPLES

    ray.init(
        num_cpus=2,
        include_dashboard=False,
        runtime_env={"env_vars": {"PYTHONPATH": EXAMPLES}},
        log_to_driver=False,
    )
    try:
        totals = ray_scaleout.run(actors=2, worlds=100, steps=50)
    finally:
        ray.shutdown()
    assert totals["env_steps"] == 2 * 100 * 50
    assert len(totals["actors"]) == 2
    # Random pushes: some episodes ended in 50 steps of 100 cart-poles.
    assert all(actor["episodes"] > 0 for actor in totals["actors"])
    # Each actor seeds its own generator: the two did different work.
    assert totals["actors"][0]["checksum"] != totals["actors"][1]["checksum"]
