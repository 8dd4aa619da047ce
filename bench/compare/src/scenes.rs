//! The engine-neutral scene descriptions: the settings both engines share, every body's shape,
//! pose and mass, and the deterministic jitter that places and tilts them.

use crate::rebond_engine::rebond_shape;

/// Step length, seconds.
pub const DT: f32 = 1.0 / 60.0;
/// Substeps per step (rebond `substeps`, rapier `num_solver_iterations`).
pub const SUBSTEPS: u32 = 4;
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
    Capsule { radius: f32, half_height: f32 },
    Cylinder { radius: f32, half_height: f32 },
    Hull(Vec<[f32; 3]>),
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

pub struct Scene {
    pub bodies: Vec<BodySpec>,
    /// Whether the largest drift of a dynamic body from its start is a meaningful figure.
    pub is_stack: bool,
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

pub fn fixed_box(half_extents: [f32; 3], position: [f32; 3]) -> BodySpec {
    BodySpec {
        fixed: true,
        shape: ShapeSpec::Cuboid(half_extents),
        position,
        rotation: [0.0; 3],
        mass: 0.0,
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
            grid.fill(&mut bodies, &[unit_box()]);
            false
        }
        // 20 boxes stacked.
        "column" => {
            bodies.push(ground(10.0, 10.0));
            for layer in 0..20 {
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
            grid.fill(&mut bodies, &shapes);
            false
        }
        other => panic!("unknown scene {other:?}"),
    };
    Scene { bodies, is_stack }
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
    /// Pushes the bodies layer by layer, row by row, taking `shapes` in turn.
    fn fill(&self, bodies: &mut Vec<BodySpec>, shapes: &[ShapeSpec]) {
        let mut jitter = Jitter(self.seed);
        let centre = (self.columns as f32 - 1.0) / 2.0;
        let mut index = 0;
        for j in 0..self.layers {
            for i in 0..self.columns {
                for k in 0..self.columns {
                    let offset = jitter.next3(0.2);
                    let tilt = jitter.next3(self.max_tilt);
                    bodies.push(dynamic(
                        shapes[index % shapes.len()].clone(),
                        [
                            (i as f32 - centre) * 1.5 + offset[0],
                            self.lowest + j as f32 * 1.5 + offset[1],
                            (k as f32 - centre) * 1.5 + offset[2],
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
