//! Point, box and shape overlaps against closed-form containment and distance.

use super::*;

/// Signed distance from `point` to a shape the overlap test has a closed form for (negative
/// inside), or `None`.
fn signed_distance(shape: &Shape, pose: &Pose, point: Vec3) -> Option<f64> {
    let (local, _) = to_local(pose, point, Vec3::ZERO);
    match shape {
        Shape::Sphere(sphere) => Some(local.length() - f64::from(sphere.radius())),
        Shape::Cuboid(cuboid) => {
            let outside = local.abs() - to_f64(cuboid.half_extents());
            Some(outside.max(DVec3::ZERO).length() + outside.max_element().min(0.0))
        }
        Shape::Capsule(capsule) => {
            let height = f64::from(capsule.half_height());
            let axis_point = DVec3::new(0.0, local.y.clamp(-height, height), 0.0);
            Some((local - axis_point).length() - f64::from(capsule.radius()))
        }
        Shape::Cylinder(cylinder) => {
            let radial = local.x.hypot(local.z) - f64::from(cylinder.radius());
            let axial = local.y.abs() - f64::from(cylinder.half_height());
            Some(radial.max(0.0).hypot(axial.max(0.0)) + radial.max(axial).min(0.0))
        }
        Shape::Halfspace(halfspace) => Some(local.dot(to_f64(halfspace.normal()))),
        Shape::ConvexHull(_) | Shape::Compound(_) | Shape::TriMesh(_) | Shape::HeightField(_) => {
            None
        }
    }
}

/// Signed distance from `point` to the surface that shape overlaps are measured on: the shape's
/// own, but for a cylinder, whose rims are rounded by its convex radius `r_c` there, the core
/// cylinder's (`r − r_c`, `h − r_c`) less `r_c`.
fn rounded_signed_distance(shape: &Shape, pose: &Pose, point: Vec3) -> Option<f64> {
    match shape {
        Shape::Cylinder(cylinder) => {
            let rounding = cylinder.convex_radius();
            let core = Shape::cylinder(
                cylinder.radius() - rounding,
                cylinder.half_height() - rounding,
            )
            .unwrap();
            signed_distance(&core, pose, point).map(|distance| distance - f64::from(rounding))
        }
        _ => signed_distance(shape, pose, point),
    }
}

/// The hull's own faces as a containment reference, with the face planes pushed out by `grow`.
fn hull_contains(shape: &Shape, pose: &Pose, point: Vec3, grow: f64) -> Option<bool> {
    let Shape::ConvexHull(hull) = shape else {
        return None;
    };
    let (local, _) = to_local(pose, point, Vec3::ZERO);
    Some(
        hull.faces()
            .iter()
            .all(|face| to_f64(face.normal).dot(local) <= f64::from(face.offset) + grow),
    )
}

/// The answer a reference gives for a yes-or-no test: sure yes, sure no, or too close to call.
fn classify(inside_shrunk: bool, inside_grown: bool) -> Option<bool> {
    match (inside_shrunk, inside_grown) {
        (true, _) => Some(true),
        (false, false) => Some(false),
        _ => None,
    }
}

fn random_scene(random: &mut Random, count: usize) -> (World, Vec<(BodyHandle, Shape, Pose)>) {
    let mut world = world();
    let mut bodies = Vec::new();
    for index in 0..count {
        let shape = match index % 7 {
            5 => random.compound(),
            6 if index % 21 == 6 => Shape::halfspace(random.unit_vector()).unwrap(),
            _ => random.convex_shape(index),
        };
        let pose = random.pose(6.0);
        let handle = world
            .add_body(
                BodyDesc::static_body(shape.clone())
                    .position(pose.position)
                    .rotation(pose.rotation),
            )
            .unwrap();
        bodies.push((handle, shape, world.body(handle).unwrap().pose()));
    }
    (world, bodies)
}

#[test]
fn point_box_and_shape_overlaps_match_closed_forms() {
    let mut random = Random(0x0e1a);
    let (world, bodies) = random_scene(&mut random, 120);
    let filter = QueryFilter::new();
    let mut found = Vec::new();
    let mut decided = 0;
    for _ in 0..3000 {
        let point = random.vec3(-8.0, 8.0);
        world
            .bodies_containing_point(point, &filter, &mut found)
            .unwrap();
        for (handle, shape, pose) in &bodies {
            let expected = match shape {
                Shape::ConvexHull(_) => classify(
                    hull_contains(shape, pose, point, -GROW).unwrap(),
                    hull_contains(shape, pose, point, GROW).unwrap(),
                ),
                Shape::Compound(compound) => {
                    let parts: Vec<_> = compound
                        .children()
                        .iter()
                        .map(|child| {
                            let child_pose = pose.mul_pose(&child.pose);
                            signed_distance(&child.shape, &child_pose, point).map_or_else(
                                || {
                                    let shrunk =
                                        hull_contains(&child.shape, &child_pose, point, -GROW);
                                    let grown =
                                        hull_contains(&child.shape, &child_pose, point, GROW);
                                    (shrunk.unwrap(), grown.unwrap())
                                },
                                |distance| (distance < -GROW, distance <= GROW),
                            )
                        })
                        .collect();
                    classify(
                        parts.iter().any(|part| part.0),
                        parts.iter().any(|part| part.1),
                    )
                }
                _ => {
                    let distance = signed_distance(shape, pose, point).unwrap();
                    classify(distance < -GROW, distance <= GROW)
                }
            };
            if let Some(inside) = expected {
                decided += 1;
                assert_eq!(found.contains(handle), inside, "{point} in {shape:?}");
            }
        }
    }
    assert!(decided > 3000 * 100);

    for _ in 0..500 {
        let aabb = Aabb::from_center_half_extents(random.vec3(-8.0, 8.0), random.vec3(0.0, 2.0));
        world
            .bodies_overlapping_aabb(&aabb, &filter, &mut found)
            .unwrap();
        let expected: Vec<_> = world
            .bodies()
            .filter(|(_, body)| body.aabb().overlaps(&aabb))
            .map(|(handle, _)| handle)
            .collect();
        assert_eq!(found, expected);
    }

    // A ball overlaps a body when its centre is within its radius of the body.
    let mut overlapping = 0;
    for _ in 0..2000 {
        let radius = random.range(0.05, 1.5);
        let centre = random.vec3(-8.0, 8.0);
        let ball = Shape::sphere(radius).unwrap();
        world
            .bodies_overlapping_shape(&ball, &Pose::from_position(centre), &filter, &mut found)
            .unwrap();
        overlapping += found.len();
        for (handle, shape, pose) in &bodies {
            let Some(distance) = rounded_signed_distance(shape, pose, centre) else {
                continue;
            };
            let gap = distance - f64::from(radius);
            if let Some(overlaps) = classify(gap < -GROW, gap <= GROW) {
                assert_eq!(
                    found.contains(handle),
                    overlaps,
                    "ball {centre} r {radius} vs {shape:?}"
                );
            }
        }
    }
    assert!(overlapping > 1000, "only {overlapping} overlaps");
}

#[test]
fn boxes_overlapping_boxes_match_the_separating_axis_test() {
    let mut random = Random(0x5a7);
    let mut world = world();
    let mut boxes = Vec::new();
    for _ in 0..150 {
        let half = random.vec3(0.1, 1.2);
        let handle = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid(half).unwrap())
                    .position(random.vec3(-6.0, 6.0))
                    .rotation(random.rotation()),
            )
            .unwrap();
        boxes.push((handle, half, world.body(handle).unwrap().pose()));
    }
    let mut found = Vec::new();
    let mut overlapping = 0;
    for _ in 0..1000 {
        let half = random.vec3(0.1, 1.5);
        let pose = Pose::new(random.vec3(-6.0, 6.0), random.rotation());
        let query = Shape::cuboid(half).unwrap();
        world
            .bodies_overlapping_shape(&query, &pose, &QueryFilter::new(), &mut found)
            .unwrap();
        overlapping += found.len();
        for &(handle, body_half, body_pose) in &boxes {
            // Travel zero along any direction: the boxes overlap where every axis says so.
            let reference = |grow: f64| {
                box_box_time_of_impact(
                    &pose,
                    to_f64(half),
                    &body_pose,
                    to_f64(body_half) + grow,
                    DVec3::X,
                )
                .is_some_and(|t| t == 0.0)
            };
            if let Some(overlaps) = classify(reference(-GROW), reference(GROW)) {
                assert_eq!(found.contains(&handle), overlaps);
            }
        }
    }
    assert!(overlapping > 500, "only {overlapping} overlaps");
}
