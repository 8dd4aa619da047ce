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
