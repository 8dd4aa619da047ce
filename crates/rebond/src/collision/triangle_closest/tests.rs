//! The closed forms against exact cases and against GJK on random placements.

use super::*;
use crate::collision::dynamic_tree::random::Random;
use crate::collision::PosedCore;
use crate::math::Quat;
use crate::shape::Shape;
use std::f32::consts::PI;

/// Exact inputs (binary fractions and 3-4-12-13 right triangles): a few f32 roundings of values
/// of about one metre.
const EXACT: f32 = 1e-6;

/// How far a point found on a shape may lie off it, metres: the triangle's own closest-point
/// routine, with which the test checks, rounds by a few 1e-6 m on the thinnest triangles here
/// (2 m long, 0.1 m across).
const ON_SHAPE: f32 = 1e-5;

/// How far GJK's distance may lie from the exact one, metres: `gjk::distance` stops once its
/// bounds are within `gjk::TOLERANCE` (1e-5) of the problem's size, at most about 4 m here, so
/// it overstates by up to 4e-5 m; both carry f32 roundings of about 1e-6 m besides.
const DISTANCE_TOLERANCE: f32 = 1e-4;

/// Beyond this distance, metres, the two normals are compared: GJK's direction is then within
/// about `√(2 · 4e-5 / 0.05)` = 0.04 of the true one even where it has not settled on the
/// closest features (its gap bounds the sideways error to second order), far less where it has.
const NORMAL_DISTANCE: f32 = 0.05;

/// The largest difference of the two unit normals allowed beyond [`NORMAL_DISTANCE`], from the
/// bound above.
const NORMAL_TOLERANCE: f32 = 0.04;

/// A random triangle of `[−1, 1]³` whose corners are at least 0.1 m from the line of the others.
fn random_triangle(random: &mut Random) -> Triangle {
    loop {
        let vertices = [0; 3].map(|_| random.vec3(-1.0, 1.0));
        let [a, b, c] = vertices;
        let doubled_area = (b - a).cross(c - a).length();
        let longest = (b - a).length().max((c - b).length()).max((a - c).length());
        if doubled_area > 0.1 * longest {
            return Triangle {
                vertices,
                edge_flags: 0,
            };
        }
    }
}

/// A pose near the triangle: a random point of it moved by up to 0.8 m along each axis (by up
/// to 0.2 m in one case of two, for more shapes within a contact's reach), turned any way.
fn random_pose(random: &mut Random, triangle: &Triangle) -> Pose {
    let (u, v) = (random.range(0.0, 1.0), random.range(0.0, 1.0));
    let (u, v) = if u + v > 1.0 {
        (1.0 - u, 1.0 - v)
    } else {
        (u, v)
    };
    let [a, b, c] = triangle.vertices;
    let on_triangle = a + (b - a) * u + (c - a) * v;
    let rotation = Quat::from_scaled_axis(random.vec3(-PI, PI) / 3.0_f32.sqrt());
    let reach = if random.chance(0.5) { 0.2 } else { 0.8 };
    Pose::new(on_triangle + random.vec3(-reach, reach), rotation)
}

/// What one comparison saw: separated beyond [`NORMAL_DISTANCE`], close, and overlapping.
#[derive(Default, Debug)]
struct Seen {
    apart: usize,
    close: usize,
    overlapping: usize,
}

/// Checks the closed form's answer (with no limit) against GJK's for the same pair, and that
/// limits just below and above the distance reject and accept it.
fn compare(
    seen: &mut Seen,
    case: usize,
    triangle: &Triangle,
    shape: &Shape,
    pose: &Pose,
    closed: impl Fn(f32) -> Option<Option<(Vec3, Vec3)>>,
    on_shape: impl Fn(Vec3) -> bool,
) {
    let found = gjk::distance(triangle, &PosedCore::new(shape, pose));
    let answer = closed(f32::INFINITY).expect("no limit");
    let distance = answer.map_or(0.0, |(on_triangle, on_core)| on_triangle.distance(on_core));
    let gjk_distance = if found.overlapping {
        0.0
    } else {
        found.distance
    };
    assert!(
        (distance - gjk_distance).abs() <= DISTANCE_TOLERANCE,
        "case {case}: closed form {distance} against GJK {gjk_distance}"
    );
    let Some((on_triangle, on_core)) = answer else {
        seen.overlapping += 1;
        return;
    };
    // The points lie on the triangle and on the core, and are no farther apart than GJK's
    // (which only overstates). Where their features are nearly parallel the points themselves
    // may slide along them (their gap changes only at second order), so they are not compared.
    let off = triangle.closest_point(on_triangle).0.distance(on_triangle);
    assert!(
        off <= ON_SHAPE,
        "case {case}: {on_triangle} off the triangle by {off}"
    );
    assert!(on_shape(on_core), "case {case}: {on_core} off the core");
    assert!(
        distance <= gjk_distance + EXACT,
        "case {case}: farther than GJK's"
    );
    if gjk_distance > NORMAL_DISTANCE {
        seen.apart += 1;
        let normal = (on_core - on_triangle) / distance;
        let gjk_normal = found.normal().expect("apart");
        assert!(
            normal.distance(gjk_normal) <= NORMAL_TOLERANCE,
            "case {case}: normal {normal} against GJK {gjk_normal}"
        );
    } else {
        seen.close += 1;
    }
    // A limit a little below the distance rejects the pair, a little above keeps it.
    if distance > 1e-3 {
        assert!(
            closed(distance - 1e-4).is_none(),
            "case {case}: limit below"
        );
    }
    assert!(
        matches!(closed(distance + 1e-4), Some(Some(_))),
        "case {case}: limit above"
    );
}

/// Each kind of placement is met often enough to count as tested.
fn assert_covered(seen: &Seen, cases: usize) {
    let least = cases / 40;
    assert!(
        seen.apart >= least && seen.close >= least && seen.overlapping >= least,
        "{seen:?}"
    );
}

#[test]
fn segments_agree_with_gjk() {
    let mut random = Random(0x7365_676d);
    let mut seen = Seen::default();
    let cases = 4000;
    for case in 0..cases {
        let triangle = random_triangle(&mut random);
        let pose = random_pose(&mut random, &triangle);
        let Shape::Capsule(capsule) = Shape::capsule(0.1, random.range(0.02, 1.0)).unwrap() else {
            unreachable!()
        };
        let segment = capsule.segment().map(|end| pose.transform_point(end));
        compare(
            &mut seen,
            case,
            &triangle,
            &Shape::Capsule(capsule),
            &pose,
            |limit| segment_triangle(&triangle, segment, limit),
            |point| {
                let [start, end] = segment;
                let t = (point - start).dot(end - start) / (end - start).length_squared();
                point.distance(start + (end - start) * t.clamp(0.0, 1.0)) <= ON_SHAPE
            },
        );
    }
    assert_covered(&seen, cases);
}

#[test]
fn boxes_agree_with_gjk() {
    let mut random = Random(0x0062_6f78);
    let mut seen = Seen::default();
    let cases = 4000;
    for case in 0..cases {
        let triangle = random_triangle(&mut random);
        let pose = random_pose(&mut random, &triangle);
        let half_extents = random.vec3(0.02, 0.6);
        let shape = Shape::cuboid(half_extents).unwrap();
        compare(
            &mut seen,
            case,
            &triangle,
            &shape,
            &pose,
            |limit| box_triangle(&triangle, half_extents, &pose, limit),
            |point| {
                let local = pose.inverse_transform_point(point);
                local.abs().cmple(half_extents + ON_SHAPE).all()
            },
        );
    }
    assert_covered(&seen, cases);
}

/// The triangle of the exact cases: in the plane y = 0, its edge 0 along +X at z = 0, the face
/// toward −Z.
fn floor_triangle() -> Triangle {
    Triangle {
        vertices: [
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -1.0),
        ],
        edge_flags: 0,
    }
}

fn distance_of(answer: Option<Option<(Vec3, Vec3)>>) -> f32 {
    let (on_triangle, on_core) = answer.flatten().expect("apart");
    on_triangle.distance(on_core)
}

#[test]
fn box_corner_beside_a_corner_is_not_an_axis_separation() {
    // Corner (1.3, 0.4, 1.2) of the unit box is 1.3 m from the triangle's corner (1, 0, 0)
    // (0.3, 0.4, 1.2: a 3-4-12-13 triangle): vertex against vertex, where the largest separation
    // along the separating-axis test's 13 axes is only 1.2 m.
    let pose = Pose::from_position(Vec3::new(1.8, 0.9, 1.7));
    let answer = box_triangle(&floor_triangle(), Vec3::splat(0.5), &pose, 2.0);
    let (on_triangle, on_box) = answer.flatten().expect("apart");
    assert!(on_triangle.distance(Vec3::X) <= EXACT);
    assert!(on_box.distance(Vec3::new(1.3, 0.4, 1.2)) <= EXACT);
    assert!(box_triangle(&floor_triangle(), Vec3::splat(0.5), &pose, 1.29).is_none());
}

#[test]
fn box_edge_across_an_edge_and_box_through_the_face() {
    // Turned 45° about Z, the box's lowest edge runs along Z at x = 0, 0.25 m over the plane,
    // from z = −0.25 to 0.75: over the face for its first quarter.
    let half = Vec3::splat(0.5);
    let lowest = 0.5 * std::f32::consts::SQRT_2;
    let turned = Quat::from_rotation_z(PI / 4.0);
    let pose = Pose::new(Vec3::new(0.0, lowest + 0.25, 0.25), turned);
    let (on_triangle, on_box) = box_triangle(&floor_triangle(), half, &pose, 1.0)
        .flatten()
        .expect("apart");
    assert!((on_box - on_triangle - Vec3::new(0.0, 0.25, 0.0)).length() <= EXACT);
    // Lowered by 0.3 m, the edge passes through the face: they meet.
    let through = Pose::new(Vec3::new(0.0, lowest - 0.05, 0.25), turned);
    assert_eq!(
        box_triangle(&floor_triangle(), half, &through, 1.0),
        Some(None)
    );
    // A small box whose section by the plane lies inside the triangle, its edges clear of the
    // triangle's: they meet.
    let inside = Pose::from_position(Vec3::new(0.0, 0.0, -0.3));
    assert_eq!(
        box_triangle(&floor_triangle(), Vec3::splat(0.1), &inside, 1.0),
        Some(None)
    );
}

#[test]
fn segment_beside_an_edge_over_the_face_and_through_it() {
    let triangle = floor_triangle();
    // Upright beside edge 0: 0.3 m from it along +Z.
    let beside = [Vec3::new(0.0, -1.0, 0.3), Vec3::new(0.0, 1.0, 0.3)];
    let (on_triangle, on_segment) = segment_triangle(&triangle, beside, 1.0)
        .flatten()
        .expect("apart");
    assert!((on_segment - on_triangle - Vec3::new(0.0, 0.0, 0.3)).length() <= EXACT);
    // Lying 0.25 m over the face, crossing its rim: the distance is the height.
    let over = [Vec3::new(-0.25, 0.25, -0.75), Vec3::new(0.5, 0.25, 0.5)];
    assert!((distance_of(segment_triangle(&triangle, over, 1.0)) - 0.25).abs() <= EXACT);
    assert!(segment_triangle(&triangle, over, 0.2).is_none());
    // Upright through the face: they meet.
    let through = [Vec3::new(-0.2, -1.0, -0.3), Vec3::new(-0.2, 1.0, -0.3)];
    assert_eq!(segment_triangle(&triangle, through, 1.0), Some(None));
}

#[test]
fn edge_toward_box_on_each_kind_of_piece() {
    let half = Vec3::splat(0.5);
    // Passing the box's edge (x = 0.5, y = 0.5) diagonally: nearest at its middle.
    let from = Vec3::new(-0.5, 2.5, 0.0);
    let point = edge_toward_box(from, Vec3::new(3.0, -3.0, 0.0), half);
    assert!(point.distance(Vec3::new(1.0, 1.0, 0.0)) <= EXACT);
    // Leaving the box's faces behind: nearest at its first end.
    let point = edge_toward_box(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 1.0, 0.0), half);
    assert_eq!(point, Vec3::new(0.0, 1.0, 0.0));
    // Through the box: a point inside it.
    let point = edge_toward_box(Vec3::new(-2.0, 0.1, 0.2), Vec3::new(4.0, 0.0, 0.0), half);
    assert!(point.abs().cmple(half).all());
}
