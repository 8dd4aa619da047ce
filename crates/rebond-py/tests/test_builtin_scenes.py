"""The scenes built into rebond load by name from any directory; a file that exists wins."""

import json
import os

import numpy as np
import pytest

import rebond
from conftest import ROOT


def test_builtin_scenes_lists_the_command_lines_scenes():
    scenes = dict(rebond.builtin_scenes())
    assert {"pendulum", "cradle", "car", "level", "platformer"} <= set(scenes)
    assert all(description for description in scenes.values())
    # Each is a scene file of the repository, embedded.
    for name in scenes:
        assert os.path.exists(os.path.join(ROOT, "scenes", f"{name}.json")), name


@pytest.mark.parametrize("name", [name for name, _ in rebond.builtin_scenes()])
def test_every_builtin_scene_loads_by_name_from_anywhere(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    world = rebond.World.from_scene(name)
    from_file = rebond.World.from_scene(os.path.join(ROOT, "scenes", f"{name}.json"))
    assert world.body_names() == from_file.body_names()
    assert np.array_equal(world.positions(), from_file.positions())


def test_a_builtin_scene_steps_as_its_file_and_batches(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    world = rebond.World.from_scene("pendulum")
    batch = rebond.Batch("pendulum", 2)
    from_file = rebond.World.from_scene(os.path.join(ROOT, "scenes", "pendulum.json"))
    for each in (world, batch, from_file):
        each.step(60)
    assert np.array_equal(world.positions(), from_file.positions())
    assert np.array_equal(batch.positions()[1], from_file.positions())


def test_a_file_that_exists_wins_over_a_builtin_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "pendulum").write_text(
        json.dumps({"bodies": [{"name": "mine", "shape": {"type": "sphere", "radius": 1}}]})
    )
    assert rebond.World.from_scene("pendulum").body_names() == ["mine"]


def test_an_unknown_name_that_is_no_file_says_both_and_lists_the_builtin_scenes(tmp_path):
    missing = str(tmp_path / "pendulums")
    with pytest.raises(FileNotFoundError) as raised:
        rebond.Batch(missing, 2)
    message = str(raised.value)
    assert message.startswith(
        f"{missing}: cannot read scene: no such file, and no built-in scene of that name "
        "(built-in scenes: showcase, pyramid,"
    )
    assert all(name in message for name, _ in rebond.builtin_scenes())

