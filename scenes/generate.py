#!/usr/bin/env python3
"""Writes the built-in scenes of `rebond` (the JSON files next to this script).

Run from anywhere with `python3 scenes/generate.py`; it overwrites every scene file it makes, and
its output is deterministic (no randomness beyond a fixed linear congruential generator).
Each body sits on one line so the files stay compact and diff well.
"""

import json
import math
from pathlib import Path

SCENES_DIR = Path(__file__).resolve().parent
UNIT_BOX = {"type": "box", "half_extents": [0.5, 0.5, 0.5]}


def rounded(values, digits=4):
    """Rounds every number of a vector or quaternion, keeping the JSON short."""
    return [round(value, digits) + 0.0 for value in values]


def axis_angle(axis, angle):
    """The unit quaternion [x, y, z, w] turning `angle` radians about the unit `axis`."""
    s = math.sin(angle / 2.0)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2.0)]


def quat_mul(a, b):
    """The quaternion product a·b (first b, then a), both [x, y, z, w]."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]


def rotate(q, v):
    """The vector v turned by the unit quaternion q."""
    x, y, z, w = q
    u = (x, y, z)
    uv = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    uuv = (u[1] * uv[2] - u[2] * uv[1], u[2] * uv[0] - u[0] * uv[2], u[0] * uv[1] - u[1] * uv[0])
    return [v[i] + 2.0 * (w * uv[i] + uuv[i]) for i in range(3)]


def ground_box(half_width):
    """A static box whose top face is the plane y = 0."""
    return {
        "name": "ground",
        "type": "static",
        "shape": {"type": "box", "half_extents": [half_width, 0.5, half_width]},
        "position": [0.0, -0.5, 0.0],
    }


def write_scene(file_name, bodies, gravity=None, substeps=None, compact=False):
    """Writes a scene with one body per line; `compact` drops the spaces inside each line."""
    separators = (",", ":") if compact else (", ", ": ")
    indent = "" if compact else "    "
    lines = ["{"]
    if gravity is not None:
        lines.append(f'  "gravity": {json.dumps(gravity)},')
    if substeps is not None:
        lines.append(f'  "substeps": {substeps},')
    lines.append('  "bodies": [')
    body_lines = [indent + json.dumps(body, separators=separators) for body in bodies]
    lines.append(",\n".join(body_lines))
    lines.append("  ]")
    lines.append("}")
    (SCENES_DIR / file_name).write_text("\n".join(lines) + "\n", encoding="utf-8")


class Lcg:
    """A small deterministic generator of numbers in [0, 1)."""

    def __init__(self, seed):
        self.state = seed

    def next(self):
        self.state = (self.state * 6364136223846793005 + 1442695040888963407) % 2**64
        return (self.state >> 11) / 2**53

    def symmetric(self, amplitude):
        """A number in [-amplitude, amplitude)."""
        return (2.0 * self.next() - 1.0) * amplitude


def pyramid_bodies(rows, x_center, z, spacing, prefix):
    """A 2D pyramid of unit boxes resting on y = 0, `rows` at the bottom, one box at the top."""
    bodies = []
    for row in range(rows):
        count = rows - row
        for index in range(count):
            x = x_center + (index - (count - 1) / 2.0) * spacing
            bodies.append({
                "name": f"{prefix}_{row}_{index}",
                "shape": UNIT_BOX,
                "position": rounded([x, 0.5 + row, z]),
            })
    return bodies


def column_bodies(count, x, z, prefix):
    """A column of unit boxes standing on y = 0."""
    return [
        {"name": f"{prefix}_{level}", "shape": UNIT_BOX, "position": rounded([x, 0.5 + level, z])}
        for level in range(count)
    ]


def on_incline(center, rotation, half_thickness, along, across, height):
    """A world point `height` above the top face of an inclined box, `along` its slope."""
    local = [along, half_thickness + height, across]
    offset = rotate(rotation, local)
    return rounded([center[i] + offset[i] for i in range(3)])


def showcase():
    """A bit of everything: stacks, bouncing and rolling balls, a ramp, a compound."""
    bodies = [ground_box(40.0)]
    bodies += pyramid_bodies(5, -10.0, -6.0, 1.05, "pyramid")
    bodies += column_bodies(6, -4.0, -6.0, "column")
    bodies.append({
        "name": "ball_restitution_0_5", "shape": {"type": "sphere", "radius": 0.5},
        "position": [0.0, 6.0, -6.0], "restitution": 0.5,
    })
    bodies.append({
        "name": "ball_restitution_0_8", "shape": {"type": "sphere", "radius": 0.5},
        "position": [2.0, 6.0, -6.0], "restitution": 0.8,
    })
    bodies.append({
        "name": "rolling_ball", "shape": {"type": "sphere", "radius": 0.5},
        "position": [-10.0, 0.5, 4.0], "linear_velocity": [4.0, 0.0, 0.0],
        "angular_velocity": [0.0, 0.0, -8.0],
    })
    slope = math.radians(25.0)
    ramp_rotation = axis_angle((0.0, 0.0, 1.0), slope)
    ramp_center = [10.0, 2.3, 4.0]
    ramp_half_thickness = 0.2
    bodies.append({
        "name": "ramp", "type": "static",
        "shape": {"type": "box", "half_extents": [5.0, ramp_half_thickness, 2.5]},
        "position": ramp_center, "rotation": rounded(ramp_rotation, 6),
    })
    lying = quat_mul(ramp_rotation, axis_angle((1.0, 0.0, 0.0), math.pi / 2.0))
    bodies.append({
        "name": "capsule", "shape": {"type": "capsule", "radius": 0.3, "half_height": 0.5},
        "position": on_incline(ramp_center, ramp_rotation, ramp_half_thickness, 3.5, -1.5, 0.35),
        "rotation": rounded(lying, 6),
    })
    bodies.append({
        "name": "cylinder", "shape": {"type": "cylinder", "radius": 0.4, "half_height": 0.4},
        "position": on_incline(ramp_center, ramp_rotation, ramp_half_thickness, 3.5, 0.0, 0.45),
        "rotation": rounded(lying, 6),
    })
    rock = [
        [0.5, 0.0, 0.0], [-0.4, 0.1, 0.1], [0.0, 0.45, -0.1], [0.1, -0.4, 0.05],
        [0.05, 0.1, 0.5], [-0.1, -0.05, -0.45], [0.3, 0.3, 0.3], [-0.3, -0.25, 0.25],
    ]
    wedge = [
        [-0.5, -0.3, -0.4], [0.5, -0.3, -0.4], [-0.5, -0.3, 0.4], [0.5, -0.3, 0.4],
        [-0.5, 0.3, 0.0], [0.5, 0.3, 0.0],
    ]
    bodies.append({
        "name": "rock", "shape": {"type": "convex_hull", "points": rock},
        "position": on_incline(ramp_center, ramp_rotation, ramp_half_thickness, 3.5, 1.5, 0.55),
        "rotation": rounded(ramp_rotation, 6),
    })
    bodies.append({
        "name": "wedge", "shape": {"type": "convex_hull", "points": wedge},
        "position": on_incline(ramp_center, ramp_rotation, ramp_half_thickness, 1.0, 0.0, 0.35),
        "rotation": rounded(ramp_rotation, 6),
    })
    bodies.append({
        "name": "dumbbell",
        "shape": {"type": "compound", "children": [
            {"shape": {"type": "capsule", "radius": 0.1, "half_height": 0.6},
             "rotation": rounded(axis_angle((0.0, 0.0, 1.0), math.pi / 2.0), 6)},
            {"shape": {"type": "sphere", "radius": 0.3}, "position": [-0.7, 0.0, 0.0]},
            {"shape": {"type": "box", "half_extents": [0.25, 0.25, 0.25]},
             "position": [0.7, 0.0, 0.0]},
        ]},
        "position": [6.0, 3.0, -6.0],
        "rotation": rounded(axis_angle((0.0, 0.6, 0.8), 0.5), 6),
    })
    write_scene("showcase.json", bodies)


def pyramid():
    """210 unit boxes in 20 rows on a ground box."""
    write_scene("pyramid.json", [ground_box(50.0)] + pyramid_bodies(20, 0.0, 0.0, 1.05, "box"))


def column():
    """10 unit boxes stacked on a ground box."""
    write_scene("column.json", [ground_box(50.0)] + column_bodies(10, 0.0, 0.0, "box"))


def rain():
    """4,096 unit boxes in a 16×16×16 grid (spacing 1.5) with small offsets and tilts."""
    generator = Lcg(20240601)
    bodies = [ground_box(30.0)]
    count = 16
    spacing = 1.5
    start = -(count - 1) / 2.0 * spacing
    for level in range(count):
        for row in range(count):
            for column_index in range(count):
                position = [
                    start + column_index * spacing + generator.symmetric(0.15),
                    3.0 + level * spacing + generator.symmetric(0.15),
                    start + row * spacing + generator.symmetric(0.15),
                ]
                axis = [generator.symmetric(1.0) for _ in range(3)]
                length = math.sqrt(sum(value * value for value in axis)) or 1.0
                axis = [value / length for value in axis]
                rotation = axis_angle(axis, generator.symmetric(0.2))
                bodies.append({
                    "shape": UNIT_BOX,
                    "position": rounded(position, 3),
                    "rotation": rounded(rotation, 4),
                })
    write_scene("rain.json", bodies, compact=True)


def ramp():
    """Lanes on a 20° incline, each with its own friction (0.1 to 0.9) for strip, box and ball."""
    slope = math.radians(20.0)
    rotation = axis_angle((0.0, 0.0, 1.0), slope)
    half_thickness = 0.1
    bodies = [{
        "name": "floor", "type": "static",
        "shape": {"type": "halfspace", "normal": [0.0, 1.0, 0.0]},
    }]
    for lane in range(9):
        friction = round(0.1 * (lane + 1), 1)
        z = (lane - 4) * 1.2
        center = [0.0, 4.0 * math.sin(slope) + 0.2, z]
        bodies.append({
            "name": f"strip_{lane}", "type": "static",
            "shape": {"type": "box", "half_extents": [4.0, half_thickness, 0.5]},
            "position": rounded(center), "rotation": rounded(rotation, 6),
            "friction": friction,
        })
        bodies.append({
            "name": f"box_{lane}", "shape": {"type": "box", "half_extents": [0.25, 0.25, 0.25]},
            "position": on_incline(center, rotation, half_thickness, 2.5, 0.0, 0.25),
            "rotation": rounded(rotation, 6), "friction": friction,
        })
        bodies.append({
            "name": f"ball_{lane}", "shape": {"type": "sphere", "radius": 0.25},
            "position": on_incline(center, rotation, half_thickness, 0.5, 0.0, 0.25),
            "friction": friction,
        })
    write_scene("ramp.json", bodies)


def cradle():
    """Newton's cradle without strings: five touching balls in zero gravity, the first moving."""
    bodies = []
    for index in range(5):
        body = {
            "name": f"ball_{index}", "shape": {"type": "sphere", "radius": 0.5},
            "position": [float(index), 1.0, 0.0], "restitution": 1.0, "friction": 0.0,
        }
        if index == 0:
            body["linear_velocity"] = [1.0, 0.0, 0.0]
        bodies.append(body)
    write_scene("cradle.json", bodies, gravity=[0.0, 0.0, 0.0])


def spinner():
    """Free spinning bodies in zero gravity; the intermediate-axis box flips (Dzhanibekov)."""
    brick = {"type": "box", "half_extents": [0.1, 0.4, 0.8]}
    bodies = [
        {"name": "intermediate_axis", "shape": brick, "position": [0.0, 0.0, 0.0],
         "angular_velocity": [0.001, 6.0, 0.0], "can_sleep": False},
        {"name": "major_axis", "shape": brick, "position": [3.0, 0.0, 0.0],
         "angular_velocity": [6.0, 0.001, 0.0], "can_sleep": False},
        {"name": "minor_axis", "shape": brick, "position": [-3.0, 0.0, 0.0],
         "angular_velocity": [0.0, 0.001, 6.0], "can_sleep": False},
        {"name": "top", "shape": {"type": "cylinder", "radius": 0.5, "half_height": 0.1},
         "position": [0.0, 0.0, 3.0], "angular_velocity": [0.3, 8.0, 0.0], "can_sleep": False},
        {"name": "baton", "shape": {"type": "capsule", "radius": 0.1, "half_height": 0.6},
         "position": [0.0, 0.0, -3.0], "angular_velocity": [4.0, 0.5, 0.0], "can_sleep": False},
    ]
    write_scene("spinner.json", bodies, gravity=[0.0, 0.0, 0.0], substeps=8)


if __name__ == "__main__":
    showcase()
    pyramid()
    column()
    rain()
    ramp()
    cradle()
    spinner()
