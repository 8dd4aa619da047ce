//! The engine-neutral scene descriptions: the settings both engines share, every body's shape,
//! pose and mass, and the deterministic jitter that places and tilts them.

use crate::rebond_engine::rebond_shape;
use rebond::{Quat, Vec3};
use std::f32::consts::FRAC_PI_2;

/// Step length, seconds.
pub const DT: f32 = 1.0 / 60.0;
/// Substeps per step (rebond `substeps`, rapier `num_solver_iterations`).
pub const SUBSTEPS: u32 = 4;

/// rebond's substeps: [`SUBSTEPS`], unless `COMPARE_REBOND_SUBSTEPS` sets another count (to run
/// rebond alone at, say, its default 8; rapier keeps [`SUBSTEPS`]).
pub fn rebond_substeps() -> u32 {
    std::env::var("COMPARE_REBOND_SUBSTEPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(SUBSTEPS)
}
/// Gravity along −Y, m/s².
pub const GRAVITY: f32 = -9.81;
/// Friction coefficient of every body, both engines.
pub const FRICTION: f32 = 0.6;
/// Coefficient of restitution of every body, both engines.
pub const RESTITUTION: f32 = 0.0;
/// Density used to turn volumes into masses, kg/m³; the mass is then given explicitly to both.
const DENSITY: f32 = 1000.0;

#[derive(Clone, Debug)]
pub enum ShapeSpec {
    Cuboid([f32; 3]),
    Sphere(f32),
    Capsule {
        radius: f32,
        half_height: f32,
    },
    Cylinder {
        radius: f32,
        half_height: f32,
    },
    Hull(Vec<[f32; 3]>),
    /// `heights[i][j]`: row `i` along +Z, column `j` along +X, the grid spanning `scale[0]` ×
    /// `scale[2]` centred on the body, heights times `scale[1]`; each cell split along the
    /// diagonal from sample `(i, j)` to `(i + 1, j + 1)` (rebond's `HeightField`).
    HeightField {
        heights: Vec<Vec<f32>>,
        scale: [f32; 3],
    },
    /// Triangles counter-clockwise seen from their front (up).
    TriMesh {
        vertices: Vec<[f32; 3]>,
        indices: Vec<[u32; 3]>,
    },
}

#[derive(Clone, Debug)]
pub struct BodySpec {
    pub fixed: bool,
    pub shape: ShapeSpec,
    pub position: [f32; 3],
    /// Rotation as a scaled axis (axis × angle, radians).
    pub rotation: [f32; 3],
    /// Mass, kg (dynamic bodies).
    pub mass: f32,
}

/// What a joint holds, with its limits (radians).
#[derive(Clone, Debug)]
pub enum JointKind {
    /// Holds the anchor point. Swing: largest angle between the twist axis as fixed in each body;
    /// twist: `[min, max]` rotation about it. rebond takes these as a swing cone and twist limits;
    /// rapier has no cone, so it gets `[-swing, swing]` on each of the two axes across the twist
    /// axis (its joint frame's Y and Z) and the twist on X: a square cone, wider on the diagonals.
    Ball { swing: f32, twist: [f32; 2] },
    /// Holds the anchor point and the axis; `[min, max]` rotation of `body_b` relative to
    /// `body_a` about the axis, right-handed (rebond's convention, and rapier's about its joint
    /// frame's X), or free.
    Revolute { limits: Option<[f32; 2]> },
}

/// A joint between two bodies of the scene, placed in the world as the bodies start: both engines
/// fix the anchor and axis to each body from the bodies' start poses, so every angle starts at 0.
#[derive(Clone, Debug)]
pub struct JointSpec {
    pub kind: JointKind,
    /// Indices in [`Scene::bodies`].
    pub body_a: usize,
    pub body_b: usize,
    /// World anchor, m.
    pub anchor: [f32; 3],
    /// Unit world axis: the hinge axis, or the ball joint's twist axis.
    pub axis: [f32; 3],
}

/// Which dynamic bodies the sink figure of a stack watches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sink {
    /// Not a stack: no sink figure.
    None,
    /// The top body of a column (the last dynamic body, in scene order).
    Top,
    /// Every dynamic body (pyramids).
    Any,
}

impl Sink {
    /// The largest drop below its start height of a watched body, m (0 when none is below its
    /// start): `max(start_y - y)` over the watched bodies, clamped at 0. `start` and `current`
    /// are the dynamic bodies' positions, in scene order; non-finite positions are skipped.
    pub fn drop(self, start: &[[f32; 3]], current: &[[f32; 3]]) -> f32 {
        let pairs = current.len().min(start.len());
        let skip = match self {
            Sink::None => return 0.0,
            Sink::Top => pairs.saturating_sub(1),
            Sink::Any => 0,
        };
        current
            .iter()
            .zip(start)
            .skip(skip)
            .filter(|(now, _)| now[1].is_finite())
            .map(|(now, then)| then[1] - now[1])
            .fold(0.0, f32::max)
    }
}

pub struct Scene {
    pub bodies: Vec<BodySpec>,
    pub joints: Vec<JointSpec>,
    /// Whether the largest drift of a dynamic body from its start is a meaningful figure.
    pub is_stack: bool,
    /// The stacks' sink: the largest drop below its start height over the run of the top body
    /// (columns) or of any body (pyramids).
    pub sink: Sink,
    /// A dynamic body (index among the dynamic bodies, in scene order) whose drop below its start
    /// height at the end of the run is reported: the bridge's middle plank.
    pub sag_body: Option<usize>,
}

fn unit_box() -> ShapeSpec {
    ShapeSpec::Cuboid([0.5, 0.5, 0.5])
}

fn volume(shape: &ShapeSpec) -> f32 {
    rebond_shape(shape).volume()
}

fn dynamic(shape: ShapeSpec, position: [f32; 3], rotation: [f32; 3]) -> BodySpec {
    let mass = DENSITY * volume(&shape);
    BodySpec {
        fixed: false,
        shape,
        position,
        rotation,
        mass,
    }
}

/// A fixed body of `shape` at the origin.
pub fn fixed(shape: ShapeSpec) -> BodySpec {
    BodySpec {
        fixed: true,
        shape,
        position: [0.0; 3],
        rotation: [0.0; 3],
        mass: 0.0,
    }
}

pub fn fixed_box(half_extents: [f32; 3], position: [f32; 3]) -> BodySpec {
    BodySpec {
        position,
        ..fixed(ShapeSpec::Cuboid(half_extents))
    }
}

/// A ground box whose top face is at y = 0.
fn ground(half_x: f32, half_z: f32) -> BodySpec {
    fixed_box([half_x, 0.5, half_z], [0.0, -0.5, 0.0])
}

/// Deterministic pseudo-random numbers in [-1, 1) (SplitMix64), so both engines get the same
/// offsets and tilts.
pub struct Jitter(pub u64);

impl Jitter {
    pub fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    }

    /// Three successive values, each times `scale`: in [-scale, scale).
    fn next3(&mut self, scale: f32) -> [f32; 3] {
        [(); 3].map(|()| self.next() * scale)
    }
}

pub fn build_scene(name: &str) -> Scene {
    let mut bodies = Vec::new();
    let mut joints = Vec::new();
    let mut sag_body = None;
    let is_stack = match name {
        // Square pyramid, 10×10 base up to 1×1: 385 boxes.
        "pyramid" => {
            bodies.push(ground(20.0, 20.0));
            for layer in 0..10 {
                let n = 10 - layer;
                let half = (n as f32 - 1.0) / 2.0;
                for i in 0..n {
                    for k in 0..n {
                        bodies.push(dynamic(
                            unit_box(),
                            [i as f32 - half, 0.5 + layer as f32, k as f32 - half],
                            [0.0; 3],
                        ));
                    }
                }
            }
            true
        }
        // 16×16×16 boxes, spacing 1.5, each moved by up to 0.2 m and tilted by up to 0.3 rad.
        "rain" => {
            bodies.push(ground(50.0, 50.0));
            let grid = JitteredGrid {
                seed: 7,
                columns: 16,
                layers: 16,
                lowest: 2.0,
                max_tilt: 0.3,
            };
            grid.fill(&mut bodies, &[unit_box()], |_, _| 0.0);
            false
        }
        // 20 boxes stacked; `column40`: 40.
        "column" | "column40" => {
            bodies.push(ground(10.0, 10.0));
            let height = if name == "column40" { 40 } else { 20 };
            for layer in 0..height {
                bodies.push(dynamic(
                    unit_box(),
                    [0.0, 0.5 + layer as f32, 0.0],
                    [0.0; 3],
                ));
            }
            true
        }
        // 20 flat pyramids of base 20 (210 boxes each), 2 m apart along Z: 4,200 boxes.
        "many_pyramids" => {
            bodies.push(ground(30.0, 30.0));
            for pyramid in 0..20 {
                let z = (pyramid as f32 - 9.5) * 2.0;
                flat_pyramid(&mut bodies, 20, z);
            }
            true
        }
        // One flat pyramid of base 100: 5,050 boxes.
        "large_pyramid" => {
            bodies.push(ground(60.0, 10.0));
            flat_pyramid(&mut bodies, 100, 0.0);
            true
        }
        // 12×12×14 = 2,016 spheres, capsules, cylinders and hulls in turn, dropped into a box
        // container (floor and four walls, inner 20 m × 20 m, walls 8 m high).
        "mixed" => {
            bodies.push(fixed_box([10.5, 0.5, 10.5], [0.0, -0.5, 0.0]));
            bodies.push(fixed_box([0.25, 4.0, 10.5], [-10.25, 4.0, 0.0]));
            bodies.push(fixed_box([0.25, 4.0, 10.5], [10.25, 4.0, 0.0]));
            bodies.push(fixed_box([10.0, 4.0, 0.25], [0.0, 4.0, -10.25]));
            bodies.push(fixed_box([10.0, 4.0, 0.25], [0.0, 4.0, 10.25]));
            let shapes = [
                ShapeSpec::Sphere(0.4),
                ShapeSpec::Capsule {
                    radius: 0.3,
                    half_height: 0.35,
                },
                ShapeSpec::Cylinder {
                    radius: 0.4,
                    half_height: 0.35,
                },
                ShapeSpec::Hull(hull_points()),
            ];
            let grid = JitteredGrid {
                seed: 11,
                columns: 12,
                layers: 14,
                lowest: 1.5,
                max_tilt: 0.5,
            };
            grid.fill(&mut bodies, &shapes, |_, _| 0.0);
            false
        }
        // 36 ragdolls of 11 bodies and 10 joints lying on their backs, 4 layers of 3×3 spaced
        // 2.2 m, the layers 0.8 m apart from 1 m up and turned 90° from one to the next, each
        // ragdoll moved by up to 0.3 m and turned by up to 0.3 rad about Y: a pile on the ground.
        "ragdolls" => {
            bodies.push(ground(20.0, 20.0));
            let mut jitter = Jitter(23);
            for layer in 0..4 {
                for i in 0..3 {
                    for k in 0..3 {
                        let offset = jitter.next3(0.3);
                        let yaw =
                            jitter.next() * 0.3 + if layer % 2 == 1 { FRAC_PI_2 } else { 0.0 };
                        let centre = Vec3::new(
                            (i as f32 - 1.0) * 2.2 + offset[0],
                            1.0 + layer as f32 * 0.8,
                            (k as f32 - 1.0) * 2.2 + offset[2],
                        );
                        let orientation =
                            Quat::from_rotation_y(yaw) * Quat::from_rotation_x(-FRAC_PI_2);
                        ragdoll(&mut bodies, &mut joints, centre, orientation);
                    }
                }
            }
            false
        }
        // A rope bridge: 30 planks (0.5 × 0.1 × 2 m, 100 kg) hanging between two fixed blocks
        // 5 m up, on 31 free hinges along Z with 2 cm between planks; it starts on a circular
        // arc 1 m deep. 20 boxes of 0.5 m (125 kg) fall on its middle 10 m from 7 to 8.3 m.
        "bridge" => {
            bodies.push(ground(20.0, 20.0));
            sag_body = Some(bridge(&mut bodies, &mut joints, 30));
            let mut jitter = Jitter(31);
            for i in 0..20 {
                let offset = jitter.next3(0.1);
                let tilt = jitter.next3(0.3);
                bodies.push(dynamic(
                    ShapeSpec::Cuboid([0.25; 3]),
                    [
                        -4.5 + (i / 2) as f32 + offset[0],
                        7.0 + 0.65 * (i % 3) as f32 + offset[1],
                        if i % 2 == 0 { -0.5 } else { 0.5 } + offset[2],
                    ],
                    tilt,
                ));
            }
            false
        }
        // 512 shapes (`pile_shapes` in turn, 8 × 8 columns, 8 layers) poured from 1.5 to 12 m
        // above the built-in `terrain` heightfield, around its middle.
        "terrain_pile" => {
            bodies.push(fixed(terrain()));
            let grid = JitteredGrid {
                seed: 41,
                columns: 8,
                layers: 8,
                lowest: 1.5,
                max_tilt: 1.0,
            };
            grid.fill(&mut bodies, &pile_shapes(), |x, z| {
                terrain_height(
                    f64::from(x / TERRAIN_SIZE + 0.5),
                    f64::from(z / TERRAIN_SIZE + 0.5),
                ) as f32
            });
            false
        }
        // The same pile poured on a bumpy triangle mesh of 32,768 triangles (`bumpy_mesh`).
        "mesh_pile" => {
            bodies.push(fixed(bumpy_mesh()));
            let grid = JitteredGrid {
                seed: 43,
                columns: 8,
                layers: 8,
                lowest: 1.5,
                max_tilt: 1.0,
            };
            grid.fill(&mut bodies, &pile_shapes(), bump_height);
            false
        }
        other => panic!("unknown scene {other:?}"),
    };
    let sink = match name {
        "column" | "column40" => Sink::Top,
        _ if is_stack => Sink::Any,
        _ => Sink::None,
    };
    Scene {
        bodies,
        joints,
        is_stack,
        sink,
        sag_body,
    }
}

/// Pushes a ragdoll of 11 bodies and 10 joints. Its parts are laid out standing in a T-pose,
/// facing +Z, centred on the origin, then turned by `orientation` and moved to `centre`.
fn ragdoll(
    bodies: &mut Vec<BodySpec>,
    joints: &mut Vec<JointSpec>,
    centre: Vec3,
    orientation: Quat,
) {
    // Capsules stand along Y; an arm lies along X.
    let along_x = Quat::from_rotation_z(FRAC_PI_2);
    let capsule = |radius, half_height| ShapeSpec::Capsule {
        radius,
        half_height,
    };
    // Half the standing height: the parts below are given from the soles up.
    let lift = Vec3::new(0.0, -0.88, 0.0);
    let first = bodies.len();
    let mut part = |shape, position: [f32; 3], rotation: Quat| {
        let position = centre + orientation * (Vec3::from(position) + lift);
        let rotation = (orientation * rotation).to_scaled_axis();
        bodies.push(dynamic(shape, position.to_array(), rotation.to_array()));
    };
    // Pelvis, chest, head, then each side's upper arm, forearm, thigh and shin. Gaps of 3 to 6 cm
    // between joined parts keep them clear of each other at rest.
    let (pelvis, chest) = ([0.16, 0.1, 0.1], [0.2, 0.22, 0.12]);
    part(ShapeSpec::Cuboid(pelvis), [0.0, 0.95, 0.0], Quat::IDENTITY);
    part(ShapeSpec::Cuboid(chest), [0.0, 1.3, 0.0], Quat::IDENTITY);
    part(ShapeSpec::Sphere(0.12), [0.0, 1.7, 0.0], Quat::IDENTITY);
    for side in [1.0, -1.0] {
        part(capsule(0.05, 0.1), [0.38 * side, 1.45, 0.0], along_x);
        part(capsule(0.045, 0.1), [0.695 * side, 1.45, 0.0], along_x);
        part(capsule(0.07, 0.15), [0.1 * side, 0.6, 0.0], Quat::IDENTITY);
        part(capsule(0.06, 0.15), [0.1 * side, 0.15, 0.0], Quat::IDENTITY);
    }
    let mut joint = |kind, body_a: usize, body_b: usize, anchor: [f32; 3], axis: [f32; 3]| {
        joints.push(JointSpec {
            kind,
            body_a: first + body_a,
            body_b: first + body_b,
            anchor: (centre + orientation * (Vec3::from(anchor) + lift)).to_array(),
            axis: (orientation * Vec3::from(axis)).to_array(),
        });
    };
    let ball = |swing, twist: f32| JointKind::Ball {
        swing,
        twist: [-twist, twist],
    };
    // Elbows and knees bend one way only, from straight: forearms forward, shins backward.
    let hinge = || JointKind::Revolute {
        limits: Some([0.0, 2.4]),
    };
    joint(ball(0.5, 0.4), 0, 1, [0.0, 1.065, 0.0], [0.0, 1.0, 0.0]); // spine
    joint(ball(0.6, 0.8), 1, 2, [0.0, 1.55, 0.0], [0.0, 1.0, 0.0]); // neck
    for (index, side) in [1.0f32, -1.0].into_iter().enumerate() {
        let (upper_arm, forearm, thigh, shin) =
            (3 + 4 * index, 4 + 4 * index, 5 + 4 * index, 6 + 4 * index);
        joint(
            ball(1.3, 0.6),
            1,
            upper_arm,
            [0.215 * side, 1.45, 0.0],
            [side, 0.0, 0.0],
        );
        // About −Y on the left (+X) side and +Y on the right, a positive angle swings the
        // forearm towards +Z on both.
        joint(
            hinge(),
            upper_arm,
            forearm,
            [0.54 * side, 1.45, 0.0],
            [0.0, -side, 0.0],
        );
        joint(
            ball(1.0, 0.5),
            0,
            thigh,
            [0.1 * side, 0.835, 0.0],
            [0.0, -1.0, 0.0],
        );
        joint(
            hinge(),
            thigh,
            shin,
            [0.1 * side, 0.37, 0.0],
            [1.0, 0.0, 0.0],
        );
    }
}

/// Pushes two fixed blocks and `planks` planks hanging between them on hinges along Z, on a
/// circular arc 1 m deep; returns the middle plank's index among the dynamic bodies.
fn bridge(bodies: &mut Vec<BodySpec>, joints: &mut Vec<JointSpec>, planks: usize) -> usize {
    const PITCH: f32 = 0.52;
    const HEIGHT: f32 = 5.0;
    // The planks turn by equal steps from −MAX_TILT to +MAX_TILT: an arc whose depth is about
    // planks × PITCH × MAX_TILT / 4 = 1 m for 30 planks.
    const MAX_TILT: f32 = 0.25;
    let tilt = |i: usize| -MAX_TILT * (1.0 - (2 * i + 1) as f32 / planks as f32);
    let span: f32 = (0..planks).map(|i| PITCH * tilt(i).cos()).sum();
    let left = Vec3::new(-span / 2.0, HEIGHT, 0.0);
    let dynamic_before = bodies.iter().filter(|b| !b.fixed).count();
    let anchor_block = bodies.len();
    bodies.push(fixed_box([0.5, 0.5, 1.2], [left.x - 0.51, HEIGHT, 0.0]));
    bodies.push(fixed_box([0.5, 0.5, 1.2], [span / 2.0 + 0.51, HEIGHT, 0.0]));
    let hinge = |body_a, body_b, anchor: Vec3| JointSpec {
        kind: JointKind::Revolute { limits: None },
        body_a,
        body_b,
        anchor: anchor.to_array(),
        axis: [0.0, 0.0, 1.0],
    };
    let mut joint_point = left;
    for i in 0..planks {
        let direction = Vec3::new(tilt(i).cos(), tilt(i).sin(), 0.0);
        let next = joint_point + PITCH * direction;
        let previous = if i == 0 {
            anchor_block
        } else {
            bodies.len() - 1
        };
        joints.push(hinge(previous, bodies.len(), joint_point));
        bodies.push(dynamic(
            ShapeSpec::Cuboid([PITCH / 2.0 - 0.01, 0.05, 1.0]),
            ((joint_point + next) / 2.0).to_array(),
            [0.0, 0.0, tilt(i)],
        ));
        joint_point = next;
    }
    joints.push(hinge(anchor_block + 1, bodies.len() - 1, joint_point));
    dynamic_before + planks / 2
}

/// Dynamic bodies on a grid of spacing 1.5 m centred on the Y axis, `columns` × `columns` per
/// layer, each moved by up to 0.2 m along each axis and tilted by up to `max_tilt` rad about each.
struct JitteredGrid {
    /// Seed of the [`Jitter`] that draws the offsets and tilts.
    seed: u64,
    /// Bodies along X and along Z.
    columns: usize,
    /// Layers along Y.
    layers: usize,
    /// Height of the lowest layer's centres before the offset, metres.
    lowest: f32,
    /// Largest tilt about each axis, radians.
    max_tilt: f32,
}

impl JitteredGrid {
    /// Pushes the bodies layer by layer, row by row, taking `shapes` in turn; each column stands
    /// on `ground(x, z)`, the height of the ground under it (metres, 0 for a flat ground).
    fn fill(
        &self,
        bodies: &mut Vec<BodySpec>,
        shapes: &[ShapeSpec],
        ground: impl Fn(f32, f32) -> f32,
    ) {
        let mut jitter = Jitter(self.seed);
        let centre = (self.columns as f32 - 1.0) / 2.0;
        let mut index = 0;
        for j in 0..self.layers {
            for i in 0..self.columns {
                for k in 0..self.columns {
                    let offset = jitter.next3(0.2);
                    let tilt = jitter.next3(self.max_tilt);
                    let x = (i as f32 - centre) * 1.5 + offset[0];
                    let z = (k as f32 - centre) * 1.5 + offset[2];
                    bodies.push(dynamic(
                        shapes[index % shapes.len()].clone(),
                        [
                            x,
                            ground(x, z) + self.lowest + j as f32 * 1.5 + offset[1],
                            z,
                        ],
                        tilt,
                    ));
                    index += 1;
                }
            }
        }
    }
}

/// A pyramid in the XY plane: `base` boxes on the ground, one fewer on each row above.
fn flat_pyramid(bodies: &mut Vec<BodySpec>, base: usize, z: f32) {
    for row in 0..base {
        let n = base - row;
        let half = (n as f32 - 1.0) / 2.0;
        for i in 0..n {
            bodies.push(dynamic(
                unit_box(),
                [i as f32 - half, 0.5 + row as f32, z],
                [0.0; 3],
            ));
        }
    }
}

/// An irregular pebble about 1 m across: 12 points, a hexagonal bipyramid with a flattened,
/// twisted top ring.
fn hull_points() -> Vec<[f32; 3]> {
    let mut points = Vec::new();
    for i in 0..6 {
        let angle = i as f32 * std::f32::consts::TAU / 6.0;
        points.push([0.5 * angle.cos(), -0.15, 0.45 * angle.sin()]);
        let angle = angle + 0.5;
        points.push([0.35 * angle.cos(), 0.25, 0.3 * angle.sin()]);
    }
    points.push([0.05, -0.4, 0.0]);
    points.push([-0.05, 0.4, 0.05]);
    points
}

/// The five shapes poured on the terrain and the mesh: those of the built-in `terrain` and
/// `level` scenes (`mixed_shape` in `scenes/generate.py`), 0.4 to 0.8 m across.
fn pile_shapes() -> [ShapeSpec; 5] {
    [
        ShapeSpec::Sphere(0.3),
        ShapeSpec::Cuboid([0.3, 0.2, 0.4]),
        ShapeSpec::Capsule {
            radius: 0.2,
            half_height: 0.3,
        },
        ShapeSpec::Cylinder {
            radius: 0.3,
            half_height: 0.2,
        },
        ShapeSpec::Hull(vec![
            [0.4, 0.0, 0.0],
            [-0.2, 0.0, 0.35],
            [-0.2, 0.0, -0.35],
            [0.0, 0.5, 0.0],
            [0.0, -0.3, 0.1],
        ]),
    ]
}

/// Samples along each side of the terrain.
const TERRAIN_SAMPLES: usize = 256;
/// Side of the terrain, metres.
const TERRAIN_SIZE: f32 = 128.0;

/// The built-in `terrain` scene's hills over the unit square (`terrain_height` in
/// `scenes/generate.py`): crossed sine waves in a bowl that rises to the sides, metres.
fn terrain_height(u: f64, v: f64) -> f64 {
    let bowl = 12.0 * ((u - 0.5).powi(2) + (v - 0.5).powi(2));
    1.2 * (u * 13.0).sin() * (v * 11.0).cos() + 0.6 * (u * 5.0 + v * 7.0).sin() + bowl
}

/// The built-in `terrain` scene's heightfield: 256 × 256 samples of [`terrain_height`] rounded to
/// the millimetre, as `scenes/terrain.json` holds them, over 128 m × 128 m (cells of 0.5 m).
pub fn terrain() -> ShapeSpec {
    let last = (TERRAIN_SAMPLES - 1) as f64;
    let heights = (0..TERRAIN_SAMPLES)
        .map(|i| {
            (0..TERRAIN_SAMPLES)
                .map(|j| {
                    let height = terrain_height(j as f64 / last, i as f64 / last);
                    ((height * 1000.0).round() / 1000.0) as f32
                })
                .collect()
        })
        .collect();
    ShapeSpec::HeightField {
        heights,
        scale: [TERRAIN_SIZE, 1.0, TERRAIN_SIZE],
    }
}

/// Cells along each side of the bumpy mesh.
const MESH_CELLS: usize = 128;
/// Side of the bumpy mesh, metres.
const MESH_SIZE: f32 = 64.0;

/// Height of the bumpy mesh's vertices, metres: bumps 7 m apart and up to half a metre high,
/// slopes up to about 27°, in a shallow bowl.
fn bump_height(x: f32, z: f32) -> f32 {
    0.35 * (0.9 * x).sin() * (0.7 * z).cos()
        + 0.2 * (0.5 * x + 1.3 * z).sin()
        + 0.003 * (x * x + z * z)
}

/// A bumpy triangle mesh, 64 m × 64 m centred on the origin: a grid of 128 × 128 cells whose
/// inner vertices are moved by up to 0.1 m along X and Z, raised to [`bump_height`], each cell
/// split along one diagonal or the other in a checkerboard: 16,641 shared vertices, 32,768
/// triangles, counter-clockwise seen from above.
pub fn bumpy_mesh() -> ShapeSpec {
    let n = MESH_CELLS;
    let mut jitter = Jitter(53);
    let mut vertices = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let offset = jitter.next3(0.2 * MESH_SIZE / n as f32);
            let inner = (1..n).contains(&i) && (1..n).contains(&j);
            let (dx, dz) = if inner {
                (offset[0], offset[2])
            } else {
                (0.0, 0.0)
            };
            let x = (j as f32 / n as f32 - 0.5) * MESH_SIZE + dx;
            let z = (i as f32 / n as f32 - 0.5) * MESH_SIZE + dz;
            vertices.push([x, bump_height(x, z), z]);
        }
    }
    let vertex = |i: usize, j: usize| (i * (n + 1) + j) as u32;
    let mut indices = Vec::with_capacity(2 * n * n);
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            );
            if (i + j) % 2 == 0 {
                indices.extend([[a, b, c], [a, c, d]]);
            } else {
                indices.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    ShapeSpec::TriMesh { vertices, indices }
}

#[cfg(test)]
mod tests {
    use super::{build_scene, ShapeSpec, Sink};

    /// `column40` is `column` twice as tall: unit boxes 1 m apart, the lowest on the ground's top
    /// (y = 0); the sink watches the top box of both, every box of the pyramids.
    #[test]
    fn column40_is_a_taller_column() {
        for (name, height) in [("column", 20), ("column40", 40)] {
            let scene = build_scene(name);
            let boxes: Vec<_> = scene.bodies.iter().filter(|body| !body.fixed).collect();
            assert_eq!(boxes.len(), height, "{name}");
            for (layer, body) in boxes.iter().enumerate() {
                assert!(matches!(body.shape, ShapeSpec::Cuboid([0.5, 0.5, 0.5])));
                assert_eq!(body.position, [0.0, 0.5 + layer as f32, 0.0], "{name}");
                assert_eq!(body.rotation, [0.0; 3]);
            }
            assert!(scene.is_stack);
            assert_eq!(scene.sink, Sink::Top, "{name}");
        }
        for name in ["pyramid", "many_pyramids", "large_pyramid"] {
            assert_eq!(build_scene(name).sink, Sink::Any, "{name}");
        }
        assert_eq!(build_scene("rain").sink, Sink::None);
    }

    /// The sink is the largest drop below the start height of the watched bodies, never
    /// negative; rising and sideways moves do not count, non-finite positions are skipped.
    #[test]
    fn sink_is_the_largest_drop() {
        let start = [[0.0, 0.5, 0.0], [0.0, 1.5, 0.0], [0.0, 2.5, 0.0]];
        let current = [[0.3, 0.2, 0.0], [0.0, 1.4, 0.0], [0.0, 2.45, 0.0]];
        assert!((Sink::Top.drop(&start, &current) - 0.05).abs() < 1e-6);
        assert!((Sink::Any.drop(&start, &current) - 0.3).abs() < 1e-6);
        assert_eq!(Sink::None.drop(&start, &current), 0.0);
        let risen = [[5.0, 0.6, 0.0], [0.0, 1.5, 0.0], [0.0, 2.6, 0.0]];
        assert_eq!(Sink::Any.drop(&start, &risen), 0.0);
        let broken = [[0.0, f32::NAN, 0.0], [0.0, 1.5, 0.0], [0.0, 2.0, 0.0]];
        assert_eq!(Sink::Any.drop(&start, &broken), 0.5);
    }
}
