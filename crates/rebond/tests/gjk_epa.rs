//! GJK distance, EPA penetration and the core contact query, against closed forms and against
//! an independent measure: for convex A and B, the signed distance between them (negative when
//! they overlap) is the largest, over unit directions d, of the gap between B's and A's extents
//! along d, `gap(d) = min_B d·x − max_A d·x`. Every gap is a lower bound; the answer's own normal
//! must reach it, which certifies the answer without trusting the algorithm, and a branch and
//! bound over directions ([`least_overlap`]) brackets the true value to compare with.
//!
//! Tolerances: GJK and EPA stop within `TOLERANCE · scale` of the answer (1e-5 of the largest
//! support point of A − B, `rebond::internals::collision::gjk::TOLERANCE`), and f32 rounds each support
//! point by about 6e-8 of its magnitude. Closed-form scenes here are at most ~6 m across, so 1e-4 m
//! covers both with margin; random scenes are at most ~15 m across, so 3e-4 m.

#[path = "common/random.rs"]
mod random;
#[path = "common/spiral.rs"]
mod spiral;

use glam::DVec3;
use proptest::prelude::*;
use random::Random;
use rebond::internals::collision::epa::{self, ContactInfo, Penetration, Polytope};
use rebond::internals::collision::gjk::{self, Distance, SimplexCache};
use rebond::internals::collision::{PosedCore, SupportMap};
use rebond::{Pose, Quat, Shape, Vec3};
use spiral::spiral_directions;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, SQRT_2};

/// Closed-form scenes (see the module comment).
const CLOSED_FORM: f32 = 1e-4;
/// Random scenes (see the module comment).
const RANDOM: f32 = 3e-4;
/// Exact ties on a curved surface, such as a sphere's centre on a cylinder's axis: every
/// direction across the axis is then as deep, and EPA can only approach the depth by
/// tessellating the whole side, which its iteration budget stops short of; it then answers with
/// the shallowest direction it found, measured within about 4e-4 m on radii up to 1.5 m.
const CURVED_TIE: f32 = 1e-3;

/// A whole shape, rounding included, placed in the world.
#[derive(Debug, Clone)]
struct Solid {
    shape: Shape,
    pose: Pose,
}

impl Solid {
    fn new(shape: Shape, position: Vec3, rotation: Quat) -> Self {
        Self {
            shape,
            pose: Pose::new(position, rotation),
        }
    }

    fn at(shape: Shape, position: Vec3) -> Self {
        Self::new(shape, position, Quat::IDENTITY)
    }

    fn core(&self) -> PosedCore<'_> {
        PosedCore {
            shape: &self.shape,
            pose: &self.pose,
        }
    }
}

impl SupportMap for Solid {
    fn support(&self, direction: Vec3) -> Vec3 {
        let local = self.pose.inverse_transform_vector(direction);
        let point = self.shape.support(local).expect("test shapes are bounded");
        self.pose.transform_point(point)
    }
}

fn sphere(radius: f32) -> Shape {
    Shape::sphere(radius).unwrap()
}

fn cuboid(x: f32, y: f32, z: f32) -> Shape {
    Shape::cuboid(Vec3::new(x, y, z)).unwrap()
}

fn capsule(radius: f32, half_height: f32) -> Shape {
    Shape::capsule(radius, half_height).unwrap()
}

fn cylinder(radius: f32, half_height: f32) -> Shape {
    Shape::cylinder(radius, half_height).unwrap()
}

/// How far B lies beyond A along unit `direction` (negative: their extents overlap).
fn gap(a: &impl SupportMap, b: &impl SupportMap, direction: Vec3) -> f32 {
    b.support(-direction).dot(direction) - a.support(direction).dot(direction)
}

/// Bounds on the least overlap of A's and B's extents over all unit directions,
/// `min_d (max_A d·x − min_B d·x)`: the penetration depth when A and B overlap, minus the distance
/// when they are apart. Found by branch and bound over the sphere, independently of GJK and EPA:
/// the sphere is cut into cells (a cube's faces, projected), each cell is sampled at its centre
/// `c`, and since the overlap along any `d` is at least `w·d` (`w` being the support point of
/// A − B along `c`), the least `w·d` over a cap holding the cell bounds the cell from below. Cells
/// that might hold a smaller value than the best sample, by more than `precision`, are split.
/// Returns `(lower, upper)`: the least overlap lies between them, `upper − lower ≤ precision`
/// unless the evaluation budget ran out first.
fn least_overlap(a: &impl SupportMap, b: &impl SupportMap, precision: f64) -> (f64, f64) {
    const INITIAL_SPLITS: usize = 8;
    const BUDGET: usize = 200_000;
    let mut best = f64::INFINITY;
    let mut evaluations = 0;
    let mut cells = BinaryHeap::new();
    let sample = |cell: Cell, best: &mut f64| {
        let (centre, cos_radius) = cell.centre_and_cos_radius();
        let direction = centre.as_vec3();
        let w = (a.support(direction) - b.support(-direction)).as_dvec3();
        let centre = direction.as_dvec3();
        let overlap = w.dot(centre);
        *best = best.min(overlap);
        let across = (w - overlap * centre).length();
        let sin_radius = (1.0 - cos_radius * cos_radius).max(0.0).sqrt();
        let lower = overlap.min(overlap * cos_radius) - across * sin_radius;
        Bounded { lower, cell }
    };
    for face in 0..6 {
        for i in 0..INITIAL_SPLITS {
            for j in 0..INITIAL_SPLITS {
                let edge = |k: usize| -1.0 + 2.0 * k as f64 / INITIAL_SPLITS as f64;
                let cell = Cell {
                    face,
                    u: [edge(i), edge(i + 1)],
                    v: [edge(j), edge(j + 1)],
                };
                cells.push(sample(cell, &mut best));
                evaluations += 1;
            }
        }
    }
    while let Some(Bounded { lower, cell }) = cells.pop() {
        if lower >= best - precision || evaluations >= BUDGET {
            return (lower.min(best), best);
        }
        for quarter in cell.quarters() {
            cells.push(sample(quarter, &mut best));
            evaluations += 1;
        }
    }
    (best, best)
}

/// A patch of the unit sphere: the square `u × v` of a cube face, projected from the centre.
#[derive(Clone, Copy)]
struct Cell {
    face: usize,
    u: [f64; 2],
    v: [f64; 2],
}

impl Cell {
    fn direction(&self, u: f64, v: f64) -> DVec3 {
        let axis = self.face % 3;
        let mut point = [0.0; 3];
        point[axis] = if self.face < 3 { 1.0 } else { -1.0 };
        point[(axis + 1) % 3] = u;
        point[(axis + 2) % 3] = v;
        DVec3::from_array(point).normalize()
    }

    /// The centre direction and the cosine of the angle to the farthest corner (the patch's
    /// edges are great-circle arcs shorter than a quarter turn, so corners are the farthest).
    fn centre_and_cos_radius(&self) -> (DVec3, f64) {
        let centre = self.direction(0.5 * (self.u[0] + self.u[1]), 0.5 * (self.v[0] + self.v[1]));
        let cos_radius = self
            .u
            .iter()
            .flat_map(|&u| self.v.iter().map(move |&v| (u, v)))
            .map(|(u, v)| self.direction(u, v).dot(centre))
            .fold(1.0f64, f64::min);
        (centre, cos_radius)
    }

    fn quarters(&self) -> [Cell; 4] {
        let u_mid = 0.5 * (self.u[0] + self.u[1]);
        let v_mid = 0.5 * (self.v[0] + self.v[1]);
        let halves = |[low, high]: [f64; 2], mid: f64| [[low, mid], [mid, high]];
        let [u_low, u_high] = halves(self.u, u_mid);
        let [v_low, v_high] = halves(self.v, v_mid);
        [
            (u_low, v_low),
            (u_low, v_high),
            (u_high, v_low),
            (u_high, v_high),
        ]
        .map(|(u, v)| Cell {
            face: self.face,
            u,
            v,
        })
    }
}

/// A cell with its lower bound, ordered so that the heap pops the smallest bound first.
struct Bounded {
    lower: f64,
    cell: Cell,
}

impl PartialEq for Bounded {
    fn eq(&self, other: &Self) -> bool {
        self.lower.total_cmp(&other.lower).is_eq()
    }
}

impl Eq for Bounded {}

impl PartialOrd for Bounded {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Bounded {
    fn cmp(&self, other: &Self) -> Ordering {
        other.lower.total_cmp(&self.lower)
    }
}

/// Branch-and-bound precision: well below the random scenes' tolerance, so the bracket adds
/// little to it.
const BRACKET: f64 = 5e-5;

/// Asserts that `value` lies in `[lower, upper]` widened by `tolerance`.
fn assert_within(value: f32, (lower, upper): (f64, f64), tolerance: f32, what: &str) {
    let value = f64::from(value);
    let tolerance = f64::from(tolerance);
    assert!(
        value >= lower - tolerance && value <= upper + tolerance,
        "{what}: {value} outside [{lower}, {upper}] ± {tolerance}"
    );
}

fn assert_close(actual: f32, expected: f32, tolerance: f32, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{what}: got {actual}, expected {expected} ± {tolerance}"
    );
}

fn assert_vec_close(actual: Vec3, expected: Vec3, tolerance: f32, what: &str) {
    assert!(
        (actual - expected).length() <= tolerance,
        "{what}: got {actual}, expected {expected} ± {tolerance}"
    );
}

fn core_distance(a: &Solid, b: &Solid) -> Distance {
    gjk::distance(&a.core(), &b.core())
}

/// GJK's distance between the cores less their roundings: the distance between the surfaces.
fn surface_distance(a: &Solid, b: &Solid) -> f32 {
    core_distance(a, b).distance - a.shape.core_radius() - b.shape.core_radius()
}

fn contact(a: &Solid, b: &Solid) -> ContactInfo {
    epa::contact(&a.core(), &b.core(), f32::INFINITY).expect("an infinite margin always reports")
}

fn deepest(a: &Solid, b: &Solid) -> Penetration {
    epa::penetration(&a.core(), &b.core()).expect("the solids overlap")
}

// ---------------------------------------------------------------- closed forms: distances

#[test]
fn spheres_apart_touching_overlapping_and_concentric() {
    let a = Solid::at(sphere(1.0), Vec3::ZERO);
    for (centre, separation) in [
        (Vec3::new(3.0, 4.0, 0.0), 2.0),
        (Vec3::new(1.8, 2.4, 0.0), 0.0),
        (Vec3::new(1.2, 1.6, 0.0), -1.0),
    ] {
        let b = Solid::at(sphere(2.0), centre);
        let found = contact(&a, &b);
        let normal = centre.normalize();
        assert_close(found.separation, separation, CLOSED_FORM, "separation");
        assert_vec_close(found.normal, normal, CLOSED_FORM, "normal");
        assert_vec_close(found.point_a, normal, CLOSED_FORM, "point on A");
        assert_vec_close(
            found.point_b,
            centre - 2.0 * normal,
            CLOSED_FORM,
            "point on B",
        );
    }
    // Same centre: every direction is a shortest way out; any unit normal will do.
    let b = Solid::at(sphere(2.0), Vec3::ZERO);
    let found = contact(&a, &b);
    assert_close(found.separation, -3.0, CLOSED_FORM, "concentric separation");
    assert_close(
        found.normal.length(),
        1.0,
        CLOSED_FORM,
        "concentric normal length",
    );
}

#[test]
fn capsules_crossed_apart_crossed_overlapping_and_cores_intersecting() {
    let a = Solid::at(capsule(0.5, 1.0), Vec3::ZERO);
    let along_x = Quat::from_rotation_z(FRAC_PI_2);
    let apart = Solid::new(capsule(0.25, 2.0), Vec3::new(0.0, 0.2, 2.0), along_x);
    let found = contact(&a, &apart);
    assert_close(
        found.separation,
        2.0 - 0.75,
        CLOSED_FORM,
        "apart separation",
    );
    assert_vec_close(found.normal, Vec3::Z, CLOSED_FORM, "apart normal");
    assert_vec_close(
        found.point_a,
        Vec3::new(0.0, 0.2, 0.5),
        CLOSED_FORM,
        "apart point on A",
    );

    let near = Solid::new(capsule(0.25, 2.0), Vec3::new(0.0, 0.2, 0.5), along_x);
    let found = contact(&a, &near);
    assert_close(found.separation, 0.5 - 0.75, CLOSED_FORM, "near separation");
    assert_vec_close(found.normal, Vec3::Z, CLOSED_FORM, "near normal");

    // The segments cross: the core difference is a flat parallelogram holding the origin, so
    // the core depth is zero and the normal is across both segments (either sign).
    let crossing = Solid::new(capsule(0.25, 2.0), Vec3::new(0.0, 0.2, 0.0), along_x);
    let found = contact(&a, &crossing);
    assert_close(found.separation, -0.75, CLOSED_FORM, "crossing separation");
    assert_close(found.normal.z.abs(), 1.0, CLOSED_FORM, "crossing normal");
}

#[test]
fn rotated_capsule_against_a_sphere() {
    let rotation = Quat::from_rotation_z(0.5);
    let a = Solid::new(capsule(0.3, 1.5), Vec3::new(1.0, -1.0, 0.5), rotation);
    let centre = Vec3::new(2.0, 2.5, -0.5);
    let b = Solid::at(sphere(0.4), centre);
    // Closest point of the segment to the centre, clamped to its ends.
    let axis = rotation * Vec3::Y;
    let t = (centre - a.pose.position).dot(axis).clamp(-1.5, 1.5);
    let on_segment = a.pose.position + t * axis;
    let expected = (centre - on_segment).length() - 0.7;
    let found = contact(&a, &b);
    assert_close(found.separation, expected, CLOSED_FORM, "separation");
    assert_vec_close(
        found.normal,
        (centre - on_segment).normalize(),
        CLOSED_FORM,
        "normal",
    );
}

#[test]
fn boxes_face_corner_edge_and_rotated() {
    let a = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::ZERO);
    let cases = [
        // Face to face, B offset sideways within A's face.
        (Vec3::new(3.0, 0.2, -0.1), Quat::IDENTITY, 1.5),
        // Corner to corner along the diagonal.
        (
            Vec3::new(3.0, 3.0, 3.0),
            Quat::IDENTITY,
            1.5 * 3.0f32.sqrt(),
        ),
        // Edge to edge.
        (Vec3::new(3.0, 3.0, 0.0), Quat::IDENTITY, 1.5 * SQRT_2),
        // B turned 45° about Z points an edge at A's face.
        (
            Vec3::new(3.0, 0.0, 0.0),
            Quat::from_rotation_z(FRAC_PI_4),
            2.0 - 0.5 * SQRT_2,
        ),
    ];
    for (position, rotation, expected) in cases {
        let b = Solid::new(cuboid(0.5, 0.5, 0.5), position, rotation);
        let found = core_distance(&a, &b);
        assert!(!found.overlapping, "{position}: apart");
        assert_close(found.distance, expected, CLOSED_FORM, "box distance");
        assert_close(
            (found.point_b - found.point_a).length(),
            expected,
            CLOSED_FORM,
            "closest points",
        );
    }
}

#[test]
fn box_against_sphere_and_cylinders() {
    let a = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::ZERO);
    let ball = Solid::at(sphere(0.5), Vec3::new(2.0, 2.0, 0.0));
    let found = contact(&a, &ball);
    assert_close(
        found.separation,
        SQRT_2 - 0.5,
        CLOSED_FORM,
        "box–sphere separation",
    );
    assert_vec_close(
        found.point_a,
        Vec3::new(1.0, 1.0, 0.0),
        CLOSED_FORM,
        "box corner",
    );

    let standing = Solid::at(cylinder(1.0, 1.0), Vec3::new(0.3, 3.0, 0.0));
    assert_close(
        surface_distance(&a, &standing),
        1.0,
        CLOSED_FORM,
        "cap on face",
    );

    let lying = Solid::new(
        cylinder(1.0, 1.0),
        Vec3::new(0.0, 2.5, 0.0),
        Quat::from_rotation_x(FRAC_PI_2),
    );
    assert_close(
        surface_distance(&a, &lying),
        0.5,
        CLOSED_FORM,
        "rim on face",
    );

    // The rim's corner toward A's edge: cylinder along Z centred at (2.5, 2.5, 0).
    let edge = Solid::new(
        cylinder(0.5, 0.5),
        Vec3::new(2.5, 2.5, 0.0),
        Quat::from_rotation_x(FRAC_PI_2),
    );
    let expected = 1.5 * SQRT_2 - 0.5;
    assert_close(
        surface_distance(&a, &edge),
        expected,
        CLOSED_FORM,
        "rim on edge",
    );
}

#[test]
fn touching_boxes_have_zero_distance() {
    let a = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::ZERO);
    let b = Solid::at(cuboid(1.0, 0.5, 0.5), Vec3::new(2.0, 0.3, 0.0));
    assert!(core_distance(&a, &b).distance <= CLOSED_FORM);
    let found = contact(&a, &b);
    assert_close(found.separation, 0.0, CLOSED_FORM, "touching separation");
    assert_vec_close(found.normal, Vec3::X, CLOSED_FORM, "touching normal");
}

#[test]
fn huge_and_tiny_scenes_keep_relative_precision() {
    // From the smallest size the engine takes (`limits::MIN_SIZE`) to 10 km.
    for size in [1e-3f32, 1e-2, 1.0, 1e2, 1e4] {
        // The separated face case and the overlapping face case, scaled; relative tolerance as
        // in the module comment (GJK and EPA tolerances are relative to the scene's size).
        let tolerance = CLOSED_FORM * size;
        let a = Solid::at(cuboid(size, size, size), Vec3::ZERO);
        let apart = Solid::at(cuboid(size, size, size), Vec3::new(2.5, 0.3, 0.1) * size);
        let found = core_distance(&a, &apart);
        assert_close(found.distance, 0.5 * size, tolerance, "scaled distance");
        let deep = Solid::at(cuboid(size, size, size), Vec3::new(1.8, 0.3, 0.1) * size);
        let found = deepest(&a, &deep);
        assert_close(found.depth, 0.2 * size, tolerance, "scaled depth");
        assert_vec_close(found.normal, Vec3::X, CLOSED_FORM, "scaled normal");
    }
}

#[test]
fn identical_shapes_overlap_fully() {
    let rotation = Quat::from_rotation_y(0.3);
    let a = Solid::new(cuboid(1.0, 2.0, 3.0), Vec3::new(1.0, 1.0, 1.0), rotation);
    let b = Solid::new(cuboid(1.0, 2.0, 3.0), Vec3::new(1.0, 1.0, 1.0), rotation);
    let found = deepest(&a, &b);
    // The thinnest way out is across the 2 m-wide X extent.
    assert_close(found.depth, 2.0, CLOSED_FORM, "depth");
    assert_close(
        (rotation.inverse() * found.normal).x.abs(),
        1.0,
        CLOSED_FORM,
        "normal",
    );
    for shape in [sphere(1.0), capsule(0.5, 1.0), cylinder(0.5, 1.0)] {
        let a = Solid::new(shape.clone(), Vec3::ONE, rotation);
        let b = Solid::new(shape, Vec3::ONE, rotation);
        let found = contact(&a, &b);
        assert!(found.separation.is_finite() && found.separation < 0.0);
        assert_close(found.normal.length(), 1.0, CLOSED_FORM, "normal length");
    }
}

#[test]
fn warm_start_direction_is_optional() {
    let a = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::ZERO);
    let b = Solid::at(sphere(0.5), Vec3::new(0.0, 4.0, 0.0));
    for direction in [
        Vec3::ZERO,
        Vec3::NAN,
        Vec3::Y,
        -Vec3::Y,
        Vec3::new(1e30, 0.0, 0.0),
    ] {
        let found = gjk::distance_from_direction(&a.core(), &b.core(), direction);
        assert_close(found.distance, 3.0, CLOSED_FORM, "distance from any start");
    }
}

// ---------------------------------------------------------------- closed forms: penetration

#[test]
fn box_penetration_face_cases() {
    let a = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::ZERO);
    let b = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::new(1.8, 0.3, -0.2));
    let found = deepest(&a, &b);
    assert_close(found.depth, 0.2, CLOSED_FORM, "depth");
    assert_vec_close(found.normal, Vec3::X, CLOSED_FORM, "normal");
    assert_close(found.point_a.x, 1.0, CLOSED_FORM, "deepest point of A");
    assert_close(found.point_b.x, 0.8, CLOSED_FORM, "deepest point of B");

    // A tall thin box poking down into A: out through the top costs 0.8, sideways 1.5.
    let tall = Solid::at(cuboid(0.5, 2.0, 0.5), Vec3::new(0.0, 2.2, 0.0));
    let found = deepest(&a, &tall);
    assert_close(found.depth, 0.8, CLOSED_FORM, "tall depth");
    assert_vec_close(found.normal, Vec3::Y, CLOSED_FORM, "tall normal");

    // A small box deep inside a big one leaves through the nearest face.
    let big = Solid::at(cuboid(2.0, 2.0, 2.0), Vec3::ZERO);
    let inside = Solid::at(cuboid(0.5, 0.5, 0.5), Vec3::new(1.0, 0.2, 0.0));
    let found = deepest(&big, &inside);
    assert_close(found.depth, 1.5, CLOSED_FORM, "inside depth");
    assert_vec_close(found.normal, Vec3::X, CLOSED_FORM, "inside normal");

    // Both turned the same way: the face case in a rotated frame.
    let rotation = Quat::from_euler(glam::EulerRot::XYZ, 0.4, -0.7, 1.1);
    let a = Solid::new(cuboid(1.0, 1.0, 1.0), Vec3::ZERO, rotation);
    let b = Solid::new(
        cuboid(1.0, 1.0, 1.0),
        rotation * Vec3::new(1.9, 0.2, 0.1),
        rotation,
    );
    let found = deepest(&a, &b);
    assert_close(found.depth, 0.1, CLOSED_FORM, "rotated depth");
    assert_vec_close(
        found.normal,
        rotation * Vec3::X,
        CLOSED_FORM,
        "rotated normal",
    );
}

#[test]
fn box_penetration_edge_against_edge() {
    // A turned 45° about X has a top edge along X at height √2; B turned 45° about Z has a
    // bottom edge along Z. Their crossing edges overlap by 0.1 along Y, the shortest way out.
    let a = Solid::new(
        cuboid(1.0, 1.0, 1.0),
        Vec3::ZERO,
        Quat::from_rotation_x(FRAC_PI_4),
    );
    let b = Solid::new(
        cuboid(1.0, 1.0, 1.0),
        Vec3::new(0.0, 2.0 * SQRT_2 - 0.1, 0.0),
        Quat::from_rotation_z(FRAC_PI_4),
    );
    let found = deepest(&a, &b);
    assert_close(found.depth, 0.1, CLOSED_FORM, "depth");
    assert_vec_close(found.normal, Vec3::Y, CLOSED_FORM, "normal");
    assert_vec_close(
        found.point_a,
        Vec3::new(0.0, SQRT_2, 0.0),
        CLOSED_FORM,
        "A's edge",
    );
    assert_vec_close(
        found.point_b,
        Vec3::new(0.0, SQRT_2 - 0.1, 0.0),
        CLOSED_FORM,
        "B's edge",
    );
}

#[test]
fn sphere_in_box_goes_through_epa() {
    let a = Solid::at(cuboid(1.0, 1.0, 1.0), Vec3::ZERO);
    // The sphere's centre (its core) is inside the box: 0.3 below the top face.
    let b = Solid::at(sphere(0.5), Vec3::new(0.2, 0.7, -0.1));
    let found = contact(&a, &b);
    assert_close(found.separation, -0.8, CLOSED_FORM, "separation");
    assert_vec_close(found.normal, Vec3::Y, CLOSED_FORM, "normal");
    assert_vec_close(
        found.point_a,
        Vec3::new(0.2, 1.0, -0.1),
        CLOSED_FORM,
        "on the box",
    );
    assert_vec_close(
        found.point_b,
        Vec3::new(0.2, 0.2, -0.1),
        CLOSED_FORM,
        "on the sphere",
    );
}

#[test]
fn margin_filters_distant_pairs() {
    let a = Solid::at(sphere(1.0), Vec3::ZERO);
    let b = Solid::at(sphere(1.0), Vec3::new(2.5, 0.0, 0.0));
    assert!(epa::contact(&a.core(), &b.core(), 0.4).is_none());
    assert!(epa::contact(&a.core(), &b.core(), 0.6).is_some());
}

// ---------------------------------------------------------------- properties

fn rotation_strategy() -> impl Strategy<Value = Quat> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_filter_map(
        "a quaternion far from zero",
        |(x, y, z, w)| {
            let q = Quat::from_xyzw(x, y, z, w);
            (q.length() > 0.1).then(|| q.normalize())
        },
    )
}

fn vec3_strategy(range: std::ops::Range<f32>) -> impl Strategy<Value = Vec3> {
    (range.clone(), range.clone(), range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A random convex shape of about a metre. Hulls are clouds of 4 to 12 points; a cloud the
/// hull builder rejects (flat or too small) is replaced by a box.
fn shape_strategy() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (0.1f32..1.5).prop_map(sphere),
        vec3_strategy(0.1..1.5).prop_map(|half| cuboid(half.x, half.y, half.z)),
        (0.1f32..1.0, 0.1f32..1.5).prop_map(|(r, h)| capsule(r, h)),
        (0.1f32..1.5, 0.1f32..1.5).prop_map(|(r, h)| cylinder(r, h)),
        prop::collection::vec(vec3_strategy(-1.5..1.5), 4..12)
            .prop_map(|points| Shape::convex_hull(&points).unwrap_or(cuboid(0.5, 0.5, 0.5))),
    ]
}

fn solid_strategy(spread: f32) -> impl Strategy<Value = Solid> {
    (
        shape_strategy(),
        vec3_strategy(-spread..spread),
        rotation_strategy(),
    )
        .prop_map(|(shape, position, rotation)| Solid::new(shape, position, rotation))
}

/// A shape with sizes in halves of a metre, turned by quarter turns about X then Y, at a point
/// of a quarter-metre grid.
fn aligned_solid_strategy() -> impl Strategy<Value = Solid> {
    let half = || (1u8..4).prop_map(|k| 0.5 * f32::from(k));
    let shape = prop_oneof![
        (half(), half(), half()).prop_map(|(x, y, z)| cuboid(x, y, z)),
        (half(), half()).prop_map(|(r, h)| cylinder(r, h)),
        (half(), half()).prop_map(|(r, h)| capsule(r, h)),
        half().prop_map(sphere),
    ];
    let turns = (0u8..4, 0u8..4).prop_map(|(x, y)| {
        Quat::from_rotation_y(FRAC_PI_2 * f32::from(y))
            * Quat::from_rotation_x(FRAC_PI_2 * f32::from(x))
    });
    let grid = vec3_strategy(-8.0..8.0)
        .prop_map(|p| (p.round() * 0.25).clamp(Vec3::splat(-2.0), Vec3::splat(2.0)));
    (shape, grid, turns)
        .prop_map(|(shape, position, rotation)| Solid::new(shape, position, rotation))
}

/// `point` lies inside `solid` (within `tolerance`) along each sampled direction.
fn assert_inside(solid: &impl SupportMap, point: Vec3, tolerance: f32, what: &str) {
    for direction in spiral_directions(64) {
        let reach = solid.support(direction).dot(direction);
        assert!(
            point.dot(direction) <= reach + tolerance,
            "{what}: {point} sticks out along {direction} by {}",
            point.dot(direction) - reach
        );
    }
}

/// `point` is on the surface of `solid` that faces `normal` (it reaches the support plane, to
/// within `tolerance`).
fn assert_on_support_plane(
    solid: &impl SupportMap,
    point: Vec3,
    normal: Vec3,
    tolerance: f32,
    what: &str,
) {
    let reach = solid.support(normal).dot(normal);
    assert_close(point.dot(normal), reach, tolerance, what);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// GJK on cores: symmetric, closest points inside the cores and on their facing support
    /// planes, the distance certified by its own normal and matching the branch-and-bound
    /// bracket.
    #[test]
    fn gjk_distance_is_certified(a in solid_strategy(3.0), b in solid_strategy(3.0)) {
        let (core_a, core_b) = (a.core(), b.core());
        let found = gjk::distance(&core_a, &core_b);
        let swapped = gjk::distance(&core_b, &core_a);
        prop_assert!(found.distance.is_finite() && found.distance >= 0.0);
        assert_close(found.distance, swapped.distance, RANDOM, "symmetry");
        assert_inside(&core_a, found.point_a, RANDOM, "point on A");
        assert_inside(&core_b, found.point_b, RANDOM, "point on B");
        let (lower, upper) = least_overlap(&core_a, &core_b, BRACKET);
        if found.overlapping {
            // A common point, and no direction separates the cores.
            assert_vec_close(found.point_a, found.point_b, RANDOM, "common point");
            prop_assert!(upper >= -f64::from(RANDOM), "separated by {} though overlapping", -upper);
        } else {
            assert_close((found.point_b - found.point_a).length(), found.distance, RANDOM, "points");
            let normal = found.normal().expect("apart");
            assert_close(gap(&core_a, &core_b, normal), found.distance, RANDOM, "certificate");
            assert_on_support_plane(&core_a, found.point_a, normal, RANDOM, "A faces B");
            assert_on_support_plane(&core_b, found.point_b, -normal, RANDOM, "B faces A");
            assert_within(found.distance, (-upper, -lower), RANDOM, "bracket");
        }
    }

    /// EPA on overlapping cores: unit normal, depth certified by its own normal and matching
    /// the branch-and-bound bracket, deepest points consistent, swapping flips the normal.
    #[test]
    fn epa_depth_is_certified(a in solid_strategy(1.0), b in solid_strategy(1.0)) {
        let (core_a, core_b) = (a.core(), b.core());
        let Some(found) = epa::penetration(&core_a, &core_b) else {
            // Apart: GJK's property covers this pair.
            return Ok(());
        };
        prop_assert!(found.depth.is_finite() && found.depth >= 0.0);
        assert_close(found.normal.length(), 1.0, 1e-5, "unit normal");
        // The overlap of the support intervals along the normal is the depth: moving B by
        // depth · normal separates the cores, and no direction does it with less.
        assert_close(-gap(&core_a, &core_b, found.normal), found.depth, RANDOM, "certificate");
        assert_within(found.depth, least_overlap(&core_a, &core_b, BRACKET), RANDOM, "bracket");
        assert_inside(&core_a, found.point_a, RANDOM, "deepest point of A");
        assert_inside(&core_b, found.point_b, RANDOM, "deepest point of B");
        assert_vec_close(found.point_a - found.point_b, found.depth * found.normal, RANDOM, "points");
        if let Some(swapped) = epa::penetration(&core_b, &core_a) {
            assert_close(swapped.depth, found.depth, RANDOM, "swapped depth");
            // Flipped, unless several directions tie for the shallowest way out (flat
            // differences, symmetric poses): then the swapped normal, flipped, must be as good.
            if (swapped.normal + found.normal).length() > 1e-3 {
                let alternative = -gap(&core_a, &core_b, -swapped.normal);
                assert_close(alternative, found.depth, RANDOM, "tied normal");
            }
        } else {
            prop_assert!(found.depth <= RANDOM, "swapped pair apart at depth {}", found.depth);
        }
    }

    /// The contact query on whole (rounded) shapes: separation is the signed distance, certified
    /// by its normal and by the bracket, with points on the two surfaces.
    #[test]
    fn contact_matches_the_signed_distance(a in solid_strategy(2.0), b in solid_strategy(2.0)) {
        check_contact(&a, &b, RANDOM);
    }

    /// The same on exact ties: boxes, cylinders and capsules turned by quarter turns and placed
    /// on a grid, so that faces are coplanar, edges parallel and shapes often exactly touching.
    #[test]
    fn contact_on_aligned_shapes(a in aligned_solid_strategy(), b in aligned_solid_strategy()) {
        check_contact(&a, &b, CURVED_TIE);
    }

    /// Warm starting: started from the simplex kept at other poses of B (nudged by up to 5 mm
    /// and 1°, as from step to step, or moved anywhere), the contact query finds the
    /// separation a cold start finds, certified by its own normal.
    #[test]
    fn contact_from_a_kept_simplex_matches_a_cold_start(
        a in solid_strategy(2.0),
        b in solid_strategy(2.0),
        offset in vec3_strategy(-1.0..1.0),
        turn in rotation_strategy(),
        jump in any::<bool>(),
    ) {
        let (mut polytope, mut simplex) = (Polytope::default(), SimplexCache::default());
        polytope.contact_from(&a.core(), &b.core(), f32::INFINITY, &mut simplex);
        let moved = if jump {
            Solid::new(b.shape.clone(), 2.0 * offset, turn)
        } else {
            // A turn of at most half a turn, taken a 180th of the way: at most 1°.
            let nudge = Quat::IDENTITY.slerp(turn, 1.0 / 180.0);
            Solid::new(b.shape.clone(), b.pose.position + 0.005 * offset, nudge * b.pose.rotation)
        };
        let warm = polytope
            .contact_from(&a.core(), &moved.core(), f32::INFINITY, &mut simplex)
            .expect("an infinite margin always reports");
        let cold = contact(&a, &moved);
        assert_close(warm.separation, cold.separation, RANDOM, "separation");
        assert_close(gap(&a, &moved, warm.normal), warm.separation, RANDOM, "certificate");
    }
}

/// Checks [`epa::contact`] on two whole shapes against the signed distance (see
/// `contact_matches_the_signed_distance`), to `tolerance`.
fn check_contact(a: &Solid, b: &Solid, tolerance: f32) {
    let found = contact(a, b);
    let swapped = contact(b, a);
    assert!(found.separation.is_finite());
    assert_close(found.normal.length(), 1.0, 1e-5, "unit normal");
    assert_close(found.separation, swapped.separation, tolerance, "symmetry");
    assert_close(
        gap(a, b, found.normal),
        found.separation,
        tolerance,
        "certificate",
    );
    let (lower, upper) = least_overlap(a, b, BRACKET);
    assert_within(found.separation, (-upper, -lower), tolerance, "bracket");
    assert_vec_close(
        found.point_b - found.point_a,
        found.separation * found.normal,
        tolerance,
        "points",
    );
    assert_inside(a, found.point_a, tolerance, "point on A");
    assert_inside(b, found.point_b, tolerance, "point on B");
    assert_on_support_plane(a, found.point_a, found.normal, tolerance, "A's surface");
    assert_on_support_plane(b, found.point_b, -found.normal, tolerance, "B's surface");
}

// ---------------------------------------------------------------- shallow contacts of round shapes

/// A sphere, capsule or cylinder touching a hull shallower than its rounding: the contact query
/// measures it with GJK on the cores, never EPA (asserted: the cores are apart), and must find the
/// depth and normal that EPA finds on the whole shapes (the rounded cylinder's support included),
/// for seeded random shapes, turns and directions of approach.
#[test]
fn shallow_round_contacts_with_a_hull_match_epa_on_the_whole_shapes() {
    let mut random = Random(0x5a11);
    let hull = Shape::convex_hull(&[
        Vec3::new(0.6, -0.3, 0.1),
        Vec3::new(-0.5, -0.4, 0.3),
        Vec3::new(-0.2, -0.35, -0.55),
        Vec3::new(0.1, 0.5, 0.05),
        Vec3::new(0.45, 0.2, -0.4),
        Vec3::new(-0.4, 0.3, 0.45),
        Vec3::new(0.05, -0.1, 0.7),
    ])
    .unwrap();
    let a = Solid::new(hull, Vec3::new(0.3, -0.2, 0.1), Quat::from_rotation_y(0.4));
    let mut compared = 0;
    for case in 0..600 {
        let shape = match case % 3 {
            0 => sphere(random.range(0.1, 0.6)),
            1 => capsule(random.range(0.1, 0.4), random.range(0.1, 0.5)),
            _ => cylinder(random.range(0.2, 0.6), random.range(0.2, 0.6)),
        };
        let rounding = shape.core_radius();
        let rotation = Quat::from_axis_angle(random.unit_vector(), random.range(0.0, 3.1));
        // B's point farthest against `direction` put on A's farthest along it, then moved in by
        // a fraction of the rounding: the extents along `direction` overlap by less than the
        // rounding, so the shapes overlap by less and their cores are apart.
        let direction = random.unit_vector();
        let depth = random.range(0.1, 0.9) * rounding;
        let mut b = Solid::new(shape, Vec3::ZERO, rotation);
        b.pose.position = a.support(direction) - b.support(-direction) - depth * direction;
        let cores = core_distance(&a, &b);
        assert!(!cores.overlapping, "case {case}: cores overlap, {b:?}");
        let Some(reference) = epa::penetration(&a, &b) else {
            continue;
        };
        let found = contact(&a, &b);
        assert_close(found.separation, -reference.depth, RANDOM, "depth");
        // Near a curved contact of radius ρ, a search stopped within the 0.1 mm of
        // `gjk::CONTACT_PRECISION` leaves the normal within √(2·1e-4 / ρ) (its documented bound),
        // ρ being at least the rounding here.
        let normal_tolerance = (2.0 * gjk::CONTACT_PRECISION / rounding).sqrt();
        assert_vec_close(found.normal, reference.normal, normal_tolerance, "normal");
        compared += 1;
    }
    // Most placements overlap; those that do not (A's extreme point is a vertex that B's
    // rounded extreme point may miss once moved in) are left out.
    assert!(compared > 400, "only {compared} overlapping cases");
}
