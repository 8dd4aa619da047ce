"""examples/ars.py: augmented random search raises InvertedPendulum's return in a few
iterations."""

import ars


def test_ars_raises_the_inverted_pendulum_return():
    lines = []
    settings = ars.SETTINGS["rebond/InvertedPendulum-v0"]
    history = ars.train("rebond/InvertedPendulum-v0", iterations=8, minutes=None,
                        horizon=100, seed=0, log=lines.append, **settings)
    assert len(history) == len(lines) == 8
    # The zero policy lets the pole fall within a few dozen steps; a linear policy that holds it
    # for the whole 100-step horizon exists, and ARS climbs towards it: the best of the last
    # iterations at least doubles the first return.
    assert max(history[4:]) >= 2 * history[0], history
