//! Hulls of known shapes against closed forms: boxes, a tetrahedron, a prism, a sphere, thin boxes.

use super::*;

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
        points.push(rng.vec3(-1.0, 1.0) * h * 0.999);
    }
    // Face centres and random points exactly on the faces.
    for axis in 0..3 {
        for sign in [-1.0, 1.0] {
            let mut centre = Vec3::ZERO;
            centre[axis] = sign;
            points.push(centre * h);
            for _ in 0..10 {
                let mut p = rng.vec3(-1.0, 1.0);
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
        let mut p = rng.vec3(-0.999, 0.999);
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
    let expected = box_mass_properties(Vec3::new(1.0, 1.0, 5e-4));
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
