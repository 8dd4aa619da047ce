"""rebond.gym.VectorEnv: Gymnasium's vector API over a Batch, same-step autoreset with final
observations, seeding, and the task given as functions or as a subclass."""

import gymnasium
import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.utils.env_checker import data_equivalence

import cartpole
import rebond
import rebond.gym


def test_import_rebond_does_not_import_gymnasium():
    import subprocess
    import sys

    code = "import sys, rebond; print('gymnasium' in sys.modules)"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.strip() == "False"


def test_it_is_a_gymnasium_vector_env_with_batched_spaces_and_same_step_autoreset():
    envs = cartpole.make_vector_env(5)
    assert isinstance(envs, gymnasium.vector.VectorEnv)
    assert envs.metadata["autoreset_mode"] == gymnasium.vector.AutoresetMode.SAME_STEP
    assert envs.num_envs == 5
    assert envs.single_action_space == spaces.Discrete(2)
    assert envs.action_space == spaces.MultiDiscrete([2] * 5)
    assert envs.observation_space.shape == (5, 4)
    observations, info = envs.reset(seed=0)
    assert observations.shape == (5, 4) and observations.dtype == np.float32
    assert observations in envs.observation_space and info == {}
    envs.action_space.seed(0)
    observations, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
    assert observations in envs.observation_space
    assert rewards.shape == (5,) and rewards.dtype == np.float64
    assert terminated.shape == truncated.shape == (5,)
    assert terminated.dtype == truncated.dtype == np.bool_
    assert isinstance(info, dict)
    envs.close()
    assert envs.closed


def run(envs, seed, steps=60):
    """Observations, rewards and flags of ``steps`` steps of seeded random pushes."""
    record = [envs.reset(seed=seed)[0]]
    rng = np.random.default_rng(seed)
    for _ in range(steps):
        observations, rewards, terminated, truncated, _ = envs.step(
            rng.integers(0, 2, size=envs.num_envs)
        )
        record += [observations, rewards, terminated, truncated]
    return record


def test_the_same_seed_gives_the_same_bits_and_another_seed_other_starts():
    first = run(cartpole.make_vector_env(8), seed=3)
    again = run(cartpole.make_vector_env(8), seed=3)
    assert data_equivalence(first, again, exact=True)
    other = run(cartpole.make_vector_env(8), seed=4)
    assert not np.array_equal(first[0], other[0])
    # Reset without a seed goes on drawing from the same generator: new starts.
    envs = cartpole.make_vector_env(8)
    start, _ = envs.reset(seed=3)
    assert not np.array_equal(envs.reset()[0], start)


def test_finished_episodes_restart_in_the_same_step_with_their_final_observation():
    # The same cart-poles with and without a time limit: up to the limit they are one run, so
    # the final observations are exactly the unlimited run's observations at the limit.
    limited = cartpole.make_vector_env(4, max_episode_steps=3)
    unlimited = cartpole.make_vector_env(4, max_episode_steps=None)
    limited.reset(seed=7)
    unlimited.reset(seed=7)
    actions = np.array([1, 0, 1, 1])
    for step in range(1, 4):
        observations, _, terminated, truncated, info = limited.step(actions)
        expected, *_ = unlimited.step(actions)
        if step < 3:
            assert not truncated.any() and "final_obs" not in info
            assert np.array_equal(observations, expected)
    assert truncated.all() and not terminated.any()
    assert info["_final_obs"].all() and info["_final_info"].all()
    assert np.array_equal(np.stack(info["final_obs"]), expected)
    # The returned observations are new episodes' starts: each value within +-0.05 (Gymnasium's
    # CartPole start; 1e-5 more for the joint coordinates' f32 read-back).
    assert np.all(np.abs(observations) <= 0.05 + 1e-5)
    assert np.array_equal(limited.episode_steps, [0, 0, 0, 0])


def test_only_the_finished_environments_get_a_final_observation_and_restart():
    def steps_done(env, observations):
        # Environments 1 and 3 end at their second step; 0 and 2 never.
        return (np.arange(env.num_envs) % 2 == 1) & (env.episode_steps >= 2)

    envs = cartpole.make_vector_env(4, terminated=steps_done)
    envs.reset(seed=0)
    envs.step(np.zeros(4, dtype=np.int64))
    before = envs.batch.positions()
    observations, _, terminated, truncated, info = envs.step(np.zeros(4, dtype=np.int64))
    assert terminated.tolist() == [False, True, False, True] and not truncated.any()
    assert info["_final_obs"].tolist() == [False, True, False, True]
    assert info["final_obs"][0] is None and info["final_obs"][2] is None
    assert info["final_obs"][1][0] < before[1, 0, 0]  # the carts pushed left moved left
    assert envs.episode_steps.tolist() == [2, 0, 2, 0]
    # World 1 starts anew (cart within +-0.05 m), world 0 goes on being pushed left.
    assert abs(observations[1, 0]) <= 0.05 + 1e-5 and observations[0, 0] < before[0, 0, 0]


def test_infos_of_finished_episodes_are_in_final_info():
    envs = cartpole.make_vector_env(
        3, max_episode_steps=2, info=lambda env, observations: {"x": observations[:, 0].copy()}
    )
    envs.reset(seed=0)
    _, _, _, _, info = envs.step(np.ones(3, dtype=np.int64))
    assert set(info) == {"x"} and info["x"].shape == (3,)
    _, _, _, _, info = envs.step(np.ones(3, dtype=np.int64))
    final = np.stack(info["final_obs"])
    assert np.array_equal(info["final_info"]["x"], final[:, 0])
    assert info["final_info"]["_x"].all()


def test_frame_skip_applies_the_action_before_every_frame():
    """A push of frame_skip frames is frame_skip pushes, bit for bit the World calls."""
    envs = cartpole.make_vector_env(2, frame_skip=3)
    envs.reset(seed=1)
    worlds = [envs.batch.world(index) for index in range(2)]
    actions = np.array([1, 0])
    envs.step(actions)
    for index, world in enumerate(worlds):
        for _ in range(3):
            world.apply_forces(cartpole.pushes(actions[index]))
            world.step(1)
        assert np.array_equal(envs.batch.positions()[index], world.positions())
        assert np.array_equal(envs.batch.linear_velocities()[index], world.linear_velocities())


def test_defaults_drive_the_motors_and_infer_the_observation_space():
    envs = rebond.gym.VectorEnv(
        "car", 2, observe=lambda env: env.batch.positions().reshape(env.num_envs, -1)
    )
    motors = len(envs.batch.motor_names())
    assert motors == 4
    assert envs.single_action_space.shape == (motors,)
    assert envs.single_observation_space.shape == (3 * envs.batch.body_count,)
    assert envs.single_observation_space.dtype == np.float32
    envs.reset(seed=0)
    _, rewards, terminated, truncated, _ = envs.step(np.full((2, motors), 5.0, np.float32))
    assert not rewards.any() and not terminated.any() and not truncated.any()
    reference = rebond.Batch("car", 2)
    reference.set_motor_targets(np.full((2, motors), 5.0, np.float32))
    reference.step(1)
    assert np.array_equal(envs.batch.positions(), reference.positions())


def test_bad_use_raises_clear_errors():
    envs = cartpole.make_vector_env(3)
    with pytest.raises(RuntimeError, match=r"call reset\(\) before step\(\)"):
        envs.step(np.zeros(3, dtype=np.int64))
    envs.reset(seed=0)
    with pytest.raises(ValueError, match=r"actions: got an array of shape \(2,\), expected \(3,\)"):
        envs.step(np.zeros(2, dtype=np.int64))
    with pytest.raises(ValueError, match="max_episode_steps: must be at least 1, got 0"):
        cartpole.make_vector_env(3, max_episode_steps=0)
    with pytest.raises(ValueError, match="frame_skip: must be at least 1, got 0"):
        cartpole.make_vector_env(3, frame_skip=0)
    with pytest.raises(ValueError, match="render_mode: 'human' is not one of"):
        cartpole.make_vector_env(3, render_mode="human")
    with pytest.raises(NotImplementedError, match="give observe="):
        rebond.gym.VectorEnv("pendulum", 2)


def test_render_gives_one_picture_per_environment_when_asked():
    assert cartpole.make_vector_env(2).render() is None
    envs = cartpole.make_vector_env(2, render_mode="rgb_array", render_size=(64, 48))
    envs.reset(seed=0)
    frames = envs.render()
    assert len(frames) == 2
    assert all(frame.shape == (48, 64, 3) and frame.dtype == np.uint8 for frame in frames)
    # Each picture is its world's, seen from the camera the first render chose, kept after.
    camera = envs.batch.world(0).render_camera(64, 48)
    for _ in range(5):
        envs.step(np.array([1, 0]))
    for index, frame in enumerate(envs.render()):
        assert np.array_equal(frame, envs.batch.world(index).render(64, 48, camera))


def test_gymnasium_vector_wrappers_run_on_it():
    envs = gymnasium.wrappers.vector.RecordEpisodeStatistics(cartpole.make_vector_env(16))
    envs.reset(seed=0)
    rng = np.random.default_rng(0)
    lengths = []
    for _ in range(60):
        _, _, terminated, truncated, info = envs.step(rng.integers(0, 2, size=16))
        if "episode" in info:
            lengths += list(info["episode"]["l"][info["_episode"]])
    # Random pushes end an episode after about 20 steps.
    assert lengths and 5 < np.mean(lengths) < 40


def test_the_docs_vector_env_example_runs(tmp_path, monkeypatch):
    import os

    from conftest import ROOT

    docs = open(os.path.join(ROOT, "docs", "python.md"), encoding="utf-8").read()
    blocks = [block.split("```", 1)[0] for block in docs.split("```python\n")[1:]]
    (block,) = [block for block in blocks if "rebond.gym.VectorEnv(" in block]
    monkeypatch.chdir(tmp_path)  # the built-in scene loads from anywhere
    names = {}
    exec(compile(block, "docs/python.md", "exec"), names)
    assert names["observations"].shape == (64, 3 * names["envs"].batch.body_count)
    assert names["rewards"].shape == (64,)
