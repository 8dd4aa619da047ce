//! Cylinders, whose rims are rounded by a small convex radius (`Cylinder::convex_radius`), resting
//! on a box and on a halfspace: on the cap and on the side they rest at the sharp cylinder's
//! exact height, the rounding hidden.

mod common;

use common::{world, DT, G};
use rebond::{BodyDesc, Quat, Shape, Vec3};
use std::f32::consts::FRAC_PI_2;

/// The cylinder of these scenes, 0.8 m across and 0.7 m tall: its rims are rounded by 1 cm.
fn cylinder() -> Shape {
    Shape::cylinder(0.4, 0.35).unwrap()
}

/// The ground: a static box whose top face is y = 0, or the halfspace below y = 0.
fn ground(halfspace: bool) -> BodyDesc {
    if halfspace {
        BodyDesc::static_body(Shape::halfspace(Vec3::Y).unwrap())
    } else {
        BodyDesc::static_body(Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)).unwrap())
            .position(Vec3::new(0.0, -0.5, 0.0))
    }
}

/// Drops the cylinder in `rotation` from 5 cm above its resting height `rest` onto the ground,
/// sleeping off, runs 5 s and returns the worst height error and the worst tilt of its axis from
/// its starting direction (radians) over the last second.
fn rest(halfspace: bool, rotation: Quat, rest: f32) -> (f32, f32) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    world.add_body(ground(halfspace)).unwrap();
    let body = world
        .add_body(
            BodyDesc::dynamic(cylinder())
                .position(Vec3::new(0.2, rest + 0.05, -0.1))
                .rotation(rotation)
                .can_sleep(false),
        )
        .unwrap();
    let axis = rotation * Vec3::Y;
    let steps = (5.0 / DT).round() as usize;
    let window = (1.0 / DT).round() as usize;
    let (mut height_error, mut tilt) = (0.0f32, 0.0f32);
    for step in 0..steps {
        world.step(DT).unwrap();
        if step + window >= steps {
            let state = world.body(body).unwrap();
            height_error = height_error.max((state.position().y - rest).abs());
            let now = state.pose().rotation * Vec3::Y;
            tilt = tilt.max(now.dot(axis).clamp(-1.0, 1.0).acos());
        }
    }
    (height_error, tilt)
}

// A resting contact sinks g/ω² = 9.81 / (2π·120 Hz)² = 17 µm (see `limits.rs`); 0.1 mm also
// holds the rounding of coordinates below 1 m and nothing of the 1 cm rounding of the rims, which
// a contact on the rounded rim instead of the flat cap or side would show. 1 mrad (0.06°) of tilt
// would lift one side of the cap 0.8 mm.
const HEIGHT: f32 = 1.0e-4;
const TILT: f32 = 1.0e-3;

#[test]
fn a_cylinder_stands_on_its_cap_at_its_half_height() {
    for halfspace in [false, true] {
        let (height, tilt) = rest(halfspace, Quat::IDENTITY, 0.35);
        assert!(
            height < HEIGHT,
            "halfspace {halfspace}: height off by {height} m"
        );
        assert!(tilt < TILT, "halfspace {halfspace}: tilted by {tilt} rad");
    }
}

#[test]
fn a_cylinder_lies_on_its_side_at_its_radius() {
    for halfspace in [false, true] {
        let (height, tilt) = rest(halfspace, Quat::from_rotation_x(FRAC_PI_2), 0.4);
        assert!(
            height < HEIGHT,
            "halfspace {halfspace}: height off by {height} m"
        );
        assert!(tilt < TILT, "halfspace {halfspace}: tilted by {tilt} rad");
    }
}

#[test]
fn a_cylinder_across_two_rails_rests_on_both_edges_of_each() {
    // The cylinder lies with its axis along z on two static capsule rails, also along z, 0.5 m
    // apart: each rail touches its side along a line, which holds it at both ends, z = ±0.35
    // (the sharp cylinder's ends, as its other contacts), the two rails' points mirror images of
    // each other. One point per rail, wherever GJK finds it on the line, leaves two points the
    // cylinder tips about, and mirrored pairs such as a car's left and right wheels get
    // different points and are pushed aside. Sleeping off; over the last second of 3 s the axis
    // tilts by under 1 mrad (0.4 mm at the ends; measured 0.35 mrad).
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let along_z = Quat::from_rotation_x(FRAC_PI_2);
    for x in [-0.25, 0.25] {
        world
            .add_body(
                BodyDesc::static_body(Shape::capsule(0.05, 1.0).unwrap())
                    .position(Vec3::new(x, 0.0, 0.0))
                    .rotation(along_z),
            )
            .unwrap();
    }
    // Resting height: the cylinder's centre is 0.45 m from each rail's axis, 0.25 m across.
    let height = (0.45f32 * 0.45 - 0.25 * 0.25).sqrt();
    let body = world
        .add_body(
            BodyDesc::dynamic(cylinder())
                .position(Vec3::new(0.0, height + 0.01, 0.0))
                .rotation(along_z)
                .can_sleep(false),
        )
        .unwrap();
    let mut tilt = 0.0f32;
    for step in 0..180 {
        world.step(DT).unwrap();
        if step < 120 {
            continue;
        }
        let axis = world.body(body).unwrap().pose().rotation * Vec3::Y;
        tilt = tilt.max(axis.dot(Vec3::Z).clamp(-1.0, 1.0).acos());
        let points: Vec<Vec3> = world
            .contacts()
            .iter()
            .flat_map(|contact| contact.points().iter().map(|point| point.position))
            .collect();
        assert_eq!(points.len(), 4, "{points:?}");
        for &point in &points {
            assert!((point.z.abs() - 0.35).abs() < 1e-3, "{points:?}");
            let mirrored = Vec3::new(-point.x, point.y, point.z);
            assert!(
                points.iter().any(|&other| other.distance(mirrored) < 1e-3),
                "{points:?}"
            );
        }
    }
    assert!(tilt < 1e-3, "tilted {tilt} rad");
}
