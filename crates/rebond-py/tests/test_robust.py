"""Robust from Python: Ctrl-C stops a long step, impossible batch sizes raise MemoryError, a
second thread gets a clear error, and errors quote what the user gave."""

import _thread
import re
import threading
import time

import numpy as np
import pytest

import rebond

# A swinging chain that never sleeps: every step does joint work.
PENDULUM = "pendulum"


def state(world):
    """Every body's pose and velocities, as bytes: equal bytes are equal bits."""
    return b"".join(
        getter().tobytes()
        for getter in [world.positions, world.rotations, world.linear_velocities,
                       world.angular_velocities]
    )


def interrupted(step, delay=0.3):
    """Runs ``step`` (a call that would run for hours) and interrupts it with Ctrl-C's signal
    after ``delay`` seconds; returns the seconds from the signal to the KeyboardInterrupt."""
    sent = []

    def interrupt():
        sent.append(time.perf_counter())
        _thread.interrupt_main()

    timer = threading.Timer(delay, interrupt)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        step()
    timer.join()
    return time.perf_counter() - sent[0]


def test_ctrl_c_stops_a_long_world_step_after_whole_steps():
    world = rebond.World.from_scene(PENDULUM)
    latency = interrupted(lambda: world.step(10**12))
    # Between signal checks a step runs 50 to 200 ms of steps (the rounds grow and shrink
    # towards 100 ms); measured 0.05 s to 0.15 s on a quiet machine. 5 s leaves room for a
    # machine loaded by parallel builds.
    assert latency < 5.0
    # The world stopped after a whole number of steps: a world stepped one step at a time
    # reaches exactly its state, and the two go on alike.
    reference = rebond.World.from_scene(PENDULUM)
    target = state(world)
    for _ in range(10**7):
        reference.step()
        if state(reference) == target:
            break
    assert state(reference) == target
    world.step(3)
    reference.step(3)
    assert state(reference) == state(world)


def test_ctrl_c_stops_a_long_batch_step_with_every_world_usable():
    batch = rebond.Batch(PENDULUM, 8)
    latency = interrupted(lambda: batch.step(10**12))
    assert latency < 5.0  # as for a world
    positions = batch.positions()
    assert np.isfinite(positions).all()
    # Every world took the same steps.
    assert all(np.array_equal(positions[0], positions[index]) for index in range(8))
    batch.step(2)
    assert np.isfinite(batch.positions()).all()


@pytest.mark.parametrize("scene", ["pendulum", "column"])
def test_a_long_step_is_bit_for_bit_the_same_steps_one_at_a_time(scene):
    """Splitting `step(n)` into rounds between signal checks changes no bit."""
    world, one_by_one = rebond.World.from_scene(scene), rebond.World.from_scene(scene)
    batch = rebond.Batch(scene, 3)
    world.step(400)
    batch.step(400)
    for _ in range(400):
        one_by_one.step()
    assert state(world) == state(one_by_one)
    assert all(state(batch.world(index)) == state(world) for index in range(3))


@pytest.mark.parametrize("count", [2**62, 10**9, 2**64 - 1])
def test_an_impossible_batch_size_raises_memory_error_at_once(count):
    # A pendulum world takes about 14 kB (measured 13,746 bytes): 10**9 of them are 14 TB.
    started = time.perf_counter()
    with pytest.raises(MemoryError, match=rf"^count: {count} worlds of \d+ bytes need"):
        rebond.Batch(PENDULUM, count)
    # Refused before any copy is made: one copy's time, not a billion.
    assert time.perf_counter() - started < 1.0
    # An ordinary exception, which `except Exception` catches.
    assert issubclass(MemoryError, Exception)


@pytest.mark.parametrize(
    "call, kind, message",
    [
        (lambda: rebond.Batch(PENDULUM, 2**70), ValueError,
         "count: must be at most 18446744073709551615, got 1180591620717411303424"),
        (lambda: rebond.Batch(PENDULUM, -3), ValueError, "count: must be at least 1, got -3"),
        (lambda: rebond.Batch(PENDULUM, 2.5), TypeError, "count: expected a whole number, got a float"),
        (lambda: rebond.World().step(2**70), ValueError,
         "n: must be at most 18446744073709551615, got 1180591620717411303424"),
        (lambda: rebond.Batch(PENDULUM, 1).step(-(2**70)), ValueError,
         "n: must not be negative, got -1180591620717411303424"),
        (lambda: rebond.World().step("many"), TypeError, "n: expected a whole number, got a str"),
        (lambda: rebond.World.from_scene({"bodies": [{"shape": {"type": "sphere", "radius": 1e39}}]}),
         rebond.SceneError,
         "bodies[0].shape.radius: must be finite, got 1e39, which is beyond the 32-bit float range"),
        (lambda: rebond.World.from_scene({"bodies": [{"shape": {"type": "sphere", "radius": "a"}}]}),
         rebond.SceneError, 'bodies[0].shape.radius: invalid type: string "a", expected f64'),
        (lambda: rebond.World.from_scene({"bodies": [{"shape": {"type": "sphere"}}]}),
         rebond.SceneError, "bodies[0].shape.radius: required field is missing (a sphere shape needs it)"),
        (lambda: rebond.World().add_body({"type": "sphere", "radius": 1}, mass=[1]),
         rebond.SceneError, "bodies[0].mass: invalid type: sequence, expected f64"),
        (lambda: rebond.World().add_body({"type": "sphere", "radius": 1}, speed=3),
         rebond.SceneError, "bodies[0].speed: unknown field `speed`, expected one of"),
        (lambda: rebond.World(gravity=[0, -1e39, 0]), rebond.SceneError,
         "gravity[1]: must be finite, got -1e39"),
    ],
)
def test_errors_name_the_argument_or_element_and_quote_the_value_as_given(call, kind, message):
    with pytest.raises(kind) as raised:
        call()
    text = str(raised.value)
    assert text.startswith(message) or message in text, text
    # Dicts become JSON text for the loader, but its lines and columns are not the user's.
    assert not re.search(r"line \d|column \d", text), text


@pytest.mark.parametrize("kind", ["World", "Batch"])
def test_a_second_thread_gets_a_clear_error_while_an_object_steps(kind):
    target = rebond.World.from_scene(PENDULUM) if kind == "World" else rebond.Batch(PENDULUM, 4)
    stepping = threading.Event()
    finished = threading.Event()
    errors = []

    def reader():
        stepping.wait()
        while not finished.is_set():
            try:
                target.positions()
            except RuntimeError as error:
                errors.append(str(error))
                return
            time.sleep(0.001)

    thread = threading.Thread(target=reader)
    thread.start()
    stepping.set()
    target.step(5_000)  # a quarter of a second of stepping, or more
    finished.set()
    thread.join()
    assert errors, "the reader never met the stepping object"
    assert errors[0].startswith(f"{kind}.positions: this {kind} is in use by another thread")
    assert "Already" not in errors[0]
    # Once the step is over the object is whole and usable from any thread.
    assert np.isfinite(target.positions()).all()
    target.step(1)
