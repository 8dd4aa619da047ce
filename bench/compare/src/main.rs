//! Side-by-side benchmark of rebond against rapier3d (issue 7).
//!
//! Run with no arguments, the binary is the driver: for each scene it starts itself once per
//! engine and round (`compare --engine E --scene S --steps N`), alternating which engine goes
//! first from one round to the next, and collects each child's `RESULT` line: median step time,
//! peak memory (VmHWM of the child) and stability figures. It prints a table, then one line per
//! scene in the form `SCENE ratio=R rebond_ms=A rapier_ms=B rebond_mb=C rapier_mb=D`.
//!
//! Every scene is described once, engine-neutrally ([`Scene`]), and built from that description
//! in each engine, so shapes, sizes, masses, poses and materials are the same by construction.
//!
//! `compare --rays` is the scene-query comparison instead: 10,000 static boxes and 10,000 rays,
//! the same in both engines, cast through each engine's query API in one process, alternating
//! engines from one round to the next ([`run_rays`]).

use std::process::Command;
use std::time::Instant;

/// Step length, seconds.
const DT: f32 = 1.0 / 60.0;
/// Substeps per step (rebond `substeps`, rapier `num_solver_iterations`).
const SUBSTEPS: u32 = 4;
/// Gravity along −Y, m/s².
const GRAVITY: f32 = -9.81;
/// Friction coefficient of every body, both engines.
const FRICTION: f32 = 0.6;
/// Coefficient of restitution of every body, both engines.
const RESTITUTION: f32 = 0.0;
/// Density used to turn volumes into masses, kg/m³; the mass is then given explicitly to both.
const DENSITY: f32 = 1000.0;
/// Steps at the start of each run left out of the timing (still simulated and checked).
const WARMUP_STEPS: usize = 10;

/// The scenes, with their default step and round counts.
const SCENES: &[(&str, usize, usize)] = &[
    ("pyramid", 600, 5),
    ("rain", 300, 5),
    ("column", 600, 5),
    ("many_pyramids", 300, 5),
    ("large_pyramid", 300, 5),
    ("mixed", 300, 5),
];

const ENGINES: [&str; 2] = ["rebond", "rapier"];

// ---------------------------------------------------------------------------------------------
// Engine-neutral scene description
// ---------------------------------------------------------------------------------------------

#[derive(Clone, Debug)]
enum ShapeSpec {
    Cuboid([f32; 3]),
    Sphere(f32),
    Capsule { radius: f32, half_height: f32 },
    Cylinder { radius: f32, half_height: f32 },
    Hull(Vec<[f32; 3]>),
}

#[derive(Clone, Debug)]
struct BodySpec {
    fixed: bool,
    shape: ShapeSpec,
    position: [f32; 3],
    /// Rotation as a scaled axis (axis × angle, radians).
    rotation: [f32; 3],
    /// Mass, kg (dynamic bodies).
    mass: f32,
}

struct Scene {
    bodies: Vec<BodySpec>,
    /// Whether the largest drift of a dynamic body from its start is a meaningful figure.
    is_stack: bool,
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

fn fixed_box(half_extents: [f32; 3], position: [f32; 3]) -> BodySpec {
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
struct Jitter(u64);

impl Jitter {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    }
}

fn build_scene(name: &str) -> Scene {
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
            let mut jitter = Jitter(7);
            for j in 0..16 {
                for i in 0..16 {
                    for k in 0..16 {
                        let offset = [jitter.next() * 0.2, jitter.next() * 0.2, jitter.next() * 0.2];
                        let tilt = [jitter.next() * 0.3, jitter.next() * 0.3, jitter.next() * 0.3];
                        bodies.push(dynamic(
                            unit_box(),
                            [
                                (i as f32 - 7.5) * 1.5 + offset[0],
                                2.0 + j as f32 * 1.5 + offset[1],
                                (k as f32 - 7.5) * 1.5 + offset[2],
                            ],
                            tilt,
                        ));
                    }
                }
            }
            false
        }
        // 20 boxes stacked.
        "column" => {
            bodies.push(ground(10.0, 10.0));
            for layer in 0..20 {
                bodies.push(dynamic(unit_box(), [0.0, 0.5 + layer as f32, 0.0], [0.0; 3]));
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
            let mut jitter = Jitter(11);
            let mut index = 0;
            for j in 0..14 {
                for i in 0..12 {
                    for k in 0..12 {
                        let offset = [jitter.next() * 0.2, jitter.next() * 0.2, jitter.next() * 0.2];
                        let tilt = [jitter.next() * 0.5, jitter.next() * 0.5, jitter.next() * 0.5];
                        bodies.push(dynamic(
                            shapes[index % shapes.len()].clone(),
                            [
                                (i as f32 - 5.5) * 1.5 + offset[0],
                                1.5 + j as f32 * 1.5 + offset[1],
                                (k as f32 - 5.5) * 1.5 + offset[2],
                            ],
                            tilt,
                        ));
                        index += 1;
                    }
                }
            }
            false
        }
        other => panic!("unknown scene {other:?}"),
    };
    Scene { bodies, is_stack }
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

// ---------------------------------------------------------------------------------------------
// Ray casts: the same rays against the same static boxes in both engines
// ---------------------------------------------------------------------------------------------

/// Number of boxes in the ray scene, and of rays cast per round.
const RAY_COUNT: usize = 10_000;
/// Half the side of the cube the boxes and ray origins fill, metres.
const RAY_EXTENT: f32 = 50.0;
/// Rounds of 10,000 rays per engine by default.
const RAY_ROUNDS: usize = 31;

/// Uniform in `[low, high)` from a jitter value in `[-1, 1)` (`(j + 1) / 2` is exact in f32).
fn uniform(jitter: &mut Jitter, low: f32, high: f32) -> f32 {
    low + (high - low) * (0.5 * (jitter.next() + 1.0))
}

fn uniform3(jitter: &mut Jitter, low: f32, high: f32) -> [f32; 3] {
    [(); 3].map(|()| uniform(jitter, low, high))
}

fn unit_vector(jitter: &mut Jitter) -> [f32; 3] {
    loop {
        let v = uniform3(jitter, -1.0, 1.0);
        let length_squared = v.iter().map(|c| c * c).sum::<f32>();
        if (0.01..=1.0).contains(&length_squared) {
            return v.map(|c| c / length_squared.sqrt());
        }
    }
}

/// The scene of `crates/rebond/benches/ray_cast.rs`, drawn from the same numbers (SplitMix64,
/// seed 0x7a75, in the same order): 10,000 static boxes of half extents 0.25–1 m turned at random
/// in a 100 m cube, and 10,000 rays (origin, unit direction) from random points of the cube in
/// random directions, without a distance limit.
fn ray_scene() -> (Scene, Vec<([f32; 3], [f32; 3])>) {
    let mut jitter = Jitter(0x7a75);
    let mut bodies = Vec::with_capacity(RAY_COUNT);
    for _ in 0..RAY_COUNT {
        let half_extents = uniform3(&mut jitter, 0.25, 1.0);
        let axis = unit_vector(&mut jitter);
        let angle = uniform(&mut jitter, 0.0, 6.3);
        let mut body = fixed_box(half_extents, uniform3(&mut jitter, -RAY_EXTENT, RAY_EXTENT));
        body.rotation = axis.map(|c| c * angle);
        bodies.push(body);
    }
    let rays = (0..RAY_COUNT)
        .map(|_| {
            let origin = uniform3(&mut jitter, -RAY_EXTENT, RAY_EXTENT);
            (origin, unit_vector(&mut jitter))
        })
        .collect();
    (
        Scene {
            bodies,
            is_stack: false,
        },
        rays,
    )
}

/// Casts every ray for its nearest hit with the normal, through `world.cast_ray` (validation,
/// the broad-phase trees, the exact shapes); writes each distance (infinity for a miss).
fn rebond_rays(world: &rebond::World, rays: &[rebond::Ray], distances: &mut [f32]) {
    let filter = rebond::QueryFilter::new();
    for (ray, distance) in rays.iter().zip(distances) {
        *distance = world
            .cast_ray(ray, &filter)
            .expect("valid ray")
            .map_or(f32::INFINITY, |hit| hit.distance);
    }
}

/// The same through rapier's query pipeline, `cast_ray_and_get_normal` (solid, no limit).
fn rapier_rays(
    world: &rapier3d::prelude::PhysicsWorld,
    rays: &[rapier3d::prelude::Ray],
    distances: &mut [f32],
) {
    let pipeline = world.query_pipeline();
    for (ray, distance) in rays.iter().zip(distances) {
        *distance = pipeline
            .cast_ray_and_get_normal(ray, f32::MAX, true)
            .map_or(f32::INFINITY, |(_, hit)| hit.time_of_impact);
    }
}

/// Builds the ray scene in both engines (one step each, so rapier's BVH is built), counts the
/// rays on which they disagree, then times `rounds` rounds of 10,000 rays per engine, alternating
/// which engine goes first, and prints the medians and their ratio.
fn run_rays(rounds: usize) {
    let (scene, ray_specs) = ray_scene();
    let mut rebond_engine = RebondEngine::new(&scene);
    let mut rapier_engine = RapierEngine::new(&scene);
    rebond_engine.step();
    rapier_engine.step();
    let rebond_ray_list: Vec<rebond::Ray> = ray_specs
        .iter()
        .map(|(o, d)| rebond::Ray::new(rebond::Vec3::from(*o), rebond::Vec3::from(*d)))
        .collect();
    let rapier_ray_list: Vec<rapier3d::prelude::Ray> = ray_specs
        .iter()
        .map(|(o, d)| {
            use rapier3d::prelude::{Ray, Vector};
            Ray::new(Vector::new(o[0], o[1], o[2]), Vector::new(d[0], d[1], d[2]))
        })
        .collect();

    let mut rebond_distances = vec![0.0f32; RAY_COUNT];
    let mut rapier_distances = vec![0.0f32; RAY_COUNT];
    rebond_rays(&rebond_engine.world, &rebond_ray_list, &mut rebond_distances);
    rapier_rays(&rapier_engine.world, &rapier_ray_list, &mut rapier_distances);
    let hits = |distances: &[f32]| distances.iter().filter(|d| d.is_finite()).count();
    // Answers agree when both miss or both hit within 1 mm (f32 rounding of a 100 m scene is
    // ~10 µm; a ray grazing an edge may hit in one engine and miss in the other).
    let disagreements = rebond_distances
        .iter()
        .zip(&rapier_distances)
        .filter(|(a, b)| !(a == b || (*a - *b).abs() <= 1e-3))
        .count();

    let mut times: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for round in 0..rounds {
        for slot in 0..2 {
            let engine = (slot + round) % 2;
            let start = thread_cpu_ms();
            if engine == 0 {
                rebond_rays(&rebond_engine.world, &rebond_ray_list, &mut rebond_distances);
            } else {
                rapier_rays(&rapier_engine.world, &rapier_ray_list, &mut rapier_distances);
            }
            times[engine].push(thread_cpu_ms() - start);
        }
    }
    let [rebond_ms, rapier_ms] = times.map(|mut t| median(&mut t));
    println!(
        "rebond vs rapier3d {}: {RAY_COUNT} rays against {RAY_COUNT} static boxes, nearest hit \
         with normal, median thread CPU time of {rounds} rounds per engine",
        rapier3d::VERSION
    );
    println!(
        "| engine | ms per 10,000 rays | µs per ray | hits |\n|---|---|---|---|\n\
         | rebond | {} | {:.2} | {} |\n| rapier3d | {} | {:.2} | {} |",
        ms(rebond_ms),
        rebond_ms * 1e3 / RAY_COUNT as f64,
        hits(&rebond_distances),
        ms(rapier_ms),
        rapier_ms * 1e3 / RAY_COUNT as f64,
        hits(&rapier_distances),
    );
    println!(
        "rays ratio={:.3} rebond_ms={rebond_ms:.3} rapier_ms={rapier_ms:.3} disagreements={disagreements}",
        rebond_ms / rapier_ms
    );
}

// ---------------------------------------------------------------------------------------------
// The two engines behind one interface
// ---------------------------------------------------------------------------------------------

trait Engine {
    fn step(&mut self);
    /// Positions of the dynamic bodies, in scene order.
    fn positions(&self, out: &mut Vec<[f32; 3]>);
    /// Most negative contact separation in the current manifolds (0 when none penetrate).
    fn deepest_penetration(&self) -> f32;
    /// Largest speed of a dynamic body, m/s.
    fn max_speed(&self) -> f32;
    fn contact_points(&self) -> usize;
    /// Most negative separation of the current manifold points re-evaluated at the current
    /// poses, for engines whose reported separations may be stale (rapier); `None` otherwise.
    fn deepest_reevaluated(&self) -> Option<f32> {
        None
    }
}

fn rebond_shape(shape: &ShapeSpec) -> rebond::Shape {
    use rebond::{Shape, Vec3};
    match shape {
        ShapeSpec::Cuboid(h) => Shape::cuboid(Vec3::from(*h)),
        ShapeSpec::Sphere(r) => Shape::sphere(*r),
        ShapeSpec::Capsule {
            radius,
            half_height,
        } => Shape::capsule(*radius, *half_height),
        ShapeSpec::Cylinder {
            radius,
            half_height,
        } => Shape::cylinder(*radius, *half_height),
        ShapeSpec::Hull(points) => {
            let points: Vec<Vec3> = points.iter().map(|p| Vec3::from(*p)).collect();
            Shape::convex_hull(&points)
        }
    }
    .expect("valid shape")
}

struct RebondEngine {
    world: rebond::World,
    dynamic: Vec<rebond::BodyHandle>,
}

impl RebondEngine {
    fn new(scene: &Scene) -> Self {
        use rebond::{BodyDesc, Quat, Vec3, World, WorldSettings};
        let mut world = World::new(WorldSettings {
            gravity: Vec3::new(0.0, GRAVITY, 0.0),
            substeps: SUBSTEPS,
            ..WorldSettings::default()
        })
        .expect("settings");
        let mut dynamic = Vec::new();
        for spec in &scene.bodies {
            let shape = rebond_shape(&spec.shape);
            let desc = if spec.fixed {
                BodyDesc::fixed(shape)
            } else {
                BodyDesc::dynamic(shape).mass(spec.mass).can_sleep(false)
            };
            let desc = desc
                .position(Vec3::from(spec.position))
                .rotation(Quat::from_scaled_axis(Vec3::from(spec.rotation)))
                .friction(FRICTION)
                .restitution(RESTITUTION);
            let handle = world.add_body(desc).expect("valid body");
            if !spec.fixed {
                dynamic.push(handle);
            }
        }
        Self { world, dynamic }
    }
}

impl Engine for RebondEngine {
    fn step(&mut self) {
        self.world.step(DT).expect("step");
    }

    fn positions(&self, out: &mut Vec<[f32; 3]>) {
        out.clear();
        for &handle in &self.dynamic {
            out.push(self.world.body(handle).expect("body").position().to_array());
        }
    }

    fn deepest_penetration(&self) -> f32 {
        let mut deepest = 0.0f32;
        for contact in self.world.contacts() {
            for point in contact.manifold.points() {
                deepest = deepest.min(point.separation);
            }
        }
        deepest
    }

    fn max_speed(&self) -> f32 {
        self.dynamic
            .iter()
            .map(|&h| self.world.body(h).expect("body").linear_velocity().length())
            .fold(0.0, f32::max)
    }

    fn contact_points(&self) -> usize {
        self.world.contact_count()
    }
}

struct RapierEngine {
    world: rapier3d::prelude::PhysicsWorld,
    dynamic: Vec<rapier3d::prelude::RigidBodyHandle>,
}

impl RapierEngine {
    fn new(scene: &Scene) -> Self {
        use rapier3d::prelude::*;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, GRAVITY, 0.0);
        world.integration_parameters.dt = DT;
        // Rapier's "solver iterations" are substeps: each one integrates velocities, runs one
        // biased PGS pass (`num_internal_pgs_iterations` = 1), integrates positions and runs one
        // relax pass (`num_internal_stabilization_iterations` = 1), at dt / iterations.
        world.integration_parameters.num_solver_iterations = SUBSTEPS as usize;
        let mut dynamic = Vec::new();
        for spec in &scene.bodies {
            let v = |a: [f32; 3]| Vector::new(a[0], a[1], a[2]);
            let collider = match &spec.shape {
                ShapeSpec::Cuboid(h) => ColliderBuilder::cuboid(h[0], h[1], h[2]),
                ShapeSpec::Sphere(r) => ColliderBuilder::ball(*r),
                ShapeSpec::Capsule {
                    radius,
                    half_height,
                } => ColliderBuilder::capsule_y(*half_height, *radius),
                ShapeSpec::Cylinder {
                    radius,
                    half_height,
                } => ColliderBuilder::cylinder(*half_height, *radius),
                ShapeSpec::Hull(points) => {
                    let points: Vec<Vector> = points.iter().map(|p| v(*p)).collect();
                    ColliderBuilder::convex_hull(&points).expect("valid hull")
                }
            }
            .friction(FRICTION)
            .restitution(RESTITUTION);
            let (body, collider) = if spec.fixed {
                (RigidBodyBuilder::fixed(), collider)
            } else {
                (
                    RigidBodyBuilder::dynamic().can_sleep(false),
                    collider.mass(spec.mass),
                )
            };
            let body = body.translation(v(spec.position)).rotation(v(spec.rotation));
            let (handle, _) = world.insert(body, collider);
            if !spec.fixed {
                dynamic.push(handle);
            }
        }
        Self { world, dynamic }
    }

    /// Separations of the current manifold points re-evaluated at the bodies' current poses:
    /// rapier recycles a pair's manifold (and its `dist`) while the pair barely moves, so `dist`
    /// can be a few steps old.
    fn reevaluated(&self) -> f32 {
        use rapier3d::geometry::PairContacts;
        let mut deepest = 0.0f32;
        for pair in self.world.narrow_phase.contact_pairs() {
            let PairContacts::Rigid(rigid) = &pair.contacts else {
                continue;
            };
            let (Some(c1), Some(c2)) = (
                self.world.colliders.get(pair.collider1),
                self.world.colliders.get(pair.collider2),
            ) else {
                continue;
            };
            let (pos1, pos2) = (c1.position(), c2.position());
            for manifold in &rigid.manifolds {
                if manifold.subshape_poses.is_some() {
                    continue; // Composite shapes only; none in these scenes.
                }
                let normal = pos1.rotation * manifold.local_n1;
                for point in &manifold.points {
                    let p1 = pos1.transform_point(point.local_p1);
                    let p2 = pos2.transform_point(point.local_p2);
                    deepest = deepest.min((p2 - p1).dot(normal));
                }
            }
        }
        deepest
    }
}

impl Engine for RapierEngine {
    fn step(&mut self) {
        self.world.step();
    }

    fn positions(&self, out: &mut Vec<[f32; 3]>) {
        out.clear();
        for &handle in &self.dynamic {
            let t = self.world.bodies[handle].translation();
            out.push([t.x, t.y, t.z]);
        }
    }

    fn deepest_penetration(&self) -> f32 {
        use rapier3d::geometry::PairContacts;
        let mut deepest = 0.0f32;
        for pair in self.world.narrow_phase.contact_pairs() {
            if let PairContacts::Rigid(rigid) = &pair.contacts {
                for manifold in &rigid.manifolds {
                    for point in &manifold.points {
                        deepest = deepest.min(point.dist);
                    }
                }
            }
        }
        deepest
    }

    fn max_speed(&self) -> f32 {
        self.dynamic
            .iter()
            .map(|&h| self.world.bodies[h].linvel().length())
            .fold(0.0, f32::max)
    }

    fn deepest_reevaluated(&self) -> Option<f32> {
        Some(self.reevaluated())
    }

    fn contact_points(&self) -> usize {
        use rapier3d::geometry::PairContacts;
        self.world
            .narrow_phase
            .contact_pairs()
            .map(|pair| match &pair.contacts {
                PairContacts::Rigid(rigid) => rigid.manifolds.iter().map(|m| m.points.len()).sum(),
                _ => 0,
            })
            .sum()
    }
}

// ---------------------------------------------------------------------------------------------
// Child: one engine, one scene, one run
// ---------------------------------------------------------------------------------------------

/// CPU time consumed by the calling thread, milliseconds (`CLOCK_THREAD_CPUTIME_ID`). Unlike the
/// wall clock it does not count the time the thread waits for a core, which on a shared, loaded
/// machine is most of the noise.
fn thread_cpu_ms() -> f64 {
    #[repr(C)]
    struct Timespec {
        tv_sec: i64,
        tv_nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, time: *mut Timespec) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut time = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `time` is a valid, writable timespec (64-bit Linux layout).
    let status = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut time) };
    assert_eq!(status, 0, "clock_gettime(CLOCK_THREAD_CPUTIME_ID) failed");
    time.tv_sec as f64 * 1e3 + time.tv_nsec as f64 * 1e-6
}

fn peak_memory_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|line| line.strip_prefix("VmHWM:"))
        .and_then(|rest| rest.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

fn run_child(engine_name: &str, scene_name: &str, steps: usize) {
    let scene = build_scene(scene_name);
    let body_count = scene.bodies.iter().filter(|b| !b.fixed).count();
    let build_start = Instant::now();
    let mut engine: Box<dyn Engine> = match engine_name {
        "rebond" => Box::new(RebondEngine::new(&scene)),
        "rapier" => Box::new(RapierEngine::new(&scene)),
        other => panic!("unknown engine {other:?}"),
    };
    let build_ms = build_start.elapsed().as_secs_f64() * 1e3;

    let mut start = Vec::new();
    engine.positions(&mut start);
    let mut current = Vec::with_capacity(start.len());
    let mut times = Vec::with_capacity(steps);
    let mut wall_times = Vec::with_capacity(steps);
    let mut max_drift = 0.0f32;
    let mut deepest = 0.0f32;
    let mut deepest_reeval = 0.0f32;
    let mut non_finite = false;
    let is_rapier = engine_name == "rapier";
    // COMPARE_TRACE=K prints the running figures every K steps on stderr.
    let trace: usize = std::env::var("COMPARE_TRACE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);

    for step in 0..steps {
        let (wall0, cpu0) = (Instant::now(), thread_cpu_ms());
        engine.step();
        let elapsed = thread_cpu_ms() - cpu0;
        let wall = wall0.elapsed().as_secs_f64() * 1e3;
        if step >= WARMUP_STEPS {
            times.push(elapsed);
            wall_times.push(wall);
        }
        // Checks, outside the timed region.
        deepest = deepest.min(engine.deepest_penetration());
        if let Some(depth) = engine.deepest_reevaluated() {
            deepest_reeval = deepest_reeval.min(depth);
        }
        engine.positions(&mut current);
        for (now, then) in current.iter().zip(&start) {
            if !now.iter().all(|c| c.is_finite()) {
                non_finite = true;
                continue;
            }
            let d = ((now[0] - then[0]).powi(2) + (now[1] - then[1]).powi(2) + (now[2] - then[2]).powi(2)).sqrt();
            max_drift = max_drift.max(d);
        }
        if trace > 0 && (step + 1) % trace == 0 {
            let top = current.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
            eprintln!(
                "step {:>5}  {elapsed:>8.3} ms  drift {max_drift:.4} m  deepest {:.4} m  \
                 highest {top:.3} m  max speed {:.3} m/s  contacts {}",
                step + 1,
                -deepest,
                engine.max_speed(),
                engine.contact_points()
            );
        }
    }
    let total_ms: f64 = times.iter().sum();
    let mean_ms = total_ms / times.len().max(1) as f64;
    let mut sorted = times.clone();
    let median_ms = median(&mut sorted);
    let p90_ms = sorted
        .get(((sorted.len() as f64) * 0.9) as usize)
        .copied()
        .unwrap_or(f64::NAN);
    let max_ms = sorted.last().copied().unwrap_or(f64::NAN);
    let wall_median_ms = median(&mut wall_times);
    // Bodies that left the scene: below the ground top by more than a box, or far out.
    engine.positions(&mut current);
    let escaped = current
        .iter()
        .filter(|p| !p.iter().all(|c| c.is_finite()) || p[1] < -1.0 || p[0].abs() > 80.0 || p[2].abs() > 80.0)
        .count();
    let max_height = current.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
    let end_speed = engine.max_speed();
    let contacts = engine.contact_points();
    let mb = peak_memory_mib();
    println!(
        "RESULT engine={engine_name} scene={scene_name} bodies={body_count} steps={steps} \
         median_ms={median_ms:.4} wall_median_ms={wall_median_ms:.4} mean_ms={mean_ms:.4} p90_ms={p90_ms:.4} max_ms={max_ms:.4} \
         build_ms={build_ms:.1} mb={mb:.1} drift_m={} penetration_m={:.5} reeval_penetration_m={} \
         end_max_speed={end_speed:.3} end_max_height={max_height:.3} escaped={escaped} \
         non_finite={non_finite} contacts={contacts}",
        if scene.is_stack { format!("{max_drift:.5}") } else { "-".to_string() },
        0.0 - deepest,
        if is_rapier { format!("{:.5}", 0.0 - deepest_reeval) } else { "-".to_string() },
    );
}

// ---------------------------------------------------------------------------------------------
// Driver
// ---------------------------------------------------------------------------------------------

#[derive(Default, Clone)]
struct Run {
    fields: Vec<(String, String)>,
}

impl Run {
    fn parse(line: &str) -> Self {
        let fields = line
            .split_whitespace()
            .skip(1)
            .filter_map(|kv| kv.split_once('='))
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        Self { fields }
    }

    fn get(&self, key: &str) -> &str {
        self.fields
            .iter()
            .find(|(k, _)| k == key)
            .map_or("?", |(_, v)| v.as_str())
    }

    fn num(&self, key: &str) -> f64 {
        self.get(key).parse().unwrap_or(f64::NAN)
    }
}

/// Milliseconds with about three significant digits.
fn ms(value: f64) -> String {
    if value < 1.0 {
        format!("{value:.3}")
    } else if value < 10.0 {
        format!("{value:.2}")
    } else {
        format!("{value:.1}")
    }
}

fn run_driver(only: &[String], rounds_override: Option<usize>, steps_override: Option<usize>) {
    let exe = std::env::current_exe().expect("own path");
    let started = Instant::now();
    println!(
        "rebond vs rapier3d {}: dt = 1/60 s, {SUBSTEPS} substeps, sleeping off, one thread, \
         friction {FRICTION}, restitution {RESTITUTION}; ms/step = median thread CPU time per step \
         (wall-clock median alongside), first {WARMUP_STEPS} steps not timed",
        rapier3d::VERSION
    );
    let mut summary = Vec::new();
    for &(scene, default_steps, default_rounds) in SCENES {
        if !only.is_empty() && !only.iter().any(|s| s == scene) {
            continue;
        }
        let steps = steps_override.unwrap_or(default_steps);
        let rounds = rounds_override.unwrap_or(default_rounds);
        let mut runs: [Vec<Run>; 2] = [Vec::new(), Vec::new()];
        for round in 0..rounds {
            for slot in 0..2 {
                // Alternate which engine goes first from one round to the next.
                let e = (slot + round) % 2;
                let output = Command::new(&exe)
                    .args(["--engine", ENGINES[e], "--scene", scene, "--steps", &steps.to_string()])
                    .output()
                    .expect("start child");
                let stdout = String::from_utf8_lossy(&output.stdout);
                let Some(line) = stdout.lines().find(|l| l.starts_with("RESULT ")) else {
                    eprintln!(
                        "{} on {scene} failed: {}\n{}",
                        ENGINES[e],
                        output.status,
                        String::from_utf8_lossy(&output.stderr)
                    );
                    std::process::exit(1);
                };
                let run = Run::parse(line);
                eprintln!(
                    "[{:>5.0} s] {scene:<14} round {}/{rounds} {:<6} median {:>9.3} ms cpu {:>9.3} ms wall {:>7.1} MiB",
                    started.elapsed().as_secs_f64(),
                    round + 1,
                    ENGINES[e],
                    run.num("median_ms"),
                    run.num("wall_median_ms"),
                    run.num("mb")
                );
                runs[e].push(run);
            }
        }
        summary.push((scene, steps, rounds, runs));
    }

    let med = |runs: &[Run], key: &str| {
        let mut v: Vec<f64> = runs.iter().map(|r| r.num(key)).collect();
        median(&mut v)
    };
    let spread = |runs: &[Run], key: &str| {
        let v: Vec<f64> = runs.iter().map(|r| r.num(key)).collect();
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    };

    println!();
    println!(
        "| scene | bodies | steps × rounds | rebond ms/step (range) | rapier ms/step (range) | ratio | wall ms rebond / rapier | rebond MiB | rapier MiB |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (scene, steps, rounds, runs) in &summary {
        let (a, b) = (med(&runs[0], "median_ms"), med(&runs[1], "median_ms"));
        let (alo, ahi) = spread(&runs[0], "median_ms");
        let (blo, bhi) = spread(&runs[1], "median_ms");
        println!(
            "| {scene} | {} | {steps} × {rounds} | {} ({}–{}) | {} ({}–{}) | {:.2} | {} / {} | {:.1} | {:.1} |",
            runs[0][0].get("bodies"),
            ms(a),
            ms(alo),
            ms(ahi),
            ms(b),
            ms(blo),
            ms(bhi),
            a / b,
            ms(med(&runs[0], "wall_median_ms")),
            ms(med(&runs[1], "wall_median_ms")),
            med(&runs[0], "mb"),
            med(&runs[1], "mb"),
        );
    }
    println!();
    println!(
        "| scene | engine | max drift m | deepest penetration m | rapier re-evaluated m | end max speed m/s | end max height m | escaped | cpu mean / p90 / max ms | build ms | contact points at end |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (scene, _, _, runs) in &summary {
        for (e, engine_runs) in runs.iter().enumerate() {
            // Stability figures come from the first round; every round runs the same scene and
            // both engines are deterministic on one thread (a difference is flagged).
            let r = &engine_runs[0];
            let same = engine_runs.iter().all(|o| {
                o.get("drift_m") == r.get("drift_m") && o.get("penetration_m") == r.get("penetration_m")
            });
            println!(
                "| {scene} | {} | {} | {} | {} | {} | {} | {}{} | {} / {} / {} | {:.0} | {} |",
                ENGINES[e],
                r.get("drift_m"),
                r.get("penetration_m"),
                r.get("reeval_penetration_m"),
                r.get("end_max_speed"),
                r.get("end_max_height"),
                r.get("escaped"),
                if r.get("non_finite") == "true" { " (non-finite!)" } else { "" },
                ms(med(engine_runs, "mean_ms")),
                ms(med(engine_runs, "p90_ms")),
                ms(med(engine_runs, "max_ms")),
                med(engine_runs, "build_ms"),
                r.get("contacts"),
            );
            if !same {
                println!("|   | {} | (stability figures differ between rounds) | | | | | | | | |", ENGINES[e]);
            }
        }
    }
    println!();
    println!("total {:.0} s", started.elapsed().as_secs_f64());
    println!();
    for (scene, _, _, runs) in &summary {
        let (a, b) = (med(&runs[0], "median_ms"), med(&runs[1], "median_ms"));
        println!(
            "{scene} ratio={:.3} rebond_ms={a:.3} rapier_ms={b:.3} rebond_mb={:.1} rapier_mb={:.1}",
            a / b,
            med(&runs[0], "mb"),
            med(&runs[1], "mb"),
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut engine = None;
    let mut scenes = Vec::new();
    let mut steps = None;
    let mut rounds = None;
    let mut rays = false;
    let mut i = 0;
    while i < args.len() {
        let value = args.get(i + 1).cloned();
        match args[i].as_str() {
            "--rays" => {
                rays = true;
                i += 1;
                continue;
            }
            "--engine" => engine = value,
            "--scene" => scenes.extend(value),
            "--steps" => steps = value.and_then(|v| v.parse().ok()),
            "--rounds" => rounds = value.and_then(|v| v.parse().ok()),
            "-h" | "--help" => {
                println!(
                    "compare [--scene S]... [--steps N] [--rounds K]   run the comparison\n\
                     compare --engine rebond|rapier --scene S [--steps N]   one run (child)\n\
                     compare --rays [--rounds K]   10,000 rays against 10,000 boxes in both \
                     engines (default {RAY_ROUNDS} rounds)\n\
                     scenes: {}",
                    SCENES.iter().map(|s| s.0).collect::<Vec<_>>().join(", ")
                );
                return;
            }
            other => {
                eprintln!("unknown argument {other:?} (try --help)");
                std::process::exit(2);
            }
        }
        i += 2;
    }
    if rays {
        run_rays(rounds.unwrap_or(RAY_ROUNDS));
        return;
    }
    match engine {
        Some(engine) => {
            let scene = scenes.first().expect("--scene with --engine");
            let default_steps = SCENES.iter().find(|s| s.0 == scene).map_or(300, |s| s.1);
            run_child(&engine, scene, steps.unwrap_or(default_steps));
        }
        None => run_driver(&scenes, rounds, steps),
    }
}
