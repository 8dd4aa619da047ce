"""Gymnasium's MuJoCo tasks on rebond (rebond/<Task>-v0): Gymnasium's checker, v5's spaces,
finite steps, the vector env against the single env, qpos/qvel read back as set, and the start
against MuJoCo's qpos0."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import rebond.gym  # noqa: F401  (registers the tasks)
from rebond.mujoco_tasks import TASKS, MujocoTaskVectorEnv

# v5's observation and action sizes (Gymnasium's documentation of each task).
SIZES = {
    "HalfCheetah": (17, 6),
    "Hopper": (11, 3),
    "Walker2d": (17, 6),
    "Ant": (105, 8),
    "Humanoid": (348, 17),
    "InvertedPendulum": (4, 1),
    "InvertedDoublePendulum": (9, 1),
    "Reacher": (10, 2),
}
FRAME_DT = {
    "HalfCheetah": 0.05, "Hopper": 0.008, "Walker2d": 0.008, "Ant": 0.05, "Humanoid": 0.015,
    "InvertedPendulum": 0.04, "InvertedDoublePendulum": 0.05, "Reacher": 0.02,
}


def test_every_task_is_registered():
    assert sorted(TASKS) == sorted(SIZES)
    for task in TASKS:
        assert f"rebond/{task}-v0" in gymnasium.registry


@pytest.mark.parametrize("task", sorted(TASKS))
def test_gymnasium_checker_passes_with_v5_spaces_and_dt(task):
    env = gymnasium.make(f"rebond/{task}-v0")
    observations, actions = SIZES[task]
    assert env.observation_space.shape == (observations,)
    assert env.observation_space.dtype == np.float64
    assert env.action_space.shape == (actions,) and env.action_space.dtype == np.float32
    assert env.unwrapped.dt == pytest.approx(FRAME_DT[task])
    assert env.spec.max_episode_steps == (50 if task == "Reacher" else 1000)
    check_env(env.unwrapped, skip_render_check=True)
    env.close()


@pytest.mark.parametrize("task", sorted(TASKS))
def test_a_vector_env_steps_finite_under_random_actions(task):
    envs = gymnasium.make_vec(f"rebond/{task}-v0", num_envs=4,
                              vectorization_mode="vector_entry_point")
    assert isinstance(envs, rebond.gym.VectorEnv)
    observations, _ = envs.reset(seed=1)
    envs.action_space.seed(1)
    ends = 0
    for _ in range(60):
        observations, rewards, terminated, truncated, _ = envs.step(envs.action_space.sample())
        assert np.all(np.isfinite(observations)), task
        assert np.all(np.isfinite(rewards)), task
        ends += int(np.sum(terminated | truncated))
    assert observations.shape == (4, SIZES[task][0])
    envs.close()


@pytest.mark.parametrize("task", ["Hopper", "Ant", "InvertedPendulum", "InvertedDoublePendulum"])
def test_the_vector_env_steps_each_world_as_the_single_env(task):
    """Without reset noise every world starts in the file's pose: the same actions give the
    same bits in a world of the vector env and in the single env, until an episode ends."""
    single = gymnasium.make(f"rebond/{task}-v0", reset_noise_scale=0.0)
    envs = gymnasium.make_vec(f"rebond/{task}-v0", num_envs=3,
                              vectorization_mode="vector_entry_point", reset_noise_scale=0.0)
    first, _ = single.reset(seed=0)
    many, _ = envs.reset(seed=5)
    np.testing.assert_array_equal(many[2], first)
    rng = np.random.default_rng(2)
    low, high = single.action_space.low, single.action_space.high
    compared = 0
    for _ in range(40):
        # Small pushes (5% of the range) keep the pendulums up for a while.
        action = (0.05 * rng.uniform(low, high)).astype(np.float32)
        observation, reward, terminated, truncated, _ = single.step(action)
        observations, rewards, ended, cut, _ = envs.step(np.tile(action, (3, 1)))
        if terminated or truncated:
            break
        for index in range(3):
            np.testing.assert_array_equal(observations[index], observation)
            assert rewards[index] == reward
        compared += 1
    assert compared >= 5, f"{task}: only {compared} steps before the episode ended"


@pytest.mark.parametrize("task", ["HalfCheetah", "Ant", "Humanoid", "Reacher"])
def test_qpos_and_qvel_read_back_as_set(task):
    """The state a reset sets (init_qpos and init_qvel plus noise) is the state observed:
    float32 positions, rotations and velocities of about 1 round to 6e-8, which the chain of
    bodies placed from the root compounds to about 1e-7 (measured: 1.2e-7 on Humanoid)."""
    envs = MujocoTaskVectorEnv(task, 3)
    model = envs.model
    rng = np.random.default_rng(3)
    qpos = model.init_qpos + rng.uniform(-0.1, 0.1, size=(3, model.nq))
    qvel = model.init_qvel + rng.uniform(-0.1, 0.1, size=(3, model.nv))
    if model.root is not None:
        qpos[:, 3:7] /= np.linalg.norm(qpos[:, 3:7], axis=1, keepdims=True)
    model.set_state(envs.batch, np.arange(3), qpos, qvel)
    np.testing.assert_allclose(model.qpos(envs.batch), qpos, atol=1e-6)
    np.testing.assert_allclose(model.qvel(envs.batch), qvel, atol=1e-6)


@pytest.mark.parametrize("task", sorted(TASKS))
def test_the_start_is_mujocos_qpos0(task):
    mujoco = pytest.importorskip("mujoco", reason="MuJoCo's qpos0 needs the mujoco package")
    envs = MujocoTaskVectorEnv(task, 1)
    reference = mujoco.MjModel.from_xml_path(envs.path)
    assert envs.model.nq == reference.nq and envs.model.nv == reference.nv
    # float32 rounding of the root's pose (measured: 6.7e-8 on Ant and Humanoid, 0 elsewhere).
    np.testing.assert_allclose(envs.model.init_qpos, reference.qpos0, atol=1e-6)
    assert envs.batch.timestep == pytest.approx(reference.opt.timestep)


@pytest.mark.parametrize("task", ["Hopper", "Ant", "Humanoid"])
def test_a_reset_state_is_mujocos_state(task):
    """After a reset to random qpos and qvel, every body's origin, centre of mass and velocities
    are MuJoCo's for the same qpos and qvel (its forward kinematics), and so are the com-based
    inertias and velocities that Humanoid observes: float32 rounding along the chain (measured
    up to 5e-7 on poses and velocities, 1.2e-6 on cinert)."""
    mujoco = pytest.importorskip("mujoco", reason="MuJoCo's kinematics need the mujoco package")
    envs = MujocoTaskVectorEnv(task, 2)
    model, batch = envs.model, envs.batch
    rng = np.random.default_rng(0)
    qpos = model.init_qpos + rng.uniform(-0.2, 0.2, (2, model.nq))
    if model.root is not None:
        qpos[:, 3:7] /= np.linalg.norm(qpos[:, 3:7], axis=1, keepdims=True)
    qvel = rng.uniform(-1, 1, (2, model.nv))
    model.set_state(batch, np.arange(2), qpos, qvel)
    reference = mujoco.MjModel.from_xml_path(envs.path)
    data = mujoco.MjData(reference)
    to_mjcf = np.array([[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]])
    names = batch.body_names()
    com = model.com_based(batch)
    for row in range(2):
        data.qpos[:], data.qvel[:] = qpos[row], qvel[row]
        mujoco.mj_forward(reference, data)
        for body, name in enumerate(model.mujoco_bodies, start=1):
            index = names.index(name)
            velocity = np.zeros(6)
            mujoco.mj_objectVelocity(reference, data, mujoco.mjtObj.mjOBJ_BODY, body, velocity, 0)
            pairs = [
                (batch.positions()[row, index], data.xpos[body]),
                (batch.centers_of_mass()[row, index], data.xipos[body]),
                (batch.linear_velocities()[row, index], velocity[3:]),
                (batch.angular_velocities()[row, index], velocity[:3]),
            ]
            for ours, theirs in pairs:
                np.testing.assert_allclose(to_mjcf @ ours, theirs, atol=2e-6, err_msg=name)
        np.testing.assert_allclose(com["cinert"][row], data.cinert[1:], atol=1e-5)
        np.testing.assert_allclose(com["cvel"][row], data.cvel[1:], atol=2e-6)


def test_rgb_array_pictures_of_the_single_and_the_vector_env():
    env = gymnasium.make("rebond/Humanoid-v0", render_mode="rgb_array")
    env.reset(seed=0)
    picture = env.render()
    assert picture.shape == (240, 320, 3) and picture.dtype == np.uint8
    assert picture.std() > 10  # the model is drawn, not a blank frame
    envs = gymnasium.make_vec("rebond/Hopper-v0", num_envs=2, render_mode="rgb_array",
                              vectorization_mode="vector_entry_point")
    envs.reset(seed=0)
    pictures = envs.render()
    assert len(pictures) == 2 and pictures[1].shape == (240, 320, 3)


def test_the_double_pendulums_constraint_force_is_the_rails_limit_alone():
    """Observation 8 is v5's clipped ``qfrc_constraint[0]``: zero while the cart runs free under
    its 50 N motor and its damping (to within the damping's change over a frame), and the limit holding
    the cart at the rail's end against the 500 N push, clipped to -10, once it gets there."""
    env = gymnasium.make("rebond/InvertedDoublePendulum-v0", reset_noise_scale=0.0)
    env.reset(seed=0)
    observation, *_ = env.step(np.array([0.1], dtype=np.float32))
    # What is taken off as damping is -d v at the frame's end, where the joint's force holds the
    # mean of -d v over the frame's substeps: from rest they differ by at most d |Δv| / 2
    # (d = 0.05 N·s/m, Δv = observation 5, the cart's speed).
    assert abs(observation[8]) < 0.5 * 0.05 * abs(observation[5]) + 1e-4
    for _ in range(40):
        observation, *_ = env.step(np.array([1.0], dtype=np.float32))
    assert observation[0] == pytest.approx(1.0, abs=0.02)  # the cart at the rail's end
    assert observation[8] == -10.0
