#!/usr/bin/env python3
"""The vertical chain of a column of unit boxes under rebond's soft step, in one dimension.

contact-model.md ("a model of the column's vertical chain") uses it: each step runs the solver's
substeps on `N` unit masses in a line over a ground, with the engine's stages (velocities, warm
start, biased passes in lane-set order, positions, relax pass) and its soft contact. A face's four
corners become one contact here; the model gives the engine's column sink at 4 and 8 substeps
(18.0 / 11.0 cm and 4.5 / 2.76 cm for 40 boxes, soft block), so it answers quickly which pass
schemes hold stiffer springs. It is a model, not a test: the engine's bending and its pyramids
are not in it.

    python3 docs/design-notes/column_chain_model.py --hertz 120 --biased 2 --relax 1
    python3 docs/design-notes/column_chain_model.py --hertz 120 --sor 1.8 --sor-first-pass-only
"""

import argparse
import math


def softness(hertz, zeta, h):
    """Box2D's soft constraint coefficients: bias rate, mass scale, impulse scale."""
    omega = 2.0 * math.pi * hertz
    a1 = 2.0 * zeta + h * omega
    a2 = h * omega * a1
    a3 = 1.0 / (1.0 + a2)
    return omega / a1, a2 * a3, a3


def run(boxes, substeps, hertz, zeta, biased, relax, sor, sor_first_only, steps):
    """Worst sink of the top box, its sink over the last 200 steps (min, max) and the largest
    speed then, metres and m/s."""
    dt, g = 1.0 / 60.0, 9.81
    h = dt / substeps
    bias_rate, mass_scale, impulse_scale = softness(hertz, zeta, h)
    y = [0.5 + i for i in range(boxes)]
    v = [0.0] * boxes
    impulse = [0.0] * boxes
    # Lane sets solve a column every other contact first.
    order = list(range(0, boxes, 2)) + list(range(1, boxes, 2))
    worst, tail, fastest = 0.0, [], 0.0

    def separation(j):
        return y[j] - (y[j - 1] if j > 0 else -0.5) - 1.0

    def solve(use_bias, relaxation):
        for j in order:
            closing = v[j] - (v[j - 1] if j > 0 else 0.0)
            s = separation(j)
            mass = 1.0 if j == 0 else 0.5
            if use_bias and s > 0.0:
                change = -mass * (closing + s / h)
            elif use_bias:
                push = max(bias_rate * s, -3.0)
                change = -mass * mass_scale * (closing + push) - impulse_scale * impulse[j]
            else:
                change = -mass * closing
            total = max(impulse[j] + relaxation * change, 0.0)
            change, impulse[j] = total - impulse[j], total
            v[j] += change
            if j > 0:
                v[j - 1] -= change

    for step in range(steps):
        for _ in range(substeps):
            for i in range(boxes):
                v[i] -= g * h
            for j in range(boxes):
                v[j] += impulse[j]
                if j > 0:
                    v[j - 1] -= impulse[j]
            for k in range(biased):
                solve(True, sor if (k == 0 or not sor_first_only) else 1.0)
            for i in range(boxes):
                y[i] += h * v[i]
            for _ in range(relax):
                solve(False, 1.0)
        sink = boxes - 0.5 - y[-1]
        worst = max(worst, sink)
        if step >= steps - 200:
            tail.append(sink)
            fastest = max(fastest, max(abs(speed) for speed in v))
    return worst, min(tail), max(tail), fastest


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--boxes", type=int, default=40)
    parser.add_argument("--substeps", type=int, default=4)
    parser.add_argument("--hertz", type=float, default=60.0, help="contact spring, Hz (no cap)")
    parser.add_argument("--zeta", type=float, default=5.0)
    parser.add_argument("--biased", type=int, default=2, help="biased passes a substep")
    parser.add_argument("--relax", type=int, default=1, help="relax passes a substep")
    parser.add_argument("--sor", type=float, default=1.0, help="over-relaxation of biased passes")
    parser.add_argument("--sor-first-pass-only", action="store_true")
    parser.add_argument("--steps", type=int, default=600)
    a = parser.parse_args()
    worst, low, high, fastest = run(a.boxes, a.substeps, a.hertz, a.zeta, a.biased, a.relax,
                                    a.sor, a.sor_first_pass_only, a.steps)
    print(f"top sink: worst {100 * worst:.2f} cm, last 200 steps {100 * low:.2f} to "
          f"{100 * high:.2f} cm; fastest box then {fastest:.4f} m/s")


if __name__ == "__main__":
    main()
