//! Scene queries through the broad phase: 10,000 rays against a world of 10,000 boxes.
//!
//! Run with `cargo bench -p rebond --bench ray_cast`.

use rebond::{BodyDesc, Pose, Quat, QueryFilter, Ray, RayHit, Shape, World, WorldSettings};

fn main() {
    divan::main();
}

/// Number of boxes in the world, and of rays cast per iteration.
const COUNT: usize = 10_000;

#[path = "../tests/common/random.rs"]
mod random;
use random::Random;

/// Half the side of the cube the boxes and the ray origins fill, metres.
const EXTENT: f32 = 50.0;

/// A world of `COUNT` static boxes of half extents 0.25–1 m, turned at random, scattered in a
/// 100 m cube, and `COUNT` rays from random points of the cube in random directions, without a
/// distance limit: 56 % of them hit a box, 20 m away on average; the others leave the cube.
fn scene() -> (World, Vec<Ray>) {
    let mut random = Random(0x7a75);
    let mut world = World::new(WorldSettings::default()).unwrap();
    for _ in 0..COUNT {
        let shape = Shape::cuboid(random.vec3(0.25, 1.0)).unwrap();
        let rotation = Quat::from_axis_angle(random.unit_vector(), random.range(0.0, 6.3));
        world
            .add_body(
                BodyDesc::static_body(shape)
                    .position(random.vec3(-EXTENT, EXTENT))
                    .rotation(rotation),
            )
            .unwrap();
    }
    let rays = (0..COUNT)
        .map(|_| Ray::new(random.vec3(-EXTENT, EXTENT), random.unit_vector()))
        .collect();
    (world, rays)
}

/// The nearest hit of each of the 10,000 rays; returns how many hit something.
#[divan::bench]
fn closest_hit_10k_rays_10k_boxes(bencher: divan::Bencher) {
    let (world, rays) = scene();
    let filter = QueryFilter::new();
    bencher.bench_local(|| {
        rays.iter()
            .filter(|ray| world.cast_ray(ray, &filter).unwrap().is_some())
            .count()
    });
}

/// Whether each ray hits anything, stopping at the first hit found.
#[divan::bench]
fn any_hit_10k_rays_10k_boxes(bencher: divan::Bencher) {
    let (world, rays) = scene();
    let filter = QueryFilter::new();
    bencher.bench_local(|| {
        rays.iter()
            .filter(|ray| world.cast_ray_any(ray, &filter).unwrap())
            .count()
    });
}

/// Every hit of each ray, into one reused vector; returns the total number of hits.
#[divan::bench]
fn all_hits_10k_rays_10k_boxes(bencher: divan::Bencher) {
    let (world, rays) = scene();
    let filter = QueryFilter::new();
    let mut hits: Vec<RayHit> = Vec::new();
    bencher.bench_local(|| {
        rays.iter()
            .map(|ray| {
                world.cast_ray_all(ray, &filter, &mut hits).unwrap();
                hits.len()
            })
            .sum::<usize>()
    });
}

/// A 0.5 m ball swept from each ray's origin along its direction, nearest hit.
#[divan::bench]
fn sphere_cast_10k_sweeps_10k_boxes(bencher: divan::Bencher) {
    let (world, rays) = scene();
    let filter = QueryFilter::new();
    let ball = Shape::sphere(0.5).unwrap();
    bencher.bench_local(|| {
        rays.iter()
            .filter(|ray| {
                let start = Pose::from_position(ray.origin);
                world
                    .cast_shape(&ball, &start, ray.direction, f32::INFINITY, &filter)
                    .unwrap()
                    .is_some()
            })
            .count()
    });
}
