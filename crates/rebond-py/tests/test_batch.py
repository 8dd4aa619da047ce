"""rebond.Batch: copies of a world stepped in parallel, bit for bit as separate worlds."""

import numpy as np
import pytest

import rebond

MIXED_SCENE = {
    "timestep": 1 / 60,
    "bodies": [
        {"name": "ground", "type": "static",
         "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
        {"name": "box0", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [0, 0.5, 0], "friction": 0.6},
        {"name": "box1", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [0.1, 1.5, 0], "rotation": [0, 0.2, 0, 1]},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.3},
         "position": [-2, 3, 0], "restitution": 0.5},
        {"name": "capsule", "shape": {"type": "capsule", "radius": 0.2, "half_height": 0.4},
         "position": [2, 2, 0.5], "rotation": [0.3, 0, 0.4, 1]},
        {"name": "arm", "shape": {"type": "box", "half_extents": [0.6, 0.05, 0.05]},
         "position": [0.6, 4, 3], "can_sleep": False},
    ],
    "joints": [
        {"name": "shoulder", "type": "revolute", "body_b": "arm", "anchor": [0, 4, 3],
         "axis": [0, 0, 1], "motor": {"target_velocity": 1.0, "max_force": 50.0}},
    ],
}


def bits(array):
    return np.ascontiguousarray(array).view(np.uint32)


def states(source):
    return [source.positions(), source.rotations(), source.linear_velocities(),
            source.angular_velocities()]


def test_a_batch_is_bit_identical_to_worlds_stepped_one_by_one():
    count, steps = 12, 90
    batch = rebond.Batch(MIXED_SCENE, count)
    worlds = [rebond.World.from_scene(MIXED_SCENE) for _ in range(count)]
    bodies = batch.body_count
    rng = np.random.default_rng(7)
    for step in range(steps):
        forces = rng.normal(0, 20, size=(count, bodies, 3)).astype(np.float32)
        targets = rng.uniform(-2, 2, size=(count, 1)).astype(np.float32)
        batch.apply_forces(forces)
        batch.set_motor_targets(targets)
        for index, world in enumerate(worlds):
            world.apply_forces(forces[index])
            world.set_motor_targets(targets[index])
        if step == 30:
            kicks = rng.normal(0, 2, size=(count, bodies, 3)).astype(np.float32)
            batch.set_linear_velocities(kicks)
            for index, world in enumerate(worlds):
                world.set_linear_velocities(kicks[index])
        if step == 60:
            batch.reset([1, 4])
            for index in (1, 4):
                worlds[index] = rebond.World.from_scene(MIXED_SCENE)
        batch.step()
        for world in worlds:
            world.step()
    batch_states = states(batch)
    for index, world in enumerate(worlds):
        for in_batch, alone in zip(batch_states, states(world)):
            np.testing.assert_array_equal(bits(in_batch[index]), bits(alone))
    # The inputs differed between worlds, so their states do too: nothing was shared.
    assert not np.array_equal(batch_states[0][0], batch_states[0][2])


def test_getters_have_a_leading_batch_axis():
    batch = rebond.Batch(MIXED_SCENE, 3)
    assert (batch.count, len(batch), batch.body_count) == (3, 3, 6)
    assert batch.body_names() == ["ground", "box0", "box1", "ball", "capsule", "arm"]
    assert batch.motor_names() == ["shoulder"] and batch.joint_names() == ["shoulder"]
    assert batch.positions().shape == (3, 6, 3)
    assert batch.rotations().shape == (3, 6, 4)
    assert batch.linear_velocities().dtype == np.float32
    assert batch.timestep == pytest.approx(1 / 60)


def test_reset_returns_chosen_worlds_to_the_start():
    batch = rebond.Batch(MIXED_SCENE, 4)
    start = batch.positions()
    batch.step(30)
    moved = batch.positions()
    batch.reset([0, 2])
    now = batch.positions()
    np.testing.assert_array_equal(now[[0, 2]], start[[0, 2]])
    np.testing.assert_array_equal(now[[1, 3]], moved[[1, 3]])
    batch.reset(np.array([3]))
    np.testing.assert_array_equal(batch.positions()[3], start[3])
    batch.reset()
    np.testing.assert_array_equal(batch.positions(), start)


def test_a_batch_of_a_world_starts_from_its_current_state():
    world = rebond.World.from_scene(MIXED_SCENE)
    world.step(20)
    batch = rebond.Batch(world, 2)
    np.testing.assert_array_equal(batch.positions()[1], world.positions())
    world.step(5)
    batch.step(5)
    np.testing.assert_array_equal(bits(batch.positions()[0]), bits(world.positions()))
    copy = batch.world(1)
    copy.step(5)
    batch.step(5)
    np.testing.assert_array_equal(bits(batch.positions()[1]), bits(copy.positions()))


def test_batch_step_releases_the_gil(counted_during):
    batch = rebond.Batch(MIXED_SCENE, 64)
    during = counted_during(lambda: batch.step(40))
    assert during > 1000, "the counting thread was held up while the batch stepped"


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda b: b.apply_forces(np.zeros((3, 6, 3))), ValueError,
         "apply_forces: got an array of shape (3, 6, 3), expected (2, 6, 3) (count, bodies, 3)"),
        (lambda b: b.set_linear_velocities(np.full((2, 6, 3), np.inf)), ValueError,
         "set_linear_velocities: element [0, 0, 0] must be finite, got inf"),
        (lambda b: b.set_motor_targets(np.zeros(2)), ValueError,
         "set_motor_targets: got an array of shape (2,), expected (2, 1) (count, motors)"),
        (lambda b: b.reset([0, 2]), IndexError, "indices[1]: 2 is not a world of this batch (0 to 1)"),
        (lambda b: b.reset([-1]), IndexError, "indices[0]: -1 is not a world of this batch"),
        (lambda b: b.reset(["a"]), ValueError, "indices: expected whole numbers"),
        (lambda b: b.world(5), IndexError, "index: 5 is not a world of this batch (0 to 1)"),
        (lambda b: rebond.Batch(MIXED_SCENE, 0), ValueError, "count: must be at least 1, got 0"),
        (lambda b: rebond.Batch(MIXED_SCENE, -3), ValueError, "count: must be at least 1, got -3"),
        (lambda b: b.world(-1), IndexError, "index: -1 is not a world of this batch (0 to 1)"),
        (lambda b: b.step(-1), ValueError, "n: must not be negative, got -1"),
        (lambda b: rebond.Batch({"bodies": [{"shape": {"type": "sphere"}}]}, 2), rebond.SceneError,
         "bodies[0].shape.radius: required field is missing"),
    ],
)
def test_bad_input_raises_an_exception_naming_the_field(call, kind, message):
    batch = rebond.Batch(MIXED_SCENE, 2)
    with pytest.raises(kind) as raised:
        call(batch)
    assert str(raised.value).startswith(message), str(raised.value)
