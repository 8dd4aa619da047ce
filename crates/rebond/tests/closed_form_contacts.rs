//! Closed-form contacts of spheres, capsules and boxes, and of a sphere or capsule against a
//! cylinder's side, against hand-computed configurations and the general GJK/EPA routine.
//!
//! Tolerance: positions are a few f32 operations on values below 10 m, so 1e-5 m covers their
//! rounding; separations likewise.

use rebond::internals::collision::closed_form::{
    capsule_capsule, rounded_segment_cylinder_side, sphere_box, sphere_capsule, sphere_sphere,
    CylinderSide,
};
use rebond::internals::collision::epa::Polytope;
use rebond::internals::collision::feature_contact::collide_features;
use rebond::internals::collision::gjk::SimplexCache;
use rebond::internals::collision::{Manifold, SPECULATIVE_DISTANCE};
use rebond::shape::{Capsule, Cuboid, Cylinder, Sphere};
use rebond::Shape;
use rebond::{Pose, Quat, Vec3};

const TOLERANCE: f32 = 1.0e-5;

fn at(x: f32, y: f32, z: f32) -> Pose {
    Pose::from_position(Vec3::new(x, y, z))
}

fn assert_vec(actual: Vec3, expected: Vec3) {
    assert!(
        (actual - expected).length() <= TOLERANCE,
        "got {actual}, expected {expected}"
    );
}

fn assert_single(manifold: Option<Manifold>, normal: Vec3, separation: f32, position: Vec3) {
    let manifold = manifold.expect("expected a contact");
    assert_eq!(manifold.len(), 1);
    assert_vec(manifold.normal, normal);
    let point = manifold.points()[0];
    assert!(
        (point.separation - separation).abs() <= TOLERANCE,
        "separation {}",
        point.separation
    );
    assert_vec(point.position, position);
}

#[test]
fn sphere_sphere_separated_touching_overlapping() {
    let (a, b) = (Sphere::new(1.0).unwrap(), Sphere::new(0.5).unwrap());
    let margin = SPECULATIVE_DISTANCE;
    assert!(sphere_sphere(&a, &at(0.0, 0.0, 0.0), &b, &at(3.0, 0.0, 0.0), margin).is_none());
    // Apart by 0.01 m, within the speculative margin: a point with positive separation.
    assert_single(
        sphere_sphere(&a, &at(0.0, 0.0, 0.0), &b, &at(1.51, 0.0, 0.0), margin),
        Vec3::X,
        0.01,
        Vec3::new(1.005, 0.0, 0.0),
    );
    assert_single(
        sphere_sphere(&a, &at(0.0, 0.0, 0.0), &b, &at(0.0, 1.5, 0.0), margin),
        Vec3::Y,
        0.0,
        Vec3::new(0.0, 1.0, 0.0),
    );
    // Overlapping along a diagonal: centres 1.2 m apart, depth 0.3 m.
    let direction = Vec3::new(1.0, 2.0, -2.0) / 3.0;
    let manifold = sphere_sphere(
        &a,
        &Pose::from_position(Vec3::ONE),
        &b,
        &Pose::from_position(Vec3::ONE + direction * 1.2),
        margin,
    );
    assert_single(manifold, direction, -0.3, Vec3::ONE + direction * 0.85);
}

#[test]
fn sphere_capsule_against_the_side_and_the_cap() {
    let sphere = Sphere::new(0.5).unwrap();
    let capsule = Capsule::new(0.25, 1.0).unwrap();
    let margin = SPECULATIVE_DISTANCE;
    // Beside the capsule's middle: the capsule axis is Y, the sphere at x = 0.7.
    assert_single(
        sphere_capsule(
            &sphere,
            &at(0.7, 0.3, 0.0),
            &capsule,
            &at(0.0, 0.0, 0.0),
            margin,
        ),
        -Vec3::X,
        -0.05,
        Vec3::new(0.225, 0.3, 0.0),
    );
    // Above the top cap, capsule lying along X after a quarter turn about Z.
    let lying = Pose::new(
        Vec3::ZERO,
        Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
    );
    assert_single(
        sphere_capsule(&sphere, &at(1.5, 0.0, 0.0), &capsule, &lying, margin),
        -Vec3::X,
        -0.25,
        Vec3::new(1.125, 0.0, 0.0),
    );
    assert!(sphere_capsule(&sphere, &at(3.0, 0.0, 0.0), &capsule, &lying, margin).is_none());
}

#[test]
fn crossing_capsules_touch_at_one_point_and_parallel_ones_at_two() {
    let capsule = Capsule::new(0.5, 1.0).unwrap();
    let margin = SPECULATIVE_DISTANCE;
    let along_x = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    let along_z = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    // A along X at the origin, B along Z 0.9 m above: one point, depth 0.1 m.
    assert_single(
        capsule_capsule(
            &capsule,
            &Pose::new(Vec3::ZERO, along_x),
            &capsule,
            &Pose::new(Vec3::new(0.2, 0.9, -0.3), along_z),
            margin,
        ),
        Vec3::Y,
        -0.1,
        Vec3::new(0.2, 0.45, 0.0),
    );
    // B along X too, lying on A and shifted by 0.5 m: two points at the ends of the overlap.
    let manifold = capsule_capsule(
        &capsule,
        &Pose::new(Vec3::ZERO, along_x),
        &capsule,
        &Pose::new(Vec3::new(0.5, 0.95, 0.0), along_x),
        margin,
    )
    .expect("contact");
    assert_eq!(manifold.len(), 2);
    assert_vec(manifold.normal, Vec3::Y);
    let mut xs: Vec<f32> = manifold.points().iter().map(|p| p.position.x).collect();
    xs.sort_by(f32::total_cmp);
    assert!(
        (xs[0] + 0.5).abs() <= TOLERANCE && (xs[1] - 1.0).abs() <= TOLERANCE,
        "{xs:?}"
    );
    for point in manifold.points() {
        assert!((point.separation + 0.05).abs() <= TOLERANCE);
        assert!((point.position.y - 0.475).abs() <= TOLERANCE);
    }
}

#[test]
fn sphere_box_face_edge_corner_and_inside() {
    let sphere = Sphere::new(0.5).unwrap();
    let cube = Cuboid::new(Vec3::new(1.0, 0.5, 2.0)).unwrap();
    let margin = SPECULATIVE_DISTANCE;
    let origin = at(0.0, 0.0, 0.0);
    // Resting on the top face, 0.1 m deep. Normal from the sphere (A) toward the box (B): −Y.
    assert_single(
        sphere_box(&sphere, &at(0.3, 0.9, 0.0), &cube, &origin, margin),
        -Vec3::Y,
        -0.1,
        Vec3::new(0.3, 0.45, 0.0),
    );
    // Beyond the edge x = 1, y = 0.5, 0.01 m apart: the closest point is on the edge.
    let edge = Vec3::new(1.0, 0.5, 0.0);
    let direction = Vec3::new(1.0, 1.0, 0.0).normalize();
    let center = edge + direction * 0.51;
    assert_single(
        sphere_box(
            &sphere,
            &Pose::from_position(center),
            &cube,
            &origin,
            margin,
        ),
        -direction,
        0.01,
        edge + direction * 0.005,
    );
    // Centre inside the box, 0.2 m below the top face: leaves through the top.
    assert_single(
        sphere_box(&sphere, &at(0.0, 0.3, 1.0), &cube, &origin, margin),
        -Vec3::Y,
        -0.7,
        Vec3::new(0.0, 0.15, 1.0),
    );
    // A rotated box: a quarter turn about Y swaps its X and Z extents.
    let turned = Pose::new(
        Vec3::ZERO,
        Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
    );
    assert_single(
        sphere_box(&sphere, &at(2.4, 0.0, 0.0), &cube, &turned, margin),
        -Vec3::X,
        -0.1,
        Vec3::new(1.95, 0.0, 0.0),
    );
    assert!(sphere_box(&sphere, &at(0.0, 2.0, 0.0), &cube, &origin, margin).is_none());
}

#[test]
fn centres_on_the_segment_give_a_unit_normal_across_it() {
    // Found by fuzzing library calls: a sphere or a capsule centred on another capsule's
    // segment fell back to a direction across that segment of the segment's length, not of unit
    // length, and the bodies stepped to NaN. Capsules of half height 3.75 make it 7.5 long.
    let rotation = Quat::from_xyzw(-5.0, -4.6875, 0.0, 4.25).normalize();
    let capsule = Capsule::new(3.75, 3.75).unwrap();
    let pose = Pose::new(Vec3::splat(3.75), rotation);
    let axis = rotation * Vec3::Y;
    let check = |manifold: Option<Manifold>| {
        let manifold = manifold.expect("overlapping shapes touch");
        assert!(
            (manifold.normal.length() - 1.0).abs() < 1e-6,
            "{}",
            manifold.normal
        );
        assert!(
            manifold.normal.dot(axis).abs() < 1e-6,
            "{}",
            manifold.normal
        );
    };
    let sphere = Sphere::new(0.5).unwrap();
    check(sphere_capsule(
        &sphere,
        &pose,
        &capsule,
        &pose,
        SPECULATIVE_DISTANCE,
    ));
    let crossing = Pose::new(pose.position, Quat::from_rotation_x(0.3) * rotation);
    check(capsule_capsule(
        &capsule,
        &pose,
        &capsule,
        &crossing,
        SPECULATIVE_DISTANCE,
    ));
}

/// The side contact of `capsule` at `pose` against `cylinder` at `cylinder_pose`, which must be
/// found on the side.
fn side_contact(
    capsule: &Capsule,
    pose: &Pose,
    cylinder: &Cylinder,
    cylinder_pose: &Pose,
) -> Option<Manifold> {
    let segment = capsule.segment().map(|end| pose.transform_point(end));
    match rounded_segment_cylinder_side(
        segment,
        capsule.radius(),
        cylinder,
        cylinder_pose,
        SPECULATIVE_DISTANCE,
    ) {
        CylinderSide::Side(manifold) => manifold,
        CylinderSide::Elsewhere => panic!("expected the side at {pose:?}"),
    }
}

#[test]
fn a_capsule_meets_a_cylinder_side_exactly() {
    // The cylinder stands on Y at the origin (radius 0.5 m, half height 1 m); the capsule
    // (radius 0.25 m) lies along Z beside it at x = 0.76, y = 0.2: 1 cm apart, normal −X from
    // the capsule to the cylinder, the point halfway between the surfaces (x = 0.51 and 0.5).
    let cylinder = Cylinder::new(0.5, 1.0).unwrap();
    let capsule = Capsule::new(0.25, 0.6).unwrap();
    let along_z = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    assert_single(
        side_contact(
            &capsule,
            &Pose::new(Vec3::new(0.76, 0.2, 0.0), along_z),
            &cylinder,
            &at(0.0, 0.0, 0.0),
        ),
        -Vec3::X,
        0.01,
        Vec3::new(0.505, 0.2, 0.0),
    );
    // Lying along the side, 1 cm deep, its segment from y = −0.3 to 0.9: two points at the ends
    // of the stretch both share, within the sharp cylinder's ends (y = ±1).
    let manifold = side_contact(&capsule, &at(0.74, 0.3, 0.0), &cylinder, &at(0.0, 0.0, 0.0))
        .expect("contact");
    assert_eq!(manifold.len(), 2);
    assert_vec(manifold.normal, -Vec3::X);
    let mut ys: Vec<f32> = manifold.points().iter().map(|p| p.position.y).collect();
    ys.sort_by(f32::total_cmp);
    assert!(
        (ys[0] + 0.3).abs() <= TOLERANCE && (ys[1] - 0.9).abs() <= TOLERANCE,
        "{ys:?}"
    );
    for point in manifold.points() {
        assert!((point.separation + 0.01).abs() <= TOLERANCE);
    }
    // Beyond the margin: nothing.
    assert!(side_contact(&capsule, &at(1.5, 0.0, 0.0), &cylinder, &at(0.0, 0.0, 0.0)).is_none());
}

#[test]
fn past_the_side_the_general_routine_answers() {
    let cylinder = Cylinder::new(0.5, 1.0).unwrap();
    let capsule = Capsule::new(0.25, 0.6).unwrap();
    let along_x = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    let side = |pose: Pose| {
        let segment = capsule.segment().map(|end| pose.transform_point(end));
        rounded_segment_cylinder_side(segment, 0.25, &cylinder, &at(0.0, 0.0, 0.0), 0.1)
    };
    // Across the top cap: the closest point of the axis is its end.
    assert_eq!(
        side(Pose::new(Vec3::new(0.0, 1.2, 0.0), along_x)),
        CylinderSide::Elsewhere
    );
    // Through the axis: no direction to push along.
    assert_eq!(
        side(Pose::new(Vec3::ZERO, along_x)),
        CylinderSide::Elsewhere
    );
    // Deeper than half the radius: the shortest way out may be through a cap.
    assert_eq!(side(at(0.4, 0.0, 0.0)), CylinderSide::Elsewhere);
}

#[test]
fn the_side_contact_agrees_with_gjk_and_epa() {
    // Capsules and spheres touching or nearly touching a turned cylinder's side from many
    // directions. GJK stops once the distance is known within `gjk::CONTACT_PRECISION` (0.1 mm);
    // on a round side its normal then leans by up to about √(2 · 1e-4 m / 0.08 m) ≈ 0.05 rad
    // (measured here: at most 5e-4 rad), and its separation is within 0.2 mm (measured: 13 µm).
    let cylinder = Cylinder::new(0.35, 0.12).unwrap();
    let cylinder_pose = Pose::new(
        Vec3::new(0.1, 0.2, -0.3),
        Quat::from_rotation_x(1.1) * Quat::from_rotation_z(0.4),
    );
    let axis = cylinder_pose.transform_vector(Vec3::Y);
    let across = axis.any_orthonormal_vector();
    let shapes = [
        Shape::Capsule(Capsule::new(0.08, 0.3).unwrap()),
        Shape::Sphere(Sphere::new(0.2).unwrap()),
    ];
    let mut compared = 0;
    for shape in &shapes {
        for turn in 0..12 {
            let angle = turn as f32 * std::f32::consts::TAU / 12.0;
            let out = Quat::from_axis_angle(axis, angle) * across;
            for gap in [-0.004f32, 0.0, 0.015] {
                let (segment, radius) = match shape {
                    Shape::Capsule(capsule) => (capsule.segment(), capsule.radius()),
                    Shape::Sphere(sphere) => ([Vec3::ZERO; 2], sphere.radius()),
                    _ => unreachable!(),
                };
                // The capsule crosses the axis's direction at 60°, its centre beside the side.
                let rotation =
                    Quat::from_rotation_arc(Vec3::Y, (axis + out.cross(axis)).normalize());
                let center = cylinder_pose.position + 0.03 * axis + out * (0.35 + radius + gap);
                let pose = Pose::new(center, rotation);
                let segment = segment.map(|end| pose.transform_point(end));
                let CylinderSide::Side(Some(closed)) = rounded_segment_cylinder_side(
                    segment,
                    radius,
                    &cylinder,
                    &cylinder_pose,
                    SPECULATIVE_DISTANCE,
                ) else {
                    panic!("expected a side contact at {angle} rad, gap {gap}");
                };
                let (mut polytope, mut simplex) = (Polytope::default(), SimplexCache::default());
                let general = collide_features(
                    &mut polytope,
                    shape,
                    &pose,
                    &Shape::Cylinder(cylinder),
                    &cylinder_pose,
                    SPECULATIVE_DISTANCE,
                    &mut simplex,
                )
                .expect("GJK finds the contact too");
                let lean = closed.normal.angle_between(general.normal);
                assert!(
                    lean < 0.05,
                    "normals {} and {} at {angle} rad",
                    closed.normal,
                    general.normal
                );
                let deepest = |m: &Manifold| {
                    m.points()
                        .iter()
                        .map(|p| p.separation)
                        .fold(f32::INFINITY, f32::min)
                };
                assert!(
                    (deepest(&closed) - deepest(&general)).abs() < 2.0e-4,
                    "separations {} and {} at {angle} rad, gap {gap}",
                    deepest(&closed),
                    deepest(&general)
                );
                assert!((deepest(&closed) - gap).abs() < TOLERANCE * 10.0);
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 72);
}
