"""Actuators from Python: names, control ranges and controls (World.set_controls and the Batch
twins, bit for bit as separate worlds), and the centre of mass and inertia readouts."""

import math
import re

import numpy as np
import pytest

import rebond

WHEEL = {"type": "box", "half_extents": [0.5, 0.5, 0.05]}


def wheels_scene():
    """Two 1 kg square plates (1 m sides) on revolute joints about z to the world, without
    gravity: a motor of gear 2 clamped to [-1, 1] on the first, a position actuator on the
    second."""
    return {
        "gravity": [0, 0, 0],
        "timestep": 0.01,
        "bodies": [
            {"name": "wheel", "shape": WHEEL, "mass": 1.0, "can_sleep": False},
            {"name": "dial", "shape": WHEEL, "position": [3, 0, 0], "mass": 1.0,
             "can_sleep": False},
        ],
        "joints": [
            {"name": "spin", "type": "revolute", "body_b": "wheel", "anchor": [0, 0, 0],
             "axis": [0, 0, 1]},
            {"name": "turn", "type": "revolute", "body_b": "dial", "anchor": [3, 0, 0],
             "axis": [0, 0, 1]},
        ],
        "actuators": [
            {"name": "drive", "joint": "spin", "type": "motor", "gear": 2, "ctrl_range": [-1, 1]},
            {"name": "servo", "joint": "turn", "type": "position", "kp": 20, "kv": 4},
        ],
    }


def bits(array):
    return np.ascontiguousarray(array).view(np.uint32)


def test_names_and_ranges_in_scene_order():
    world = rebond.World.from_scene(wheels_scene())
    assert world.actuator_names() == ["drive", "servo"]
    ranges = world.ctrl_ranges()
    assert ranges.shape == (2, 2) and ranges.dtype == np.float32
    np.testing.assert_array_equal(ranges[0], [-1, 1])
    np.testing.assert_array_equal(ranges[1], [-math.inf, math.inf])  # no ctrl_range: unclamped
    batch = rebond.Batch(wheels_scene(), 3)
    assert batch.actuator_names() == ["drive", "servo"]
    np.testing.assert_array_equal(batch.ctrl_ranges(), ranges)


def test_a_motor_gives_gear_times_the_clamped_control():
    world = rebond.World.from_scene(wheels_scene())
    world.set_controls([3.0, 0.0])  # clamped to 1: a torque of 2 N m
    world.step(100)
    # I = m (w² + h²) / 12 = 1/6 kg m² about z, so ω = τ t / I = 2 · 1 / (1/6) = 12 rad/s after
    # 1 s; a constant torque integrates exactly up to float32 rounding (1e-4 relative).
    spin = world.joint_velocities()[0]
    assert spin == pytest.approx(12.0, rel=1e-4)


def test_a_position_actuator_holds_its_target():
    world = rebond.World.from_scene(wheels_scene())
    world.set_controls([0.0, 0.5])
    world.step(600)
    # kp 20, kv 4 on I = 1/6: ω₀ = 11 rad/s, damping ratio 1.1, settled well within 6 s; the
    # implicit motor leaves no steady error beyond float32 rounding.
    assert world.joint_positions()[1] == pytest.approx(0.5, abs=1e-4)


def test_batch_controls_match_separate_worlds_bit_for_bit():
    rng = np.random.default_rng(0)
    controls = rng.uniform(-1.5, 1.5, size=(4, 30, 2)).astype(np.float32)
    batch = rebond.Batch(wheels_scene(), 4)
    worlds = [rebond.World.from_scene(wheels_scene()) for _ in range(4)]
    for step in range(30):
        batch.set_controls(controls[:, step])
        batch.step(2)
        for index, world in enumerate(worlds):
            world.set_controls(controls[index, step])
            world.step(2)
    for index, world in enumerate(worlds):
        np.testing.assert_array_equal(bits(batch.positions()[index]), bits(world.positions()))
        np.testing.assert_array_equal(
            bits(batch.joint_velocities()[index]), bits(world.joint_velocities())
        )
    assert np.any(batch.joint_velocities()[0] != batch.joint_velocities()[1])


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda w: w.set_controls([1.0]), "set_controls: got an array of shape (1,), expected (2,)"),
        (lambda w: w.set_controls([math.nan, 0]), "set_controls: element [0] must be finite"),
        (lambda w: w.set_controls("fast"), "set_controls: cannot be read as an array"),
    ],
)
def test_bad_controls_are_refused_and_change_nothing(call, message):
    world = rebond.World.from_scene(wheels_scene())
    world.set_controls([0.5, 0.2])
    before = world.save()
    with pytest.raises(ValueError, match=re.escape(message)):
        call(world)
    assert world.save() == before


def test_batch_controls_of_the_wrong_shape_are_refused():
    batch = rebond.Batch(wheels_scene(), 3)
    with pytest.raises(ValueError, match=r"set_controls: got an array of shape \(2,\), expected "
                                         r"\(3, 2\) \(count, actuators\)"):
        batch.set_controls([0.0, 1.0])


def test_a_scene_without_actuators_takes_empty_controls():
    world = rebond.World(gravity=[0, 0, 0])
    world.add_body({"type": "sphere", "radius": 0.5}, name="ball")
    assert world.actuator_names() == []
    assert world.ctrl_ranges().shape == (0, 2)
    world.set_controls(np.zeros(0))


def test_centers_of_mass_and_inertias():
    world = rebond.World.from_scene(wheels_scene())
    np.testing.assert_allclose(world.centers_of_mass()[1], [3, 0, 0], atol=1e-6)
    # A 1 kg plate 1 m × 1 m × 0.1 m: Ixx = Iyy = (1 + 0.01) / 12, Izz = 2 / 12, no products.
    expected = [1.01 / 12, 1.01 / 12, 2 / 12, 0, 0, 0]
    np.testing.assert_allclose(world.inertias()[0], expected, rtol=1e-5, atol=1e-7)
    # A quarter turn about x swaps the y and z moments in world axes: R I Rᵀ.
    half = math.sqrt(0.5)
    world.set_rotations([[half, 0, 0, half], [0, 0, 0, 1]])
    np.testing.assert_allclose(
        world.inertias()[0], [1.01 / 12, 2 / 12, 1.01 / 12, 0, 0, 0], rtol=1e-5, atol=1e-6
    )
    batch = rebond.Batch(wheels_scene(), 2)
    assert batch.centers_of_mass().shape == (2, 2, 3)
    assert batch.inertias().shape == (2, 2, 6)
