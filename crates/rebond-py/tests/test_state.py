"""Setting any state: teleports, joint coordinates read and set, and Batch.reset with states."""

import math
import os

import numpy as np
import pytest

import rebond

# A floating torso with a two-link arm (revolute shoulder about z, prismatic forearm along x),
# a pendulum on a revolute pivot to the world, a ball-jointed bob, and a box on the ground.
ARM_SCENE = {
    "timestep": 1 / 60,
    "bodies": [
        {"name": "ground", "type": "static",
         "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
        {"name": "torso", "shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]},
         "position": [0, 3, 0], "can_sleep": False},
        {"name": "upper", "shape": {"type": "box", "half_extents": [0.5, 0.05, 0.05]},
         "position": [0.8, 3, 0], "can_sleep": False},
        {"name": "fore", "shape": {"type": "box", "half_extents": [0.5, 0.04, 0.04]},
         "position": [1.8, 3, 0], "can_sleep": False},
        {"name": "bob", "shape": {"type": "sphere", "radius": 0.2}, "mass": 1.0,
         "position": [5, 2, 0]},
        {"name": "hanging", "shape": {"type": "sphere", "radius": 0.1},
         "position": [-3, 2, 0]},
        {"name": "box", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [-6, 0.5, 0]},
    ],
    "joints": [
        {"name": "shoulder", "type": "revolute", "body_a": "torso", "body_b": "upper",
         "anchor": [0.3, 3, 0], "axis": [0, 0, 1],
         "motor": {"target_velocity": 0.0, "max_force": 50.0}},
        {"name": "slide", "type": "prismatic", "body_a": "upper", "body_b": "fore",
         "anchor": [1.3, 3, 0], "axis": [1, 0, 0], "limits": [-0.5, 0.5],
         "motor": {"target_position": 0.0, "stiffness": 200.0, "damping": 20.0,
                   "max_force": 100.0}},
        {"name": "pivot", "type": "revolute", "body_b": "bob", "anchor": [5, 4, 0],
         "axis": [0, 0, 1]},
        {"name": "neck", "type": "ball", "body_b": "hanging", "anchor": [-3, 3, 0]},
    ],
}
JOINTS = 4
BODIES = 7


def bits(array):
    return np.ascontiguousarray(array).view(np.uint32)


def world():
    return rebond.World.from_scene(ARM_SCENE)


def zero_rotation_at(index):
    rotations = np.tile(np.array([0, 0, 0, 1], np.float32), (BODIES, 1))
    rotations[index] = 0
    return rotations


def everything(source):
    return [source.positions(), source.rotations(), source.linear_velocities(),
            source.angular_velocities(), source.joint_positions(), source.joint_velocities()]


def test_joint_coordinates_have_one_entry_per_joint_and_nan_without_a_coordinate():
    w = world()
    assert w.joint_names() == ["shoulder", "slide", "pivot", "neck"]
    for read in (w.joint_positions(), w.joint_velocities()):
        assert read.shape == (JOINTS,) and read.dtype == np.float32
        np.testing.assert_array_equal(read[:3], [0, 0, 0])
        assert math.isnan(read[3])
    batch = rebond.Batch(ARM_SCENE, 3)
    assert batch.joint_positions().shape == (3, JOINTS)
    assert batch.joint_velocities().dtype == np.float32


def test_a_pendulum_set_to_an_angle_reads_it_and_hangs_there():
    # The bob hangs 2 m below its pivot at (5, 4, 0); turned by θ about +z it sits at
    # pivot + R(θ)(0, -2, 0) = (5 + 2 sin θ, 4 - 2 cos θ, 0). f32 positions near 5 m: 1e-5 m.
    w = world()
    angle = 1.1
    w.set_joint_positions([0, 0, angle, np.nan])
    assert w.joint_positions()[2] == pytest.approx(angle, abs=1e-5)
    bob = w.positions()[4]
    np.testing.assert_allclose(
        bob, [5 + 2 * math.sin(angle), 4 - 2 * math.cos(angle), 0], atol=1e-5)
    # Released from rest at θ, it swings back through the bottom: the angle falls.
    w.step(10)
    assert w.joint_positions()[2] < angle


def test_three_turns_read_six_pi():
    w = world()
    w.set_joint_positions([0, 0, 6 * math.pi, np.nan])
    assert w.joint_positions()[2] == pytest.approx(6 * math.pi, abs=1e-5)


def test_joint_positions_and_rates_set_on_the_arm_read_back_and_the_torso_stays():
    w = world()
    torso = (w.positions()[1].copy(), w.rotations()[1].copy())
    w.set_joint_positions([0.8, 0.3, -0.4, np.nan])
    np.testing.assert_allclose(w.joint_positions()[:3], [0.8, 0.3, -0.4], atol=1e-5)
    np.testing.assert_array_equal(w.positions()[1], torso[0])
    np.testing.assert_array_equal(w.rotations()[1], torso[1])
    w.set_joint_velocities([1.5, -0.25, 2.0, np.nan])
    np.testing.assert_allclose(w.joint_velocities()[:3], [1.5, -0.25, 2.0], atol=1e-5)
    # A round trip through the readings (NaN at the ball joint) changes no coordinate.
    w.set_joint_positions(w.joint_positions())
    np.testing.assert_allclose(w.joint_positions()[:3], [0.8, 0.3, -0.4], atol=1e-5)


def test_teleports_set_poses_normalise_rotations_and_wake_bodies():
    w = world()
    w.step(240)  # the box on the ground falls asleep
    assert np.all(w.linear_velocities()[6] == 0)
    positions = w.positions()
    positions[6] = [-6, 4, 0]
    w.set_positions(positions)
    np.testing.assert_array_equal(w.positions()[6], [-6, 4, 0])
    rotations = w.rotations()
    rotations[6] = [0, 0, 2, 0]
    w.set_rotations(rotations)
    np.testing.assert_allclose(w.rotations()[6], [0, 0, 1, 0], atol=1e-7)
    w.step()
    assert w.linear_velocities()[6][1] < 0, "the teleported box did not wake and fall"


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda w: w.set_positions(np.zeros((3, 3))), ValueError,
         "set_positions: got an array of shape (3, 3), expected (7, 3) (bodies, 3)"),
        (lambda w: w.set_positions(np.full((7, 3), np.nan)), ValueError,
         "set_positions: element [0, 0] must be finite, got NaN"),
        (lambda w: w.set_positions(np.full((7, 3), 2e4)), ValueError,
         "set_positions: element [0] must lie between -10000 and 10000 m, got 20000"),
        (lambda w: w.set_rotations(zero_rotation_at(2)), ValueError,
         "set_rotations: element [2] is a zero quaternion [0.0, 0.0, 0.0, 0.0]"),
        (lambda w: w.set_rotations(np.zeros((7, 3))), ValueError,
         "set_rotations: got an array of shape (7, 3), expected (7, 4) (bodies, 4)"),
        (lambda w: w.set_joint_positions([0, 0, 0, 0]), ValueError,
         "set_joint_positions: element [3] is joint 'neck', which has no coordinate"),
        (lambda w: w.set_joint_positions([0, np.nan, 0, np.nan]), ValueError,
         "set_joint_positions: element [1] must be finite, got NaN"),
        (lambda w: w.set_joint_velocities([0, 0, 2e4, np.nan]), ValueError,
         "set_joint_velocities: element [2] must lie between -10000 and 10000, got 20000"),
        (lambda w: w.set_joint_positions([0, 0, 0]), ValueError,
         "set_joint_positions: got an array of shape (3,), expected (4,) (joints,)"),
        (lambda w: w.set_joint_velocities("fast"), ValueError,
         "set_joint_velocities: cannot be read as an array of float32 numbers"),
    ],
)
def test_bad_states_raise_naming_the_element_and_leave_the_world_unchanged(call, kind, message):
    w = world()
    w.set_joint_positions([0.5, 0.1, 0.2, np.nan])
    before = everything(w)
    with pytest.raises(kind) as error:
        call(w)
    assert message in str(error.value)
    for after, then in zip(everything(w), before):
        np.testing.assert_array_equal(bits(after), bits(then))


def test_batch_setters_are_bit_identical_to_separate_worlds():
    count = 5
    batch = rebond.Batch(ARM_SCENE, count)
    worlds = [world() for _ in range(count)]
    rng = np.random.default_rng(3)
    positions = batch.positions() + rng.normal(0, 0.1, (count, BODIES, 3)).astype(np.float32)
    rotations = rng.normal(0, 1, (count, BODIES, 4)).astype(np.float32)
    angles = rng.uniform(-1, 1, (count, JOINTS)).astype(np.float32)
    angles[:, 1] *= 0.4
    angles[:, 3] = np.nan
    rates = rng.uniform(-2, 2, (count, JOINTS)).astype(np.float32)
    rates[:, 3] = np.nan
    batch.set_positions(positions)
    batch.set_rotations(rotations)
    batch.set_joint_positions(angles)
    batch.set_joint_velocities(rates)
    for index, w in enumerate(worlds):
        w.set_positions(positions[index])
        w.set_rotations(rotations[index])
        w.set_joint_positions(angles[index])
        w.set_joint_velocities(rates[index])
    batch.step(20)
    for w in worlds:
        w.step(20)
    for in_batch, alone in zip(everything(batch), zip(*[everything(w) for w in worlds])):
        for index in range(count):
            np.testing.assert_array_equal(bits(in_batch[index]), bits(alone[index]))


def test_reset_with_states_sets_them_on_the_chosen_worlds_only():
    batch = rebond.Batch(ARM_SCENE, 4)
    start = batch.positions()
    batch.step(30)
    moved = everything(batch)
    angles = np.array([[0.3, 0.2, 0.9, np.nan], [-0.3, -0.1, -0.9, np.nan]], np.float32)
    rates = np.array([[1, 0, 0, np.nan], [0, 0, -1, np.nan]], np.float32)
    batch.reset([2, 0], joint_positions=angles, joint_velocities=rates)
    now = everything(batch)
    np.testing.assert_allclose(now[4][[2, 0], :3], angles[:, :3], atol=1e-5)
    np.testing.assert_allclose(now[5][[2, 0], :3], rates[:, :3], atol=1e-5)
    # The torso (a root) is back at its start; worlds 1 and 3 are untouched.
    np.testing.assert_array_equal(now[0][[2, 0], 1], start[[2, 0], 1])
    for after, then in zip(now, moved):
        np.testing.assert_array_equal(bits(after[[1, 3]]), bits(then[[1, 3]]))
    # The same as a fresh world given the same calls.
    alone = world()
    alone.set_joint_positions(angles[0])
    alone.set_joint_velocities(rates[0])
    for in_batch, single in zip(now, everything(alone)):
        np.testing.assert_array_equal(bits(in_batch[2]), bits(single))


def test_reset_with_every_state_matches_the_setters_in_order():
    batch = rebond.Batch(ARM_SCENE, 2)
    rng = np.random.default_rng(11)
    states = {
        "positions": batch.positions()[:1] + np.float32(0.5),
        "rotations": rng.normal(0, 1, (1, BODIES, 4)).astype(np.float32),
        "linear_velocities": rng.normal(0, 1, (1, BODIES, 3)).astype(np.float32),
        "angular_velocities": rng.normal(0, 1, (1, BODIES, 3)).astype(np.float32),
        "joint_positions": np.array([[0.2, 0.1, 0.4, np.nan]], np.float32),
        "joint_velocities": np.array([[0.5, 0.0, -0.5, np.nan]], np.float32),
    }
    batch.step(5)
    batch.reset([1], **states)
    alone = world()
    alone.set_positions(states["positions"][0])
    alone.set_rotations(states["rotations"][0])
    alone.set_joint_positions(states["joint_positions"][0])
    alone.set_linear_velocities(states["linear_velocities"][0])
    alone.set_angular_velocities(states["angular_velocities"][0])
    alone.set_joint_velocities(states["joint_velocities"][0])
    for in_batch, single in zip(everything(batch), everything(alone)):
        np.testing.assert_array_equal(bits(in_batch[1]), bits(single))


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda b: b.reset([0, 1], positions=np.zeros((3, BODIES, 3))), ValueError,
         "positions: got an array of shape (3, 7, 3), expected (2, 7, 3) "
         "(len(indices), bodies, 3)"),
        (lambda b: b.reset([5], positions=np.zeros((1, BODIES, 3))), IndexError,
         "indices[0]: 5 is not a world of this batch (0 to 2)"),
        (lambda b: b.reset(rotations=np.zeros((3, BODIES, 4))), ValueError,
         "rotations: element [0, 0] is a zero quaternion"),
        (lambda b: b.reset([1], joint_positions=np.zeros((1, JOINTS))), ValueError,
         "joint_positions: element [0, 3] is joint 'neck', which has no coordinate"),
        (lambda b: b.reset([1], joint_velocities=np.full((1, JOINTS), np.inf)), ValueError,
         "joint_velocities: element [0, 0] must be finite, got inf"),
        (lambda b: b.set_positions(np.zeros((2, BODIES, 3))), ValueError,
         "set_positions: got an array of shape (2, 7, 3), expected (3, 7, 3) "
         "(count, bodies, 3)"),
        (lambda b: b.set_joint_positions(np.zeros((3, JOINTS))), ValueError,
         "set_joint_positions: element [0, 3] is joint 'neck'"),
    ],
)
def test_bad_batch_states_raise_and_leave_the_batch_unchanged(call, kind, message):
    batch = rebond.Batch(ARM_SCENE, 3)
    batch.step(10)
    before = everything(batch)
    with pytest.raises(kind) as error:
        call(batch)
    assert message in str(error.value)
    for after, then in zip(everything(batch), before):
        np.testing.assert_array_equal(bits(after), bits(then))



def test_the_docs_reset_example_runs_and_sets_the_angles(monkeypatch):
    from conftest import ROOT

    text = open(os.path.join(ROOT, "docs", "python.md"), encoding="utf-8").read()
    section = text.split("## State and joint coordinates", 1)[1]
    block = section.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)
    names = {}
    exec(compile(block, "docs/python.md", "exec"), names)
    batch, done, angles = names["batch"], names["done"], names["angles"]
    read = batch.joint_positions()[done]
    pivot = names["names"].index("rod_pivot")
    np.testing.assert_allclose(read[:, pivot], angles[:, pivot], atol=1e-5)
