"""Driving bodies and per-environment parameters: torque motors, forces at points and torques held
through step(n), masses, frictions, restitutions, gravity and motor gains per world."""

import math

import numpy as np
import pytest

import rebond

GROUND = {"type": "box", "half_extents": [10.0, 0.5, 10.0]}
BALL = {"type": "sphere", "radius": 0.5}


def floating(mass=2.0, timestep=0.1, substeps=1):
    """One ball of `mass` kg at the origin, no gravity: I = 2/5 m r² = 0.2 m about any axis."""
    world = rebond.World(gravity=[0, 0, 0], timestep=timestep, substeps=substeps)
    world.add_body(BALL, name="ball", mass=mass)
    return world


def test_a_torque_motor_target_is_its_torque():
    # A ball hinged at its centre about z, driven by a torque motor: θ̈ = τ / I, I = 2/5 m r²
    # = 0.2 kg·m² for 2 kg and r = 0.5, so τ = 0.5 N·m gives 2.5 rad/s² and ω = 2.5 t.
    world = rebond.World(gravity=[0, 0, 0], timestep=0.01, substeps=4)
    world.add_body(BALL, name="wheel", mass=2.0)
    world.add_joint("revolute", body_b="wheel", anchor=[0, 0, 0], axis=[0, 0, 1],
                    motor={"torque": 0.0})
    assert world.motor_names() == ["joint0"]
    world.set_motor_targets([0.5])
    world.step(100)  # one second
    # The joint holds the centre without touching the spin: measured 1e-6 relative (f32
    # rounding over 400 substeps); 1e-4 leaves room for other platforms' rounding.
    assert world.angular_velocities()[0, 2] == pytest.approx(2.5, rel=1e-4)
    world.set_motor_targets([-0.5])
    world.step(100)
    assert world.angular_velocities()[0, 2] == pytest.approx(0.0, abs=1e-4)


def test_forces_act_on_every_step_of_the_next_step_call():
    # F = 4 N on 2 kg for dt = 0.1 s: 0.2 m/s a step. step(4) pushes 4 times as long as step(1).
    once = floating()
    once.apply_forces([[4, 0, 0]])
    once.step(1)
    assert once.linear_velocities()[0, 0] == pytest.approx(0.2, rel=1e-6)
    skipped = floating()
    skipped.apply_forces([[4, 0, 0]])
    skipped.step(4)
    assert skipped.linear_velocities()[0, 0] == pytest.approx(0.8, rel=1e-6)
    # ... bit for bit as giving the force before each of 4 single steps,
    stepwise = floating()
    for _ in range(4):
        stepwise.apply_forces([[4, 0, 0]])
        stepwise.step()
    np.testing.assert_array_equal(stepwise.positions(), skipped.positions())
    np.testing.assert_array_equal(stepwise.linear_velocities(), skipped.linear_velocities())
    # ... and then they stop.
    skipped.step(3)
    assert skipped.linear_velocities()[0, 0] == pytest.approx(0.8, rel=1e-6)


def test_forces_add_up_until_the_step_and_step_zero_drops_them():
    world = floating()
    world.apply_forces([[1, 0, 0]])
    world.apply_forces([[3, 0, 0]])
    world.step()
    assert world.linear_velocities()[0, 0] == pytest.approx(0.2, rel=1e-6)
    world.apply_forces([[4, 0, 0]])
    world.step(0)
    world.step()
    assert world.linear_velocities()[0, 0] == pytest.approx(0.2, rel=1e-6)


def test_a_force_at_a_point_also_turns_the_body():
    # F = (0, 1, 0) N at (1, 0, 0) m: the same push, and τ = r × F = (0, 0, 1) N·m, so
    # ω_z = τ dt / I = 1 · 0.1 / 0.2 = 0.5 rad/s after one step.
    world = floating()
    world.apply_forces([[0, 1, 0]], points=[[1, 0, 0]])
    world.step()
    assert world.linear_velocities()[0] == pytest.approx([0, 0.05, 0], abs=1e-7)
    assert world.angular_velocities()[0] == pytest.approx([0, 0, 0.5], rel=1e-6)
    # The same as the force at the centre and the torque r × F given apart, bit for bit.
    apart = floating()
    apart.apply_forces([[0, 1, 0]])
    apart.apply_torques([[0, 0, 1]])
    apart.step()
    np.testing.assert_array_equal(apart.angular_velocities(), world.angular_velocities())
    np.testing.assert_array_equal(apart.linear_velocities(), world.linear_velocities())


def test_torques_turn_bodies_by_torque_over_inertia():
    world = floating()
    world.apply_torques([[0, 2, 0]])
    world.step(2)
    # α = τ / I = 2 / 0.2 = 10 rad/s² for 0.2 s.
    assert world.angular_velocities()[0] == pytest.approx([0, 2, 0], rel=1e-6)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda w: w.apply_forces([[0, 0, 0]], points=[[0, 0]]),
         "points: got an array of shape (1, 2), expected (1, 3) (bodies, 3)"),
        (lambda w: w.apply_forces([[2e12, 0, 0]]),
         "apply_forces: element [0] the force held on the body would be 2e12 N, past the limit 1e12"),
        (lambda w: w.apply_forces([[1, 0, 0]], points=[[2e4, 0, 0]]),
         "apply_forces: element [0] point [20000, 0, 0] is farther than 1e4 m out"),
        (lambda w: w.apply_torques([[0, math.inf, 0]]),
         "apply_torques: element [0, 1] must be finite, got inf"),
    ],
)
def test_bad_forces_are_refused_and_nothing_is_held(call, message):
    world = floating()
    world.apply_forces([[1, 0, 0]])
    with pytest.raises(ValueError) as error:
        call(world)
    assert str(error.value) == message
    world.step()
    assert world.linear_velocities()[0, 0] == pytest.approx(0.05, rel=1e-6)
    assert world.angular_velocities()[0, 2] == 0


def test_batch_forces_and_torques_last_through_step_n_as_in_worlds():
    batch = rebond.Batch(floating(), 3)
    rng = np.random.default_rng(7)
    forces = rng.normal(size=(3, 1, 3))
    points = rng.normal(size=(3, 1, 3))
    torques = rng.normal(size=(3, 1, 3))
    batch.apply_forces(forces, points=points)
    batch.apply_torques(torques)
    batch.step(3)
    for index in range(3):
        world = floating()
        world.apply_forces(forces[index], points=points[index])
        world.apply_torques(torques[index])
        world.step(3)
        np.testing.assert_array_equal(batch.positions()[index], world.positions())
        np.testing.assert_array_equal(batch.angular_velocities()[index], world.angular_velocities())
    with pytest.raises(ValueError, match=r"apply_forces: element \[1, 0\] the force held"):
        batch.apply_forces([[[0, 0, 0]], [[5e11, 0, 0]], [[0, 0, 0]]])
        batch.apply_forces([[[0, 0, 0]], [[6e11, 0, 0]], [[0, 0, 0]]])


def parameter_scene():
    """A box sliding on the ground, a ball dropping onto it, and a pendulum with a position motor."""
    world = rebond.World(timestep=1 / 60, substeps=4)
    world.add_body(GROUND, name="ground", type="static", position=[0, -0.5, 0])
    world.add_body({"type": "box", "half_extents": [0.5, 0.5, 0.5]}, name="box",
                   position=[0, 0.5, 0], linear_velocity=[3, 0, 0], can_sleep=False)
    world.add_body(BALL, name="ball", position=[4, 2, 3], can_sleep=False)
    world.add_body(BALL, name="bob", position=[-4, 3, 0], mass=1.0)
    world.add_joint("revolute", body_b="bob", anchor=[-5, 3, 0], axis=[0, 0, 1],
                    motor={"target_position": 0.5, "stiffness": 20.0, "damping": 1.0})
    return world


def randomise(rng, count):
    return {
        "masses": rng.uniform(0.5, 3.0, size=(count, 4)),
        "frictions": rng.uniform(0.1, 1.0, size=(count, 4)),
        "restitutions": rng.uniform(0.0, 0.8, size=(count, 4)),
        "gravity": rng.uniform(-12, -5, size=(count, 3)) * [0.1, 1, 0.1],
        "stiffness": rng.uniform(5, 50, size=(count, 1)),
        "damping": rng.uniform(0, 3, size=(count, 1)),
    }


def test_a_batch_with_per_env_parameters_equals_worlds_set_alike():
    count = 4
    values = randomise(np.random.default_rng(3), count)
    batch = rebond.Batch(parameter_scene(), count)
    batch.set_masses(values["masses"])
    batch.set_frictions(values["frictions"])
    batch.set_restitutions(values["restitutions"])
    batch.set_gravity(values["gravity"])
    batch.set_motor_gains(values["stiffness"], values["damping"])
    batch.step(90)
    for index in range(count):
        world = parameter_scene()
        world.set_masses(values["masses"][index])
        world.set_frictions(values["frictions"][index])
        world.set_restitutions(values["restitutions"][index])
        world.set_gravity(values["gravity"][index])
        world.set_motor_gains(values["stiffness"][index], values["damping"][index])
        world.step(90)
        for getter in ["positions", "rotations", "linear_velocities", "angular_velocities"]:
            np.testing.assert_array_equal(
                getattr(batch, getter)()[index], getattr(world, getter)(), err_msg=getter)
    # The worlds did differ: the parameters took.
    assert len({float(x) for x in batch.positions()[:, 1, 0]}) == count
    masses = batch.masses()
    assert masses.dtype == np.float32 and masses.shape == (count, 4)
    assert (masses[:, 0] == 0).all()  # the static ground has no mass
    np.testing.assert_array_equal(masses[:, 1:], values["masses"][:, 1:].astype(np.float32))
    np.testing.assert_array_equal(batch.frictions(), values["frictions"].astype(np.float32))
    np.testing.assert_array_equal(batch.restitutions(),
                                  values["restitutions"].astype(np.float32))
    np.testing.assert_array_equal(batch.gravity(), values["gravity"].astype(np.float32))
    gains = batch.motor_gains()
    assert gains.shape == (count, 1, 2)
    np.testing.assert_array_equal(gains[:, 0, 0], values["stiffness"][:, 0].astype(np.float32))


def test_a_heavier_body_accelerates_less():
    # a = F / m: 6 N on 1, 2 and 3 kg for 0.5 s gives 3, 1.5 and 1 m/s.
    batch = rebond.Batch(floating(timestep=0.05), 3)
    batch.set_masses([[1.0], [2.0], [3.0]])
    batch.apply_forces(np.tile([6.0, 0.0, 0.0], (3, 1, 1)))
    batch.step(10)
    np.testing.assert_allclose(batch.linear_velocities()[:, 0, 0], [3.0, 1.5, 1.0], rtol=1e-5)


def test_set_masses_scales_the_inertia_with_the_mass():
    # 2 kg → 8 kg: I = 0.2 → 0.8 kg·m², so 1 N·m for 0.1 s gives 0.125 rad/s.
    world = floating()
    world.set_masses([8.0])
    world.apply_torques([[0, 0, 1]])
    world.step()
    assert world.angular_velocities()[0, 2] == pytest.approx(0.125, rel=1e-6)


def test_set_gravity_changes_free_fall_and_wakes_bodies():
    world = rebond.World(timestep=0.05, substeps=2)
    world.add_body(GROUND, type="static", position=[0, -0.5, 0])
    world.add_body(BALL, position=[0, 0.5, 0])
    world.step(120)  # at rest, asleep
    world.set_gravity([0, 2.0, 0])
    np.testing.assert_array_equal(world.gravity(), np.float32([0, 2, 0]))
    world.step(20)  # one second upward
    assert world.linear_velocities()[1, 1] == pytest.approx(2.0, rel=1e-4)


def test_motor_gains_set_the_spring_of_position_motors():
    # A 1 kg slider on a prismatic joint along x, no gravity, its position motor's target 0 and
    # a constant 10 N push: it settles where the spring holds the push, x = F / k.
    world = rebond.World(gravity=[0, 0, 0], timestep=0.01, substeps=4)
    world.add_body(BALL, name="slider", mass=1.0)
    world.add_joint("prismatic", body_b="slider", anchor=[0, 0, 0], axis=[1, 0, 0],
                    motor={"target_position": 0.0, "stiffness": 10.0, "damping": 1.0})
    world.set_motor_gains([200.0], [30.0])
    np.testing.assert_array_equal(world.motor_gains(), [[200.0, 30.0]])
    world.apply_forces([[10, 0, 0]])
    world.step(500)  # 5 s, about 20 time constants of the overdamped spring
    # x = 10 / 200 = 0.05 m; measured 6e-8 m off (f32 rounding of 0.05); 1e-5 m is 0.02 %.
    assert world.positions()[0, 0] == pytest.approx(0.05, abs=1e-5)


def test_gains_of_velocity_and_torque_motors_are_ignored():
    world = rebond.World(gravity=[0, 0, 0])
    world.add_body(BALL, name="wheel")
    world.add_joint("revolute", body_b="wheel", anchor=[0, 0, 0], axis=[0, 0, 1],
                    motor={"target_velocity": 1.0})
    world.set_motor_gains([5.0], [1.0])
    np.testing.assert_array_equal(world.motor_gains(), [[0.0, 0.0]])


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda w: w.set_masses([0.0, 1.0, -2.0, 1.0]),
         "set_masses: element [2] must be from 1e-6 to 1e9 kg, got -2"),
        (lambda w: w.set_masses([0.0, 0.0, 1.0, 1.0]),
         "set_masses: element [1] must be from 1e-6 to 1e9 kg, got 0"),
        (lambda w: w.set_frictions([0.5, -0.1, 0.5, 0.5]),
         "set_frictions: element [1] must be at least 0, got -0.1"),
        (lambda w: w.set_restitutions([0.5, 0.5, 1.5, 0.5]),
         "set_restitutions: element [2] must be from 0 to 1, got 1.5"),
        (lambda w: w.set_gravity([0, -2000, 0]),
         "set_gravity: element [1] must be from -1000 to 1000 m/s², got -2000"),
        (lambda w: w.set_motor_gains([-1.0], [0.0]),
         "stiffness: element [0] must be from 0 to 1e12, got -1"),
        (lambda w: w.set_motor_gains([1.0], [1.0, 2.0]),
         "damping: got an array of shape (2,), expected (1,) (motors,)"),
    ],
)
def test_bad_parameters_are_refused_and_the_world_is_unchanged(call, message):
    world = parameter_scene()
    before = (world.masses(), world.frictions(), world.restitutions(), world.gravity(),
              world.motor_gains())
    with pytest.raises(ValueError) as error:
        call(world)
    assert str(error.value) == message
    after = (world.masses(), world.frictions(), world.restitutions(), world.gravity(),
             world.motor_gains())
    for old, new in zip(before, after):
        np.testing.assert_array_equal(old, new)


def test_batch_parameter_errors_name_the_world_and_change_no_world():
    batch = rebond.Batch(parameter_scene(), 2)
    masses = np.ones((2, 4))
    masses[1, 3] = -1
    before = batch.masses()
    with pytest.raises(ValueError) as error:
        batch.set_masses(masses)
    assert str(error.value) == "set_masses: element [1, 3] must be from 1e-6 to 1e9 kg, got -1"
    np.testing.assert_array_equal(batch.masses(), before)
    with pytest.raises(ValueError, match=r"set_gravity: element \[1, 2\] must be from"):
        batch.set_gravity([[0, -9, 0], [0, -9, 5000]])
    np.testing.assert_array_equal(batch.gravity(), np.float32([[0, -9.81, 0]] * 2))
