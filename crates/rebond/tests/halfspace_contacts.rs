//! Contacts of every convex shape with a halfspace, against hand-computed configurations.
//!
//! Tolerance 1e-5 m: a handful of f32 operations on coordinates below 10 m.

use rebond::internals::collision::halfspace::collide_halfspace;
use rebond::internals::collision::{Manifold, SPECULATIVE_DISTANCE};
use rebond::shape::Halfspace;
use rebond::{Pose, Quat, Shape, Vec3};

const TOLERANCE: f32 = 1.0e-5;

fn ground() -> Halfspace {
    Halfspace::new(Vec3::Y).unwrap()
}

fn collide(shape: &Shape, pose: Pose) -> Option<Manifold> {
    collide_halfspace(
        &ground(),
        &Pose::IDENTITY,
        shape,
        &pose,
        SPECULATIVE_DISTANCE,
    )
}

fn assert_points(manifold: &Manifold, count: usize, separation: f32) {
    assert_eq!(manifold.len(), count, "{manifold:?}");
    assert!((manifold.normal - Vec3::Y).length() <= TOLERANCE);
    for point in manifold.points() {
        assert!(
            (point.separation - separation).abs() <= TOLERANCE,
            "separation {} expected {separation}",
            point.separation
        );
        assert!((point.position.y - 0.5 * separation).abs() <= TOLERANCE);
    }
}

#[test]
fn sphere_touches_at_its_lowest_point() {
    let sphere = Shape::sphere(0.5).unwrap();
    let manifold = collide(&sphere, Pose::from_position(Vec3::new(1.0, 0.45, 2.0))).unwrap();
    assert_points(&manifold, 1, -0.05);
    assert!((manifold.points()[0].position.x - 1.0).abs() <= TOLERANCE);
    assert!(collide(&sphere, Pose::from_position(Vec3::new(0.0, 0.6, 0.0))).is_none());
    // 0.01 m above: a speculative point.
    let above = collide(&sphere, Pose::from_position(Vec3::new(0.0, 0.51, 0.0))).unwrap();
    assert_points(&above, 1, 0.01);
}

#[test]
fn capsule_lying_flat_gives_two_points_and_standing_one() {
    let capsule = Shape::capsule(0.25, 1.0).unwrap();
    let lying = Pose::new(
        Vec3::new(0.0, 0.24, 0.0),
        Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
    );
    assert_points(&collide(&capsule, lying).unwrap(), 2, -0.01);
    let standing = Pose::from_position(Vec3::new(0.0, 1.24, 0.0));
    assert_points(&collide(&capsule, standing).unwrap(), 1, -0.01);
}

#[test]
fn box_flat_gives_four_points_and_on_its_edge_two() {
    let cube = Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let flat = collide(&cube, Pose::from_position(Vec3::new(0.0, 0.49, 0.0))).unwrap();
    assert_points(&flat, 4, -0.01);
    let edge = Pose::new(
        Vec3::new(0.0, 0.5f32.hypot(0.5) - 0.01, 0.0),
        Quat::from_rotation_z(std::f32::consts::FRAC_PI_4),
    );
    assert_points(&collide(&cube, edge).unwrap(), 2, -0.01);
}

#[test]
fn cylinder_standing_gives_four_points_and_lying_two() {
    let cylinder = Shape::cylinder(0.5, 1.0).unwrap();
    let standing = collide(&cylinder, Pose::from_position(Vec3::new(0.0, 0.98, 0.0))).unwrap();
    assert_points(&standing, 4, -0.02);
    let lying = Pose::new(
        Vec3::new(0.0, 0.49, 0.0),
        Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
    );
    assert_points(&collide(&cylinder, lying).unwrap(), 2, -0.01);
}

#[test]
fn hull_of_a_cube_rests_like_the_box() {
    let corners: Vec<Vec3> = (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 == 0 { -0.5 } else { 0.5 },
                if i & 2 == 0 { -0.5 } else { 0.5 },
                if i & 4 == 0 { -0.5 } else { 0.5 },
            )
        })
        .collect();
    let hull = Shape::convex_hull(&corners).unwrap();
    let manifold = collide(&hull, Pose::from_position(Vec3::new(0.0, 0.49, 0.0))).unwrap();
    assert_points(&manifold, 4, -0.01);
}

#[test]
fn tilted_plane_measures_along_its_normal() {
    let normal = Vec3::new(1.0, 1.0, 0.0).normalize();
    let tilt = Pose::new(
        Vec3::new(0.0, 1.0, 0.0),
        Quat::from_rotation_arc(Vec3::Y, normal),
    );
    let sphere = Shape::sphere(1.0).unwrap();
    let center = tilt.position + normal * 0.9;
    let manifold = collide_halfspace(
        &ground(),
        &tilt,
        &sphere,
        &Pose::from_position(center),
        SPECULATIVE_DISTANCE,
    )
    .unwrap();
    assert!((manifold.normal - normal).length() <= TOLERANCE);
    assert!((manifold.points()[0].separation + 0.1).abs() <= TOLERANCE);
}
