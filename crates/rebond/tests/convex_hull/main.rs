//! Convex hull: topology, geometry, mass properties and validation.
//!
//! Tolerances: `f32` has a relative precision of 6e-8, and the hull computes its mass properties in
//! `f64` from the exact `f32` input, so a hull of exact points matches an analytic formula to a few
//! `f32` roundings: relative 1e-5 leaves a wide margin. Geometric checks (points behind planes,
//! vertices on their face) allow a few times the hull's own tolerance, 1e-5 of the cloud's extent,
//! since merged faces are planar only to within that tolerance (see `geometric_tolerance`); exact
//! inputs (lattices, axis-aligned boxes) are checked to 1e-6.

use std::f32::consts::PI;

use rebond::internals::math::rotate_tensor;
use rebond::shape::{ConvexHull, Cuboid};
use rebond::{ErrorKind, MassProperties, Mat3, Pose, Quat, Vec3};

#[path = "../common/random.rs"]
mod random;
use random::Random as Rng;

impl Rng {
    /// Uniform on the unit sphere (rejection from the cube, then normalised).
    fn on_sphere(&mut self) -> Vec3 {
        loop {
            let v = self.vec3(-1.0, 1.0);
            let length = v.length();
            if length > 0.1 && length <= 1.0 {
                return v / length;
            }
        }
    }

    fn in_ball(&mut self, radius: f32) -> Vec3 {
        loop {
            let v = self.vec3(-radius, radius);
            if v.length() <= radius {
                return v;
            }
        }
    }

    fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            let j = self.below(i + 1);
            items.swap(i, j);
        }
    }
}

fn box_corners(h: Vec3) -> Vec<Vec3> {
    let mut corners = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                corners.push(Vec3::new(sx, sy, sz) * h);
            }
        }
    }
    corners
}

/// Mass properties of a box of half extents `h` at unit density, `m = 8 hx hy hz`,
/// `Ixx = m/3 (hy² + hz²)`: also for boxes thinner than a `Cuboid` may be.
fn box_mass_properties(h: Vec3) -> MassProperties {
    let mass = 8.0 * h.x * h.y * h.z;
    let squared = h * h;
    MassProperties {
        mass,
        center_of_mass: Vec3::ZERO,
        inertia: Mat3::from_diagonal(
            mass / 3.0
                * Vec3::new(
                    squared.y + squared.z,
                    squared.x + squared.z,
                    squared.x + squared.y,
                ),
        ),
    }
}

fn extent(points: &[Vec3]) -> f32 {
    let min = points.iter().fold(Vec3::INFINITY, |m, p| m.min(*p));
    let max = points.iter().fold(Vec3::NEG_INFINITY, |m, p| m.max(*p));
    (max - min).max_element()
}

fn assert_close(actual: f32, expected: f32, tolerance: f32, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{what}: {actual} vs {expected} (tolerance {tolerance})"
    );
}

fn assert_vec_close(actual: Vec3, expected: Vec3, tolerance: f32, what: &str) {
    assert!(
        (actual - expected).abs().max_element() <= tolerance,
        "{what}: {actual} vs {expected} (tolerance {tolerance})"
    );
}

/// Entry-wise, relative to the largest entry of `expected`.
fn assert_mat_close(actual: Mat3, expected: Mat3, relative: f32, what: &str) {
    let scale = expected
        .abs()
        .to_cols_array()
        .into_iter()
        .fold(0.0, f32::max);
    let error = (actual - expected)
        .abs()
        .to_cols_array()
        .into_iter()
        .fold(0.0, f32::max);
    assert!(
        error <= relative * scale,
        "{what}: {actual} vs {expected} (error {error}, allowed {})",
        relative * scale
    );
}

/// Mass within `relative`, centre within `relative` of `size`, inertia within `relative` of its
/// largest entry.
fn assert_mass_close(actual: MassProperties, expected: MassProperties, relative: f32, size: f32) {
    assert_close(actual.mass, expected.mass, relative * expected.mass, "mass");
    assert_vec_close(
        actual.center_of_mass,
        expected.center_of_mass,
        relative * size,
        "centre of mass",
    );
    assert_mat_close(actual.inertia, expected.inertia, relative, "inertia");
}

/// Everything a hull of `points` must satisfy. `tolerance` is a distance, metres.
fn check_invariants(hull: &ConvexHull, points: &[Vec3], tolerance: f32) {
    check_topology_and_planes(hull, points, tolerance);
    // A corner of a polyhedron lies on at least three faces; one on two would be in an edge.
    let mut faces_of_vertex = vec![0; hull.vertices().len()];
    for &vertex in hull.faces().iter().flat_map(|face| &face.vertices) {
        faces_of_vertex[vertex as usize] += 1;
    }
    for (vertex, count) in faces_of_vertex.iter().enumerate() {
        assert!(*count >= 3, "vertex {vertex} is on {count} faces only");
    }
}

/// The invariants that hold for every input, even one with features at the scale of the hull's
/// tolerance: there, two nearly coplanar faces may meet along a bent edge, whose inner corner
/// is then on two faces only.
fn check_topology_and_planes(hull: &ConvexHull, points: &[Vec3], tolerance: f32) {
    let vertices = hull.vertices();
    let faces = hull.faces();
    let edges = hull.edges();
    let (v, e, f) = (vertices.len(), edges.len(), faces.len());
    assert_eq!(v + f, e + 2, "Euler: V {v}, E {e}, F {f}");
    assert!(v >= 4 && f >= 4 && e >= 6);

    for vertex in vertices {
        assert!(
            points.contains(vertex),
            "hull vertex {vertex} is not an input point"
        );
    }
    let mut faces_of_vertex = vec![0; v];
    let mut corners = 0;
    for (index, face) in faces.iter().enumerate() {
        assert!(face.vertices.len() >= 3, "face {index} has < 3 vertices");
        assert_close(face.normal.length(), 1.0, 1e-6, "unit normal");
        assert_eq!(
            face.vertices.iter().min(),
            face.vertices.first(),
            "face {index} starts with its smallest vertex"
        );
        for (k, &vertex) in face.vertices.iter().enumerate() {
            assert!((vertex as usize) < v);
            assert!(
                !face.vertices[k + 1..].contains(&vertex),
                "face {index} repeats vertex {vertex}"
            );
            faces_of_vertex[vertex as usize] += 1;
            let height = face.normal.dot(vertices[vertex as usize]) - face.offset;
            assert!(
                height.abs() <= tolerance,
                "vertex {vertex} of face {index} is {height} off its plane"
            );
        }
        corners += face.vertices.len();
        for point in points {
            let height = face.normal.dot(*point) - face.offset;
            assert!(
                height <= tolerance,
                "point {point} is {height} in front of face {index}"
            );
        }
        // Counter-clockwise seen from outside: the polygon's area vector points along the normal.
        let origin = vertices[face.vertices[0] as usize];
        let area: Vec3 = face
            .vertices
            .windows(2)
            .map(|pair| {
                (vertices[pair[0] as usize] - origin).cross(vertices[pair[1] as usize] - origin)
            })
            .sum();
        assert!(area.dot(face.normal) > 0.0, "face {index} is clockwise");
    }
    assert_eq!(corners, 2 * e, "every edge borders two faces");
    for (vertex, count) in faces_of_vertex.iter().enumerate() {
        assert!(*count >= 2, "vertex {vertex} is on {count} faces only");
    }
    let runs = |face: u32, from: u32, to: u32| {
        let ring = &faces[face as usize].vertices;
        (0..ring.len()).any(|k| ring[k] == from && ring[(k + 1) % ring.len()] == to)
    };
    for (index, edge) in edges.iter().enumerate() {
        let [a, b] = edge.vertices;
        let [left, right] = edge.faces;
        assert!(a < b, "edge {index} vertices unsorted");
        assert_ne!(left, right, "edge {index} borders one face twice");
        assert!(
            runs(left, a, b),
            "edge {index}: face {left} does not run {a}→{b}"
        );
        assert!(
            runs(right, b, a),
            "edge {index}: face {right} does not run {b}→{a}"
        );
        if index > 0 {
            assert!(edges[index - 1].vertices < edge.vertices, "edges unsorted");
        }
    }

    assert!(hull.mass_properties(1.0).mass > 0.0);
    let mut rng = Rng(0xD1CE);
    for _ in 0..20 {
        let direction = rng.on_sphere();
        let best = points
            .iter()
            .map(|p| p.dot(direction))
            .fold(f32::NEG_INFINITY, f32::max);
        let support = hull.support(direction);
        assert!(vertices.contains(&support));
        assert!(
            support.dot(direction) >= best - tolerance,
            "support falls short along {direction}: {} vs {best}",
            support.dot(direction)
        );
    }
}

/// Three times the hull's tolerance (1e-5 × extent, at least 4 f32 ulps of the largest
/// coordinate): the hull promises face vertices on their plane and points behind it to within
/// twice the tolerance (the worst seen over 200 000 adversarial clouds is 1.9×), plus the f32
/// rounding of the checks themselves at coordinates up to ~15.
fn geometric_tolerance(points: &[Vec3]) -> f32 {
    let magnitude = points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f32::max);
    let tolerance = (1e-5 * extent(points)).max(4.0 * f32::EPSILON * magnitude);
    3.0 * tolerance + 4e-6
}

fn degenerate_reason(points: &[Vec3]) -> &'static str {
    match ConvexHull::new(points) {
        Ok(hull) => panic!(
            "expected a degenerate hull, got {} faces",
            hull.faces().len()
        ),
        Err(error) => {
            assert_eq!(error.field, "points");
            match error.kind {
                ErrorKind::DegenerateHull(reason) => reason,
                kind => panic!("expected DegenerateHull, got {kind:?}"),
            }
        }
    }
}

fn not_finite_field(points: &[Vec3]) -> String {
    let error = ConvexHull::new(points).expect_err("non-finite input must fail");
    assert_eq!(error.kind, ErrorKind::NotFinite);
    error.field
}

mod robustness;
mod shapes;
mod support;
