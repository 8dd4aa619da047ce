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


def add(a, b):
    """The sum of two vectors."""
    return [a[i] + b[i] for i in range(3)]


def scaled(v, factor):
    """The vector v times a number."""
    return [value * factor for value in v]


def normalized(v):
    """The unit vector along v."""
    length = math.sqrt(sum(value * value for value in v))
    return [value / length for value in v]


def quat_from_y(direction):
    """The unit quaternion [x, y, z, w] turning +Y onto the unit `direction` (the axis of a
    capsule or cylinder)."""
    x, y, z = direction
    if y < -0.999999:
        return [1.0, 0.0, 0.0, 0.0]
    # Half-way quaternion: the axis +Y × d, with w = 1 + +Y · d, then normalised.
    q = [z, 0.0, -x, 1.0 + y]
    length = math.sqrt(sum(value * value for value in q))
    return [value / length for value in q]


def ground_box(half_width):
    """A static box whose top face is the plane y = 0."""
    return {
        "name": "ground",
        "type": "static",
        "shape": {"type": "box", "half_extents": [half_width, 0.5, half_width]},
        "position": [0.0, -0.5, 0.0],
    }


def write_scene(file_name, bodies, gravity=None, substeps=None, compact=False, joints=None,
                restitution_threshold=None, character=None):
    """Writes a scene with one body (and joint) per line; `compact` drops the spaces inside each
    line."""
    separators = (",", ":") if compact else (", ", ": ")
    indent = "" if compact else "    "
    lines = ["{"]
    if gravity is not None:
        lines.append(f'  "gravity": {json.dumps(gravity)},')
    if substeps is not None:
        lines.append(f'  "substeps": {substeps},')
    if restitution_threshold is not None:
        lines.append(f'  "restitution_threshold": {restitution_threshold},')
    if character is not None:
        lines.append(f'  "character": {json.dumps(character, separators=separators)},')
    lines.append('  "bodies": [')
    body_lines = [indent + json.dumps(body, separators=separators) for body in bodies]
    lines.append(",\n".join(body_lines))
    if joints:
        lines.append("  ],")
        lines.append('  "joints": [')
        joint_lines = [indent + json.dumps(joint, separators=separators) for joint in joints]
        lines.append(",\n".join(joint_lines))
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
    """Newton's cradle without strings: five touching balls in zero gravity, the first moving at
    1 m/s; elastic balls bounce at any speed (restitution threshold 0)."""
    bodies = []
    for index in range(5):
        body = {
            "name": f"ball_{index}", "shape": {"type": "sphere", "radius": 0.5},
            "position": [float(index), 1.0, 0.0], "restitution": 1.0, "friction": 0.0,
        }
        if index == 0:
            body["linear_velocity"] = [1.0, 0.0, 0.0]
        bodies.append(body)
    write_scene("cradle.json", bodies, gravity=[0.0, 0.0, 0.0], restitution_threshold=0.0)


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


def pendulum():
    """Pendulums hung from the world: revolute and ball, small and large swings, a rod, and a
    double pendulum."""
    bodies = [ground_box(20.0)]
    joints = []
    pivot_height = 5.0
    bob = {"type": "sphere", "radius": 0.2}

    def hinged_bob(name, z, angle, joint_type, velocity=None):
        """A 1 kg bob 2 m below a pivot of the world, started `angle` radians out along +X."""
        pivot = [0.0, pivot_height, z]
        body = {
            "name": name, "shape": bob, "mass": 1.0,
            "position": rounded(add(pivot, [2.0 * math.sin(angle), -2.0 * math.cos(angle), 0.0])),
        }
        if velocity is not None:
            body["linear_velocity"] = velocity
        bodies.append(body)
        joint = {"name": f"{name}_pivot", "type": joint_type, "body_b": name, "anchor": pivot}
        if joint_type == "revolute":
            joint["axis"] = [0.0, 0.0, 1.0]
        joints.append(joint)

    hinged_bob("revolute_small", -3.0, math.radians(10.0), "revolute")
    hinged_bob("revolute_large", -1.5, math.radians(150.0), "revolute")
    hinged_bob("ball_small", 4.0, math.radians(15.0), "ball", velocity=[0.0, 0.0, 0.8])
    hinged_bob("ball_large", 9.0, math.radians(90.0), "ball", velocity=[0.0, 0.0, 3.0])

    # A physical pendulum: a 1.9 m rod hinged at its top end, started 60 degrees out.
    angle = math.radians(60.0)
    direction = [math.sin(angle), -math.cos(angle), 0.0]
    pivot = [0.0, pivot_height, 0.0]
    bodies.append({
        "name": "rod", "shape": {"type": "capsule", "radius": 0.05, "half_height": 0.9},
        "position": rounded(add(pivot, scaled(direction, 0.95))),
        "rotation": rounded(quat_from_y(direction), 6), "mass": 2.0,
    })
    joints.append({
        "name": "rod_pivot", "type": "revolute", "body_b": "rod", "anchor": pivot,
        "axis": [0.0, 0.0, 1.0],
    })

    # A double pendulum of two 1 m rods, both started horizontal: chaotic.
    upper_pivot = [0.0, pivot_height, 1.5]
    elbow = add(upper_pivot, [1.0, 0.0, 0.0])
    along_x = rounded(axis_angle((0.0, 0.0, 1.0), math.pi / 2.0), 6)
    link = {"type": "capsule", "radius": 0.05, "half_height": 0.45}
    bodies.append({
        "name": "double_upper", "shape": link, "mass": 1.0,
        "position": add(upper_pivot, [0.5, 0.0, 0.0]), "rotation": along_x,
    })
    bodies.append({
        "name": "double_lower", "shape": link, "mass": 1.0,
        "position": add(elbow, [0.5, 0.0, 0.0]), "rotation": along_x,
    })
    joints.append({
        "name": "double_shoulder", "type": "revolute", "body_b": "double_upper",
        "anchor": upper_pivot, "axis": [0.0, 0.0, 1.0],
    })
    joints.append({
        "name": "double_elbow", "type": "revolute", "body_a": "double_upper",
        "body_b": "double_lower", "anchor": elbow, "axis": [0.0, 0.0, 1.0],
    })
    write_scene("pendulum.json", bodies, joints=joints)


def chain():
    """Two chains of 16 links hanging from the world, each with a 25 kg weight at its end: one on
    ball joints, started askew, and one on revolute joints, started horizontal."""
    bodies = [ground_box(30.0)]
    joints = []
    link_length = 0.5
    link = {"type": "capsule", "radius": 0.07, "half_height": link_length / 2.0 - 0.07}
    for prefix, joint_type, start, direction, weight in [
        ("ball", "ball", [-6.0, 12.0, -2.0], normalized([1.0, 0.0, 0.4]),
         {"type": "sphere", "radius": 0.35}),
        ("hinge", "revolute", [-6.0, 12.0, 2.0], [1.0, 0.0, 0.0],
         {"type": "box", "half_extents": [0.35, 0.35, 0.35]}),
    ]:
        rotation = rounded(quat_from_y(direction), 6)
        previous = None
        point = start
        for index in range(16):
            name = f"{prefix}_link_{index}"
            bodies.append({
                "name": name, "shape": link, "mass": 1.0,
                "position": rounded(add(point, scaled(direction, link_length / 2.0))),
                "rotation": rotation,
            })
            joint = {"name": f"{prefix}_joint_{index}", "type": joint_type, "body_b": name,
                     "anchor": rounded(point)}
            if previous is not None:
                joint["body_a"] = previous
            if joint_type == "revolute":
                joint["axis"] = [0.0, 0.0, 1.0]
            joints.append(joint)
            previous = name
            point = add(point, scaled(direction, link_length))
        name = f"{prefix}_weight"
        bodies.append({
            "name": name, "shape": weight, "mass": 25.0,
            "position": rounded(add(point, scaled(direction, 0.35))), "rotation": rotation,
        })
        joint = {"name": f"{prefix}_joint_weight", "type": joint_type, "body_a": previous,
                 "body_b": name, "anchor": rounded(point)}
        if joint_type == "revolute":
            joint["axis"] = [0.0, 0.0, 1.0]
        joints.append(joint)
    write_scene("chain.json", bodies, joints=joints)


def bridge():
    """A rope bridge: 14 planks on revolute joints hung with some slack between two static
    pillars, and boxes and a ball dropped on it."""
    bodies = [ground_box(30.0)]
    joints = []
    count = 14
    plank_length = 1.0
    height = 5.0
    max_slope = 0.35
    slopes = [max_slope * (2.0 * (index + 0.5) / count - 1.0) for index in range(count)]
    span = sum(plank_length * math.cos(slope) for slope in slopes)
    points = [[-span / 2.0, height, 0.0]]
    for slope in slopes:
        points.append(add(points[-1], [plank_length * math.cos(slope),
                                       plank_length * math.sin(slope), 0.0]))
    for side, x in [("left", points[0][0] - 0.5), ("right", points[-1][0] + 0.5)]:
        bodies.append({
            "name": f"pillar_{side}", "type": "static",
            "shape": {"type": "box", "half_extents": [0.5, height / 2.0, 1.2]},
            "position": rounded([x, height / 2.0, 0.0]),
        })
    axis = [0.0, 0.0, 1.0]
    for index, slope in enumerate(slopes):
        name = f"plank_{index}"
        bodies.append({
            "name": name, "shape": {"type": "box", "half_extents": [0.48, 0.08, 1.0]},
            "mass": 10.0, "friction": 0.8,
            "position": rounded(scaled(add(points[index], points[index + 1]), 0.5)),
            "rotation": rounded(axis_angle(axis, slope), 6),
        })
        body_a = "pillar_left" if index == 0 else f"plank_{index - 1}"
        joints.append({"name": f"hinge_{index}", "type": "revolute", "body_a": body_a,
                       "body_b": name, "anchor": rounded(points[index]), "axis": axis})
    joints.append({"name": f"hinge_{count}", "type": "revolute", "body_a": "pillar_right",
                   "body_b": f"plank_{count - 1}", "anchor": rounded(points[-1]), "axis": axis})
    for index, x in enumerate([-4.5, -2.0, 0.5, 3.0, 5.0]):
        bodies.append({
            "name": f"crate_{index}", "shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]},
            "mass": 20.0, "position": [x, height + 1.5 + 0.7 * index, 0.3 * (index % 3 - 1)],
        })
    bodies.append({
        "name": "ball", "shape": {"type": "sphere", "radius": 0.4}, "mass": 30.0,
        "position": [-1.0, height + 6.0, 0.0],
    })
    write_scene("bridge.json", bodies, joints=joints)


def ragdoll_parts():
    """One ragdoll standing in its own frame (facing +Z, feet near y = 0, arms out along X):
    (name, shape, mass, position, rotation) of each part, and (name, type, body_a, body_b,
    anchor, axis, limits) of each joint."""
    along_x = axis_angle((0.0, 0.0, 1.0), math.pi / 2.0)
    upright = [0.0, 0.0, 0.0, 1.0]
    parts = [
        ("torso", {"type": "box", "half_extents": [0.18, 0.3, 0.1]}, 25.0, [0.0, 1.25, 0.0], upright),
        ("head", {"type": "sphere", "radius": 0.12}, 5.0, [0.0, 1.70, 0.0], upright),
    ]
    # Joint friction, N·m, a few percent of the weight torque of the parts each joint carries
    # held out level, as the stiffness of real joints gives: without it a limb that its own
    # body lets pass (an arm through the torso) swings on for ever and the piles never sleep.
    joints = [("neck", "ball", "torso", "head", [0.0, 1.57, 0.0], [0.0, 1.0, 0.0],
               {"swing_limit": 0.7, "twist_limits": [-0.8, 0.8], "friction": 0.5})]
    for side, sign in [("left", 1.0), ("right", -1.0)]:
        parts += [
            (f"upper_arm_{side}", {"type": "capsule", "radius": 0.06, "half_height": 0.11}, 2.5,
             [0.36 * sign, 1.47, 0.0], along_x),
            (f"lower_arm_{side}", {"type": "capsule", "radius": 0.05, "half_height": 0.11}, 1.5,
             [0.69 * sign, 1.47, 0.0], along_x),
            (f"upper_leg_{side}", {"type": "capsule", "radius": 0.08, "half_height": 0.14}, 8.0,
             [0.1 * sign, 0.73, 0.0], upright),
            (f"lower_leg_{side}", {"type": "capsule", "radius": 0.07, "half_height": 0.16}, 4.0,
             [0.1 * sign, 0.28, 0.0], upright),
        ]
        # Elbows bend the forearm forward (+Z) and knees the shin backward (-Z), by the
        # right-hand rule about these axes; both start straight, at their lower limit.
        joints += [
            (f"shoulder_{side}", "ball", "torso", f"upper_arm_{side}", [0.19 * sign, 1.47, 0.0],
             [sign, 0.0, 0.0], {"swing_limit": 1.6, "twist_limits": [-0.7, 0.7], "friction": 0.5}),
            (f"elbow_{side}", "revolute", f"upper_arm_{side}", f"lower_arm_{side}",
             [0.53 * sign, 1.47, 0.0], [0.0, -sign, 0.0], {"limits": [0.0, 2.5], "friction": 0.3}),
            (f"hip_{side}", "ball", "torso", f"upper_leg_{side}", [0.1 * sign, 0.95, 0.0],
             [0.0, -1.0, 0.0], {"swing_limit": 1.2, "twist_limits": [-0.5, 0.5], "friction": 2.0}),
            (f"knee_{side}", "revolute", f"upper_leg_{side}", f"lower_leg_{side}",
             [0.1 * sign, 0.51, 0.0], [1.0, 0.0, 0.0], {"limits": [0.0, 2.4], "friction": 1.0}),
        ]
    return parts, joints


def ragdolls():
    """30 ragdolls (ten parts, nine joints each) dropped lying down in six piles of five, each
    turned its own way, onto a ground box."""
    generator = Lcg(20261202)
    parts, part_joints = ragdoll_parts()
    center = [0.0, 0.9, 0.0]
    lying = axis_angle((1.0, 0.0, 0.0), -math.pi / 2.0)
    bodies = [ground_box(20.0)]
    joints = []
    index = 0
    for level in range(5):
        for pile_x in [-2.6, 0.0, 2.6]:
            for pile_z in [-1.3, 1.3]:
                heading = level * math.pi / 2.0 + generator.symmetric(0.4)
                tilt = axis_angle((1.0, 0.0, 0.0), generator.symmetric(0.15))
                turn = quat_mul(axis_angle((0.0, 1.0, 0.0), heading), quat_mul(tilt, lying))
                origin = [pile_x, 0.8 + 0.7 * level, pile_z]

                def place(point):
                    return rounded(add(origin, rotate(turn, add(point, scaled(center, -1.0)))))

                prefix = f"ragdoll{index}"
                for name, shape, mass, position, rotation in parts:
                    bodies.append({
                        "name": f"{prefix}_{name}", "shape": shape, "mass": mass,
                        "position": place(position),
                        "rotation": rounded(quat_mul(turn, rotation), 6),
                    })
                for name, joint_type, body_a, body_b, anchor, axis, extra in part_joints:
                    joint = {
                        "name": f"{prefix}_{name}", "type": joint_type,
                        "body_a": f"{prefix}_{body_a}", "body_b": f"{prefix}_{body_b}",
                        "anchor": place(anchor), "axis": rounded(rotate(turn, axis), 6),
                    }
                    joint.update(extra)
                    joints.append(joint)
                index += 1
    write_scene("ragdolls.json", bodies, joints=joints, compact=True)


def car():
    """A car: a box chassis on four cylinder wheels, each on a revolute joint about its axle with
    a velocity motor, driving over bumps."""
    bodies = [ground_box(40.0)]
    joints = []
    start_x = -10.0
    wheel_radius = 0.35
    bodies.append({
        "name": "chassis", "shape": {"type": "box", "half_extents": [1.0, 0.15, 0.55]},
        "mass": 150.0, "position": [start_x, 0.75, 0.0],
    })
    # A cylinder's axis is its local Y: a quarter turn about X lays it along Z, the axle.
    axle = rounded(axis_angle((1.0, 0.0, 0.0), math.pi / 2.0), 6)
    for name, dx, z in [("front_left", 0.75, -0.75), ("front_right", 0.75, 0.75),
                        ("rear_left", -0.75, -0.75), ("rear_right", -0.75, 0.75)]:
        wheel = f"wheel_{name}"
        center = [start_x + dx, wheel_radius, z]
        bodies.append({
            "name": wheel,
            "shape": {"type": "cylinder", "radius": wheel_radius, "half_height": 0.12},
            "mass": 10.0, "friction": 1.2, "position": center, "rotation": axle,
        })
        # Rolling towards +X turns a wheel clockwise seen from +Z, a negative angular velocity:
        # -10 rad/s is 3.5 m/s.
        joints.append({
            "name": f"axle_{name}", "type": "revolute", "body_a": "chassis", "body_b": wheel,
            "anchor": center, "axis": [0.0, 0.0, 1.0],
            "motor": {"target_velocity": -10.0, "max_force": 60.0},
        })
    for index, (x, radius) in enumerate([(-5.0, 0.08), (-2.0, 0.12), (1.0, 0.1), (4.0, 0.15),
                                         (7.0, 0.1), (9.0, 0.12)]):
        bodies.append({
            "name": f"bump_{index}", "type": "static",
            "shape": {"type": "capsule", "radius": radius, "half_height": 1.5},
            "position": [x, 0.0, 0.0], "rotation": axle,
        })
    write_scene("car.json", bodies, joints=joints)


def cradle_hanging():
    """Newton's cradle on strings: five touching balls of restitution 1, each hung from two
    points of the world by two distance joints (a V), the first pulled 40 degrees aside."""
    bodies = [ground_box(10.0)]
    joints = []
    bar_height = 4.0
    string_drop = 2.5
    for index in range(5):
        angle = math.radians(-40.0) if index == 0 else 0.0
        bar = [float(index), bar_height, 0.0]
        center = rounded(add(bar, [string_drop * math.sin(angle),
                                   -string_drop * math.cos(angle), 0.0]))
        name = f"ball_{index}"
        bodies.append({
            "name": name, "shape": {"type": "sphere", "radius": 0.5}, "mass": 1.0,
            "position": center, "restitution": 1.0, "friction": 0.0,
        })
        for side, z in [("back", -1.0), ("front", 1.0)]:
            joints.append({
                "name": f"string_{index}_{side}", "type": "distance", "body_b": name,
                "anchor": add(bar, [0.0, 0.0, z]), "anchor_b": center,
            })
    write_scene("cradle_hanging.json", bodies, joints=joints)


def mixed_shape(index, rng):
    """One of five dropped shapes in turn: ball, box, capsule, cylinder, hull (a tetrahedron
    with a cap)."""
    kind = index % 5
    if kind == 0:
        return {"type": "sphere", "radius": 0.3}
    if kind == 1:
        return {"type": "box", "half_extents": [0.3, 0.2, 0.4]}
    if kind == 2:
        return {"type": "capsule", "radius": 0.2, "half_height": 0.3}
    if kind == 3:
        return {"type": "cylinder", "radius": 0.3, "half_height": 0.2}
    return {"type": "convex_hull", "points": [
        [0.4, 0.0, 0.0], [-0.2, 0.0, 0.35], [-0.2, 0.0, -0.35], [0.0, 0.5, 0.0],
        [0.0, -0.3, 0.1]]}


def terrain_height(u, v):
    """Hills over the unit square: crossed sine waves in a bowl that rises to the sides."""
    bowl = 12.0 * ((u - 0.5) ** 2 + (v - 0.5) ** 2)
    return (1.2 * math.sin(u * 13.0) * math.cos(v * 11.0)
            + 0.6 * math.sin(u * 5.0 + v * 7.0) + bowl)


# Rolling resistance of the terrain's balls, capsules and cylinders: they rest on slopes up to
# atan 0.3 = 17 degrees and come to rest in the hollows instead of rolling on for ever.
TERRAIN_ROLLING_RESISTANCE = 0.3


def terrain():
    """500 mixed shapes poured on hilly terrain: a 256 x 256 heightfield over 128 m x 128 m; the
    round ones with rolling resistance."""
    samples = 256
    size = 128.0
    heights = [[round(terrain_height(j / (samples - 1), i / (samples - 1)), 3)
                for j in range(samples)] for i in range(samples)]
    bodies = [{
        "name": "terrain", "type": "static", "friction": 0.7,
        "shape": {"type": "heightfield", "heights": heights, "scale": [size, 1.0, size]},
    }]
    rng = Lcg(256)
    for index in range(500):
        u = 0.3 + 0.4 * rng.next()
        v = 0.3 + 0.4 * rng.next()
        ground = terrain_height(u, v)
        position = [(u - 0.5) * size, ground + 2.0 + 10.0 * rng.next(), (v - 0.5) * size]
        axis = normalized([rng.symmetric(1.0), rng.symmetric(1.0), rng.symmetric(1.0) + 0.01])
        shape = mixed_shape(index, rng)
        body = {
            "name": f"shape_{index}", "shape": shape,
            "position": rounded(position), "rotation": rounded(axis_angle(axis, rng.next() * 6.0)),
            "friction": 0.7,
        }
        if shape["type"] in ("sphere", "capsule", "cylinder"):
            body["rolling_resistance"] = TERRAIN_ROLLING_RESISTANCE
        bodies.append(body)
    write_scene("terrain.json", bodies, compact=True)


class ObjWriter:
    """Triangles for a Wavefront OBJ file, each box or wedge a closed solid."""

    def __init__(self):
        self.vertices = []
        self.faces = []

    def quad(self, a, b, c, d):
        """A quad counter-clockwise seen from outside."""
        base = len(self.vertices) + 1
        self.vertices.extend([a, b, c, d])
        self.faces.append([base, base + 1, base + 2, base + 3])

    def box(self, low, high):
        """A box from corner `low` to corner `high`."""
        (x0, y0, z0), (x1, y1, z1) = low, high
        self.quad([x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0])
        self.quad([x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1])
        self.quad([x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1])
        self.quad([x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0])
        self.quad([x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1])
        self.quad([x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0])

    def floor(self, half, cell):
        """A floor at y = 0 of square cells, from -half to half along X and Z."""
        count = int(round(2 * half / cell))
        for i in range(count):
            for j in range(count):
                x0, z0 = -half + j * cell, -half + i * cell
                x1, z1 = x0 + cell, z0 + cell
                self.quad([x0, 0.0, z0], [x0, 0.0, z1], [x1, 0.0, z1], [x1, 0.0, z0])

    def ramp(self, x0, x1, z0, z1, height):
        """A wedge rising along +X from the floor at x0 to `height` at x1."""
        self.quad([x0, 0.0, z0], [x0, 0.0, z1], [x1, height, z1], [x1, height, z0])
        self.quad([x1, 0.0, z0], [x1, height, z0], [x1, height, z1], [x1, 0.0, z1])
        self.quad([x0, 0.0, z0], [x1, 0.0, z0], [x1, 0.0, z1], [x0, 0.0, z1])
        base = len(self.vertices) + 1
        self.vertices.extend([[x0, 0.0, z1], [x1, 0.0, z1], [x1, height, z1],
                              [x0, 0.0, z0], [x1, height, z0], [x1, 0.0, z0]])
        self.faces.extend([[base, base + 1, base + 2], [base + 3, base + 4, base + 5]])

    def write(self, file_name, comment):
        lines = [f"# {comment}", "# written by scenes/generate.py"]
        lines += ["v " + " ".join(f"{c:g}" for c in v) for v in self.vertices]
        lines += ["f " + " ".join(str(i) for i in face) for face in self.faces]
        (SCENES_DIR / file_name).write_text("\n".join(lines) + "\n", encoding="utf-8")


def level():
    """A room (level.obj): a 24 m floor of 2 m tiles, four walls, a flight of 8 stairs up to a
    platform 2.4 m high, and a 15-degree ramp down from it; 150 mixed shapes dropped in."""
    obj = ObjWriter()
    half = 12.0
    obj.floor(half, 2.0)
    for low, high in [([-half - 0.5, 0.0, -half - 0.5], [half + 0.5, 3.0, -half]),
                      ([-half - 0.5, 0.0, half], [half + 0.5, 3.0, half + 0.5]),
                      ([-half - 0.5, 0.0, -half], [-half, 3.0, half]),
                      ([half, 0.0, -half], [half + 0.5, 3.0, half])]:
        obj.box(low, high)
    rise, run, steps = 0.3, 0.5, 8
    for step in range(steps):
        x0 = -6.0 + step * run
        obj.box([x0, 0.0, -11.0], [-6.0 + steps * run, (step + 1) * rise, -7.0])
    platform = steps * rise
    obj.box([-2.0, 0.0, -11.0], [2.0, platform, -7.0])
    ramp_length = platform / math.tan(math.radians(15.0))
    obj.ramp(2.0 + ramp_length, 2.0, -11.0, -7.0, platform)
    obj.write("level.obj", "a room with stairs, a platform and a ramp")
    bodies = [{
        "name": "level", "type": "static", "friction": 0.6,
        "shape": {"type": "trimesh", "file": "level.obj"},
    }]
    rng = Lcg(150)
    for index in range(150):
        position = [rng.symmetric(10.0), 4.0 + 6.0 * rng.next(), -9.0 + rng.symmetric(2.5)
                    if index % 3 == 0 else rng.symmetric(10.0)]
        axis = normalized([rng.symmetric(1.0), rng.symmetric(1.0), rng.symmetric(1.0) + 0.01])
        bodies.append({
            "name": f"shape_{index}", "shape": mixed_shape(index, rng),
            "position": rounded(position), "rotation": rounded(axis_angle(axis, rng.next() * 6.0)),
            "friction": 0.6,
        })
    write_scene("level.json", bodies)


def soak():
    """A scene that never settles, for `rebond soak`: a motor turns a closed box (a compound of
    six walls) about a horizontal axle, tumbling 30 mixed shapes inside; its corners knock a
    chain of five capsules hung on ball joints; 10 more shapes lie in the bowl below (a
    heightfield). No body sleeps."""
    samples = 24
    size = 16.0
    heights = [[round(5.0 * ((j / (samples - 1) - 0.5) ** 2 + (i / (samples - 1) - 0.5) ** 2)
                      + 0.05 * math.sin(j * 0.9) * math.cos(i * 0.7), 3)
                for j in range(samples)] for i in range(samples)]
    center = [0.0, 4.0, 0.0]
    half = 2.0
    walls = []
    for axis in range(3):
        for side in (-1.0, 1.0):
            extents = [half + 0.1] * 3
            extents[axis] = 0.1
            position = [0.0, 0.0, 0.0]
            position[axis] = side * half
            walls.append({"shape": {"type": "box", "half_extents": extents},
                          "position": position})
    bodies = [{
        "name": "bowl", "type": "static", "friction": 0.6,
        "shape": {"type": "heightfield", "heights": heights, "scale": [size, 1.0, size]},
    }, {
        "name": "drum", "shape": {"type": "compound", "children": walls}, "mass": 200.0,
        "position": center, "can_sleep": False,
    }]
    joints = [{
        "name": "drum_axle", "type": "revolute", "body_b": "drum", "anchor": center,
        "axis": [0.0, 0.0, 1.0], "motor": {"target_velocity": 0.8, "max_force": 20000.0},
    }]
    rng = Lcg(40)
    for index in range(40):
        if index < 30:
            position = [rng.symmetric(1.4), center[1] + rng.symmetric(1.4), rng.symmetric(1.4)]
        else:
            position = [-4.0 + rng.symmetric(2.0), 2.0 + rng.next(), rng.symmetric(4.0)]
        axis = normalized([rng.symmetric(1.0), rng.symmetric(1.0), rng.symmetric(1.0) + 0.01])
        bodies.append({
            "name": f"shape_{index}", "shape": mixed_shape(index, rng), "mass": 10.0,
            "position": rounded(position), "rotation": rounded(axis_angle(axis, rng.next() * 6.0)),
            "friction": 0.6, "can_sleep": False,
        })
    previous = None
    for index in range(5):
        name = f"link_{index}"
        top = [2.8, 8.0 - 0.8 * index, 0.0]
        bodies.append({
            "name": name, "shape": {"type": "capsule", "radius": 0.15, "half_height": 0.25},
            "position": add(top, [0.0, -0.4, 0.0]), "can_sleep": False,
        })
        joints.append({"name": f"link_joint_{index}", "type": "ball", "body_a": previous,
                       "body_b": name, "anchor": top})
        previous = name
    write_scene("soak.json", bodies, joints=joints, compact=True)


def slope(name, low_end, angle, length, half_width):
    """A static plank rising along +x at `angle` radians, its top face meeting the ground (y = 0)
    at x = `low_end[0]`, z = `low_end[1]`."""
    half_thickness = 0.1
    rotation = axis_angle((0.0, 0.0, 1.0), angle)
    # The top face's low edge is the centre plus the turned local (-length/2, half_thickness, 0).
    edge = rotate(rotation, [-length / 2.0, half_thickness, 0.0])
    center = [low_end[0] - edge[0], -edge[1], low_end[1]]
    return {
        "name": name, "type": "static",
        "shape": {"type": "box", "half_extents": [length / 2.0, half_thickness, half_width]},
        "position": rounded(center), "rotation": rounded(rotation, 6),
    }


def platformer():
    """A level for the viewer's keyboard-driven character (a kinematic capsule, `player`): stairs
    of 0.25 m steps up to a landing, slopes of 30 and 60 degrees, two one-way ledges to jump up
    through, a conveyor carrying crates, a platform moving on a looping path, a self-closing door
    on a motorised hinge, and crates to push."""
    bodies = [ground_box(20.0)]
    # Stairs along +x from x = 2: four steps 0.25 m high and 0.6 m deep, then a 2 m landing 1 m up.
    for step in range(4):
        height = 0.25 * (step + 1)
        bodies.append({
            "name": f"stair_{step}", "type": "static",
            "shape": {"type": "box", "half_extents": [0.3, height / 2.0, 1.5]},
            "position": [2.3 + 0.6 * step, height / 2.0, 0.0],
        })
    bodies.append({
        "name": "landing", "type": "static",
        "shape": {"type": "box", "half_extents": [1.0, 0.5, 1.5]}, "position": [5.4, 0.5, 0.0],
    })
    # Slopes: 30 degrees is walked up, 60 is steeper than the character's 45-degree limit.
    bodies.append(slope("slope_30", (2.0, -4.5), math.radians(30.0), 4.0, 1.5))
    bodies.append(slope("slope_60", (2.0, -8.5), math.radians(60.0), 2.5, 1.5))
    # One-way ledges on the -x side, solid from above only: 1.2 m up, then 2.2 m up.
    for index, (x, top) in enumerate([(-3.0, 1.2), (-6.0, 2.2)]):
        bodies.append({
            "name": f"ledge_{index}", "type": "static", "one_way": [0.0, 1.0, 0.0],
            "shape": {"type": "box", "half_extents": [1.0, 0.05, 1.5]},
            "position": rounded([x, top - 0.05, 0.0]),
        })
    # A conveyor belt at +z whose surface runs along +x at 1.5 m/s, two crates on it.
    bodies.append({
        "name": "conveyor", "type": "static", "surface_velocity": [1.5, 0.0, 0.0],
        "shape": {"type": "box", "half_extents": [3.0, 0.1, 1.0]}, "position": [0.0, 0.1, 4.5],
    })
    for index, x in enumerate([-2.5, -1.0]):
        bodies.append({
            "name": f"belt_crate_{index}", "shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]},
            "mass": 20.0, "position": [x, 0.5, 4.5],
        })
    # A platform 0.25 m high (a step) that waits 1 s at x = -4, moves to x = 2 at 2 m/s, waits,
    # and comes back, forever.
    def at(time, x):
        return {"time": time, "position": [x, 0.15, 8.0]}
    bodies.append({
        "name": "platform", "type": "kinematic",
        "shape": {"type": "box", "half_extents": [1.0, 0.1, 1.0]},
        "path": {"loop": True, "points": [at(0.0, -4.0), at(1.0, -4.0), at(4.0, 2.0),
                                          at(5.0, 2.0), at(8.0, -4.0)]},
    })
    # A door 2 m high and 1.2 m wide hinged at its edge about +y, held 5 cm off the ground by the
    # hinge; a position motor closes it again after the character pushes it open.
    bodies.append({
        "name": "door", "shape": {"type": "box", "half_extents": [0.05, 1.0, 0.6]},
        "mass": 20.0, "position": [-3.0, 1.05, -3.1],
    })
    joints = [{
        "name": "door_hinge", "type": "revolute", "body_b": "door", "anchor": [-3.0, 1.05, -2.5],
        "axis": [0.0, 1.0, 0.0],
        "motor": {"target_position": 0.0, "stiffness": 200.0, "damping": 60.0, "max_force": 300.0},
    }]
    for index, (x, z) in enumerate([(-1.0, -2.0), (-1.0, -3.0), (-1.5, -2.5)]):
        bodies.append({
            "name": f"crate_{index}", "shape": {"type": "box", "half_extents": [0.25, 0.25, 0.25]},
            "mass": 10.0, "position": [x, 0.25, z],
        })
    # The player: a capsule 1.6 m tall standing 1 cm above the ground (the controller's offset).
    bodies.append({
        "name": "player", "type": "kinematic",
        "shape": {"type": "capsule", "radius": 0.3, "half_height": 0.5},
        "position": [0.0, 0.81, 0.0],
    })
    character = {"body": "player", "walk_speed": 4.0, "jump_speed": 6.0}
    write_scene("platformer.json", bodies, joints=joints, character=character)


if __name__ == "__main__":
    showcase()
    pyramid()
    column()
    rain()
    ramp()
    cradle()
    spinner()
    pendulum()
    chain()
    bridge()
    ragdolls()
    car()
    cradle_hanging()
    terrain()
    level()
    soak()
    platformer()
