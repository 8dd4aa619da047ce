"""Pictures: ``World.render``, ``World.render_camera`` and ``Batch.render``, and the video
example."""

import math
import os

import numpy as np
import pytest
from PIL import Image

import rebond
import video

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
PENDULUM = os.path.join(ROOT, "scenes", "pendulum.json")


def camera_axes(camera, height):
    """The camera's position, its forward, right and up unit vectors, and its focal length in
    pixels, by the camera maths of docs/python.md."""
    position, target, up = (np.array(camera[key], dtype=float) for key in ("position", "target", "up"))
    forward = (target - position) / np.linalg.norm(target - position)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    focal = height / 2 / math.tan(math.radians(camera["fov"]) / 2)
    return position, forward, right, np.cross(right, forward), focal


def project(camera, point, width, height):
    """The picture point (column, row, pixels from the top-left corner) and depth (m) of a world
    point."""
    position, forward, right, up, focal = camera_axes(camera, height)
    offset = np.asarray(point, dtype=float) - position
    x, y, z = offset @ right, offset @ up, offset @ forward
    return width / 2 + focal * x / z, height / 2 - focal * y / z, z


def angles_from(camera, point, width, height):
    """The angle (rad) between each pixel centre's ray and the direction to ``point``."""
    position, forward, right, up, focal = camera_axes(camera, height)
    columns, rows = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    rays = (
        forward[None, None, :]
        + ((columns - width / 2) / focal)[..., None] * right
        + ((height / 2 - rows) / focal)[..., None] * up
    )
    rays /= np.linalg.norm(rays, axis=-1, keepdims=True)
    direction = np.asarray(point, dtype=float) - position
    direction /= np.linalg.norm(direction)
    return np.arccos(np.clip(rays @ direction, -1.0, 1.0))


def floating_world():
    """A world without gravity or ground."""
    return rebond.World(gravity=(0, 0, 0))


CAMERA = {"position": [1.0, 2.0, 6.0], "target": [0.5, 0.3, 0.0], "fov": 50, "up": [0, 1, 0]}


def test_a_picture_is_height_by_width_by_three_bytes():
    world = rebond.World.from_scene(PENDULUM)
    picture = world.render(64, 48)
    assert picture.shape == (48, 64, 3)
    assert picture.dtype == np.uint8
    assert picture.flags["C_CONTIGUOUS"]


def test_a_ball_changes_the_pixels_where_it_projects_and_nowhere_else():
    width, height = 160, 120
    empty = floating_world().render(width, height, CAMERA)
    world = floating_world()
    centre, radius = np.array([0.3, -0.2, 0.5]), 0.4
    world.add_body({"type": "sphere", "radius": radius}, name="ball", position=centre.tolist())
    picture = world.render(width, height, CAMERA)
    camera = world.render_camera(width, height, CAMERA)
    column, row, depth = project(camera, centre, width, height)
    assert 0 <= column < width and 0 <= row < height and depth > 0
    assert not np.array_equal(picture[int(row), int(column)], empty[int(row), int(column)])
    # The ball's outline seen from the camera is the cone of half-angle asin(r / d). The drawn
    # ball is its tessellation, inside the sphere by at most 1.9 % of the radius (the module
    # docs of rebond::shape::tessellation), so every pixel whose ray is more than that cone plus
    # one pixel's angle (1 / focal) from the centre keeps the empty picture's colour, and every
    # pixel within the shrunk cone less one pixel shows the ball.
    angles = angles_from(camera, centre, width, height)
    distance = np.linalg.norm(centre - np.array(camera["position"]))
    pixel = math.tan(math.radians(camera["fov"]) / 2) / (height / 2)
    outside = angles > math.asin(radius / distance) + pixel
    inside = angles < math.asin(0.981 * radius / distance) - pixel
    changed = np.any(picture != empty, axis=-1)
    assert inside.sum() > 100 and outside.sum() > 100
    assert not changed[outside].any()
    assert changed[inside].all()


def test_pictures_are_the_same_bytes_every_time():
    world = rebond.World.from_scene(PENDULUM)
    world.step(30)
    first = world.render(96, 72)
    assert first.tobytes() == world.render(96, 72).tobytes()
    assert first.tobytes() == world.copy().render(96, 72).tobytes()


def test_an_empty_world_is_sky_and_a_halfspace_is_ground_below_it():
    width, height = 80, 60
    sky = rebond.World().render(width, height)
    # The sky's colours, from the horizon's to the zenith's, are blue over green over red.
    assert np.all(sky[..., 2] >= sky[..., 1]) and np.all(sky[..., 1] >= sky[..., 0])
    # Rows nearer the top look higher above the horizon: no row is nearer the horizon's colour
    # than the row below it.
    blue_shortfall = sky[..., 2].astype(int) - sky[..., 0].astype(int)
    assert np.all(np.diff(blue_shortfall.mean(axis=1)) <= 0)
    world = rebond.World()
    world.add_body({"type": "halfspace", "normal": [0, 1, 0]}, type="static")
    level = {"position": [0, 2, 10], "target": [0, 2, 0]}
    ground = world.render(width, height, level)
    # Looking level from 2 m up, the upper half is sky and the lower half ground (greys).
    assert np.array_equal(ground[: height // 2 - 1], rebond.World().render(width, height, level)[: height // 2 - 1])
    bottom = ground[-height // 4 :].astype(int)
    assert np.all(np.abs(bottom[..., 0] - bottom[..., 2]) < 12)
    # Looking at it from above, the ground shows its one-metre squares: two shades.
    above = world.render(width, height, {"position": [0.5, 3, 0.5], "target": [0.5, 0, 0.6]})
    assert len({tuple(pixel) for pixel in above.reshape(-1, 3)}) >= 2


def test_the_default_camera_frames_the_moving_bodies():
    world = rebond.World.from_scene(PENDULUM)
    world.step(20)
    width, height = 120, 90
    camera = world.render_camera(width, height)
    assert set(camera) == {"position", "target", "fov", "up"}
    assert camera["fov"] == 45 and camera["up"] == [0.0, 1.0, 0.0]
    # Every body origin is on the picture.
    for position in world.positions():
        column, row, depth = project(camera, position, width, height)
        assert depth > 0 and 0 <= column < width and 0 <= row < height
    # The camera the default resolves to draws the same picture.
    assert np.array_equal(world.render(width, height), world.render(width, height, camera))
    # Fields left out are the default's.
    wide = world.render_camera(width, height, {"fov": 70})
    assert wide["target"] == camera["target"] and wide["fov"] == 70
    moved = world.render_camera(width, height, {"position": [0, 1, 30]})
    assert moved["position"] == [0, 1, 30] and moved["target"] == camera["target"]


def test_up_is_against_gravity_and_static_bodies_show_squares():
    world = rebond.World(gravity=(0, 0, -9.81))
    world.add_body({"type": "box", "half_extents": [4, 4, 0.5]}, type="static", position=[0, 0, -0.5])
    world.add_body({"type": "sphere", "radius": 0.5}, position=[0, 0, 0.5])
    camera = world.render_camera(80, 60)
    assert camera["up"] == [0.0, 0.0, 1.0]
    # The default camera is above the bodies, looking down at them.
    assert camera["position"][2] > camera["target"][2] + 1
    # Looking straight down at the floor's top from 2 m, the view spans about 1.7 m: the floor
    # shows its one-metre squares, greys of two shades (78 % apart, less the slight fading
    # toward their mean and the haze, which move a channel by a level or two).
    top = world.render(60, 60, {"position": [2.3, 2.3, 2], "target": [2.3, 2.3, 0], "up": [0, 1, 0]})
    pixels = top.reshape(-1, 3).astype(int)
    assert np.all(pixels.max(axis=1) - pixels.min(axis=1) < 12)
    dark, light = pixels[pixels[:, 0] < 140], pixels[pixels[:, 0] >= 140]
    assert len(dark) > 500 and len(light) > 500
    assert np.ptp(dark[:, 0]) <= 2 and np.ptp(light[:, 0]) <= 2
    assert light[:, 0].min() - dark[:, 0].max() > 20


def test_a_batch_draws_its_worlds_as_worlds_do():
    batch = rebond.Batch(PENDULUM, 3)
    batch.apply_forces(np.random.default_rng(0).normal(size=(3, batch.body_count, 3)) * 5)
    batch.step(25)
    pictures = batch.render([2, 0, 1], 64, 48)
    assert pictures.shape == (3, 48, 64, 3) and pictures.dtype == np.uint8
    for place, index in enumerate([2, 0, 1]):
        expected = batch.world(index).render(64, 48)
        assert np.array_equal(pictures[place], expected)
        assert np.array_equal(batch.render(index, 64, 48), expected)
    assert np.array_equal(batch.render(np.int64(1), 64, 48, CAMERA), batch.world(1).render(64, 48, CAMERA))
    assert batch.render(np.arange(3), 16, 12).shape == (3, 12, 16, 3)


@pytest.mark.parametrize(
    "width, height, camera, message",
    [
        (0, 10, None, "width: must be from 1 to 8192 pixels, got 0"),
        (10, -3, None, "height: must be from 1 to 8192 pixels, got -3"),
        (8193, 10, None, "width: must be from 1 to 8192 pixels, got 8193"),
        (10, 10, [0, 1, 2], "camera: expected a dict"),
        (10, 10, {"zoom": 2}, "camera.zoom: unknown field"),
        (10, 10, {"fov": 0}, "camera.fov: must be between 0 and 180"),
        (10, 10, {"fov": 180}, "camera.fov: must be between 0 and 180"),
        (10, 10, {"fov": "wide"}, "camera.fov: expected a number of degrees"),
        (10, 10, {"position": [0, 1]}, "camera.position: got an array of shape (2,)"),
        (10, 10, {"target": [0, float("nan"), 0]}, "camera.target: element [1] must be finite"),
        (10, 10, {"up": [0, 0, 0]}, "camera.up: must not be zero"),
        (10, 10, {"position": [0, 5, 0], "target": [0, 0, 0]}, "camera.up: must not lie along"),
        (10, 10, {"position": [1, 2, 3], "target": [1, 2, 3]}, "camera.target: must differ"),
        (10, 10, {"position": [1e6, 0, 0]}, "camera.position: coordinates must be at most"),
    ],
)
def test_bad_sizes_and_cameras_raise_value_errors_naming_the_field(width, height, camera, message):
    world = rebond.World.from_scene(PENDULUM)
    before = world.save()
    with pytest.raises(ValueError) as raised:
        world.render(width, height, camera)
    assert message in str(raised.value)
    with pytest.raises(ValueError) as raised:
        world.render_camera(width, height, camera)
    assert message in str(raised.value)
    assert world.save() == before


def test_bad_batch_indices_raise():
    batch = rebond.Batch(PENDULUM, 2)
    with pytest.raises(IndexError, match=r"index: 2 is not a world of this batch \(0 to 1\)"):
        batch.render(2, 8, 8)
    with pytest.raises(IndexError, match=r"index\[1\]: -1 is not a world"):
        batch.render([0, -1], 8, 8)
    with pytest.raises(ValueError, match="index: expected a world index or a list"):
        batch.render("first", 8, 8)
    with pytest.raises(ValueError, match="width"):
        batch.render(0, 0, 8)


def test_the_video_example_writes_an_animated_gif(tmp_path):
    output = str(tmp_path / "cradle.gif")
    count = video.main(
        ["--scene", "cradle", "--seconds", "0.5", "--fps", "10", "--width", "64", "--height", "48",
         "--output", output]
    )
    assert count == 5
    with Image.open(output) as gif:
        assert gif.format == "GIF" and gif.size == (64, 48) and gif.n_frames == 5
