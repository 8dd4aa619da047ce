"""Batch.rollout and World.rollout: T steps of motor targets, recorded, with no Python between
steps, bit for bit as the calls one by one."""

import numpy as np
import pytest

import rebond
from test_state import ARM_SCENE, BODIES, JOINTS, bits

MOTORS = 2
SHAPES = {
    "positions": (BODIES, 3),
    "rotations": (BODIES, 4),
    "linear_velocities": (BODIES, 3),
    "angular_velocities": (BODIES, 3),
    "joint_positions": (JOINTS,),
    "joint_velocities": (JOINTS,),
}


def record(source):
    return {
        "positions": source.positions(),
        "rotations": source.rotations(),
        "linear_velocities": source.linear_velocities(),
        "angular_velocities": source.angular_velocities(),
        "joint_positions": source.joint_positions(),
        "joint_velocities": source.joint_velocities(),
    }


def controls(steps, count, seed=5):
    rng = np.random.default_rng(seed)
    values = rng.uniform(-2, 2, (steps, count, MOTORS)).astype(np.float32)
    values[:, :, 1] *= 0.2  # the slide's position target, m, within its limits
    return values


def test_a_batch_rollout_returns_every_step_with_the_documented_shapes():
    count, steps = 3, 7
    batch = rebond.Batch(ARM_SCENE, count)
    out = batch.rollout(controls(steps, count))
    assert set(out) == set(SHAPES)
    for name, inner in SHAPES.items():
        assert out[name].shape == (steps, count) + inner, name
        assert out[name].dtype == np.float32
    assert batch.rollout(np.zeros((0, count, MOTORS)))["positions"].shape == (0, count, BODIES, 3)


def test_a_batch_rollout_is_bit_identical_to_targets_and_single_steps():
    count, steps = 4, 40
    batch = rebond.Batch(ARM_SCENE, count)
    stepped = rebond.Batch(ARM_SCENE, count)
    worlds = [rebond.World.from_scene(ARM_SCENE) for _ in range(count)]
    given = controls(steps, count)
    out = batch.rollout(given)
    for t in range(steps):
        stepped.set_motor_targets(given[t])
        stepped.step(1)
        for index, world in enumerate(worlds):
            world.set_motor_targets(given[t, index])
            world.step(1)
        by_calls = record(stepped)
        alone = [record(world) for world in worlds]
        for name in SHAPES:
            np.testing.assert_array_equal(bits(out[name][t]), bits(by_calls[name]), name)
            for index in range(count):
                np.testing.assert_array_equal(
                    bits(out[name][t, index]), bits(alone[index][name]), name)
    # The batch stands where its last step left it.
    for name, now in record(batch).items():
        np.testing.assert_array_equal(bits(now), bits(out[name][-1]))
    # Different controls gave different worlds: nothing was shared.
    assert not np.array_equal(out["joint_positions"][-1, 0], out["joint_positions"][-1, 1])


def test_a_world_rollout_is_bit_identical_to_targets_and_single_steps():
    steps = 30
    world = rebond.World.from_scene(ARM_SCENE)
    alone = rebond.World.from_scene(ARM_SCENE)
    given = controls(steps, 1)[:, 0]
    out = world.rollout(given)
    for name, inner in SHAPES.items():
        assert out[name].shape == (steps,) + inner
    for t in range(steps):
        alone.set_motor_targets(given[t])
        alone.step(1)
        for name, now in record(alone).items():
            np.testing.assert_array_equal(bits(out[name][t]), bits(now), name)


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda b: b.rollout(np.zeros((5, 3, MOTORS))), ValueError,
         "controls: got an array of shape (5, 3, 2), expected (5, 2, 2) (T, count, motors)"),
        (lambda b: b.rollout(np.full((2, 2, MOTORS), np.nan)), ValueError,
         "controls: element [0, 0, 0] must be finite, got NaN"),
        (lambda b: b.rollout(1.0), ValueError, "controls: got a single number"),
        (lambda b: b.world(0).rollout(np.zeros((4, 3))), ValueError,
         "controls: got an array of shape (4, 3), expected (4, 2) (T, motors)"),
    ],
)
def test_bad_controls_raise_before_any_step(call, kind, message):
    batch = rebond.Batch(ARM_SCENE, 2)
    before = record(batch)
    with pytest.raises(kind) as error:
        call(batch)
    assert message in str(error.value)
    for name, now in record(batch).items():
        np.testing.assert_array_equal(bits(now), bits(before[name]))


def test_batch_rollout_releases_the_gil(counted_during):
    batch = rebond.Batch(ARM_SCENE, 64)
    given = controls(40, 64)
    during = counted_during(lambda: batch.rollout(given))
    assert during > 1000, "the counting thread was held up during the rollout"
