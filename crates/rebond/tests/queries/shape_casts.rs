//! Shape casts against closed-form times of impact, landings on a floor, starts in contact.

use super::*;
use rebond::ShapeHit;

/// When a ball of `radius` whose centre moves along `o + t d` (box frame, unit `d`) first
/// touches the box of half extents `half`: the ray against the box rounded by the radius, the
/// union of the box grown along each axis, a cylinder on each edge and a ball on each corner.
fn ball_box_time_of_impact(o: DVec3, d: DVec3, half: DVec3, radius: f64) -> Option<f64> {
    let mut crossing = None;
    for axis in 0..3 {
        let mut grown = half;
        grown[axis] += radius;
        let slabs = (0..3).try_fold((f64::NEG_INFINITY, f64::INFINITY), |slabs, k| {
            intersection(
                Some(slabs),
                line_slab(o, d, DVec3::ZERO, DVec3::AXES[k], grown[k]),
            )
        });
        crossing = union(crossing, slabs);
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for (su, sv) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
            let mut centre = DVec3::ZERO;
            centre[u] = su * half[u];
            centre[v] = sv * half[v];
            let edge = intersection(
                line_tube(o, d, centre, DVec3::AXES[axis], radius),
                line_slab(o, d, centre, DVec3::AXES[axis], half[axis]),
            );
            crossing = union(crossing, edge);
        }
    }
    for corner in 0..8 {
        let signs = DVec3::new(
            if corner & 1 == 0 { -1.0 } else { 1.0 },
            if corner & 2 == 0 { -1.0 } else { 1.0 },
            if corner & 4 == 0 { -1.0 } else { 1.0 },
        );
        crossing = union(crossing, line_ball(o, d, signs * half, radius));
    }
    ray_answer(crossing, true)
}

/// Classifies a shape cast from references evaluated on a target grown and shrunk by `GROW`.
fn expected_cast(grown: Option<f64>, shrunk: Option<f64>, exact: Option<f64>) -> Expected {
    match (grown, shrunk) {
        (None, _) => Expected::Miss,
        (Some(outer), Some(inner)) if (outer - inner).abs() < 1e-2 => {
            Expected::Hit(exact.unwrap_or(inner))
        }
        _ => Expected::Either,
    }
}

/// Checks a cast's answer against its reference: a sure miss must miss, a sure hit must hit
/// within `tolerance` of the reference time of impact and never more than 1e-5 past it. Returns
/// the hit when the reference is a sure hit, for the caller's further checks.
fn clear_hit(
    expected: Expected,
    hit: Option<ShapeHit>,
    tolerance: f64,
    what: &str,
) -> Option<ShapeHit> {
    match (expected, hit) {
        (Expected::Miss, Some(hit)) => panic!("should miss, got {hit:?}"),
        (Expected::Hit(t), None) => panic!("should hit at {t}"),
        (Expected::Hit(t), Some(hit)) => {
            let error = f64::from(hit.distance) - t;
            assert!(
                error.abs() <= tolerance,
                "time of impact {} instead of {t}",
                hit.distance
            );
            assert!(error <= 1e-5, "the {what} passes the contact by {error}");
            Some(hit)
        }
        _ => None,
    }
}

#[test]
fn a_sphere_swept_at_a_box_finds_the_closed_form_time_of_impact_within_1e_4() {
    let mut random = Random(0xba11);
    let mut compared = 0;
    for _ in 0..3000 {
        let half = random.vec3(0.2, 1.5);
        let mut world = world();
        let target = world
            .add_body(
                BodyDesc::static_body(Shape::cuboid(half).unwrap())
                    .position(random.vec3(-5.0, 5.0))
                    .rotation(random.rotation()),
            )
            .unwrap();
        let box_pose = world.body(target).unwrap().pose();
        let radius = random.range(0.1, 1.0);
        let start = box_pose.position + random.unit_vector() * random.range(4.0, 7.0);
        let aim = box_pose.position + random.vec3(-1.5, 1.5);
        let direction = (aim - start).normalize();
        let ball = Shape::sphere(radius).unwrap();
        let hit = world
            .cast_shape(
                &ball,
                &Pose::from_position(start),
                direction,
                f32::INFINITY,
                &QueryFilter::new(),
            )
            .unwrap();
        let (o, d) = to_local(&box_pose, start, direction);
        let half64 = to_f64(half);
        let reference = |grow: f64| ball_box_time_of_impact(o, d, half64, f64::from(radius) + grow);
        let expected = expected_cast(reference(GROW), reference(-GROW), reference(0.0));
        if let Some(hit) = clear_hit(expected, hit, 1e-4, "ball") {
            compared += 1;
            assert_eq!(hit.body, target);
            // The point is on the box, the normal points from it to the ball's centre.
            let centre = start + hit.distance * direction;
            let (local, _) = to_local(&box_pose, hit.point, Vec3::ZERO);
            let outside = (local.abs() - half64).max_element();
            assert!(outside.abs() < 1e-3, "point {local} off the box surface");
            let towards_centre = (centre - hit.point) / radius;
            assert!(
                hit.normal.dot(towards_centre) > 0.999,
                "normal {}",
                hit.normal
            );
        }
    }
    assert!(compared > 1500, "only {compared} clear hits");
}

#[test]
fn a_box_swept_at_a_box_finds_the_closed_form_time_of_impact_within_1e_3() {
    let mut random = Random(0xb0b0);
    let mut compared = 0;
    for _ in 0..3000 {
        let (half_a, half_b) = (random.vec3(0.1, 1.2), random.vec3(0.2, 1.5));
        let mut world = world();
        let target = world
            .add_body(
                BodyDesc::static_body(Shape::cuboid(half_b).unwrap())
                    .position(random.vec3(-5.0, 5.0))
                    .rotation(random.rotation()),
            )
            .unwrap();
        let pose_b = world.body(target).unwrap().pose();
        let pose_a = Pose::new(
            pose_b.position + random.unit_vector() * random.range(4.5, 8.0),
            random.rotation().normalize(),
        );
        let direction = (pose_b.position + random.vec3(-1.5, 1.5) - pose_a.position).normalize();
        let moving = Shape::cuboid(half_a).unwrap();
        let hit = world
            .cast_shape(
                &moving,
                &pose_a,
                direction,
                f32::INFINITY,
                &QueryFilter::new(),
            )
            .unwrap();
        let reference = |grow: f64| {
            box_box_time_of_impact(
                &pose_a,
                to_f64(half_a),
                &pose_b,
                to_f64(half_b) + grow,
                to_f64(direction),
            )
        };
        let expected = expected_cast(reference(GROW), reference(-GROW), reference(0.0));
        if let Some(hit) = clear_hit(expected, hit, 1e-3, "box") {
            assert!(
                hit.normal.dot(direction) < 0.0,
                "normal {} faces away",
                hit.normal
            );
            let moved = Pose::new(pose_a.position + hit.distance * direction, pose_a.rotation);
            // The contact plane separates the boxes, to within a few milliradians (GJK's
            // precision at the distance the normal is measured from).
            let target = Shape::cuboid(half_b).unwrap();
            let gaps = [
                outward_normal_gap(&target, &pose_b, hit.point, hit.normal),
                outward_normal_gap(&moving, &moved, hit.point, -hit.normal),
            ];
            assert!(
                gaps.iter().all(|&gap| gap <= 2.5e-3),
                "normal {hit:?}: {gaps:?}"
            );
            compared += 1;
        }
    }
    assert!(compared > 1500, "only {compared} clear hits");
}

#[test]
fn every_shape_dropped_on_a_floor_lands_on_its_lowest_point() {
    let mut random = Random(0xf100);
    let mut world = world();
    let floor = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(50.0, 1.0, 50.0)).unwrap())
                .position(Vec3::new(0.0, -1.0, 0.0)),
        )
        .unwrap();
    let ground = world
        .add_body(
            BodyDesc::static_body(Shape::halfspace(Vec3::Y).unwrap())
                .position(Vec3::new(0.0, -4.0, 0.0)),
        )
        .unwrap();
    let floor_only = [ground];
    let ground_only = [floor];
    for round in 0..300 {
        let shape = if round % 6 == 5 {
            random.compound()
        } else {
            random.convex_shape(round)
        };
        let pose = Pose::new(
            random.vec3(-5.0, 5.0) + Vec3::Y * 8.0,
            random.rotation().normalize(),
        );
        // Bounding boxes are exact for every shape kind: the box's floor is the lowest point.
        let lowest_y = shape.aabb(&pose).min.y;
        // Straight down onto the floor's top at y = 0, and through it (excluded) onto the ground.
        let down = Vec3::NEG_Y;
        let onto_floor = QueryFilter::new().exclude_bodies(&floor_only);
        let hit = world
            .cast_shape(&shape, &pose, down, 100.0, &onto_floor)
            .unwrap()
            .unwrap();
        assert_eq!(hit.body, floor);
        // GJK measures to 1e-5 of the problem's size, here the floor's 71 m half diagonal, and
        // the cast stays on the near side: it never sinks the shape into the floor.
        let error = hit.distance - lowest_y;
        assert!(
            error.abs() < 1e-5 * 71.0 && error < 1e-5,
            "{shape:?}: {error}"
        );
        assert!((hit.normal - Vec3::Y).length() < 3e-3, "{hit:?}");
        assert!(hit.point.y.abs() < 1e-3, "{hit:?}");
        let onto_ground = QueryFilter::new().exclude_bodies(&ground_only);
        let hit = world
            .cast_shape(&shape, &pose, down, 100.0, &onto_ground)
            .unwrap()
            .unwrap();
        assert_eq!((hit.body, hit.normal), (ground, Vec3::Y));
        assert!((hit.distance - lowest_y - 4.0).abs() < 1e-4);
        // Not far enough.
        assert_eq!(
            world
                .cast_shape(&shape, &pose, down, lowest_y - 0.01, &onto_floor)
                .unwrap(),
            None
        );
        // Sideways, nothing is in the way.
        assert_eq!(
            world
                .cast_shape(&shape, &pose, Vec3::X, 100.0, &onto_floor)
                .unwrap(),
            None
        );
    }
}

#[test]
fn shape_casts_starting_in_contact_halfspaces_and_the_nearest_body() {
    let mut world = world();
    let block = world
        .add_body(BodyDesc::static_body(
            Shape::cuboid(Vec3::splat(1.0)).unwrap(),
        ))
        .unwrap();
    let far_block = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(1.0)).unwrap())
                .position(Vec3::new(10.0, 0.0, 0.0)),
        )
        .unwrap();
    let filter = QueryFilter::new();

    // Overlapping from the start: distance zero, the normal pushing the ball out of the block.
    let ball = Shape::sphere(0.5).unwrap();
    let inside = Pose::from_position(Vec3::new(0.8, 0.1, 0.0));
    let hit = world
        .cast_shape(&ball, &inside, Vec3::X, 5.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.distance), (block, 0.0));
    assert!(hit.normal.x > 0.99, "{hit:?}");
    let deep = Shape::cuboid(Vec3::splat(0.2)).unwrap();
    let hit = world
        .cast_shape(
            &deep,
            &Pose::from_position(Vec3::new(0.0, 0.7, 0.0)),
            Vec3::X,
            5.0,
            &filter,
        )
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.distance), (block, 0.0));
    assert!(hit.normal.y > 0.99, "{hit:?}");

    // The nearest of two bodies in the way, then the far one once the near one is excluded.
    let start = Pose::from_position(Vec3::new(-5.0, 0.0, 0.0));
    let hit = world
        .cast_shape(&ball, &start, Vec3::X, f32::INFINITY, &filter)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, block);
    assert!(
        (hit.distance - 3.5).abs() < 1e-4
            && (hit.point - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-3
    );
    let skip = [block];
    let hit = world
        .cast_shape(
            &ball,
            &start,
            Vec3::X,
            f32::INFINITY,
            &QueryFilter::new().exclude_bodies(&skip),
        )
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, far_block);
    assert!((hit.distance - 13.5).abs() < 1e-4);
    assert_eq!(
        world
            .cast_shape(
                &ball,
                &start,
                Vec3::X,
                13.0,
                &QueryFilter::new().exclude_bodies(&skip)
            )
            .unwrap(),
        None
    );

    // A halfspace swept down onto the block, and a halfspace swept at a facing one.
    let ceiling = Shape::halfspace(Vec3::NEG_Y).unwrap();
    let above = Pose::from_position(Vec3::new(0.0, 4.0, 0.0));
    let hit = world
        .cast_shape(&ceiling, &above, Vec3::NEG_Y, 10.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, block);
    assert!((hit.distance - 3.0).abs() < 1e-5 && hit.normal == Vec3::Y && hit.point.y == 1.0);
    let floor = world
        .add_body(
            BodyDesc::static_body(Shape::halfspace(Vec3::Y).unwrap())
                .position(Vec3::new(0.0, -20.0, 0.0)),
        )
        .unwrap();
    let only_floor = QueryFilter::new()
        .only_type(BodyType::Static)
        .exclude_bodies(&skip);
    let hit = world
        .cast_shape(&ceiling, &above, Vec3::NEG_Y, 100.0, &only_floor)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.normal), (floor, Vec3::Y));
    assert!((hit.distance - 24.0).abs() < 1e-4);
    let tilted = Shape::halfspace(Vec3::new(1.0, -1.0, 0.0)).unwrap();
    let hit = world
        .cast_shape(&tilted, &above, Vec3::Y, 100.0, &only_floor)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.distance), (floor, 0.0));

    // A compound of two balls: its lower ball lands first.
    let dumbbell = Shape::compound(vec![
        CompoundChild::new(
            Shape::sphere(0.25).unwrap(),
            Pose::from_position(Vec3::new(0.0, -1.0, 0.0)),
        ),
        CompoundChild::new(
            Shape::sphere(0.5).unwrap(),
            Pose::from_position(Vec3::new(0.0, 1.0, 0.0)),
        ),
    ])
    .unwrap();
    let hit = world
        .cast_shape(&dumbbell, &above, Vec3::NEG_Y, 100.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, block);
    assert!((hit.distance - 1.75).abs() < 1e-4, "{hit:?}");
}
