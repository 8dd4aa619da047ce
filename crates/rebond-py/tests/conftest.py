"""Shared helpers for the binding tests: the repository's examples on the import path, and a
measure of whether a call releases the GIL."""

import os
import sys
import threading

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
EXAMPLES = os.path.join(ROOT, "examples")
if EXAMPLES not in sys.path:
    sys.path.insert(0, EXAMPLES)


@pytest.fixture
def counted_during():
    """A function that runs ``work`` while another Python thread counts, and returns how far that
    thread counted meanwhile: a call that holds the GIL lets it count hardly at all."""

    def measure(work):
        counter = [0]
        running = threading.Event()

        def count():
            running.set()
            while running.is_set():
                counter[0] += 1

        thread = threading.Thread(target=count)
        thread.start()
        running.wait()
        before = counter[0]
        work()
        during = counter[0] - before
        running.clear()
        thread.join()
        return during

    return measure
