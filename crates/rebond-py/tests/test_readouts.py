"""Readouts: contact forces, joint reaction forces and torques, contact and sensor events, and
batched ray casts, against closed forms."""

import math

import numpy as np
import pytest

import rebond

GROUND = {"type": "box", "half_extents": [10.0, 0.5, 10.0]}
CRATE = {"type": "box", "half_extents": [0.5, 0.5, 0.5]}
BALL = {"type": "sphere", "radius": 0.5}
G = 9.81


def resting_crate(angle=0.0):
    """A 2 kg crate settled on a ground tilted by `angle` rad about z, never asleep."""
    world = rebond.World(timestep=1 / 60, substeps=4)
    half = [0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2)]
    up = np.array([-math.sin(angle), math.cos(angle), 0.0])
    world.add_body(GROUND, name="ground", type="static", position=list(-0.5 * up), rotation=half,
                   friction=1.0)
    world.add_body(CRATE, name="crate", mass=2.0, position=list(0.5 * up), rotation=half,
                   friction=1.0, can_sleep=False)
    return world


@pytest.mark.parametrize("angle", [0.0, 0.3])
def test_a_resting_crate_reads_its_weight_up(angle):
    # At rest the contacts carry the weight: the crate reads (0, m g, 0) = (0, 19.62, 0) N, the
    # ground the opposite. On the 0.3 rad slope (tan 0.3 = 0.31 < μ = 1, so it holds) friction
    # carries the downhill part, and the sum is vertical only if its sign is right.
    world = resting_crate(angle)
    world.step(30)  # half a second to settle from the first touch
    worst = 0.0
    for _ in range(60):
        world.step()
        forces = world.contact_forces()
        worst = max(worst, float(np.abs(forces[1] - [0, 2 * G, 0]).max()))
        np.testing.assert_array_equal(forces[0], -forces[1])
    assert forces.dtype == np.float32 and forces.shape == (2, 3)
    # Measured worst over the next second: 2e-5 N flat and on the slope, the soft contacts'
    # residual creep (1e-7 m/s); the first steps of settling read up to 1.8 N off on the slope.
    # 1e-3 N is 5e-5 of the weight.
    assert worst < 1e-3, worst


def test_a_crate_asleep_still_reads_its_weight():
    # Sleeping contacts keep the impulses they fell asleep with: the crate is still within a
    # few steps and asleep after the default 0.5 s of stillness, and after 5 s reads m g;
    # measured 1e-5 N off, as awake.
    world = rebond.World(timestep=1 / 60, substeps=4)
    world.add_body(GROUND, type="static", position=[0, -0.5, 0])
    world.add_body(CRATE, mass=2.0, position=[0, 0.5, 0])
    world.step(300)
    np.testing.assert_allclose(world.contact_forces()[1], [0, 2 * G, 0], atol=1e-3)


def test_contact_forces_of_a_falling_body_are_zero_and_batches_match_worlds():
    world = resting_crate()
    world.add_body(BALL, name="ball", position=[5, 5, 5])
    batch = rebond.Batch(world, 2)
    batch.step(3)
    world.step(3)
    np.testing.assert_array_equal(batch.contact_forces()[1], world.contact_forces())
    assert (world.contact_forces()[2] == 0).all()
    assert batch.contact_forces().shape == (2, 3, 3)


def pendulum(angle):
    """A 1 kg ball on a revolute joint 2 m above its centre, let go `angle` rad from the bottom."""
    world = rebond.World(gravity=[0, -G, 0], timestep=1 / 240, substeps=4)
    world.add_body(GROUND, name="ground", type="static", position=[0, -10, 0])
    world.add_body({"type": "sphere", "radius": 0.1}, name="bob", mass=1.0,
                   position=[2 * math.sin(angle), 2 - 2 * math.cos(angle), 0], can_sleep=False)
    world.add_joint("revolute", name="pivot", body_b="bob", anchor=[0, 2, 0], axis=[0, 0, 1])
    return world


def test_a_hanging_pendulum_joint_carries_its_weight():
    world = pendulum(0.0)
    world.step(60)
    forces = world.joint_forces()
    assert forces.dtype == np.float32 and forces.shape == (1, 3)
    # At rest the joint holds m g = 9.81 N up on the bob; measured 4e-7 N off, f32 rounding;
    # 1e-4 N is 1e-5 of the weight.
    np.testing.assert_allclose(forces[0], [0, G, 0], atol=1e-4)
    torques = world.joint_torques()
    assert torques.shape == (1, 3)
    # The hinge holds no torque about its free axis (measured exactly 0).
    assert abs(torques[0, 2]) < 1e-4


def test_a_swinging_pendulum_joint_pulls_m_g_plus_m_v2_over_l_at_the_bottom():
    # Let go at 60°: at the bottom T = m g + m v² / L, with v read there (about √(g L) = 4.4
    # m/s, so T ≈ 2 m g). The step nearest the bottom is found by the bob's x crossing 0.
    world = pendulum(math.radians(60))
    previous_x = world.positions()[1, 0]
    for _ in range(240):
        world.step()
        x = world.positions()[1, 0]
        if previous_x > 0 >= x:
            break
        previous_x = x
    else:
        pytest.fail("the bob never reached the bottom")
    speed = float(np.linalg.norm(world.linear_velocities()[1]))
    expected = 1.0 * G + 1.0 * speed**2 / 2.0
    force = world.joint_forces()[0]
    # The force is the step's mean while the bob turns 1/240 s · v / L ≈ 0.5° around the
    # bottom, where T changes as the cosine of that angle (4e-5 relative). Measured 2.7e-5
    # relative off; 1e-3 leaves room for the bottom falling anywhere in the step.
    assert force[1] == pytest.approx(expected, rel=1e-3)
    # Energy kept: v² = g L within 5e-4 measured (the solver's damping over 0.76 s).
    assert expected == pytest.approx(2 * G, rel=5e-3)
    # Sideways, the step's mean of T sin θ over ±0.25°: about 0.08 N at most; measured 0.04 N.
    assert abs(force[0]) < 0.1


def test_batch_joint_forces_match_worlds():
    batch = rebond.Batch(pendulum(0.5), 2)
    batch.step(30)
    world = pendulum(0.5)
    world.step(30)
    np.testing.assert_array_equal(batch.joint_forces()[0], world.joint_forces())
    np.testing.assert_array_equal(batch.joint_torques()[1], world.joint_torques())
    assert batch.joint_forces().shape == (2, 1, 3)


def test_contact_events_of_every_step_of_the_last_step_call():
    world = rebond.World(timestep=1 / 60, substeps=4)
    world.add_body(GROUND, name="ground", type="static", position=[0, -0.5, 0])
    world.add_body(BALL, name="ball", position=[0, 1.0, 0])
    world.add_body(CRATE, name="sensor", type="static", sensor=True, position=[0, 3, 0])
    world.add_body(BALL, name="dropper", position=[0, 5, 0])
    assert world.contact_events() == [] and world.sensor_events() == []
    world.step(30)  # the ball lands (0.5 m fall, 0.32 s) and the dropper enters the sensor
    assert world.contact_events()[0] == ("started", 0, 1)
    assert ("entered", 2, 3) in world.sensor_events()
    world.step(1)
    assert ("started", 0, 1) not in world.contact_events()  # only the last call's
    batch = rebond.Batch(world, 2)
    batch.step(40)
    world.step(40)
    assert batch.contact_events() == [world.contact_events()] * 2
    assert batch.sensor_events() == [world.sensor_events()] * 2
    assert ("exited", 2, 3) in world.sensor_events()


def ground_at(height):
    world = rebond.World()
    world.add_body(GROUND, name="ground", type="static", position=[0, height - 0.5, 0])
    world.add_body(BALL, name="ball", type="static", position=[3, height + 2, 0])
    return world


def test_rays_down_onto_the_ground_read_the_height():
    world = ground_at(0.0)
    origins = [[0, 1.5, 0], [1, 4, 2], [3, 10, 0], [50, 1, 0]]
    down = [[0, -1, 0]] * 4
    distances = world.ray_casts(origins, down)
    assert distances.dtype == np.float32 and distances.shape == (4,)
    # Exact in f32 for these heights; the ball's top at y = 2.5 stops the third ray at 7.5 m;
    # the fourth misses the 20 m wide ground.
    np.testing.assert_array_equal(distances, np.float32([1.5, 4, 7.5, math.inf]))
    distances, bodies, normals = world.ray_hits(origins, down)
    assert bodies.dtype == np.int64 and bodies.tolist() == [0, 0, 1, -1]
    np.testing.assert_array_equal(normals, [[0, 1, 0], [0, 1, 0], [0, 1, 0], [0, 0, 0]])
    short = world.ray_casts(origins, down, max_distance=2.0)
    np.testing.assert_array_equal(short, np.float32([1.5, math.inf, math.inf, math.inf]))
    assert world.ray_casts(np.zeros((0, 3)), np.zeros((0, 3))).shape == (0,)


def test_batched_rays_read_each_worlds_height():
    # Each world's range sensor at its own height: 2, 3 and 4 m above the ground.
    batch = rebond.Batch(ground_at(0.0), 3)
    origins = np.zeros((3, 2, 3))
    origins[:, :, 1] = [[2.0], [3.0], [4.0]]
    origins[:, 1, 2] = 5.0
    down = np.tile([0.0, -1.0, 0.0], (3, 2, 1))
    distances = batch.ray_casts(origins, down)
    assert distances.shape == (3, 2) and distances.dtype == np.float32
    np.testing.assert_array_equal(distances, np.float32([[2, 2], [3, 3], [4, 4]]))
    distances, bodies, normals = batch.ray_hits(origins, down)
    assert bodies.shape == (3, 2) and normals.shape == (3, 2, 3)
    assert (bodies == 0).all()
    world = ground_at(0.0)
    np.testing.assert_array_equal(world.ray_casts(origins[1], down[1]), distances[1])
    with pytest.raises(ValueError) as error:
        batch.ray_casts(origins, np.zeros((3, 2, 3)))
    assert str(error.value) == "ray_casts: ray [0, 0]: direction: vector has zero length"


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda w: w.ray_casts([[0, 1, 0]], [[0, 0, 0]]),
         "ray_casts: ray [0]: direction: vector has zero length"),
        (lambda w: w.ray_casts([[0, 1, 0]], [[0, -1, 0], [0, -1, 0]]),
         "directions: got 2 rays, origins has 1"),
        (lambda w: w.ray_casts([[0, 1]], [[0, -1]]),
         "origins: got an array of shape (1, 2), expected (1, 3) (rays, 3)"),
        (lambda w: w.ray_casts([[0, 1, 0]], [[0, -1, 0]], max_distance=0.0),
         "max_distance: must be positive, got 0"),
    ],
)
def test_bad_rays_are_refused(call, message):
    with pytest.raises(ValueError) as error:
        call(ground_at(0.0))
    assert str(error.value) == message
