//! Random, lattice, degenerate and adversarial clouds: invariants, determinism, errors, no panics.

use super::*;

#[test]
fn random_clouds_satisfy_euler_and_convexity() {
    let mut rng = Rng(42);
    for &count in &[4usize, 5, 8, 20, 100, 1000] {
        for trial in 0..6 {
            let points: Vec<Vec3> = (0..count)
                .map(|_| match trial % 3 {
                    0 => rng.vec3(-1.0, 1.0),
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
fn scale_and_offset_do_not_matter() {
    for (half, centre) in [
        (1e-6, Vec3::ZERO),
        (2e4, Vec3::ZERO),
        (1.0, Vec3::new(1e3, -2e3, 5e2)),
        (1e-3, Vec3::new(0.5, 0.0, 0.0)),
    ] {
        let h = Vec3::new(1.0, 2.0, 3.0) * half;
        let points: Vec<Vec3> = box_corners(h).into_iter().map(|p| p + centre).collect();
        let hull = ConvexHull::new(&points).unwrap();
        assert_eq!(hull.faces().len(), 6, "half {half}, centre {centre}");
        assert_eq!(hull.vertices().len(), 8);
        // Corners at 2e3 carry f32 rounding of ~6e-5 relative to a box of size 2: relative 1e-4.
        let expected = box_mass_properties(h);
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
    let noisy: Vec<Vec3> = line.iter().map(|q| *q + rng.vec3(-1e-6, 1e-6)).collect();
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

    // A volume an f32 cannot hold; points past the engine's size limit are refused first.
    let reason = degenerate_reason(&box_corners(Vec3::splat(1e-16)));
    assert!(reason.contains("f32"), "{reason}");
    let error = ConvexHull::new(&box_corners(Vec3::splat(1e16))).unwrap_err();
    assert_eq!(error.field, "points[0]");
    assert!(matches!(error.kind, ErrorKind::TooLarge { .. }));

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
        let base: Vec<Vec3> = (0..1 + rng.below(6)).map(|_| rng.vec3(-1.0, 1.0)).collect();
        let count = rng.below(30);
        let points: Vec<Vec3> = (0..count)
            .map(|_| {
                let q = base[rng.below(base.len())];
                match rng.below(3) {
                    0 => q,
                    1 => q + rng.vec3(-1e-6, 1e-6),
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
        let shift = rng.vec3(-10.0, 10.0);
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
                let centres: Vec<Vec3> =
                    (0..4 + rng.below(5)).map(|_| rng.vec3(-1.0, 1.0)).collect();
                (0..4 + rng.below(100))
                    .map(|_| {
                        let spread = rng.range(0.0, 3e-5);
                        centres[rng.below(centres.len())] + rng.vec3(-spread, spread)
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
