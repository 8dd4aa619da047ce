"""examples/ars.py: augmented random search raises InvertedPendulum's return in a few
iterations."""

import pytest

import ars
from conftest import mjcf_unreadable

UNREADABLE = mjcf_unreadable()


@pytest.mark.skipif(UNREADABLE is not None, reason=str(UNREADABLE))
def test_ars_raises_the_inverted_pendulum_return():
    lines = []
    history = ars.train("rebond/InvertedPendulum-v0", iterations=6, minutes=None, directions=4,
                        top=2, step_size=0.02, noise=0.03, horizon=100, seed=0,
                        log=lines.append)
    assert len(history) == len(lines) == 6
    # The zero policy lets the pole fall within a few dozen steps; a linear policy that holds it
    # for the whole 100-step horizon exists, and ARS climbs towards it.
    assert max(history[3:]) > history[0] + 10, history
