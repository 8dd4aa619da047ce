//! Narrow-phase cost of each shape pair in a resting contact: B lies on A, slightly overlapping
//! and a little tilted, the configuration a solver sees every step; and of the separating-axis
//! pairs while B is still a little above A (a speculative contact, measured by GJK).
//!
//! Run with `cargo bench -p rebond --bench narrow_phase`.

use rebond::internals::collision::narrow_phase::NarrowPhase;
use rebond::internals::collision::SPECULATIVE_DISTANCE;
use rebond::{Pose, Quat, Shape, Vec3};

fn main() {
    divan::main();
}

/// The shapes of the benchmark, each about 1 m across.
fn shape(name: &str) -> Shape {
    let result = match name {
        "sphere" => Shape::sphere(0.5),
        "box" => Shape::cuboid(Vec3::splat(0.5)),
        "capsule" => Shape::capsule(0.3, 0.4),
        "cylinder" => Shape::cylinder(0.5, 0.5),
        "halfspace" => Shape::halfspace(Vec3::Y),
        _ => {
            let points: Vec<Vec3> = (0..12)
                .map(|i| {
                    let angle = i as f32 * std::f32::consts::TAU / 6.0;
                    let y = if i < 6 { -0.5 } else { 0.5 };
                    Vec3::new(0.5 * angle.cos(), y, 0.5 * angle.sin())
                })
                .collect();
            Shape::convex_hull(&points)
        }
    };
    result.unwrap_or_else(|error| panic!("benchmark shape {name}: {error}"))
}

/// Highest point of a shape above its origin along +Y.
fn top(shape: &Shape) -> f32 {
    shape.support(Vec3::Y).map_or(0.0, |point| point.y)
}

const PAIRS: &[(&str, &str)] = &[
    ("sphere", "sphere"),
    ("sphere", "capsule"),
    ("capsule", "capsule"),
    ("sphere", "box"),
    ("sphere", "hull"),
    ("sphere", "cylinder"),
    ("box", "box"),
    ("box", "hull"),
    ("hull", "hull"),
    ("box", "capsule"),
    ("box", "cylinder"),
    ("hull", "capsule"),
    ("hull", "cylinder"),
    ("cylinder", "cylinder"),
    ("capsule", "cylinder"),
    ("halfspace", "box"),
    ("halfspace", "cylinder"),
];

/// The separating-axis pairs, also timed while B is still above A: its unturned bottom 15 mm up,
/// its lowest corner, once turned, about 7 mm up (within the 20 mm speculative margin).
const SEPARATING_AXIS_PAIRS: &[(&str, &str)] = &[("box", "box"), ("box", "hull"), ("hull", "hull")];

#[divan::bench(args = PAIRS)]
fn resting_pair(bencher: divan::Bencher, pair: (&str, &str)) {
    bench_pair(bencher, pair, -0.005);
}

#[divan::bench(args = SEPARATING_AXIS_PAIRS)]
fn approaching_pair(bencher: divan::Bencher, pair: (&str, &str)) {
    bench_pair(bencher, pair, 0.015);
}

/// Times [`NarrowPhase::collide_convex`], its scratch space reused from call to call as in the
/// world's step, with B's unturned bottom `gap` metres above A's top, B then turned by about 0.6°.
fn bench_pair(bencher: divan::Bencher, pair: (&str, &str), gap: f32) {
    let (a, b) = (shape(pair.0), shape(pair.1));
    let pose_a = Pose::IDENTITY;
    let bottom_b = -b.support(Vec3::NEG_Y).map_or(0.0, |point| point.y);
    let pose_b = Pose::new(
        Vec3::new(0.02, top(&a) + bottom_b + gap, -0.01),
        Quat::from_rotation_x(0.01) * Quat::from_rotation_z(0.005),
    );
    let mut narrow_phase = NarrowPhase::default();
    bencher.bench_local(move || {
        narrow_phase.collide_convex(
            divan::black_box(&a),
            divan::black_box(&pose_a),
            divan::black_box(&b),
            divan::black_box(&pose_b),
            SPECULATIVE_DISTANCE,
        )
    });
}
