//! The `--rays` mode: the same rays against the same static scenes in both engines, cast through
//! each engine's query API in one process: 10,000 boxes, then the `mesh_pile` ground (a bumpy
//! mesh of 32,768 triangles).

use crate::measure::{alternate, median, ms, thread_cpu_ms};
use crate::rapier_engine::RapierEngine;
use crate::rebond_engine::RebondEngine;
use crate::scenes::{bumpy_mesh, fixed, fixed_box, Jitter, Scene, Sink};
use crate::Engine;

/// Number of boxes in the ray scene, and of rays cast per round.
const RAY_COUNT: usize = 10_000;
/// Half the side of the cube the boxes and ray origins fill, metres.
const RAY_EXTENT: f32 = 50.0;
/// Rounds of 10,000 rays per engine by default.
pub const RAY_ROUNDS: usize = 31;

/// A ray, engine-neutrally: origin and unit direction, metres.
type RaySpec = ([f32; 3], [f32; 3]);

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
fn ray_scene() -> (Scene, Vec<RaySpec>) {
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
            joints: Vec::new(),
            is_stack: false,
            sink: Sink::None,
            sag_body: None,
        },
        rays,
    )
}

/// The `mesh_pile` scene's ground alone, and 10,000 rays (SplitMix64, seed 0x6d65) from random
/// points 1–20 m above its 64 m square, in random directions that go down at least a fifth as
/// fast as they go sideways, so most meet the mesh, some past its edge.
fn mesh_ray_scene() -> (Scene, Vec<RaySpec>) {
    let mut jitter = Jitter(0x6d65);
    let rays = (0..RAY_COUNT)
        .map(|_| {
            let origin = [
                uniform(&mut jitter, -32.0, 32.0),
                uniform(&mut jitter, 1.0, 20.0),
                uniform(&mut jitter, -32.0, 32.0),
            ];
            let direction = loop {
                let v = unit_vector(&mut jitter);
                if v[1] < -0.2 {
                    break v;
                }
            };
            (origin, direction)
        })
        .collect();
    (
        Scene {
            bodies: vec![fixed(bumpy_mesh())],
            joints: Vec::new(),
            is_stack: false,
            sink: Sink::None,
            sag_body: None,
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

/// Runs both ray scenes ([`compare_rays`]): the boxes, then the mesh.
pub fn run_rays(rounds: usize) {
    let (boxes, box_rays) = ray_scene();
    compare_rays("boxes", &format!("{RAY_COUNT} static boxes"), &boxes, &box_rays, rounds);
    let (mesh, mesh_rays) = mesh_ray_scene();
    compare_rays("mesh", "a mesh of 32,768 triangles", &mesh, &mesh_rays, rounds);
}

/// Builds `scene` in both engines (one step each, so rapier's BVH is built), counts the rays on
/// which they disagree, then times `rounds` rounds of the rays per engine, alternating which
/// engine goes first, and prints the medians and their ratio.
fn compare_rays(name: &str, what: &str, scene: &Scene, ray_specs: &[RaySpec], rounds: usize) {
    let mut rebond_engine = RebondEngine::new(scene);
    let mut rapier_engine = RapierEngine::new(scene);
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
    rebond_rays(
        &rebond_engine.world,
        &rebond_ray_list,
        &mut rebond_distances,
    );
    rapier_rays(
        &rapier_engine.world,
        &rapier_ray_list,
        &mut rapier_distances,
    );
    // Answers agree when both miss or both hit within 1 mm (f32 rounding of a 100 m scene is
    // ~10 µm; a ray grazing an edge may hit in one engine and miss in the other).
    let disagreements = rebond_distances
        .iter()
        .zip(&rapier_distances)
        .filter(|(a, b)| !(a == b || (*a - *b).abs() <= 1e-3))
        .count();

    let mut times: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    alternate(rounds, |_, engine| {
        let start = thread_cpu_ms();
        if engine == 0 {
            rebond_rays(
                &rebond_engine.world,
                &rebond_ray_list,
                &mut rebond_distances,
            );
        } else {
            rapier_rays(
                &rapier_engine.world,
                &rapier_ray_list,
                &mut rapier_distances,
            );
        }
        times[engine].push(thread_cpu_ms() - start);
    });
    let [rebond_ms, rapier_ms] = times.map(|mut t| median(&mut t));
    println!(
        "rebond vs rapier3d {}: {RAY_COUNT} rays against {what}, nearest hit with normal, \
         median thread CPU time of {rounds} rounds per engine",
        rapier3d::VERSION
    );
    let row = |engine: &str, median_ms: f64, distances: &[f32]| {
        let hits = distances.iter().filter(|d| d.is_finite()).count();
        let per_ray_us = median_ms * 1e3 / RAY_COUNT as f64;
        format!(
            "| {engine} | {} | {per_ray_us:.2} | {hits} |",
            ms(median_ms)
        )
    };
    println!("| engine | ms per 10,000 rays | µs per ray | hits |\n|---|---|---|---|");
    println!("{}", row("rebond", rebond_ms, &rebond_distances));
    println!("{}", row("rapier3d", rapier_ms, &rapier_distances));
    println!(
        "rays {name} ratio={:.3} rebond_ms={rebond_ms:.3} rapier_ms={rapier_ms:.3} \
         disagreements={disagreements}",
        rebond_ms / rapier_ms
    );
}
