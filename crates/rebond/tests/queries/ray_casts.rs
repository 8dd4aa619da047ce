//! Ray casts against the references: every shape, scenes, distance limits, solid and hollow rays,
//! and the tree walk.

use super::*;

#[test]
fn ray_casts_match_closed_forms_and_brute_force_for_every_shape() {
    let mut random = Random(0xa11ce);
    let kinds = [
        "sphere",
        "box",
        "capsule",
        "cylinder",
        "hull",
        "compound",
        "halfspace",
    ];
    for (kind, label) in kinds.iter().enumerate() {
        let mut clear_hits = 0;
        let mut rays = 0;
        for _ in 0..10 {
            let shape = match kind {
                0..=4 => random.convex_shape(kind),
                5 => random.compound(),
                _ => Shape::halfspace(random.unit_vector()).unwrap(),
            };
            let pose = random.pose(3.0);
            let mut world = world();
            let body = world
                .add_body(
                    BodyDesc::static_body(shape.clone())
                        .position(pose.position)
                        .rotation(pose.rotation),
                )
                .unwrap();
            let pose = world.body(body).unwrap().pose();
            for _ in 0..500 {
                let size = shape.aabb(&pose).half_extents().max_element().min(1.5);
                let ray = random_ray(&mut random, pose.position, size);
                let hit = world.cast_ray(&ray, &QueryFilter::new()).unwrap();
                if let Some(hit) = hit {
                    assert_eq!(hit.body, body);
                }
                rays += 1;
                if matches!(expected_ray(&shape, &pose, &ray), Expected::Hit(_)) {
                    clear_hits += 1;
                }
                if let Shape::Compound(compound) = &shape {
                    check_compound_hit(compound.children(), &pose, &ray, hit, label);
                } else {
                    check_convex_hit(&shape, &pose, &ray, hit, label);
                }
            }
        }
        assert!(
            clear_hits * 4 > rays,
            "{label}: only {clear_hits} of {rays} rays hit clearly"
        );
    }
}

/// A compound: the distance against the brute-force reference; the normal against the child
/// hit when one child is clearly nearer than the others.
fn check_compound_hit(
    children: &[CompoundChild],
    pose: &Pose,
    ray: &Ray,
    hit: Option<RayHit>,
    label: &str,
) {
    let compound = Shape::compound(children.to_vec()).unwrap();
    let direction = ray.direction.normalize();
    match (expected_ray(&compound, pose, ray), hit) {
        (Expected::Miss, Some(hit)) => panic!("{label}: {ray:?} should miss, got {hit:?}"),
        (Expected::Hit(t), None) => panic!("{label}: {ray:?} should hit at {t}"),
        (Expected::Hit(t), Some(hit)) => {
            assert!(
                (f64::from(hit.distance) - t).abs() <= 1e-4 * (1.0 + t),
                "{label}: {ray:?} hit at {} instead of {t}",
                hit.distance
            );
            let mut by_child: Vec<(f64, usize)> = children
                .iter()
                .enumerate()
                .filter_map(|(index, child)| {
                    reference_ray(&child.shape, &pose.mul_pose(&child.pose), ray, 0.0)
                        .map(|t| (t, index))
                })
                .collect();
            by_child.sort_by(|a, b| a.0.total_cmp(&b.0));
            let clearly_first = by_child.len() == 1 || by_child[1].0 - by_child[0].0 > 1e-3;
            if clearly_first && !(hit.distance == 0.0 && ray.solid) {
                let child = &children[by_child[0].1];
                let child_pose = pose.mul_pose(&child.pose);
                let entering = hit.normal.dot(direction) <= 0.0
                    && is_outward_normal(&child.shape, &child_pose, hit.point, hit.normal);
                let leaving = !ray.solid
                    && is_outward_normal(&child.shape, &child_pose, hit.point, -hit.normal);
                assert!(
                    entering || leaving,
                    "{label}: {ray:?} got normal {} at {}",
                    hit.normal,
                    hit.point
                );
            }
        }
        _ => {}
    }
}

#[test]
fn scene_ray_casts_find_every_body_brute_force_finds() {
    let mut random = Random(0x5ce4e);
    let mut world = world();
    let mut bodies: Vec<(BodyHandle, Shape, Pose)> = Vec::new();
    let ground = Shape::halfspace(Vec3::Y).unwrap();
    let handle = world
        .add_body(BodyDesc::static_body(ground.clone()).position(Vec3::new(0.0, -12.0, 0.0)))
        .unwrap();
    bodies.push((handle, ground, world.body(handle).unwrap().pose()));
    for index in 0..400 {
        let shape = if index % 6 == 5 {
            random.compound()
        } else {
            random.convex_shape(index)
        };
        let body_type = [BodyType::Static, BodyType::Dynamic, BodyType::Kinematic][index % 3];
        let pose = random.pose(10.0);
        let handle = world
            .add_body(
                BodyDesc::new(body_type, shape.clone())
                    .position(pose.position)
                    .rotation(pose.rotation),
            )
            .unwrap();
        bodies.push((handle, shape, world.body(handle).unwrap().pose()));
    }
    let (mut all, mut total_hits) = (Vec::new(), 0);
    for _ in 0..2000 {
        let origin = random.vec3(-14.0, 14.0);
        let mut ray = Ray::new(origin, random.unit_vector());
        ray.solid = random.chance(0.5);
        if random.chance(0.5) {
            ray.max_distance = random.range(2.0, 30.0);
        }
        let filter = QueryFilter::new();
        world.cast_ray_all(&ray, &filter, &mut all).unwrap();
        let nearest = world.cast_ray(&ray, &filter).unwrap();
        assert_eq!(nearest, all.first().copied(), "{ray:?}");
        assert_eq!(world.cast_ray_any(&ray, &filter).unwrap(), !all.is_empty());
        for pair in all.windows(2) {
            assert!((pair[0].distance, pair[0].body) < (pair[1].distance, pair[1].body));
        }
        total_hits += all.len();
        for (handle, shape, pose) in &bodies {
            let found = all.iter().find(|hit| hit.body == *handle);
            match (expected_ray(shape, pose, &ray), found) {
                (Expected::Miss, Some(hit)) => panic!("{ray:?} should miss {shape:?}: {hit:?}"),
                (Expected::Hit(t), None) => panic!("{ray:?} should hit {shape:?} at {t}"),
                (Expected::Hit(t), Some(hit)) => {
                    assert!((f64::from(hit.distance) - t).abs() <= 1e-4 * (1.0 + t));
                }
                _ => {}
            }
        }
    }
    assert!(total_hits > 1000, "only {total_hits} hits");
}

#[test]
fn ray_distance_limit_solid_and_hollow_rays() {
    let mut world = world();
    let wall = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::splat(1.0)).unwrap())
                .position(Vec3::new(6.0, 0.0, 0.0)),
        )
        .unwrap();
    let ball = world
        .add_body(BodyDesc::static_body(Shape::sphere(1.0).unwrap()))
        .unwrap();
    let ground = world
        .add_body(
            BodyDesc::static_body(Shape::halfspace(Vec3::Y).unwrap())
                .position(Vec3::new(0.0, -5.0, 0.0)),
        )
        .unwrap();
    let filter = QueryFilter::new();
    let toward_wall = Ray::new(Vec3::new(2.0, 0.0, 0.0), Vec3::X * 3.0);
    assert_eq!(
        world
            .cast_ray(&toward_wall.max_distance(2.9), &filter)
            .unwrap(),
        None
    );
    for limit in [3.0, 3.1, f32::INFINITY] {
        let hit = world
            .cast_ray(&toward_wall.max_distance(limit), &filter)
            .unwrap()
            .unwrap();
        assert_eq!(
            (hit.body, hit.distance, hit.normal),
            (wall, 3.0, Vec3::NEG_X)
        );
        assert_eq!(hit.point, Vec3::new(5.0, 0.0, 0.0));
    }

    // From the ball's centre: solid hits the ball at once, hollow where it leaves it.
    let from_inside = Ray::new(Vec3::ZERO, Vec3::X);
    let solid = world.cast_ray(&from_inside, &filter).unwrap().unwrap();
    assert_eq!(
        (solid.body, solid.distance, solid.point, solid.normal),
        (ball, 0.0, Vec3::ZERO, Vec3::NEG_X)
    );
    let hollow = world
        .cast_ray(&from_inside.hollow(), &filter)
        .unwrap()
        .unwrap();
    assert_eq!(
        (hollow.body, hollow.distance, hollow.normal),
        (ball, 1.0, Vec3::NEG_X)
    );
    let mut hits = Vec::new();
    world
        .cast_ray_all(&from_inside.hollow(), &filter, &mut hits)
        .unwrap();
    let bodies: Vec<_> = hits.iter().map(|hit| (hit.body, hit.distance)).collect();
    assert_eq!(bodies, [(ball, 1.0), (wall, 5.0)]);

    // Below the ground: a hollow ray going deeper never leaves it, one going up leaves it.
    let under = Vec3::new(0.0, -7.0, 0.0);
    let down = Ray::new(under, Vec3::NEG_Y);
    assert_eq!(
        world.cast_ray(&down, &filter).unwrap().unwrap().distance,
        0.0
    );
    assert_eq!(world.cast_ray(&down.hollow(), &filter).unwrap(), None);
    let up = world
        .cast_ray(&Ray::new(under, Vec3::Y).hollow(), &filter)
        .unwrap()
        .unwrap();
    assert_eq!(
        (up.body, up.distance, up.normal),
        (ground, 2.0, Vec3::NEG_Y)
    );
}

#[test]
fn tree_casts_visit_exactly_the_boxes_on_the_path_nearest_first() {
    let mut random = Random(0x7ee);
    let mut tree = DynamicTree::new();
    let proxies: Vec<_> = (0..600)
        .map(|index| {
            let centre = random.vec3(-20.0, 20.0);
            tree.create_proxy(
                Aabb::from_center_half_extents(centre, random.vec3(0.1, 1.5)),
                index,
            )
        })
        .collect();
    // The entry of a ray into a box in f64, for a box grown by `grow` on every side.
    let entry = |origin: Vec3, direction: Vec3, max: f32, aabb: &Aabb, grow: f64| {
        let (o, d) = (to_f64(origin), to_f64(direction));
        let (min, max_corner) = (to_f64(aabb.min) - grow, to_f64(aabb.max) + grow);
        let (mut enter, mut leave) = (0.0_f64, f64::from(max));
        for axis in 0..3 {
            if d[axis] == 0.0 {
                if o[axis] < min[axis] || o[axis] > max_corner[axis] {
                    return None;
                }
                continue;
            }
            let (t1, t2) = (
                (min[axis] - o[axis]) / d[axis],
                (max_corner[axis] - o[axis]) / d[axis],
            );
            enter = enter.max(t1.min(t2));
            leave = leave.min(t1.max(t2));
        }
        (enter <= leave).then_some(enter)
    };
    for round in 0..600 {
        let origin = random.vec3(-25.0, 25.0);
        let mut direction = random.unit_vector();
        if round % 10 == 0 {
            direction[round / 10 % 3] = 0.0;
            direction = direction.normalize();
        }
        let max = if round % 2 == 0 {
            f32::INFINITY
        } else {
            random.range(0.0, 40.0)
        };
        let swept = Aabb::from_center_half_extents(origin, random.vec3(0.0, 1.0));
        let is_box_cast = round % 3 == 0;
        let mut visited = Vec::new();
        let record = |proxy, entry_distance| {
            visited.push((proxy, entry_distance));
            ControlFlow::Continue(f32::INFINITY)
        };
        if is_box_cast {
            tree.box_cast(&swept, direction, max, record);
        } else {
            tree.ray_cast(origin, direction, max, record);
        }
        let grown_by = if is_box_cast {
            swept.half_extents()
        } else {
            Vec3::ZERO
        };
        for &proxy in &proxies {
            let fat = tree.fat_aabb(proxy);
            let fat = Aabb::new(fat.min - grown_by, fat.max + grown_by);
            let start = swept.center();
            let found = visited.iter().find(|(visited, _)| *visited == proxy);
            let inner = entry(start, direction, max, &fat, -1e-4);
            let outer = entry(start, direction, max, &fat, 1e-4);
            match (found, inner, outer) {
                (Some(_), _, None) => panic!("visited a box off the path"),
                (None, Some(_), _) => panic!("missed a box on the path"),
                (Some(&(_, distance)), Some(_), _) => {
                    let exact = entry(start, direction, max, &fat, 0.0).unwrap();
                    assert!((f64::from(distance) - exact).abs() < 1e-4 * (1.0 + exact));
                }
                _ => {}
            }
        }
        let nearest = visited
            .iter()
            .map(|&(_, distance)| distance)
            .reduce(f32::min);
        let mut closest = None;
        let mut first_calls = 0;
        tree.ray_cast(swept.center(), direction, max, |_, distance| {
            first_calls += 1;
            if !is_box_cast {
                closest = Some(closest.map_or(distance, |best: f32| best.min(distance)));
            }
            ControlFlow::Continue(distance)
        });
        if !is_box_cast {
            assert_eq!(closest, nearest);
        }
        let mut calls = 0;
        tree.ray_cast(swept.center(), direction, max, |_, _| {
            calls += 1;
            ControlFlow::Break(())
        });
        assert!(calls <= 1 && first_calls >= calls);
    }
}
