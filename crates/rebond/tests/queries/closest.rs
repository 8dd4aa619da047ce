//! Closest points, distances and point projections against exact answers.
//!
//! Tolerances. Closed forms (a sphere against a sphere, box, capsule or halfspace, a point
//! projected on a box, sphere, capsule, cylinder, halfspace, a point inside a hull, a triangle's
//! nearest point) are exact to f32 rounding: a few roundings of 6e-8 relative on coordinates of
//! at most 5 m, so `EXACT` = 2e-6 m. GJK answers (boxes, hulls, cylinders, meshes against
//! anything but a sphere) stop within `gjk::TOLERANCE` = 1e-5 of the problem's size, the largest
//! coordinate of its support points, here at most 5 m: `GJK` = 5e-5 m. Measured: at most
//! 2.4e-7 m off the exact distance (a cylinder's side and cap), 9e-8 m for boxes.

use super::*;
use rebond::query::{closest_points, ClosestPoints};

const EXACT: f32 = 2e-6;
const GJK: f32 = 5e-5;

fn at(x: f32, y: f32, z: f32) -> Pose {
    Pose::from_position(Vec3::new(x, y, z))
}

fn close(a: Vec3, b: Vec3, tolerance: f32) -> bool {
    (a - b).length() <= tolerance
}

/// The answer's points, normal and signed distance, checked against each other: a unit normal
/// and `point_b − point_a = signed distance · normal`. `apart` says which answer is expected.
fn answer(found: ClosestPoints, apart: bool, tolerance: f32) -> (Vec3, Vec3, Vec3, f32) {
    let (point_a, point_b, normal, signed) = match found {
        ClosestPoints::Separated {
            point_a,
            point_b,
            normal,
            distance,
        } if apart => (point_a, point_b, normal, distance),
        ClosestPoints::Overlapping {
            point_a,
            point_b,
            normal,
            depth,
        } if !apart => (point_a, point_b, normal, -depth),
        _ => panic!("expected apart: {apart}, got {found:?}"),
    };
    assert!((normal.length() - 1.0).abs() < 1e-5, "{found:?}");
    assert!(
        close(point_b - point_a, signed * normal, tolerance),
        "{found:?}"
    );
    (point_a, point_b, normal, signed)
}

fn separated(found: ClosestPoints, tolerance: f32) -> (Vec3, Vec3, Vec3, f32) {
    answer(found, true, tolerance)
}

/// As [`separated`], with the depth (positive) last.
fn overlapping(found: ClosestPoints, tolerance: f32) -> (Vec3, Vec3, Vec3, f32) {
    let (point_a, point_b, normal, signed) = answer(found, false, tolerance);
    (point_a, point_b, normal, -signed)
}

/// The octahedron `|x| + |y| + |z| ≤ 1`.
fn octahedron() -> Shape {
    let corners: Vec<Vec3> = [Vec3::X, Vec3::Y, Vec3::Z]
        .into_iter()
        .flat_map(|axis| [axis, -axis])
        .collect();
    Shape::convex_hull(&corners).unwrap()
}

fn sphere(radius: f32) -> Shape {
    Shape::sphere(radius).unwrap()
}

fn cube(half: f32) -> Shape {
    Shape::cuboid(Vec3::splat(half)).unwrap()
}

#[test]
fn spheres_apart_overlapping_and_beyond() {
    let (a, b) = (sphere(1.0), sphere(0.5));
    let found = closest_points(&a, &at(0.0, 0.0, 0.0), &b, &at(0.0, 4.0, 0.0), 10.0).unwrap();
    let (point_a, point_b, normal, distance) = separated(found, EXACT);
    assert!((distance - 2.5).abs() <= EXACT);
    assert_eq!(normal, Vec3::Y);
    assert!(close(point_a, Vec3::Y, EXACT) && close(point_b, Vec3::new(0.0, 3.5, 0.0), EXACT));
    let found = closest_points(&a, &at(0.0, 0.0, 0.0), &b, &at(1.2, 0.0, 0.0), 10.0).unwrap();
    let (point_a, _, normal, depth) = overlapping(found, EXACT);
    assert!((depth - 0.3).abs() <= EXACT && normal == Vec3::X && close(point_a, Vec3::X, EXACT));
    // The cut-off: 2.5 m apart is beyond 2.4 m and within 2.5 m.
    let far = |limit| closest_points(&a, &at(0.0, 0.0, 0.0), &b, &at(0.0, 4.0, 0.0), limit);
    assert_eq!(far(2.4).unwrap(), ClosestPoints::Beyond);
    assert!(far(2.5).unwrap().distance().is_some());
    assert_eq!(far(2.4).unwrap().distance(), None);
}

#[test]
fn boxes_face_to_face_edge_to_edge_and_corner_to_face() {
    let unit = cube(1.0);
    let found = closest_points(&unit, &at(0.0, 0.0, 0.0), &unit, &at(3.0, 0.5, 0.0), 10.0);
    let (point_a, point_b, normal, distance) = separated(found.unwrap(), GJK);
    assert!((distance - 1.0).abs() <= GJK && close(normal, Vec3::X, GJK));
    assert!((point_a.x - 1.0).abs() <= GJK && (point_b.x - 2.0).abs() <= GJK);
    // A turned 45° about Z shows an edge along Z at x = √2; B turned 45° about Y, at x = 4, an
    // edge along Y at x = 4 − √2: the edges cross 4 − 2√2 apart on the X axis.
    let quarter = std::f32::consts::FRAC_PI_4;
    let a = Pose::new(Vec3::ZERO, Quat::from_rotation_z(quarter));
    let b = Pose::new(Vec3::new(4.0, 0.0, 0.0), Quat::from_rotation_y(quarter));
    let (point_a, point_b, normal, distance) =
        separated(closest_points(&unit, &a, &unit, &b, 10.0).unwrap(), GJK);
    let root_two = std::f32::consts::SQRT_2;
    assert!(
        (distance - (4.0 - 2.0 * root_two)).abs() <= GJK,
        "{distance}"
    );
    assert!(close(normal, Vec3::X, GJK));
    assert!(close(point_a, Vec3::new(root_two, 0.0, 0.0), GJK));
    assert!(close(point_b, Vec3::new(4.0 - root_two, 0.0, 0.0), GJK));
    // A's corner (1, 1, 1) turned onto +X reaches x = √3; B's face at x = 3.
    let corner = Quat::from_rotation_arc(Vec3::ONE.normalize(), Vec3::X);
    let a = Pose::new(Vec3::ZERO, corner);
    let (point_a, _, normal, distance) = separated(
        closest_points(&unit, &a, &unit, &at(4.0, 0.0, 0.0), 10.0).unwrap(),
        GJK,
    );
    assert!((distance - (3.0 - 3f32.sqrt())).abs() <= GJK, "{distance}");
    assert!(close(normal, Vec3::X, GJK) && close(point_a, Vec3::new(3f32.sqrt(), 0.0, 0.0), GJK));
    // Overlapping by 0.25 face to face: EPA's depth.
    let found = closest_points(&unit, &at(0.0, 0.0, 0.0), &unit, &at(0.0, 0.0, 1.75), 10.0);
    let (_, _, normal, depth) = overlapping(found.unwrap(), GJK);
    assert!((depth - 0.25).abs() <= GJK && close(normal, Vec3::Z, GJK));
}

#[test]
fn capsules_cross_at_their_segments_distance() {
    let (a, b) = (
        Shape::capsule(0.5, 1.0).unwrap(),
        Shape::capsule(0.3, 2.0).unwrap(),
    );
    // B lies along X two metres in front of A's segment along Y.
    let along_x = Pose::new(
        Vec3::new(0.0, 0.2, 2.0),
        Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
    );
    let found = closest_points(&a, &at(0.0, 0.0, 0.0), &b, &along_x, 10.0).unwrap();
    let (point_a, point_b, normal, distance) = separated(found, GJK);
    assert!((distance - 1.2).abs() <= GJK && close(normal, Vec3::Z, GJK));
    assert!(close(point_a, Vec3::new(0.0, 0.2, 0.5), GJK));
    assert!(close(point_b, Vec3::new(0.0, 0.2, 1.7), GJK));
    // A sphere against a capsule end, in closed form.
    let found = closest_points(
        &sphere(0.5),
        &at(0.0, 4.0, 0.0),
        &a,
        &at(0.0, 0.0, 0.0),
        10.0,
    );
    let (_, point_b, normal, distance) = separated(found.unwrap(), EXACT);
    assert!((distance - 2.0).abs() <= EXACT && normal == Vec3::NEG_Y);
    assert!(close(point_b, Vec3::new(0.0, 1.5, 0.0), EXACT));
}

#[test]
fn cylinder_side_and_cap() {
    let cylinder = Shape::cylinder(1.0, 1.0).unwrap();
    let origin = at(0.0, 0.0, 0.0);
    let found = closest_points(&cylinder, &origin, &sphere(0.5), &at(3.0, 0.2, 0.0), 10.0);
    let (point_a, _, normal, distance) = separated(found.unwrap(), GJK);
    assert!((distance - 1.5).abs() <= GJK && close(normal, Vec3::X, GJK));
    assert!(close(point_a, Vec3::new(1.0, 0.2, 0.0), GJK));
    let found = closest_points(&cube(0.5), &at(0.3, 3.0, 0.0), &cylinder, &origin, 10.0);
    let (_, point_b, normal, distance) = separated(found.unwrap(), GJK);
    assert!((distance - 1.5).abs() <= GJK && close(normal, Vec3::NEG_Y, GJK));
    assert!((point_b.y - 1.0).abs() <= GJK);
}

#[test]
fn convex_hull_face_and_corner() {
    // The octahedron |x| + |y| + |z| ≤ 1: its face x + y + z = 1 lies (6 − 1)/√3 from (2, 2, 2).
    let hull = octahedron();
    let origin = at(0.0, 0.0, 0.0);
    let found = closest_points(&hull, &origin, &sphere(0.5), &at(2.0, 2.0, 2.0), 10.0);
    let (point_a, _, normal, distance) = separated(found.unwrap(), GJK);
    assert!(
        (distance - (5.0 / 3f32.sqrt() - 0.5)).abs() <= GJK,
        "{distance}"
    );
    assert!(close(normal, Vec3::ONE.normalize(), GJK));
    assert!(close(point_a, Vec3::splat(1.0 / 3.0), GJK));
    // A box's face at x = 2 against the corner (1, 0, 0).
    let found = closest_points(&hull, &origin, &cube(0.5), &at(2.5, 0.1, 0.0), 10.0);
    let (point_a, _, _, distance) = separated(found.unwrap(), GJK);
    assert!((distance - 1.0).abs() <= GJK && close(point_a, Vec3::X, GJK));
}

#[test]
fn halfspaces_in_closed_form() {
    let floor = Shape::halfspace(Vec3::Y).unwrap();
    let origin = at(0.0, 0.0, 0.0);
    let tilted = Pose::new(Vec3::new(0.0, 3.0, 0.0), Quat::from_rotation_z(0.3));
    let found = closest_points(&floor, &origin, &cube(1.0), &tilted, 10.0).unwrap();
    let (_, point_b, normal, distance) = separated(found, EXACT);
    // The box's lowest corner, turned 0.3 rad: 3 − cos 0.3 − sin 0.3 above the floor.
    let expected = 3.0 - 0.3f32.cos() - 0.3f32.sin();
    assert!((distance - expected).abs() <= EXACT && normal == Vec3::Y);
    assert!((point_b.y - expected).abs() <= EXACT);
    let ceiling = Shape::halfspace(Vec3::NEG_Y).unwrap();
    let found = closest_points(&floor, &origin, &ceiling, &at(0.0, 2.0, 0.0), 10.0).unwrap();
    assert_eq!(found.distance(), Some(2.0));
    let found = closest_points(&floor, &origin, &ceiling, &at(0.0, -1.0, 0.0), 10.0).unwrap();
    assert_eq!(found.distance(), Some(-1.0));
    let wall = Shape::halfspace(Vec3::X).unwrap();
    let found = closest_points(&floor, &origin, &wall, &at(3.0, 0.0, 0.0), 10.0).unwrap();
    let common = Vec3::new(3.0, 0.0, 0.0);
    let expected = ClosestPoints::Overlapping {
        point_a: common,
        point_b: common,
        normal: Vec3::Y,
        depth: f32::INFINITY,
    };
    assert_eq!(found, expected);
}

#[test]
fn compounds_take_their_nearest_children() {
    let pair = Shape::compound(vec![
        CompoundChild::new(sphere(0.5), at(-2.0, 0.0, 0.0)),
        CompoundChild::new(cube(0.5), at(2.0, 0.0, 0.0)),
    ])
    .unwrap();
    let found = closest_points(
        &pair,
        &at(0.0, 0.0, 0.0),
        &sphere(1.0),
        &at(5.0, 0.0, 0.0),
        10.0,
    );
    let (point_a, _, _, distance) = separated(found.unwrap(), EXACT);
    assert!((distance - 1.5).abs() <= EXACT && close(point_a, Vec3::new(2.5, 0.0, 0.0), EXACT));
}

fn floor_mesh() -> Shape {
    let vertices = vec![
        Vec3::new(-5.0, 0.0, -5.0),
        Vec3::new(5.0, 0.0, -5.0),
        Vec3::new(5.0, 0.0, 5.0),
        Vec3::new(-5.0, 0.0, 5.0),
    ];
    Shape::trimesh(vertices, &[[0, 2, 1], [0, 3, 2]]).unwrap()
}

/// A heightfield over [−4, 4]² rising along X with slope 1/4: `y = (x + 4) / 4`.
fn ramp() -> Shape {
    let row: Vec<f32> = (0..5).map(|j| j as f32 * 0.5).collect();
    Shape::heightfield(&vec![row; 5], Vec3::new(8.0, 1.0, 8.0)).unwrap()
}

#[test]
fn meshes_and_heightfields_by_their_nearest_triangle() {
    let (mesh, origin) = (floor_mesh(), at(0.0, 0.0, 0.0));
    let found = closest_points(&sphere(0.5), &at(1.0, 2.0, 1.0), &mesh, &origin, 10.0).unwrap();
    let (_, point_b, normal, distance) = separated(found, EXACT);
    assert!((distance - 1.5).abs() <= EXACT && normal == Vec3::NEG_Y);
    assert!(close(point_b, Vec3::new(1.0, 0.0, 1.0), EXACT));
    // The mesh first: the normal points up toward the box.
    let turned = Pose::new(Vec3::new(0.0, 3.0, 0.0), Quat::from_rotation_x(0.4));
    let found = closest_points(&mesh, &origin, &cube(0.5), &turned, 10.0).unwrap();
    let (_, _, normal, distance) = separated(found, GJK);
    let expected = 3.0 - 0.5 * (0.4f32.cos() + 0.4f32.sin());
    assert!((distance - expected).abs() <= GJK && close(normal, Vec3::Y, GJK));
    // Sunk 0.2 m into the mesh: the narrow phase's own triangle contact, to its 0.1 mm.
    let found = closest_points(&cube(0.5), &at(0.0, 0.3, 0.0), &mesh, &origin, 10.0).unwrap();
    let (_, _, normal, depth) = overlapping(found, 1e-4);
    assert!((depth - 0.2).abs() <= 1e-4 && close(normal, Vec3::NEG_Y, 1e-4));
    // Beyond the cut-off.
    let far = closest_points(&sphere(0.5), &at(1.0, 2.0, 1.0), &mesh, &origin, 1.0).unwrap();
    assert_eq!(far, ClosestPoints::Beyond);
    // The ramp's plane x − 4y + 4 = 0: a sphere at (0, 3, 0) is (4·3 − 4)/√17 from it.
    let found = closest_points(&sphere(0.5), &at(0.0, 3.0, 0.0), &ramp(), &origin, 10.0);
    let (_, _, normal, distance) = separated(found.unwrap(), EXACT);
    assert!(
        (distance - (8.0 / 17f32.sqrt() - 0.5)).abs() <= EXACT,
        "{distance}"
    );
    assert!(close(
        normal,
        Vec3::new(1.0, -4.0, 0.0) / 17f32.sqrt(),
        EXACT
    ));
    // A box buried below the ramp's surface is in its solid.
    let found = closest_points(&cube(0.2), &at(0.0, -1.0, 0.0), &ramp(), &origin, 10.0).unwrap();
    assert!(
        matches!(found, ClosestPoints::Overlapping { .. }),
        "{found:?}"
    );
    // Two surfaces: the ramp raised 2 m rises from y = 2 to 4 above the floor at y = 0; lowered
    // 1 m it crosses the floor, and crossing surfaces touch.
    let found = closest_points(&mesh, &origin, &ramp(), &at(0.0, 2.0, 0.0), 10.0).unwrap();
    assert!((found.distance().unwrap() - 2.0).abs() <= GJK, "{found:?}");
    let found = closest_points(&mesh, &origin, &ramp(), &at(0.0, -1.0, 0.0), 10.0).unwrap();
    assert_eq!(found.distance(), Some(0.0));
}

/// A world of one static body of `shape` at `pose`.
fn world_of(shape: Shape, pose: Pose) -> (World, BodyHandle) {
    let mut world = world();
    let body = world
        .add_body(
            BodyDesc::static_body(shape)
                .position(pose.position)
                .rotation(pose.rotation),
        )
        .unwrap();
    (world, body)
}

/// The projection of `point` in a world of one body, checked for unit normal and for
/// `point = surface + distance · normal` (closed forms: exact to `tolerance`).
fn project(shape: Shape, pose: Pose, point: Vec3, tolerance: f32) -> rebond::PointProjection {
    let (world, body) = world_of(shape, pose);
    let found = world
        .project_point(point, f32::INFINITY, &QueryFilter::new())
        .unwrap()
        .expect("one body");
    assert_eq!(found.body, body);
    assert!((found.normal.length() - 1.0).abs() < 1e-5, "{found:?}");
    assert!(
        close(
            point,
            found.point + found.distance * found.normal,
            tolerance
        ),
        "{found:?}"
    );
    assert_eq!(found.inside, found.distance <= 0.0);
    found
}

#[test]
fn point_projection_on_each_convex_kind() {
    let turned = Pose::new(Vec3::new(1.0, 2.0, 3.0), Quat::from_rotation_y(0.5));
    let local = |v: Vec3| turned.transform_point(v);
    let outward = |v: Vec3| turned.transform_vector(v);
    // Sphere: radial.
    let found = project(sphere(1.0), turned, local(Vec3::new(0.0, 3.0, 0.0)), EXACT);
    assert!(close(found.point, local(Vec3::Y), EXACT) && (found.distance - 2.0).abs() <= EXACT);
    // Box: outside a corner, inside the nearest face.
    let boxed = Shape::cuboid(Vec3::new(1.0, 2.0, 3.0)).unwrap();
    let found = project(
        boxed.clone(),
        turned,
        local(Vec3::new(2.0, 4.0, 0.5)),
        EXACT,
    );
    assert!(close(found.point, local(Vec3::new(1.0, 2.0, 0.5)), EXACT));
    assert!((found.distance - 5f32.sqrt()).abs() <= EXACT);
    let found = project(boxed, turned, local(Vec3::new(0.2, 1.5, -0.5)), EXACT);
    assert!(found.inside && (found.distance + 0.5).abs() <= EXACT);
    assert!(close(found.normal, outward(Vec3::Y), EXACT));
    // Capsule: from its segment.
    let capsule = Shape::capsule(0.5, 1.0).unwrap();
    let found = project(capsule, turned, local(Vec3::new(0.0, 3.0, 0.0)), EXACT);
    assert!(close(found.point, local(Vec3::new(0.0, 1.5, 0.0)), EXACT));
    assert!((found.distance - 1.5).abs() <= EXACT);
    // Cylinder (sharp): beside the side, above the rim, inside nearer the cap.
    let cylinder = Shape::cylinder(1.0, 2.0).unwrap();
    let found = project(
        cylinder.clone(),
        turned,
        local(Vec3::new(0.0, 0.5, 3.0)),
        EXACT,
    );
    assert!((found.distance - 2.0).abs() <= EXACT && close(found.normal, outward(Vec3::Z), EXACT));
    let found = project(
        cylinder.clone(),
        turned,
        local(Vec3::new(4.0, 6.0, 0.0)),
        EXACT,
    );
    assert!(close(found.point, local(Vec3::new(1.0, 2.0, 0.0)), EXACT));
    assert!((found.distance - 5.0).abs() <= EXACT);
    let found = project(cylinder, turned, local(Vec3::new(0.1, -1.8, 0.0)), EXACT);
    assert!(
        (found.distance + 0.2).abs() <= EXACT && close(found.normal, outward(Vec3::NEG_Y), EXACT)
    );
    // Hull: inside to the nearest face plane, outside by GJK.
    let hull = octahedron();
    let found = project(hull.clone(), turned, local(Vec3::new(0.1, 0.1, 0.1)), EXACT);
    assert!((found.distance - (0.3 - 1.0) / 3f32.sqrt()).abs() <= EXACT);
    let found = project(hull, turned, local(Vec3::new(3.0, 0.0, 0.0)), GJK);
    assert!((found.distance - 2.0).abs() <= GJK && close(found.point, local(Vec3::X), GJK));
    // Halfspace.
    let floor = Shape::halfspace(Vec3::Y).unwrap();
    let found = project(floor, turned, local(Vec3::new(5.0, -0.75, 2.0)), EXACT);
    assert!(found.inside && (found.distance + 0.75).abs() <= EXACT);
    assert!(close(found.point, local(Vec3::new(5.0, 0.0, 2.0)), EXACT));
}

#[test]
fn point_projection_on_compounds_meshes_and_heightfields() {
    let origin = at(0.0, 0.0, 0.0);
    let pair = Shape::compound(vec![
        CompoundChild::new(sphere(0.5), at(-2.0, 0.0, 0.0)),
        CompoundChild::new(cube(0.5), at(2.0, 0.0, 0.0)),
    ])
    .unwrap();
    let found = project(pair, origin, Vec3::new(4.0, 0.0, 0.0), EXACT);
    assert_eq!((found.collider, found.triangle), (1, None));
    assert!((found.distance - 1.5).abs() <= EXACT);
    let found = project(floor_mesh(), origin, Vec3::new(2.0, -3.0, 1.0), EXACT);
    assert!(!found.inside && (found.distance - 3.0).abs() <= EXACT);
    assert!(close(found.normal, Vec3::NEG_Y, EXACT) && found.triangle.is_some());
    // Above the ramp, and below it (inside its solid), both √17/… from the plane x − 4y + 4 = 0.
    let found = project(ramp(), origin, Vec3::new(0.0, 3.0, 0.0), EXACT);
    assert!((found.distance - 8.0 / 17f32.sqrt()).abs() <= EXACT && !found.inside);
    assert!(close(
        found.normal,
        Vec3::new(-1.0, 4.0, 0.0) / 17f32.sqrt(),
        EXACT
    ));
    let found = project(ramp(), origin, Vec3::new(0.0, 0.5, 0.0), EXACT);
    assert!(found.inside && (found.distance + 2.0 / 17f32.sqrt()).abs() <= EXACT);
    assert!(close(
        found.normal,
        Vec3::new(-1.0, 4.0, 0.0) / 17f32.sqrt(),
        EXACT
    ));
}

#[test]
fn point_projection_ranks_cuts_off_and_filters() {
    let mut world = world();
    let near = world
        .add_body(BodyDesc::static_body(cube(0.5)).position(Vec3::new(3.0, 0.0, 0.0)))
        .unwrap();
    let twin = world
        .add_body(BodyDesc::static_body(cube(0.5)).position(Vec3::new(-3.0, 0.0, 0.0)))
        .unwrap();
    let far = world
        .add_body(BodyDesc::dynamic(sphere(1.0)).position(Vec3::new(0.0, 100.0, 0.0)))
        .unwrap();
    let all = QueryFilter::new();
    let nearest = |point, limit, filter: &QueryFilter| {
        world
            .project_point(point, limit, filter)
            .unwrap()
            .map(|found| (found.body, found.distance))
    };
    // Equally near: the smaller handle.
    assert_eq!(nearest(Vec3::ZERO, f32::INFINITY, &all), Some((near, 2.5)));
    assert_eq!(nearest(Vec3::ZERO, 2.5, &all), Some((near, 2.5)));
    assert_eq!(nearest(Vec3::ZERO, 2.4, &all), None);
    let skip = [near];
    let filter = QueryFilter::new().exclude_bodies(&skip);
    assert_eq!(
        nearest(Vec3::ZERO, f32::INFINITY, &filter),
        Some((twin, 2.5))
    );
    // Found by the widening search, 99 m away.
    let filter = QueryFilter::new().only_type(BodyType::Dynamic);
    assert_eq!(
        nearest(Vec3::ZERO, f32::INFINITY, &filter),
        Some((far, 99.0))
    );
    // Inside a body wins over every body outside.
    for limit in [f32::INFINITY, 0.0] {
        let (body, distance) = nearest(Vec3::new(-3.2, 0.0, 0.0), limit, &all).unwrap();
        assert!(body == twin && (distance + 0.3).abs() <= EXACT);
    }
}

#[test]
fn world_distances_between_bodies() {
    let mut world = world();
    let a = world.add_body(BodyDesc::static_body(cube(1.0))).unwrap();
    let b = world
        .add_body(BodyDesc::dynamic(sphere(0.5)).position(Vec3::new(0.0, 0.0, 4.0)))
        .unwrap();
    assert!((world.distance(a, b).unwrap() - 2.5).abs() <= EXACT);
    let found = world.closest_points(b, a, 10.0).unwrap();
    let (point_a, point_b, normal, _) = separated(found, EXACT);
    assert_eq!(normal, Vec3::NEG_Z);
    assert!(close(point_a, Vec3::new(0.0, 0.0, 3.5), EXACT) && close(point_b, Vec3::Z, EXACT));
    assert_eq!(
        world.closest_points(a, b, 1.0).unwrap(),
        ClosestPoints::Beyond
    );
    world.remove_body(b).unwrap();
    let error = world.closest_points(a, b, 1.0).unwrap_err();
    assert_eq!(
        (error.field.as_str(), error.kind),
        ("body_b", ErrorKind::StaleHandle)
    );
}

#[test]
fn bad_inputs_are_errors_naming_the_field() {
    let (a, b) = (sphere(1.0), cube(1.0));
    let origin = at(0.0, 0.0, 0.0);
    let field = |result: rebond::Result<ClosestPoints>| result.unwrap_err().field;
    let nan = at(f32::NAN, 0.0, 0.0);
    assert_eq!(
        field(closest_points(&a, &nan, &b, &origin, 1.0)),
        "pose_a.position"
    );
    assert_eq!(
        field(closest_points(&a, &origin, &b, &nan, 1.0)),
        "pose_b.position"
    );
    let zero = Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 0.0));
    assert_eq!(
        field(closest_points(&a, &zero, &b, &origin, 1.0)),
        "pose_a.rotation"
    );
    assert_eq!(
        field(closest_points(&a, &origin, &b, &origin, -1.0)),
        "max_distance"
    );
    assert_eq!(
        field(closest_points(&a, &origin, &b, &origin, f32::NAN)),
        "max_distance"
    );
    let (world, body) = world_of(a, origin);
    let all = QueryFilter::new();
    let error = world.project_point(Vec3::NAN, 1.0, &all).unwrap_err();
    assert_eq!(
        (error.field.as_str(), error.kind),
        ("point", ErrorKind::NotFinite)
    );
    let error = world.project_point(Vec3::ZERO, -1.0, &all).unwrap_err();
    assert_eq!(error.field, "max_distance");
    let error = world.closest_points(body, body, f32::NAN).unwrap_err();
    assert_eq!(error.field, "max_distance");
    let foreign = [world_of(sphere(1.0), origin).1];
    let filter = QueryFilter::new().exclude_bodies(&foreign);
    let error = world.project_point(Vec3::ZERO, 1.0, &filter).unwrap_err();
    assert_eq!(error.field, "excluded_bodies[0]");
}

/// Random pairs of spheres, boxes, capsules and hulls (cylinders are measured rounded but
/// projected sharp, so they are left out): the signed distance agrees with the overlap query,
/// and each closest point lies on its shape's surface (its projection there is within `GJK`).
#[test]
fn random_pairs_agree_with_overlaps_and_lie_on_the_surfaces() {
    let mut random = Random(0xc105e);
    let kinds = [0, 1, 2, 4];
    for case in 0..400 {
        let shape_a = random.convex_shape(kinds[case % 4]);
        let shape_b = random.convex_shape(kinds[(case / 4) % 4]);
        let (pose_a, pose_b) = (random.pose(1.5), random.pose(1.5));
        let found = closest_points(&shape_a, &pose_a, &shape_b, &pose_b, f32::INFINITY).unwrap();
        let signed = found.distance().unwrap();
        let (world, a) = world_of(shape_a.clone(), pose_a);
        let mut overlapping = Vec::new();
        let all = QueryFilter::new();
        world
            .bodies_overlapping_shape(&shape_b, &pose_b, &all, &mut overlapping)
            .unwrap();
        // Within GJK's tolerance of touching, either answer is right.
        if signed.abs() > GJK {
            assert_eq!(overlapping == [a], signed < 0.0, "case {case}: {found:?}");
        }
        let (point_a, point_b, _, _) = answer(found, signed > 0.0, GJK);
        let on_a = world.project_point(point_a, f32::INFINITY, &all).unwrap();
        assert!(
            on_a.unwrap().distance.abs() <= GJK,
            "case {case}: {found:?}"
        );
        let (world_b, _) = world_of(shape_b, pose_b);
        let on_b = world_b.project_point(point_b, f32::INFINITY, &all).unwrap();
        assert!(
            on_b.unwrap().distance.abs() <= GJK,
            "case {case}: {found:?}"
        );
    }
}
