#!/usr/bin/env python3
"""Writes the three scenes of the awake-cost benchmark (BENCHMARKS.md, "What a step costs"):

- alone.json: 200 unit boxes falling onto a ground, kept awake (`can_sleep: false`);
- static.json: the same, and 20,000 static unit boxes 1 km away;
- sleeping.json: the same, and 20,000 unit boxes resting on a ground 1 km away, free to sleep.

Usage: python3 bench/awake_cost/generate.py [DIRECTORY]   (default: bench/awake_cost/scenes)
"""

import json
import os
import sys


def box(name, position, **fields):
    body = {"name": name, "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
            "position": position}
    body.update(fields)
    return body


def ground(name, x, half):
    return {"name": name, "type": "static", "position": [x, -0.5, 0.0],
            "shape": {"type": "box", "half_extents": [half, 0.5, half]}}


def falling():
    bodies = [ground("ground", 0.0, 50.0)]
    for i in range(200):
        x, z, y = i % 10, (i // 10) % 10, i // 100
        bodies.append(box(f"falling{i}", [2.0 * x - 9.0, 2.0 + 2.0 * y + 0.1 * x, 2.0 * z - 9.0],
                          can_sleep=False))
    return bodies


def far_grid(count):
    """`count` positions on a 2 m grid around x = 1000 m, resting on y = 0."""
    side = int(count ** 0.5) + 1
    return [[1000.0 + 2.0 * (i % side), 0.5, 2.0 * (i // side) - side] for i in range(count)]


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "scenes")
    os.makedirs(directory, exist_ok=True)
    far = far_grid(20_000)
    scenes = {
        "alone": falling(),
        "static": falling() + [dict(box(f"static{i}", p), type="static") for i, p in enumerate(far)],
        "sleeping": falling() + [ground("far_ground", 1150.0, 160.0)]
        + [box(f"resting{i}", p) for i, p in enumerate(far)],
    }
    for name, bodies in scenes.items():
        with open(os.path.join(directory, f"{name}.json"), "w") as file:
            json.dump({"bodies": bodies}, file)


if __name__ == "__main__":
    main()
