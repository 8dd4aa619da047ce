//! Convex hull: topology, geometry, mass properties and validation.
//!
//! Tolerances: `f32` has a relative precision of 6e-8, and the hull computes its mass properties in
//! `f64` from the exact `f32` input, so a hull of exact points matches an analytic formula to a few
//! `f32` roundings: relative 1e-5 leaves a wide margin. Geometric checks (points behind planes,
//! vertices on their face) allow a few times the hull's own tolerance, 1e-5 of the cloud's extent,
//! since merged faces are planar only to within that tolerance (see `geometric_tolerance`); exact
//! inputs (lattices, axis-aligned boxes) are checked to 1e-6.

use std::f32::consts::PI;

use rebond::math::rotate_tensor;
use rebond::shape::{ConvexHull, Cuboid};
use rebond::{ErrorKind, MassProperties, Mat3, Pose, Quat, Vec3};

#[path = "common/random.rs"]
mod random;
use random::Random as Rng;

impl Rng {
    fn in_cube(&mut self, half: f32) -> Vec3 {
        Vec3::new(
            self.range(-half, half),
            self.range(-half, half),
            self.range(-half, half),
        )
    }

    /// Uniform on the unit sphere (rejection from the cube, then normalised).
    fn on_sphere(&mut self) -> Vec3 {
        loop {
            let v = self.in_cube(1.0);
            let length = v.length();
            if length > 0.1 && length <= 1.0 {
                return v / length;
            }
        }
    }

    fn in_ball(&mut self, radius: f32) -> Vec3 {
        loop {
            let v = self.in_cube(radius);
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

#[test]
fn cube_corners_give_six_quads() {
    for h in [Vec3::ONE, Vec3::new(0.5, 1.5, 2.0)] {
        let points = box_corners(h);
        let hull = ConvexHull::new(&points).unwrap();
        assert_eq!(hull.vertices().len(), 8);
        assert_eq!(hull.faces().len(), 6);
        assert_eq!(hull.edges().len(), 12);
        assert_eq!(
            hull.vertices(),
            points.as_slice(),
            "vertices keep input order"
        );
        for face in hull.faces() {
            assert_eq!(face.vertices.len(), 4);
            assert_eq!(face.normal.abs().max_element(), 1.0);
            assert_close(face.offset, face.normal.abs().dot(h), 1e-6, "offset");
        }
        check_invariants(&hull, &points, 1e-6);
        let density = 7.8;
        let expected = Cuboid::new(h).unwrap().mass_properties(density);
        assert_mass_close(
            hull.mass_properties(density),
            expected,
            1e-5,
            h.max_element(),
        );
    }
}

#[test]
fn cube_with_duplicates_interior_and_surface_points() {
    let h = Vec3::new(1.0, 0.75, 0.5);
    let corners = box_corners(h);
    let mut rng = Rng(7);
    let mut points = Vec::new();
    points.extend(corners.iter().copied());
    points.extend(corners.iter().copied());
    points.push(Vec3::ZERO);
    for _ in 0..50 {
        points.push(rng.in_cube(1.0) * h * 0.999);
    }
    // Face centres and random points exactly on the faces.
    for axis in 0..3 {
        for sign in [-1.0, 1.0] {
            let mut centre = Vec3::ZERO;
            centre[axis] = sign;
            points.push(centre * h);
            for _ in 0..10 {
                let mut p = rng.in_cube(1.0);
                p[axis] = sign;
                points.push(p * h);
            }
        }
    }
    // Edge midpoints and random points exactly on the edges.
    for a in &corners {
        for b in &corners {
            if (*a - *b).abs().cmpgt(Vec3::ZERO).bitmask().count_ones() == 1 {
                points.push(0.5 * (*a + *b));
                let t = rng.range(0.0, 1.0);
                points.push(*a + (*b - *a) * t);
            }
        }
    }
    rng.shuffle(&mut points);

    let hull = ConvexHull::new(&points).unwrap();
    assert_eq!(hull.vertices().len(), 8);
    assert_eq!(hull.faces().len(), 6);
    assert_eq!(hull.edges().len(), 12);
    for corner in &corners {
        assert!(hull.vertices().contains(corner));
    }
    check_invariants(&hull, &points, 1e-6);
    let expected = Cuboid::new(h).unwrap().mass_properties(2.5);
    assert_mass_close(hull.mass_properties(2.5), expected, 1e-5, 1.0);
}

#[test]
fn noise_below_the_tolerance_merges_into_the_faces() {
    // Face points pushed in or out by up to 1e-7 of the size (f32 rounding level, 200× below the
    // tolerance): the faces stay six quads through the eight corners.
    let h = Vec3::ONE;
    let corners = box_corners(h);
    let mut rng = Rng(11);
    let mut points = corners.clone();
    for _ in 0..300 {
        let axis = rng.below(3);
        let mut p = rng.in_cube(0.999);
        p[axis] = if rng.below(2) == 0 { -1.0 } else { 1.0 } + rng.range(-2e-7, 2e-7);
        points.push(p);
    }
    let hull = ConvexHull::new(&points).unwrap();
    assert_eq!(hull.vertices().len(), 8);
    assert_eq!(hull.faces().len(), 6);
    assert_eq!(hull.edges().len(), 12);
    check_invariants(&hull, &points, geometric_tolerance(&points));
    let expected = Cuboid::new(h).unwrap().mass_properties(1.0);
    assert_mass_close(hull.mass_properties(1.0), expected, 1e-5, 1.0);
}

#[test]
fn rotated_translated_box_has_rotated_inertia() {
    let h = Vec3::new(0.5, 1.0, 2.0);
    let rotation = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let pose = Pose::new(Vec3::new(3.0, -2.0, 5.0), rotation);
    let points: Vec<Vec3> = box_corners(h)
        .into_iter()
        .map(|p| pose.transform_point(p))
        .collect();
    let hull = ConvexHull::new(&points).unwrap();
    assert_eq!(hull.vertices().len(), 8);
    assert_eq!(hull.faces().len(), 6);
    assert_eq!(hull.edges().len(), 12);
    check_invariants(&hull, &points, geometric_tolerance(&points));

    // The rotated corners are rounded to f32 at coordinates up to ~7, an error of ~5e-7 in each,
    // i.e. ~1e-6 of the smallest half extent: mass and inertia agree to a few 1e-6 (measured: 2e-7
    // relative), within 1e-5.
    let density = 3.0;
    let expected = Cuboid::new(h)
        .unwrap()
        .mass_properties(density)
        .transformed(&pose);
    assert_mass_close(hull.mass_properties(density), expected, 1e-5, 1.0);
    assert_mat_close(
        hull.mass_properties(density).inertia,
        rotate_tensor(
            rotation,
            Cuboid::new(h).unwrap().mass_properties(density).inertia,
        ),
        1e-5,
        "R I Rᵀ",
    );

    let aabb = hull.aabb(&Pose::IDENTITY);
    let expected = Cuboid::new(h).unwrap().aabb(&pose);
    assert_vec_close(aabb.min, expected.min, 1e-5, "aabb min");
    assert_vec_close(aabb.max, expected.max, 1e-5, "aabb max");
}

#[test]
fn tetrahedron_matches_closed_form() {
    // For the solid with corners 0, a·x, b·y, c·z: V = abc/6, centroid (a, b, c)/4,
    // ∫x² dV = abc·a²/60 and ∫xy dV = abc·ab/120 (scaled from the unit corner tetrahedron, where
    // ∫x² = 1/60, ∫xy = 1/120). About the centroid: ∫x'² = abc·a²(1/60 − 1/96) = abc·a²/160 and
    // ∫x'y' = abc·ab(1/120 − 1/96) = −abc·ab/480. With m = ρ·abc/6:
    // Ixx = 3m(b² + c²)/80 and likewise; Ixy = −ρ∫x'y' = m·ab/80 and likewise.
    let (a, b, c) = (1.5, 2.0, 0.5);
    let offset = Vec3::new(-1.0, 0.25, 2.0);
    let corners = [
        Vec3::ZERO,
        Vec3::new(a, 0.0, 0.0),
        Vec3::new(0.0, b, 0.0),
        Vec3::new(0.0, 0.0, c),
    ];
    let density = 1.25;
    let m = density * a * b * c / 6.0;
    let expected_inertia = Mat3::from_cols(
        Vec3::new(
            3.0 * m * (b * b + c * c) / 80.0,
            m * a * b / 80.0,
            m * a * c / 80.0,
        ),
        Vec3::new(
            m * a * b / 80.0,
            3.0 * m * (a * a + c * c) / 80.0,
            m * b * c / 80.0,
        ),
        Vec3::new(
            m * a * c / 80.0,
            m * b * c / 80.0,
            3.0 * m * (a * a + b * b) / 80.0,
        ),
    );
    for shift in [Vec3::ZERO, offset] {
        let mut points: Vec<Vec3> = corners.iter().map(|p| *p + shift).collect();
        // Extra points inside, on the slanted face (its centroid) and on an edge.
        points.push(shift + Vec3::new(a, b, c) / 5.0);
        points.push(shift + Vec3::new(a, b, c) / 3.0);
        points.push(shift + Vec3::new(a, 0.0, c) / 2.0);
        let hull = ConvexHull::new(&points).unwrap();
        assert_eq!(hull.vertices().len(), 4);
        assert_eq!(hull.faces().len(), 4);
        assert_eq!(hull.edges().len(), 6);
        check_invariants(&hull, &points, geometric_tolerance(&points));
        let expected = MassProperties {
            mass: m,
            center_of_mass: shift + Vec3::new(a, b, c) / 4.0,
            inertia: expected_inertia,
        };
        assert_mass_close(hull.mass_properties(density), expected, 1e-5, 2.0);
    }
}

#[test]
fn regular_prism_has_polygon_caps() {
    // A 32-gon prism with extra points in the middle of the side faces and the caps.
    let sides = 32;
    let (radius, half_height) = (1.0f32, 0.5f32);
    let mut points = Vec::new();
    for k in 0..sides {
        let angle = 2.0 * PI * k as f32 / sides as f32;
        let rim = Vec3::new(radius * angle.cos(), 0.0, radius * angle.sin());
        points.push(rim + Vec3::Y * half_height);
        points.push(rim - Vec3::Y * half_height);
        points.push(rim);
    }
    points.push(Vec3::Y * half_height);
    points.push(-Vec3::Y * half_height);
    let hull = ConvexHull::new(&points).unwrap();
    assert_eq!(hull.vertices().len(), 2 * sides);
    assert_eq!(hull.faces().len(), sides + 2);
    assert_eq!(hull.edges().len(), 3 * sides);
    let caps = hull
        .faces()
        .iter()
        .filter(|f| f.vertices.len() == sides)
        .count();
    assert_eq!(caps, 2);
    check_invariants(&hull, &points, geometric_tolerance(&points));
    // Volume of the prism: n/2·r²·sin(2π/n)·2h.
    let volume =
        sides as f32 / 2.0 * radius * radius * (2.0 * PI / sides as f32).sin() * 2.0 * half_height;
    assert_close(
        hull.mass_properties(1.0).mass,
        volume,
        1e-5 * volume,
        "prism volume",
    );
}

#[test]
fn random_clouds_satisfy_euler_and_convexity() {
    let mut rng = Rng(42);
    for &count in &[4usize, 5, 8, 20, 100, 1000] {
        for trial in 0..6 {
            let points: Vec<Vec3> = (0..count)
                .map(|_| match trial % 3 {
                    0 => rng.in_cube(1.0),
                    1 => rng.in_ball(2.0) + Vec3::new(5.0, -3.0, 1.0),
                    _ => rng.on_sphere() * 0.5,
                })
                .collect();
            let hull = ConvexHull::new(&points)
                .unwrap_or_else(|error| panic!("{count} points, trial {trial}: {error}"));
            check_invariants(&hull, &points, geometric_tolerance(&points));
        }
    }
}

/// Whether integer points are all on one plane, exactly.
fn coplanar(points: &[[i64; 3]]) -> bool {
    let sub = |a: [i64; 3], b: [i64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [i64; 3], b: [i64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let p0 = points[0];
    for p1 in points {
        for p2 in points {
            let normal = cross(sub(*p1, p0), sub(*p2, p0));
            if normal != [0, 0, 0] {
                return points.iter().all(|p| {
                    let d = sub(*p, p0);
                    normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2] == 0
                });
            }
        }
    }
    true
}

#[test]
fn lattice_subsets_merge_exactly_coplanar_faces() {
    // Points of a small integer lattice: many exactly coplanar and collinear subsets.
    let mut rng = Rng(3);
    for trial in 0..400 {
        let count = 4 + rng.below(40);
        let lattice: Vec<[i64; 3]> = (0..count)
            .map(|_| {
                [
                    rng.below(4) as i64,
                    rng.below(4) as i64,
                    rng.below(3) as i64,
                ]
            })
            .collect();
        let points: Vec<Vec3> = lattice
            .iter()
            .map(|p| Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32) * 0.5)
            .collect();
        match ConvexHull::new(&points) {
            Ok(hull) => {
                assert!(
                    !coplanar(&lattice),
                    "trial {trial}: coplanar points gave a hull"
                );
                check_invariants(&hull, &points, 1e-6);
                // No two neighbouring faces share a plane.
                for edge in hull.edges() {
                    let [f, g] = edge.faces.map(|k| &hull.faces()[k as usize]);
                    assert!(
                        f.normal.dot(g.normal) < 1.0 - 1e-6,
                        "trial {trial}: coplanar faces"
                    );
                }
                let reordered: Vec<Vec3> = points.iter().rev().copied().collect();
                let again = ConvexHull::new(&reordered).unwrap();
                assert_eq!(again.vertices().len(), hull.vertices().len());
                assert_eq!(again.faces().len(), hull.faces().len());
                assert_mass_close(
                    again.mass_properties(1.0),
                    hull.mass_properties(1.0),
                    1e-5,
                    2.0,
                );
            }
            Err(error) => {
                assert!(
                    matches!(error.kind, ErrorKind::DegenerateHull(_)),
                    "trial {trial}: {error}"
                );
                assert!(coplanar(&lattice), "trial {trial}: {error}");
            }
        }
    }
}

#[test]
fn sphere_volume_approaches_from_below() {
    // Hulls of growing prefixes of one random sequence on a sphere: nested, so their volume grows,
    // stays below the ball's, and the gap shrinks like 1/N; the inertia tends to 2/5·m·r².
    let radius = 2.0;
    let ball = 4.0 / 3.0 * PI * radius * radius * radius;
    let mut rng = Rng(99);
    let points: Vec<Vec3> = (0..4000).map(|_| rng.on_sphere() * radius).collect();
    let mut previous = 0.0;
    for count in [50, 200, 1000, 4000] {
        let hull = ConvexHull::new(&points[..count]).unwrap();
        let properties = hull.mass_properties(1.0);
        assert!(
            properties.mass < ball,
            "{count}: {} ≥ {ball}",
            properties.mass
        );
        assert!(properties.mass > previous, "{count}: volume did not grow");
        previous = properties.mass;
        if count == 4000 {
            // Random points on a sphere are all corners, bar the odd pair of nearly coplanar
            // triangles merged within the tolerance.
            assert!(hull.vertices().len() > count * 99 / 100);
            check_invariants(&hull, &points, geometric_tolerance(&points));
            assert!(properties.mass > 0.995 * ball, "{}", properties.mass / ball);
            let isotropic = 0.4 * properties.mass * radius * radius;
            assert_mat_close(
                properties.inertia,
                Mat3::from_diagonal(Vec3::splat(isotropic)),
                0.01,
                "sphere inertia",
            );
            assert!(properties.center_of_mass.length() < 0.01);
        }
    }
}

#[test]
fn building_is_deterministic() {
    let mut rng = Rng(5);
    let points: Vec<Vec3> = (0..500).map(|_| rng.in_ball(1.0)).collect();
    let first = ConvexHull::new(&points).unwrap();
    let second = ConvexHull::new(&points).unwrap();
    assert_eq!(first, second);
    // Vertices come in input order.
    let positions: Vec<usize> = first
        .vertices()
        .iter()
        .map(|v| points.iter().position(|p| p == v).unwrap())
        .collect();
    assert!(positions.windows(2).all(|pair| pair[0] < pair[1]));
}

#[test]
fn support_breaks_ties_by_lowest_index() {
    let hull = ConvexHull::new(&box_corners(Vec3::ONE)).unwrap();
    for direction in [Vec3::X, -Vec3::Y, Vec3::Z, Vec3::ZERO] {
        let best = hull
            .vertices()
            .iter()
            .map(|v| v.dot(direction))
            .fold(f32::NEG_INFINITY, f32::max);
        let first = hull
            .vertices()
            .iter()
            .find(|v| v.dot(direction) == best)
            .unwrap();
        assert_eq!(hull.support(direction), *first);
    }
    assert_eq!(hull.support(Vec3::NAN), hull.vertices()[0]);
    assert_eq!(hull.support(Vec3::new(1.0, 1.0, 1.0)), Vec3::ONE);
}

#[test]
fn scale_and_offset_do_not_matter() {
    for (half, centre) in [
        (1e-6, Vec3::ZERO),
        (1e6, Vec3::ZERO),
        (1.0, Vec3::new(1e3, -2e3, 5e2)),
        (1e-3, Vec3::new(0.5, 0.0, 0.0)),
    ] {
        let h = Vec3::new(1.0, 2.0, 3.0) * half;
        let points: Vec<Vec3> = box_corners(h).into_iter().map(|p| p + centre).collect();
        let hull = ConvexHull::new(&points).unwrap();
        assert_eq!(hull.faces().len(), 6, "half {half}, centre {centre}");
        assert_eq!(hull.vertices().len(), 8);
        // Corners at 2e3 carry f32 rounding of ~6e-5 relative to a box of size 2: relative 1e-4.
        let expected = Cuboid::new(h).unwrap().mass_properties(1.0);
        let actual = hull.mass_properties(1.0);
        assert_close(actual.mass, expected.mass, 1e-4 * expected.mass, "mass");
        assert_vec_close(
            actual.center_of_mass,
            centre,
            1e-4 * h.max_element(),
            "centre",
        );
        assert_mat_close(actual.inertia, expected.inertia, 1e-4, "inertia");
    }
}

#[test]
fn degenerate_inputs_are_errors() {
    let p = Vec3::new(1.0, 2.0, 3.0);
    assert_eq!(degenerate_reason(&[]), "fewer than 4 points");
    assert_eq!(degenerate_reason(&[p]), "fewer than 4 points");
    assert_eq!(degenerate_reason(&[p, Vec3::ZERO]), "fewer than 4 points");
    assert_eq!(
        degenerate_reason(&[p, Vec3::ZERO, Vec3::X]),
        "fewer than 4 points"
    );
    assert_eq!(degenerate_reason(&[p; 10]), "all points coincide");

    // Collinear: exactly, and with noise 1e-7 of the length (below the tolerance).
    let direction = Vec3::new(1.0, -2.0, 0.5);
    let line: Vec<Vec3> = (0..10).map(|k| p + direction * k as f32).collect();
    assert_eq!(degenerate_reason(&line), "all points are collinear");
    let mut rng = Rng(1);
    let noisy: Vec<Vec3> = line.iter().map(|q| *q + rng.in_cube(1e-6)).collect();
    assert_eq!(degenerate_reason(&noisy), "all points are collinear");
    assert_eq!(
        degenerate_reason(&[p, p, Vec3::ZERO, Vec3::ZERO, p]),
        "all points are collinear"
    );

    // Coplanar: a square with its centre, a tilted lattice, three distinct points repeated, and a
    // square with one point 1e-7 of its size off the plane.
    let square = [
        Vec3::ZERO,
        Vec3::X,
        Vec3::Y,
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::splat(0.5).with_z(0.0),
    ];
    assert_eq!(degenerate_reason(&square), "all points are coplanar");
    let tilt = Quat::from_axis_angle(Vec3::new(0.3, 1.0, -0.2).normalize(), 0.9);
    let lattice: Vec<Vec3> = (0..25)
        .map(|k| tilt * Vec3::new((k % 5) as f32, (k / 5) as f32, 0.0) + p)
        .collect();
    assert_eq!(degenerate_reason(&lattice), "all points are coplanar");
    assert_eq!(
        degenerate_reason(&[p, Vec3::X, Vec3::Y, p, Vec3::X, Vec3::Y]),
        "all points are coplanar"
    );
    let mut nearly = square.to_vec();
    nearly.push(Vec3::new(0.3, 0.6, 1e-7));
    assert_eq!(degenerate_reason(&nearly), "all points are coplanar");

    // Volumes an f32 cannot hold.
    for half in [1e-16, 1e16] {
        let reason = degenerate_reason(&box_corners(Vec3::splat(half)));
        assert!(reason.contains("f32"), "{half}: {reason}");
    }

    // Non-finite coordinates, reported before the count.
    let mut cube = box_corners(Vec3::ONE);
    cube[2].y = f32::NAN;
    assert_eq!(not_finite_field(&cube), "points[2]");
    cube[2].y = 1.0;
    cube[5].z = f32::INFINITY;
    assert_eq!(not_finite_field(&cube), "points[5]");
    cube[5].z = 1.0;
    cube[7].x = f32::NEG_INFINITY;
    assert_eq!(not_finite_field(&cube), "points[7]");
    assert_eq!(not_finite_field(&[Vec3::ZERO, Vec3::NAN]), "points[1]");
}

#[test]
fn random_degenerate_and_tiny_clouds_never_panic() {
    // Clouds mixing duplicates, near-duplicates and flat subsets: each builds or fails cleanly.
    let mut rng = Rng(17);
    for trial in 0..300 {
        let base: Vec<Vec3> = (0..1 + rng.below(6)).map(|_| rng.in_cube(1.0)).collect();
        let count = rng.below(30);
        let points: Vec<Vec3> = (0..count)
            .map(|_| {
                let q = base[rng.below(base.len())];
                match rng.below(3) {
                    0 => q,
                    1 => q + rng.in_cube(1e-6),
                    _ => q.with_z(0.25),
                }
            })
            .collect();
        match ConvexHull::new(&points) {
            Ok(hull) => check_topology_and_planes(&hull, &points, geometric_tolerance(&points)),
            Err(error) => assert!(
                matches!(error.kind, ErrorKind::DegenerateHull(_)),
                "trial {trial}: {error}"
            ),
        }
    }
}

#[test]
fn adversarial_clouds_stay_valid() {
    // Rotated lattices (f32 rounding makes their planes only nearly flat), rotated prisms with
    // points in their side edges, slabs a few tolerances thick, noisy spheres and clusters of
    // points about a tolerance apart.
    let mut rng = Rng(1234);
    for trial in 0..1200 {
        let kind = trial % 6;
        let rotation = Quat::from_axis_angle(rng.on_sphere(), rng.range(0.0, 6.0));
        let shift = rng.in_cube(10.0);
        let points: Vec<Vec3> = match kind {
            0 => {
                let n = 2 + rng.below(5) as i32;
                let mut lattice = Vec::new();
                for i in 0..n {
                    for j in 0..n {
                        for k in 0..n {
                            let p = Vec3::new(i as f32, j as f32, k as f32 * 0.7);
                            lattice.push(rotation * p + shift);
                        }
                    }
                }
                lattice
            }
            1 => {
                let sides = 3 + rng.below(40);
                let mut prism = Vec::new();
                for side in 0..sides {
                    let angle = 2.0 * PI * side as f32 / sides as f32;
                    for y in [-0.5, 0.0, 0.5] {
                        prism.push(rotation * Vec3::new(angle.cos(), y, angle.sin()) + shift);
                    }
                }
                prism
            }
            2 => {
                let thickness = rng.range(0.0, 1e-4);
                (0..4 + rng.below(50))
                    .map(|_| {
                        let z = if rng.below(2) == 0 { 0.0 } else { thickness };
                        rotation * Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), z)
                    })
                    .collect()
            }
            3 => (0..4 + rng.below(500))
                .map(|_| rng.on_sphere() * (1.0 + rng.range(-3e-5, 3e-5)) + shift * 0.1)
                .collect(),
            4 => {
                let centres: Vec<Vec3> = (0..4 + rng.below(5)).map(|_| rng.in_cube(1.0)).collect();
                (0..4 + rng.below(100))
                    .map(|_| {
                        let spread = rng.range(0.0, 3e-5);
                        centres[rng.below(centres.len())] + rng.in_cube(spread)
                    })
                    .collect()
            }
            _ => {
                let count = 4 + rng.below(60);
                (0..count)
                    .map(|_| {
                        let p = Vec3::new(
                            rng.below(5) as f32,
                            rng.below(4) as f32,
                            rng.below(3) as f32,
                        );
                        rotation * p * 0.3 + shift
                    })
                    .collect()
            }
        };
        match ConvexHull::new(&points) {
            Ok(hull) => {
                let tolerance = geometric_tolerance(&points);
                if kind <= 1 {
                    check_invariants(&hull, &points, tolerance);
                } else {
                    check_topology_and_planes(&hull, &points, tolerance);
                }
                let counts = (
                    hull.vertices().len(),
                    hull.faces().len(),
                    hull.edges().len(),
                );
                if kind == 0 {
                    assert_eq!(counts, (8, 6, 12), "trial {trial}: rotated lattice");
                }
                if kind == 1 {
                    let sides = points.len() / 3;
                    assert_eq!(counts, (2 * sides, sides + 2, 3 * sides), "trial {trial}");
                }
            }
            Err(error) => assert!(
                matches!(error.kind, ErrorKind::DegenerateHull(_)) && kind >= 2,
                "trial {trial}: {error}"
            ),
        }
    }
}

#[test]
fn thin_box_is_a_box_and_thinner_is_flat() {
    // Tolerance: 1e-5 × 2 = 2e-5. A box 1e-3 thick (50 tolerances) keeps its six faces; a slab
    // 3e-5 thick fits in the ±tolerance band faces merge within and counts as flat.
    let thin = box_corners(Vec3::new(1.0, 1.0, 5e-4));
    let hull = ConvexHull::new(&thin).unwrap();
    assert_eq!(
        (
            hull.vertices().len(),
            hull.faces().len(),
            hull.edges().len()
        ),
        (8, 6, 12)
    );
    check_invariants(&hull, &thin, 1e-6);
    let expected = Cuboid::new(Vec3::new(1.0, 1.0, 5e-4))
        .unwrap()
        .mass_properties(1.0);
    assert_mass_close(hull.mass_properties(1.0), expected, 1e-5, 1.0);

    let mut rng = Rng(8);
    let slab: Vec<Vec3> = (0..40)
        .map(|k| {
            Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                (k % 2) as f32 * 3e-5,
            )
        })
        .collect();
    assert_eq!(degenerate_reason(&slab), "all points are coplanar");
}

/// The support point is the vertex of largest `vertex · direction`, the lowest index on ties (a
/// direction along a face normal of a cube ties four corners) and vertex 0 for a NaN direction,
/// exactly as a plain scan finds it; the bounding radius is the farthest vertex's distance.
#[test]
fn support_and_bounding_radius_match_a_plain_scan() {
    let scan = |hull: &ConvexHull, direction: Vec3| {
        let dots = hull.vertices().iter().map(|vertex| vertex.dot(direction));
        let farthest = dots.clone().fold(f32::NEG_INFINITY, f32::max);
        dots.zip(hull.vertices())
            .find(|(dot, _)| *dot == farthest)
            .map_or(hull.vertices()[0], |(_, vertex)| *vertex)
    };
    let mut rng = Rng(7);
    let cube = ConvexHull::new(&box_corners(Vec3::ONE)).unwrap();
    let mut hulls = vec![cube];
    for count in [4, 5, 9, 14, 40] {
        let points: Vec<Vec3> = (0..count).map(|_| rng.in_ball(1.5)).collect();
        if let Ok(hull) = ConvexHull::new(&points) {
            hulls.push(hull);
        }
    }
    for hull in &hulls {
        let axes = [Vec3::X, Vec3::NEG_Y, Vec3::Z, Vec3::ONE];
        let random = (0..200).map(|_| rng.on_sphere());
        for direction in axes.into_iter().chain(random) {
            assert_eq!(
                hull.support(direction),
                scan(hull, direction),
                "{direction}"
            );
        }
        assert_eq!(hull.support(Vec3::NAN), hull.vertices()[0]);
        let farthest = hull.vertices().iter().map(|vertex| vertex.length());
        assert_eq!(hull.bounding_radius(), farthest.fold(0.0, f32::max));
    }
}
