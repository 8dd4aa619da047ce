//! Contact manifolds between boxes and convex hulls: known resting configurations, symmetry under
//! swapping the shapes, id stability, hulls against boxes, and a property test of random box pairs
//! against an independent separating-axis computation.

use std::f32::consts::{FRAC_PI_4, PI};

use proptest::prelude::*;
use rebond::internals::collision::clipping::SIDE_PLANE_SLOP;
use rebond::internals::collision::polyhedron::Polyhedron;
use rebond::internals::collision::polyhedron_contact::collide_polyhedra;
use rebond::internals::collision::{Manifold, SPECULATIVE_DISTANCE};
use rebond::shape::{ConvexHull, Cuboid, Shape};
use rebond::{Mat3, Pose, Quat, Vec3};

const MARGIN: f32 = SPECULATIVE_DISTANCE;

fn cuboid(x: f32, y: f32, z: f32) -> Cuboid {
    Cuboid::new(Vec3::new(x, y, z)).expect("valid box")
}

/// A ground box with its top face at y = 0.5.
fn ground() -> Cuboid {
    cuboid(5.0, 0.5, 5.0)
}

fn collide(a: &Polyhedron, pose_a: Pose, b: &Polyhedron, pose_b: Pose) -> Option<Manifold> {
    collide_polyhedra(a, &pose_a, b, &pose_b, MARGIN)
}

fn collide_boxes(a: &Cuboid, pose_a: Pose, b: &Cuboid, pose_b: Pose) -> Option<Manifold> {
    collide(
        &Polyhedron::cuboid(a),
        pose_a,
        &Polyhedron::cuboid(b),
        pose_b,
    )
}

fn assert_near(actual: Vec3, expected: Vec3, tolerance: f32) {
    assert!(
        (actual - expected).length() <= tolerance,
        "{actual} is not within {tolerance} of {expected}"
    );
}

/// Every expected point appears once in the manifold, each with the expected separation.
fn assert_points(manifold: &Manifold, expected: &[Vec3], separation: f32) {
    assert_eq!(manifold.len(), expected.len(), "{manifold:?}");
    for &point in expected {
        let found = manifold
            .points()
            .iter()
            .find(|contact| (contact.position - point).length() < 1e-4)
            .unwrap_or_else(|| panic!("no point near {point} in {manifold:?}"));
        assert!(
            (found.separation - separation).abs() < 1e-4,
            "separation {} instead of {separation}",
            found.separation
        );
    }
}

/// Same normal (within 1e-4) and the same points (positions within `tolerance`, separations
/// within 1e-4), in any order; ids are not compared.
fn assert_same_contact(left: &Manifold, right: &Manifold, tolerance: f32) {
    assert_near(left.normal, right.normal, 1e-4);
    assert_eq!(left.len(), right.len(), "{left:?}\n{right:?}");
    for point in left.points() {
        assert!(
            right.points().iter().any(|other| {
                (other.position - point.position).length() <= tolerance
                    && (other.separation - point.separation).abs() <= 1e-4
            }),
            "{point:?} has no match in {right:?}"
        );
    }
}

fn ids(manifold: &Manifold) -> Vec<u32> {
    let mut ids: Vec<u32> = manifold.points().iter().map(|point| point.id).collect();
    ids.sort_unstable();
    ids
}

fn corners(half: f32, height: f32) -> Vec<Vec3> {
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, z)| Vec3::new(x * half, height, z * half))
        .collect()
}

#[test]
fn box_lying_flat_gives_four_corners() {
    let manifold = collide_boxes(
        &ground(),
        Pose::IDENTITY,
        &cuboid(0.5, 0.5, 0.5),
        Pose::from_position(Vec3::new(0.0, 0.99, 0.0)),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    assert_points(&manifold, &corners(0.5, 0.495), -0.01);
    let mut unique = ids(&manifold);
    unique.dedup();
    assert_eq!(unique.len(), 4);
}

#[test]
fn swapping_the_boxes_flips_the_normal_and_keeps_the_points() {
    let configurations = [
        Pose::from_position(Vec3::new(0.0, 0.99, 0.0)),
        Pose::new(
            Vec3::new(0.3, 0.49 + 0.5 * 2.0_f32.sqrt(), -0.2),
            Quat::from_rotation_z(FRAC_PI_4),
        ),
        Pose::new(Vec3::new(1.0, 0.98, 2.0), Quat::from_rotation_y(0.5)),
        Pose::new(Vec3::new(0.0, 1.1, 0.0), Quat::from_rotation_z(0.35)),
    ];
    for pose in configurations {
        let forward = collide_boxes(&ground(), Pose::IDENTITY, &cuboid(0.5, 0.5, 0.5), pose)
            .expect("touching");
        let backward = collide_boxes(&cuboid(0.5, 0.5, 0.5), pose, &ground(), Pose::IDENTITY)
            .expect("touching");
        assert_same_contact(&forward, &backward.flipped(), 1e-4);
    }
}

#[test]
fn box_on_its_edge_gives_two_points() {
    let height = 0.49 + 0.5 * 2.0_f32.sqrt();
    let manifold = collide_boxes(
        &ground(),
        Pose::IDENTITY,
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(
            Vec3::new(0.0, height, 0.0),
            Quat::from_rotation_z(FRAC_PI_4),
        ),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    assert_points(
        &manifold,
        &[Vec3::new(0.0, 0.495, -0.5), Vec3::new(0.0, 0.495, 0.5)],
        -0.01,
    );
}

#[test]
fn box_tilted_by_twenty_degrees_rests_on_its_lowest_edge() {
    let angle = 20.0_f32.to_radians();
    let (sin, cos) = angle.sin_cos();
    let center = Vec3::new(0.2, 0.49 + 0.5 * (sin + cos), 0.0);
    let manifold = collide_boxes(
        &ground(),
        Pose::IDENTITY,
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(center, Quat::from_rotation_z(angle)),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    let x = center.x + 0.5 * (sin - cos);
    assert_points(
        &manifold,
        &[Vec3::new(x, 0.495, -0.5), Vec3::new(x, 0.495, 0.5)],
        -0.01,
    );
}

#[test]
fn box_on_its_corner_gives_one_point() {
    let rotation = Quat::from_rotation_arc(Vec3::ONE.normalize(), Vec3::Y);
    let height = 0.49 + 0.5 * 3.0_f32.sqrt();
    let manifold = collide_boxes(
        &ground(),
        Pose::IDENTITY,
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(Vec3::new(0.0, height, 0.0), rotation),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    assert_points(&manifold, &[Vec3::new(0.0, 0.495, 0.0)], -0.01);
}

#[test]
fn crossed_edges_give_one_point_between_them() {
    let reach = 0.5 * 2.0_f32.sqrt();
    let manifold = collide_boxes(
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4)),
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(
            Vec3::new(0.0, 2.0 * reach - 0.01, 0.0),
            Quat::from_rotation_x(FRAC_PI_4),
        ),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-5);
    assert_points(&manifold, &[Vec3::new(0.0, reach - 0.005, 0.0)], -0.01);
}

#[test]
fn apart_by_more_than_the_margin_gives_none() {
    let far = collide_boxes(
        &ground(),
        Pose::IDENTITY,
        &cuboid(0.5, 0.5, 0.5),
        Pose::from_position(Vec3::new(0.0, 1.0 + MARGIN + 0.005, 0.0)),
    );
    assert!(far.is_none());
    // Apart sideways along an edge axis only: the corner of one box past the edge of the other.
    let reach = 0.5 * 2.0_f32.sqrt();
    let edge_apart = collide_boxes(
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4)),
        &cuboid(0.5, 0.5, 0.5),
        Pose::new(
            Vec3::new(0.0, 2.0 * reach + MARGIN + 0.005, 0.0),
            Quat::from_rotation_x(FRAC_PI_4),
        ),
    );
    assert!(edge_apart.is_none());
}

/// Two unit boxes corner to corner along their diagonal, 1 cm apart: every axis of the separating-
/// axis test (faces and edge pairs) measures less than the distance (0.01/√3 along a face normal),
/// so the contact is the one point midway between the corners, along the diagonal, 1 cm apart.
#[test]
fn corners_apart_are_measured_by_their_distance() {
    let diagonal = Vec3::ONE.normalize();
    let corner = Vec3::splat(0.5);
    for (pose_a, pose_b) in [
        (
            Pose::IDENTITY,
            Pose::from_position(2.0 * corner + diagonal * 0.01),
        ),
        (
            Pose::new(Vec3::new(0.3, -0.2, 0.1), Quat::from_rotation_y(0.7)),
            Pose::new(
                Vec3::new(0.3, -0.2, 0.1)
                    + Quat::from_rotation_y(0.7) * (2.0 * corner + diagonal * 0.01),
                Quat::from_rotation_y(0.7),
            ),
        ),
    ] {
        let unit = cuboid(0.5, 0.5, 0.5);
        let manifold = collide_boxes(&unit, pose_a, &unit, pose_b).expect("within the margin");
        let expected = pose_a.transform_point(corner + diagonal * 0.005);
        assert_near(manifold.normal, pose_a.rotation * diagonal, 1e-4);
        assert_points(&manifold, &[expected], 0.01);
        let swapped = collide_boxes(&unit, pose_b, &unit, pose_a).expect("within the margin");
        assert_near(swapped.normal, -manifold.normal, 1e-4);
        assert_points(&swapped, &[expected], 0.01);
    }
}

#[test]
fn within_the_margin_gives_speculative_points() {
    let manifold = collide_boxes(
        &ground(),
        Pose::IDENTITY,
        &cuboid(0.5, 0.5, 0.5),
        Pose::from_position(Vec3::new(0.0, 1.01, 0.0)),
    )
    .expect("within the margin");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    assert_points(&manifold, &corners(0.5, 0.505), 0.01);
}

#[test]
fn rotated_scenes_keep_normal_and_depth() {
    let scenes = [
        (Vec3::new(3.0, -2.0, 1.0), Quat::from_rotation_x(0.7)),
        (
            Vec3::new(-10.0, 4.0, 0.5),
            Quat::from_euler(glam::EulerRot::XYZ, 1.1, -0.4, 2.5),
        ),
        (Vec3::ZERO, Quat::from_rotation_z(PI)),
    ];
    let yaw = Quat::from_rotation_y(0.5);
    let local_box = Pose::new(Vec3::new(0.4, 0.99, -1.0), yaw);
    for (offset, rotation) in scenes {
        let scene = Pose::new(offset, rotation);
        let manifold = collide_boxes(
            &ground(),
            scene,
            &cuboid(0.5, 0.5, 0.5),
            scene.mul_pose(&local_box),
        )
        .expect("touching");
        assert_near(manifold.normal, rotation * Vec3::Y, 1e-5);
        let expected: Vec<Vec3> = corners(0.5, 0.0)
            .into_iter()
            .map(|corner| {
                let flat = local_box.position + yaw * corner;
                scene.transform_point(Vec3::new(flat.x, 0.495, flat.z))
            })
            .collect();
        assert_points(&manifold, &expected, -0.01);
    }
}

#[test]
fn ids_survive_small_motions() {
    let rest = Pose::from_position(Vec3::new(0.3, 0.99, -0.2));
    let reference =
        collide_boxes(&ground(), Pose::IDENTITY, &cuboid(0.5, 0.5, 0.5), rest).expect("touching");
    let nudges = [
        Pose::from_position(Vec3::new(0.001, 0.0, 0.0)),
        Pose::from_position(Vec3::new(0.0, -0.001, 0.001)),
        Pose::new(Vec3::ZERO, Quat::from_rotation_y(0.5_f32.to_radians())),
        Pose::new(Vec3::ZERO, Quat::from_rotation_x(0.5_f32.to_radians())),
        Pose::new(
            Vec3::new(0.001, 0.0, -0.001),
            Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.5_f32.to_radians()),
        ),
    ];
    for nudge in nudges {
        let moved = Pose::new(
            rest.position + nudge.position,
            nudge.rotation * rest.rotation,
        );
        let manifold = collide_boxes(&ground(), Pose::IDENTITY, &cuboid(0.5, 0.5, 0.5), moved)
            .expect("touching");
        assert_eq!(ids(&manifold), ids(&reference));
        for point in manifold.points() {
            let before = reference
                .points()
                .iter()
                .find(|other| other.id == point.id)
                .expect("same ids");
            assert!((before.position - point.position).length() < 0.01);
        }
    }
}

#[test]
fn equal_boxes_stacked_keep_their_vertex_ids_through_round_off() {
    let block = cuboid(0.5, 0.5, 0.5);
    let at = |x: f32, z: f32| Pose::from_position(Vec3::new(x, 0.99, z));
    let aligned = collide_boxes(&block, Pose::IDENTITY, &block, at(0.0, 0.0)).expect("touching");
    assert_points(&aligned, &corners(0.5, 0.495), -0.01);
    for (x, z) in [(5e-5, 0.0), (-3e-5, 6e-5), (0.0, -8e-5)] {
        let nudged = collide_boxes(&block, Pose::IDENTITY, &block, at(x, z)).expect("touching");
        assert_eq!(ids(&nudged), ids(&aligned));
    }
}

/// The 8 corners of a box with the given half extents, in a scrambled order.
fn box_corners(half: Vec3) -> Vec<Vec3> {
    [5, 0, 3, 6, 1, 7, 2, 4]
        .iter()
        .map(|&i: &u32| {
            let sign = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
            Vec3::new(sign(1), sign(2), sign(4)) * half
        })
        .collect()
}

fn hull(points: &[Vec3]) -> ConvexHull {
    ConvexHull::new(points).expect("valid hull")
}

/// A few poses of a box of half extent 0.5 near the ground box's top, no two candidate axes tied.
fn resting_poses() -> Vec<Pose> {
    vec![
        Pose::from_position(Vec3::new(0.0, 0.99, 0.0)),
        Pose::new(Vec3::new(0.1, 1.05, 0.2), Quat::from_rotation_z(0.35)),
        Pose::new(
            Vec3::new(-0.3, 1.1, 0.4),
            Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.2, 0.1),
        ),
        Pose::new(
            Vec3::new(4.9, 1.0, 0.1),
            Quat::from_euler(glam::EulerRot::XYZ, 0.05, 0.7, 0.02),
        ),
    ]
}

#[test]
fn hull_of_box_corners_collides_like_the_box() {
    let solid = cuboid(0.5, 0.5, 0.5);
    let solid_hull = hull(&box_corners(solid.half_extents()));
    let ground_box = ground();
    let ground_hull = hull(&box_corners(ground_box.half_extents()));
    for pose in resting_poses() {
        let expected = collide_boxes(&ground_box, Pose::IDENTITY, &solid, pose).expect("touching");
        let box_and_hull = collide(
            &Polyhedron::cuboid(&ground_box),
            Pose::IDENTITY,
            &Polyhedron::hull(&solid_hull),
            pose,
        )
        .expect("touching");
        assert_same_contact(&box_and_hull, &expected, 1e-4);
        let hulls = collide(
            &Polyhedron::hull(&ground_hull),
            Pose::IDENTITY,
            &Polyhedron::hull(&solid_hull),
            pose,
        )
        .expect("touching");
        assert_same_contact(&hulls, &expected, 1e-4);
    }
}

#[test]
fn tetrahedron_on_a_box() {
    let base = [
        Vec3::new(-0.5, 0.0, -0.3),
        Vec3::new(0.5, 0.0, -0.3),
        Vec3::new(0.0, 0.0, 0.5),
    ];
    let ground_box = ground();
    let ground_hull = hull(&box_corners(ground_box.half_extents()));
    let at = Vec3::new(1.0, 0.49, -1.0);

    // Face down: three points at the base corners, on the box and on its hull.
    let face_down = hull(&[base[0], base[1], base[2], Vec3::new(0.0, 0.8, 0.0)]);
    let expected: Vec<Vec3> = base
        .iter()
        .map(|corner| *corner + at + Vec3::Y * 0.005)
        .collect();
    for ground_view in [
        Polyhedron::cuboid(&ground_box),
        Polyhedron::hull(&ground_hull),
    ] {
        let manifold = collide(
            &ground_view,
            Pose::IDENTITY,
            &Polyhedron::hull(&face_down),
            Pose::from_position(at),
        )
        .expect("touching");
        assert_near(manifold.normal, Vec3::Y, 1e-6);
        assert_points(&manifold, &expected, -0.01);
    }

    // Apex down: one point, the same from either side.
    let apex_down = hull(&[
        Vec3::ZERO,
        base[0] + Vec3::Y * 0.8,
        base[1] + Vec3::Y * 0.8,
        base[2] + Vec3::Y * 0.8,
    ]);
    let ground_view = Polyhedron::cuboid(&ground_box);
    let tetrahedron = Polyhedron::hull(&apex_down);
    let manifold = collide(
        &ground_view,
        Pose::IDENTITY,
        &tetrahedron,
        Pose::from_position(at),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    assert_points(&manifold, &[at + Vec3::Y * 0.005], -0.01);
    let swapped = collide(
        &tetrahedron,
        Pose::from_position(at),
        &ground_view,
        Pose::IDENTITY,
    )
    .expect("touching");
    assert_same_contact(&swapped.flipped(), &manifold, 1e-4);
}

#[test]
fn round_hulls_rest_on_their_lowest_features() {
    let ground_box = ground();
    let ground_view = Polyhedron::cuboid(&ground_box);

    // A 40-sided prism standing on its cap: the cap's loop is longer than the clipper reads, so
    // an evenly spaced subset of it is clipped, and the reduction keeps four points of the rim.
    let sides = 40;
    let prism_points: Vec<Vec3> = (0..2 * sides)
        .map(|k| {
            let angle = 2.0 * PI * (k % sides) as f32 / sides as f32;
            let y = if k < sides { 0.0 } else { 0.6 };
            Vec3::new(0.4 * angle.cos(), y, 0.4 * angle.sin())
        })
        .collect();
    let prism = hull(&prism_points);
    let at = Vec3::new(-1.0, 0.49, 2.0);
    let manifold = collide(
        &ground_view,
        Pose::IDENTITY,
        &Polyhedron::hull(&prism),
        Pose::from_position(at),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-6);
    assert_eq!(manifold.len(), 4);
    for point in manifold.points() {
        assert!((point.separation + 0.01).abs() < 1e-5);
        let radius = (point.position - at).with_y(0.0).length();
        assert!((radius - 0.4).abs() < 1e-4, "on the rim: {radius}");
    }

    // A ball of 60 points, tilted: the contact is at its lowest vertex, 1 cm deep.
    let golden = PI * (3.0 - 5.0_f32.sqrt());
    let ball_points: Vec<Vec3> = (0..60)
        .map(|k| {
            let y = 1.0 - 2.0 * (k as f32 + 0.5) / 60.0;
            let ring = (1.0 - y * y).sqrt();
            let angle = golden * k as f32;
            0.5 * Vec3::new(ring * angle.cos(), y, ring * angle.sin())
        })
        .collect();
    let ball = hull(&ball_points);
    let rotation = Quat::from_euler(glam::EulerRot::XYZ, 0.4, 1.3, -0.2);
    let lowest = ball
        .vertices()
        .iter()
        .map(|vertex| rotation * *vertex)
        .min_by(|p, q| p.y.total_cmp(&q.y))
        .expect("vertices");
    let at = Vec3::new(0.7, 0.49 - lowest.y, -0.3);
    let manifold = collide(
        &ground_view,
        Pose::IDENTITY,
        &Polyhedron::hull(&ball),
        Pose::new(at, rotation),
    )
    .expect("touching");
    assert_near(manifold.normal, Vec3::Y, 1e-5);
    let deepest = manifold
        .points()
        .iter()
        .min_by(|p, q| p.separation.total_cmp(&q.separation))
        .expect("points");
    assert!((deepest.separation + 0.01).abs() < 1e-5);
    assert_near(deepest.position, at + lowest + Vec3::Y * 0.005, 1e-4);
}

#[test]
fn only_boxes_and_hulls_are_polyhedra() {
    let sphere = Shape::sphere(1.0).expect("valid sphere");
    assert!(Polyhedron::from_shape(&sphere).is_none());
    let boxed = Shape::cuboid(Vec3::ONE).expect("valid box");
    let view = Polyhedron::from_shape(&boxed).expect("a box is a polyhedron");
    assert_eq!(
        (view.vertex_count(), view.face_count(), view.edge_count()),
        (8, 6, 12)
    );
}

#[test]
fn extreme_but_finite_inputs_stay_finite() {
    // Every half extent within the engine's size limits (`limits::MIN_SIZE` to `MAX_SIZE`).
    let sizes = [4e-3, 1.0, 1e4];
    let rotation = Quat::from_euler(glam::EulerRot::XYZ, 0.3, 1.2, -0.7);
    for &size_a in &sizes {
        for &size_b in &sizes {
            for &distance in &[0.0, 1e-3, 1.0, 1e4, 1e6] {
                let a = cuboid(size_a, size_a * 0.5, size_a * 2.0);
                let b = cuboid(size_b, size_b, size_b * 0.3);
                let pose_b = Pose::new(Vec3::new(distance, distance * 0.5, 0.0), rotation);
                if let Some(manifold) = collide_boxes(&a, Pose::IDENTITY, &b, pose_b) {
                    assert!(manifold.normal.is_finite());
                    assert!(!manifold.is_empty());
                    for point in manifold.points() {
                        assert!(point.position.is_finite() && point.separation.is_finite());
                    }
                }
            }
        }
    }
}

/// Signed distance from `point` to a box of `half` extents at `pose`: negative inside.
fn box_signed_distance(half: Vec3, pose: &Pose, point: Vec3) -> f32 {
    let excess = pose.inverse_transform_point(point).abs() - half;
    excess.max(Vec3::ZERO).length() + excess.max_element().min(0.0)
}

/// The separating-axis value of two boxes computed directly over all 15 axes: the largest gap
/// between their projections (negative: the smallest overlap).
fn sat_separation(half_a: Vec3, pose_a: &Pose, half_b: Vec3, pose_b: &Pose) -> f32 {
    let rotation_a = Mat3::from_quat(pose_a.rotation);
    let rotation_b = Mat3::from_quat(pose_b.rotation);
    let axes_a = [rotation_a.x_axis, rotation_a.y_axis, rotation_a.z_axis];
    let axes_b = [rotation_b.x_axis, rotation_b.y_axis, rotation_b.z_axis];
    let mut axes: Vec<Vec3> = axes_a.iter().chain(&axes_b).copied().collect();
    for a in axes_a {
        for b in axes_b {
            let cross = a.cross(b);
            if cross.length() > 1e-3 {
                axes.push(cross.normalize());
            }
        }
    }
    let offset = pose_b.position - pose_a.position;
    let radius = |half: Vec3, box_axes: &[Vec3; 3], axis: Vec3| {
        (0..3)
            .map(|k| half[k] * box_axes[k].dot(axis).abs())
            .sum::<f32>()
    };
    axes.iter()
        .map(|&axis| {
            offset.dot(axis).abs() - radius(half_a, &axes_a, axis) - radius(half_b, &axes_b, axis)
        })
        .fold(f32::NEG_INFINITY, f32::max)
}

/// Checks one manifold between boxes A and B: unit normal, distinct ids, separations within the
/// margin, each point's two witnesses on the two surfaces, deepest separation against the
/// reference SAT value.
fn check_box_manifold(
    manifold: &Manifold,
    (half_a, pose_a): (Vec3, &Pose),
    (half_b, pose_b): (Vec3, &Pose),
    sat: f32,
) -> Result<(), TestCaseError> {
    prop_assert!((manifold.normal.length() - 1.0).abs() < 1e-5);
    prop_assert!((1..=4).contains(&manifold.len()));
    let mut unique = ids(manifold);
    unique.dedup();
    prop_assert_eq!(unique.len(), manifold.len());
    // Each point was built from a point on one surface and its partner on the other, half the
    // separation away on either side along the normal. Both must lie on their surfaces: exactly
    // but for round-off (1e-4 at coordinates of a few metres is ~10x the f32 error of the
    // transforms), plus SIDE_PLANE_SLOP, by which a vertex may stick out of a reference face.
    // The exception is an edge contact (id bit 31) between shapes still apart: the closest
    // points of the two edge segments may sit at an end, off the common perpendicular, so only
    // the weaker property holds that the point lies in the gap, at least half the separation
    // from each shape (each shape lies behind its supporting edge along the normal). Overlapping,
    // the edge axis is the least-overlap axis and its closest points are inside both edges.
    let tolerance = SIDE_PLANE_SLOP + 1e-4;
    let mut deepest = f32::INFINITY;
    for point in manifold.points() {
        prop_assert!(point.separation <= MARGIN);
        let half_step = 0.5 * point.separation * manifold.normal;
        if point.id & (1 << 31) != 0 && point.separation > 0.0 {
            let from_a = box_signed_distance(half_a, pose_a, point.position);
            let from_b = box_signed_distance(half_b, pose_b, point.position);
            let half = 0.5 * point.separation - tolerance;
            prop_assert!(from_a >= half && from_b >= half, "{} {}", from_a, from_b);
        } else {
            let on_a = box_signed_distance(half_a, pose_a, point.position - half_step);
            let on_b = box_signed_distance(half_b, pose_b, point.position + half_step);
            prop_assert!(on_a.abs() <= tolerance, "witness on A off by {}", on_a);
            prop_assert!(on_b.abs() <= tolerance, "witness on B off by {}", on_b);
            // So the point itself lies on or within both shapes, up to half its separation.
            let reach = 0.5 * point.separation.abs() + tolerance;
            prop_assert!(box_signed_distance(half_a, pose_a, point.position) <= reach);
            prop_assert!(box_signed_distance(half_b, pose_b, point.position) <= reach);
        }
        deepest = deepest.min(point.separation);
    }
    // The chosen axis may trail the best one by one hysteresis tolerance (10 % of the chosen
    // axis's separation + 0.5 mm for a face kept over an edge, 5 % + 0.5 mm for A's face kept
    // over B's), plus round-off.
    let allowed = 0.1 * sat.abs().max(deepest.abs()) + 5e-4 + 1e-4;
    prop_assert!(
        deepest >= sat - allowed,
        "deepest {} below SAT {}",
        deepest,
        sat
    );
    // Overlapping, the SAT value is the penetration depth and the deepest point must reach it.
    // Apart, it is only a lower bound on the distance: when the closest vertex lies outside the
    // reference face's side planes, the nearest clipped point is farther.
    if sat <= 0.0 {
        prop_assert!(
            deepest <= sat + allowed,
            "deepest {} above SAT {}",
            deepest,
            sat
        );
    }
    Ok(())
}

/// A float spread evenly over `[low, high]` in a million steps, drawn as an integer (proptest's
/// own float ranges trip an internal assertion once in a few million draws).
fn uniform(low: f32, high: f32) -> impl Strategy<Value = f32> {
    (0u32..=1_000_000).prop_map(move |step| low + (high - low) * (step as f32 * 1e-6))
}

fn vector(low: f32, high: f32) -> impl Strategy<Value = Vec3> {
    (uniform(low, high), uniform(low, high), uniform(low, high))
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn half_extents() -> impl Strategy<Value = Vec3> {
    vector(0.1, 1.0)
}

fn rotation() -> impl Strategy<Value = Quat> {
    vector(-PI, PI)
        .prop_map(|angles| Quat::from_euler(glam::EulerRot::XYZ, angles.x, angles.y, angles.z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_box_pairs_agree_with_the_separating_axis_test(
        half_a in half_extents(),
        half_b in half_extents(),
        rotation_a in rotation(),
        rotation_b in rotation(),
        position_a in vector(-5.0, 5.0),
        offset in vector(-1.5, 1.5),
    ) {
        let pose_a = Pose::new(position_a, rotation_a);
        let pose_b = Pose::new(position_a + offset, rotation_b);
        let a = cuboid(half_a.x, half_a.y, half_a.z);
        let b = cuboid(half_b.x, half_b.y, half_b.z);
        let sat = sat_separation(half_a, &pose_a, half_b, &pose_b);

        let forward = collide_boxes(&a, pose_a, &b, pose_b);
        let backward = collide_boxes(&b, pose_b, &a, pose_a);
        if sat > MARGIN + 1e-4 {
            prop_assert!(forward.is_none() && backward.is_none());
        }
        if sat < -1e-4 {
            prop_assert!(forward.is_some() && backward.is_some(), "overlap {} but no contact", sat);
        }
        if let (Some(forward), Some(backward)) = (forward, backward) {
            check_box_manifold(&forward, (half_a, &pose_a), (half_b, &pose_b), sat)?;
            check_box_manifold(&backward, (half_b, &pose_b), (half_a, &pose_a), sat)?;
            // When both calls pick the same axis (opposite normals up to round-off) the contact
            // is the same seen from the other side. Otherwise two axes were within the
            // hysteresis tolerance and each call kept its own A's face; both manifolds were
            // checked against the SAT above.
            // Between nearly parallel edges (down to a 1e-3 sine) the closest points slide
            // along the edges under round-off, by about the f32 error over that sine, so an
            // edge contact's position is only compared to 1 cm.
            if (forward.normal + backward.normal).length() < 1e-5 {
                let is_edge_contact = forward.points()[0].id & (1 << 31) != 0;
                let tolerance = if is_edge_contact { 1e-2 } else { 1e-4 };
                assert_same_contact(&forward, &backward.flipped(), tolerance);
            }
        }
    }

    #[test]
    fn hulls_of_boxes_collide_like_the_boxes(
        half_a in half_extents(),
        half_b in half_extents(),
        rotation_a in rotation(),
        rotation_b in rotation(),
        offset in vector(-1.5, 1.5),
    ) {
        let pose_a = Pose::new(Vec3::ZERO, rotation_a);
        let pose_b = Pose::new(offset, rotation_b);
        let (box_a, box_b) = (cuboid(half_a.x, half_a.y, half_a.z), cuboid(half_b.x, half_b.y, half_b.z));
        let (hull_a, hull_b) = (hull(&box_corners(half_a)), hull(&box_corners(half_b)));
        let boxes = collide_boxes(&box_a, pose_a, &box_b, pose_b);
        let hulls = collide(&Polyhedron::hull(&hull_a), pose_a, &Polyhedron::hull(&hull_b), pose_b);
        prop_assert_eq!(boxes.is_some(), hulls.is_some());
        if let (Some(boxes), Some(hulls)) = (boxes, hulls) {
            // Same axis and depth, and the hull's points pass every check of the boxes' own.
            // Which points the reduction keeps may differ: the hull's face loops start at other
            // corners, so near-ties between candidates go the other way.
            prop_assert!((boxes.normal - hulls.normal).length() < 1e-4);
            let deepest = |manifold: &Manifold| {
                manifold.points().iter().map(|point| point.separation).fold(f32::INFINITY, f32::min)
            };
            prop_assert!((deepest(&boxes) - deepest(&hulls)).abs() < 1e-4);
            let sat = sat_separation(half_a, &pose_a, half_b, &pose_b);
            check_box_manifold(&hulls, (half_a, &pose_a), (half_b, &pose_b), sat)?;
        }
    }
}
