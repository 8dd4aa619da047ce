"""rebond.World: building, stepping, reading and writing state, queries, errors."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

import rebond

GROUND = {"type": "box", "half_extents": [10.0, 0.5, 10.0]}
BALL = {"type": "sphere", "radius": 0.5}


def ball_world(**settings):
    world = rebond.World(**settings)
    world.add_body(GROUND, name="ground", type="static", position=[0, -0.5, 0])
    world.add_body(BALL, name="ball", position=[0, 4, 0], restitution=0.5)
    return world


def test_a_dropped_ball_comes_to_rest_on_the_ground():
    world = ball_world()
    assert world.body_names() == ["ground", "ball"]
    world.step(180)
    positions = world.positions()
    assert positions.dtype == np.float32 and positions.shape == (2, 3)
    assert positions[1, 1] == pytest.approx(0.5, abs=0.01)
    assert np.abs(world.linear_velocities()[1]).max() < 0.05


def test_free_fall_follows_gravity_and_timestep():
    world = rebond.World(gravity=[0.0, -2.0, 0.0], timestep=0.05, substeps=2)
    world.add_body(BALL, position=[0, 100, 0])
    world.step(20)  # one second
    assert world.timestep == pytest.approx(0.05)
    assert world.linear_velocities()[0, 1] == pytest.approx(-2.0, rel=1e-5)
    assert world.positions()[0, 1] == pytest.approx(100 - 0.5 * 2.0, abs=0.06)


def test_getters_have_the_documented_shapes_and_types():
    world = ball_world()
    for getter, width in [
        (world.positions, 3),
        (world.rotations, 4),
        (world.linear_velocities, 3),
        (world.angular_velocities, 3),
    ]:
        array = getter()
        assert array.dtype == np.float32
        assert array.shape == (2, width)
    np.testing.assert_array_equal(world.rotations()[1], [0, 0, 0, 1])
    empty = rebond.World()
    assert empty.positions().shape == (0, 3)
    assert empty.rotations().shape == (0, 4)


def test_from_scene_reads_a_file_and_a_dict_alike(tmp_path):
    scene = {
        "bodies": [
            {"name": "ground", "type": "static", "shape": GROUND, "position": [0, -0.5, 0]},
            {"name": "ball", "shape": BALL, "position": [0, 3, 0], "angular_velocity": [0, 2, 0]},
        ]
    }
    path = tmp_path / "ball.json"
    path.write_text(json.dumps(scene))
    from_file = rebond.World.from_scene(str(path))
    from_path = rebond.World.from_scene(path)
    from_dict = rebond.World.from_scene(scene)
    for world in (from_file, from_path, from_dict):
        world.step(30)
    np.testing.assert_array_equal(from_file.positions(), from_dict.positions())
    np.testing.assert_array_equal(from_path.rotations(), from_dict.rotations())
    assert from_dict.angular_velocities()[1, 1] == pytest.approx(2.0)


def test_rolling_resistance_slows_a_rolling_ball_at_five_sevenths_c_g():
    world = rebond.World()
    world.add_body(GROUND, type="static", position=[0, -0.5, 0], friction=0.8)
    for index, resistance in enumerate([0.0, 0.1]):
        world.add_body(
            BALL, position=[0, 0.5, 3 * index - 1.5], linear_velocity=[2, 0, 0],
            angular_velocity=[0, 0, -4], friction=0.8, rolling_resistance=resistance,
        )
    world.step(60)
    free, resisted = world.linear_velocities()[1:, 0]
    # Without resistance it rolls on at 2 m/s; with c = 0.1 it loses 5/7 c g = 0.70 m/s in 1 s.
    assert free == pytest.approx(2.0, abs=1e-3)
    assert resisted == pytest.approx(2.0 - 5 / 7 * 0.1 * 9.81, abs=0.02)
    with pytest.raises(rebond.SceneError, match=r"bodies\[3\]\.rolling_resistance"):
        world.add_body(BALL, rolling_resistance=-0.1)


def test_numpy_values_are_accepted_in_scenes_and_bodies():
    world = rebond.World(gravity=np.array([0.0, -9.81, 0.0]), substeps=np.int64(4))
    index = world.add_body(
        {"type": "sphere", "radius": np.float32(0.25)}, position=np.array([1.0, 2.0, 3.0])
    )
    assert index == 0
    np.testing.assert_array_equal(world.positions()[0], [1.0, 2.0, 3.0])


def test_set_linear_velocities_and_apply_forces():
    world = rebond.World(gravity=[0, 0, 0], timestep=0.1, substeps=1)
    world.add_body(BALL, name="a", mass=2.0)
    world.add_body(BALL, name="b", position=[5, 0, 0], mass=2.0)
    world.set_linear_velocities(np.array([[1, 0, 0], [0, 0, 0]], dtype=np.float64))
    world.apply_forces([[0, 0, 0], [0, 4, 0]])
    world.step()
    velocities = world.linear_velocities()
    assert velocities[0] == pytest.approx([1, 0, 0])
    assert velocities[1] == pytest.approx([0, 0.2, 0])  # a / m * dt = 4 / 2 * 0.1
    world.step()  # the force was for the one step call only
    assert world.linear_velocities()[1] == pytest.approx([0, 0.2, 0])
    world.set_angular_velocities([[0, 0, 3], [0, 0, 0]])
    assert world.angular_velocities()[0, 2] == pytest.approx(3)


def test_motor_targets_drive_velocity_and_position_motors():
    world = rebond.World(gravity=[0, 0, 0])
    door = {"type": "box", "half_extents": [0.5, 1.0, 0.05]}
    world.add_body(door, name="wheel", position=[0, 0, 0], mass=1.0)
    world.add_body(door, name="slider", position=[3, 0, 0], mass=1.0)
    world.add_body(door, name="free", position=[6, 0, 0], mass=1.0)
    world.add_joint(
        "revolute", body_b="wheel", anchor=[0, 0, 0], axis=[0, 1, 0],
        motor={"target_velocity": 0.0, "max_force": 1000.0}, name="spin",
    )
    world.add_joint("ball", body_b=np.int64(2), anchor=[6, 0, 0], name="plain")
    world.add_joint(
        "prismatic", body_b=1, anchor=[3, 0, 0], axis=[1, 0, 0], name="push",
        # Critically damped on a 1 kg body: settles within a second.
        motor={"target_position": 0.0, "stiffness": 400.0, "damping": 40.0, "max_force": 1e4},
    )
    assert world.joint_names() == ["spin", "plain", "push"]
    assert world.motor_names() == ["spin", "push"]
    world.set_motor_targets(np.array([2.0, 0.5]))
    world.step(120)
    assert world.angular_velocities()[0, 1] == pytest.approx(2.0, abs=1e-3)
    assert world.positions()[1, 0] == pytest.approx(3.5, abs=0.01)


def test_ray_cast_reports_the_nearest_body():
    world = ball_world()
    hit = world.ray_cast([0, 10, 0], [0, -1, 0], 100.0)
    assert hit is not None
    assert (hit.body, hit.name) == (1, "ball")
    assert hit.distance == pytest.approx(5.5)
    assert hit.point == pytest.approx([0, 4.5, 0])
    assert hit.normal == pytest.approx([0, 1, 0])
    assert world.ray_cast([0, 10, 0], [0, -1, 0], 5.0) is None
    assert world.ray_cast([0, 10, 0], [0, 1, 0]) is None
    assert world.ray_cast([3, 10, 0], [0, -1, 0]).name == "ground"


def test_copy_steps_on_exactly_like_the_original():
    world = ball_world()
    world.step(10)
    twin = world.copy()
    world.step(50)
    twin.step(50)
    np.testing.assert_array_equal(world.positions(), twin.positions())
    np.testing.assert_array_equal(world.angular_velocities(), twin.angular_velocities())


def test_a_loaded_world_steps_on_bit_for_bit_like_the_saved_one():
    world = ball_world()
    world.add_body({"type": "box", "half_extents": [0.3, 0.3, 0.3]}, name="crate", position=[1, 2, 0])
    world.add_joint("ball", body_a="ball", body_b="crate", anchor=[0.5, 3, 0], friction=0.1)
    world.step(40)
    data = world.save()
    assert isinstance(data, bytes) and data[:8] == b"REBONDSC"
    restored = rebond.World.load(data)
    assert restored.body_names() == world.body_names()
    world.step(60)
    restored.step(60)
    for getter in ["positions", "rotations", "linear_velocities", "angular_velocities"]:
        np.testing.assert_array_equal(getattr(world, getter)(), getattr(restored, getter)())


def test_bytes_that_are_not_a_saved_world_raise_state_error():
    data = ball_world().save()
    damaged = bytearray(data)
    damaged[len(data) // 2] ^= 1
    for bad, message in [
        (b"not a state", "not a rebond state file"),
        (data[:-3], "truncated state"),
        (bytes(damaged), "damaged state"),
    ]:
        with pytest.raises(rebond.StateError, match=message):
            rebond.World.load(bad)


def test_step_releases_the_gil(counted_during):
    world = rebond.World(gravity=[0, -9.81, 0])
    for index in range(400):
        world.add_body(BALL, position=[(index % 20) * 1.1, 1 + index // 20 * 1.1, 0])
    during = counted_during(lambda: world.step(60))
    assert during > 1000, "the counting thread was held up while the world stepped"


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda w: w.add_body({"type": "sphere", "radius": -1}), rebond.SceneError,
         "bodies[2].shape.radius: must be positive, got -1"),
        (lambda w: w.add_body({"type": "sphere", "radius": math.nan}), rebond.SceneError,
         "bodies[2].shape.radius: must be finite, got NaN"),
        (lambda w: w.add_body(BALL, mass=math.inf), rebond.SceneError,
         "bodies[2].mass: must be finite, got inf"),
        (lambda w: w.add_body(BALL, name="ball"), rebond.SceneError,
         'bodies[2].name: duplicate name "ball": bodies[1] and bodies[2] both have it'),
        (lambda w: w.add_body(BALL, colour="red"), rebond.SceneError, "bodies[2].colour: unknown field"),
        (lambda w: w.add_joint("revolute", body_b="ball"), rebond.SceneError,
         "joints[0].axis: required field is missing (a revolute joint needs it)"),
        (lambda w: w.add_joint("ball", body_b="nobody"), rebond.SceneError,
         'joints[0].body_b: no body is named "nobody"'),
        (lambda w: w.add_joint("ball", body_b=7), ValueError,
         "joints[0].body_b: no body has index 7 (2 bodies)"),
        (lambda w: w.set_linear_velocities(np.zeros((3, 3))), ValueError,
         "set_linear_velocities: got an array of shape (3, 3), expected (2, 3) (bodies, 3)"),
        (lambda w: w.apply_forces([[0, 0, 0], [0, math.nan, 0]]), ValueError,
         "apply_forces: element [1, 1] must be finite, got NaN"),
        (lambda w: w.set_linear_velocities("fast"), ValueError,
         "set_linear_velocities: cannot be read as an array of float32 numbers"),
        (lambda w: w.set_motor_targets([1.0]), ValueError,
         "set_motor_targets: got an array of shape (1,), expected (0,) (motors,)"),
        (lambda w: w.ray_cast([0, 0, 0], [0, 0, 0]), ValueError,
         "ray_cast: direction: vector has zero length"),
        (lambda w: w.ray_cast([0, 0, 0], [0, 1, 0], -1.0), ValueError, "ray_cast: max_distance"),
        (lambda w: w.step(-2), ValueError, "n: must not be negative, got -2"),
        (lambda w: rebond.World(timestep=0), rebond.SceneError, "timestep: must be positive, got 0"),
        (lambda w: rebond.World(timestep=1.0), rebond.SceneError,
         "timestep: must lie between 0.0001 and 0.1 (the engine's limits), got 1"),
        (lambda w: rebond.World(gravity=[0, -1e30, 0]), rebond.SceneError,
         "gravity: must not exceed 1e3 (the engine's limit), got 1e30"),
        (lambda w: w.add_body({"type": "sphere", "radius": 1e6}), rebond.SceneError,
         "bodies[2].shape.radius: must lie between 0.001 and 100000, got 1000000"),
        (lambda w: rebond.World(substeps=0), rebond.SceneError, "substeps: must lie between 1 and 64"),
        (lambda w: rebond.World(gravity=[0, 1]), rebond.SceneError, "gravity: invalid length 2"),
        (lambda w: rebond.World.from_scene({"bodies": [{"shape": {"type": "cone"}}]}),
         rebond.SceneError, "bodies[0].shape.type: unknown variant `cone`"),
        (lambda w: rebond.World.from_scene({"bodies": [{1: 2}]}), rebond.SceneError,
         "bodies[0]: keys must be strings"),
        (lambda w: rebond.World.from_scene(42), ValueError,
         "scene: expected a path, a dict in the scene format or a World, got a int"),
    ],
)
def test_bad_input_raises_an_exception_naming_the_field(call, kind, message):
    world = ball_world()
    with pytest.raises(kind) as raised:
        call(world)
    assert str(raised.value).startswith(message), str(raised.value)


def test_a_missing_file_is_an_os_error_with_the_command_line_message(tmp_path):
    missing = tmp_path / "missing.json"
    with pytest.raises(OSError) as raised:
        rebond.World.from_scene(str(missing))
    assert str(raised.value).startswith(f"{missing}: cannot read scene: ")


def command_line():
    path = os.environ.get("REBOND_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("REBOND_CLI does not name the built `rebond` binary (scripts/test sets it)")
    return path


@pytest.mark.parametrize(
    "scene",
    [
        {"bodies": [{"shape": {"type": "sphere", "radius": -2}}]},
        {"bodies": [{"shape": {"type": "sphere", "radius": 1}, "velocity": [1, 0, 0]}]},
        {"gravity": [0, 0], "bodies": []},
        {"bodies": [{"shape": BALL}], "joints": [{"type": "hinge", "body_b": "body0"}]},
        {"bodies": [{"shape": BALL}], "joints": [{"type": "prismatic", "body_b": "body0"}]},
    ],
)
def test_scene_errors_are_the_command_line_messages(tmp_path, scene):
    cli = command_line()
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(scene))
    run = subprocess.run([cli, "run", str(path), "--steps", "1"], capture_output=True, text=True)
    assert run.returncode == 2
    with pytest.raises(rebond.SceneError) as raised:
        rebond.World.from_scene(str(path))
    assert run.stderr.strip() == f"error: {raised.value}"
