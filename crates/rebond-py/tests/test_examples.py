"""The examples: Gymnasium environments (cart-pole, reaching arm) and the Ray scale-out."""

import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import cartpole
import reacher


def test_cartpole_passes_the_gymnasium_checks():
    check_env(cartpole.CartPoleEnv(render_mode="rgb_array"))


def cartpole_derivative(state, force):
    """d/dt of (x, x_dot, theta, theta_dot) for the example's cart and pole: a cart of mass M on a
    frictionless rail pushed by ``force``, and a pole of mass m hinged at the cart's centre, its
    centre of mass l from the hinge, inertia I about it (the capsule's, as the engine computes
    it), under the engine's default gravity g. Lagrange's equations:
    (M + m) x'' + m l cos(theta) theta'' = force + m l sin(theta) theta'^2,
    m l cos(theta) x'' + (I + m l^2) theta'' = m g l sin(theta)."""
    _, x_dot, theta, theta_dot = state
    big_m, m, l, g = cartpole.CART_MASS, cartpole.POLE_MASS, cartpole.POLE_HALF_LENGTH, 9.81
    # Solid capsule of radius r, cylinder half-height h: inertia about a transverse axis through
    # its centre, for a density of 1, then scaled to the pole's mass.
    r = cartpole.POLE_RADIUS
    h = l - r
    cylinder, spheres = np.pi * r * r * 2 * h, 4 / 3 * np.pi * r**3
    inertia = cylinder * (r * r / 4 + h * h / 3) + spheres * (0.4 * r * r + h * h + 0.75 * h * r)
    inertia *= m / (cylinder + spheres)
    c, s = np.cos(theta), np.sin(theta)
    matrix = np.array([[big_m + m, m * l * c], [m * l * c, inertia + m * l * l]])
    x_acc, theta_acc = np.linalg.solve(matrix, [force + m * l * s * theta_dot**2, m * g * l * s])
    return np.array([x_dot, x_acc, theta_dot, theta_acc])


def cartpole_reference(state, force, duration, steps=50):
    """The state after ``duration`` seconds of a constant push ``force``: classic fourth-order
    Runge-Kutta in ``steps`` steps, whose error (order h^5 a step, 0.4 ms steps) is far below
    the engine's."""
    h = duration / steps
    for _ in range(steps):
        k1 = cartpole_derivative(state, force)
        k2 = cartpole_derivative(state + h / 2 * k1, force)
        k3 = cartpole_derivative(state + h / 2 * k2, force)
        k4 = cartpole_derivative(state + h * k3, force)
        state = state + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return state


def test_cartpole_follows_the_cartpole_equations():
    """The joint-built cart-pole tracks the equations of the same cart and pole, integrated by
    RK4, to within millimetres and milliradians over 20 steps of pushes either way."""
    start = np.array([0.01, 0.02, 0.03, -0.02])
    env = cartpole.CartPoleEnv()
    env.reset(seed=0)
    env.world = cartpole.rebond.World.from_scene(cartpole.cartpole_scene(*start))
    expected = start
    actions = [1, 0, 0, 1, 1, 1, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0]
    for step, action in enumerate(actions):
        force = cartpole.PUSH if action == 1 else -cartpole.PUSH
        expected = cartpole_reference(expected, force, cartpole.TIMESTEP)
        observed, *_ = env.step(action)
        error = np.abs(observed - expected)
        # The engine's semi-implicit Euler substeps put a body ahead of the exact path by
        # a h T / 2 in a step of acceleration a (substep h, step T): 0.45 mm of cart for a
        # push, added up over the pushes, one way or the other; velocities come out exact for
        # a constant acceleration. Measured at most 0.97 mm (two pushes more one way than the
        # other) and 1.35 mrad, 0.023 mm/s and 0.49 mrad/s, the last growing by about
        # 0.025 mrad/s a step. Bounds 1.5 mm, 2 mrad, 0.1 mm/s, 1 mrad/s.
        assert np.all(error < [1.5e-3, 1e-4, 2e-3, 1e-3]), (
            f"step {step}: (x, x_dot, theta, theta_dot) off by {error}"
        )


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


def test_the_cartpole_vector_env_resets_finished_episodes():
    envs = cartpole.make_vector_env(200)
    observation, _ = envs.reset(seed=1)
    rng = np.random.default_rng(2)
    episodes = 0
    for _ in range(100):
        observation, rewards, terminated, truncated, info = envs.step(rng.integers(0, 2, size=200))
        assert observation.shape == (200, 4) and rewards.shape == (200,)
        # Every observation returned is of a running episode: finished ones restarted upright.
        assert np.all(np.abs(observation[:, 2]) <= cartpole.ANGLE_LIMIT + 1e-6)
        for index in np.flatnonzero(terminated):
            x, _, theta, _ = info["final_obs"][index]
            assert abs(x) > cartpole.X_LIMIT or abs(theta) > cartpole.ANGLE_LIMIT
        episodes += int(np.sum(terminated | truncated))
    # Random pushes end an episode after about 20 steps.
    mean_length = 200 * 100 / episodes
    assert 12 < mean_length < 40


def test_reacher_passes_the_gymnasium_checks():
    check_env(reacher.ReacherEnv(render_mode="rgb_array"))


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


def test_the_reacher_vector_env_brings_every_tip_onto_its_target():
    envs = reacher.ReacherVectorEnv(16)
    observations, _ = envs.reset(seed=0)
    starts = np.linalg.norm(observations[:, 8:10], axis=1)
    for step in range(1, reacher.MAX_STEPS + 1):
        observations, rewards, terminated, truncated, info = envs.step(
            reacher.reaching_policy(observations)
        )
        assert not terminated.any()
        assert truncated.all() == (step == reacher.MAX_STEPS)
    assert np.all(starts > 0.05)
    # As the single arm's bound: within 1 cm after 2 s (measured at most 1.3 mm over 64 arms).
    assert np.all(info["final_info"]["distance"] < 0.01)
    assert np.all(info["_final_obs"])
    # The episodes restarted with new targets, drawn from the seeded generator.
    finished = np.stack(info["final_obs"])
    assert np.all(np.any(observations[:, 4:6] != finished[:, 4:6], axis=1))


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
