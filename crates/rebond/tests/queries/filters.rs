//! Query filters, ties between equally near hits, sleeping bodies and input validation.

use super::*;

#[test]
fn filters_pick_bodies_by_handle_type_and_predicate() {
    let mut world = world();
    let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let at = |x: f32| Vec3::new(x, 0.0, 0.0);
    let fixed = world
        .add_body(BodyDesc::static_body(cube()).position(at(2.0)))
        .unwrap();
    let moving = world
        .add_body(BodyDesc::dynamic(cube()).position(at(4.0)))
        .unwrap();
    let pushed = world
        .add_body(BodyDesc::kinematic(cube()).position(at(6.0)))
        .unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let first = |filter: &QueryFilter| world.cast_ray(&ray, filter).unwrap().map(|hit| hit.body);
    assert_eq!(first(&QueryFilter::new()), Some(fixed));
    assert_eq!(
        first(&QueryFilter::new().exclude_bodies(&[fixed])),
        Some(moving)
    );
    assert_eq!(
        first(&QueryFilter::new().exclude_bodies(&[fixed, moving])),
        Some(pushed)
    );
    assert_eq!(
        first(&QueryFilter::new().exclude_bodies(&[fixed, moving, pushed])),
        None
    );
    assert_eq!(
        first(&QueryFilter::new().exclude_type(BodyType::Static)),
        Some(moving)
    );
    assert_eq!(
        first(&QueryFilter::new().only_type(BodyType::Kinematic)),
        Some(pushed)
    );
    assert_eq!(
        first(&QueryFilter::new().only_type(BodyType::Static)),
        Some(fixed)
    );
    let heavy = |_: BodyHandle, body: &RigidBody| body.mass() > 0.0;
    assert_eq!(first(&QueryFilter::new().predicate(&heavy)), Some(moving));
    let last = |handle: BodyHandle, _: &RigidBody| handle == pushed;
    assert_eq!(first(&QueryFilter::new().predicate(&last)), Some(pushed));

    let mut hits = Vec::new();
    world
        .cast_ray_all(
            &ray,
            &QueryFilter::new().exclude_type(BodyType::Dynamic),
            &mut hits,
        )
        .unwrap();
    assert_eq!(
        hits.iter().map(|hit| hit.body).collect::<Vec<_>>(),
        [fixed, pushed]
    );
    assert!(!world
        .cast_ray_any(
            &ray,
            &QueryFilter::new().exclude_bodies(&[fixed, moving, pushed])
        )
        .unwrap());
    let mut found = Vec::new();
    let everything = Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0));
    world
        .bodies_overlapping_aabb(
            &everything,
            &QueryFilter::new().predicate(&heavy),
            &mut found,
        )
        .unwrap();
    assert_eq!(found, [moving]);
    world
        .bodies_containing_point(
            at(6.0),
            &QueryFilter::new().exclude_type(BodyType::Kinematic),
            &mut found,
        )
        .unwrap();
    assert!(found.is_empty());
    let sweep = world
        .cast_shape(
            &cube(),
            &Pose::IDENTITY,
            Vec3::X,
            10.0,
            &QueryFilter::new().only_type(BodyType::Dynamic),
        )
        .unwrap()
        .unwrap();
    assert_eq!(sweep.body, moving);
}

#[test]
fn equally_near_hits_go_to_the_smaller_handle_and_sleeping_bodies_count() {
    let mut world = world();
    let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let handles: Vec<_> = (0..4)
        .map(|_| {
            world
                .add_body(BodyDesc::static_body(cube()).position(Vec3::new(3.0, 0.0, 0.0)))
                .unwrap()
        })
        .collect();
    world.remove_body(handles[0]).unwrap();
    let reused = world
        .add_body(BodyDesc::static_body(cube()).position(Vec3::new(3.0, 0.0, 0.0)))
        .unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let hit = world.cast_ray(&ray, &QueryFilter::new()).unwrap().unwrap();
    let smallest = *[handles[1], handles[2], handles[3], reused]
        .iter()
        .min()
        .unwrap();
    assert_eq!(hit.body, smallest);
    let mut hits = Vec::new();
    world
        .cast_ray_all(&ray, &QueryFilter::new(), &mut hits)
        .unwrap();
    let mut expected = vec![handles[1], handles[2], handles[3], reused];
    expected.sort();
    assert_eq!(
        hits.iter().map(|hit| hit.body).collect::<Vec<_>>(),
        expected
    );
    let sweep = world
        .cast_shape(
            &Shape::sphere(0.25).unwrap(),
            &Pose::IDENTITY,
            Vec3::X,
            10.0,
            &QueryFilter::new(),
        )
        .unwrap()
        .unwrap();
    assert_eq!(sweep.body, smallest);

    // A box resting on the ground falls asleep and is still found.
    let mut world = self::world();
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0)).unwrap())
                .position(Vec3::new(0.0, -0.5, 0.0)),
        )
        .unwrap();
    let sleeper = world
        .add_body(BodyDesc::dynamic(cube()).position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert!(world.body(sleeper).unwrap().is_sleeping());
    let down = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y);
    let hit = world.cast_ray(&down, &QueryFilter::new()).unwrap().unwrap();
    assert_eq!(hit.body, sleeper);
    assert!((hit.distance - 4.0).abs() < 0.01);
    let mut found = Vec::new();
    world
        .bodies_containing_point(Vec3::new(0.0, 0.5, 0.0), &QueryFilter::new(), &mut found)
        .unwrap();
    assert_eq!(found, [sleeper]);
}

#[test]
fn bad_inputs_are_errors_naming_the_field() {
    let mut world = world();
    world
        .add_body(BodyDesc::static_body(Shape::sphere(1.0).unwrap()))
        .unwrap();
    let filter = QueryFilter::new();
    let ray = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y);
    let error = |ray: Ray| {
        let error = world.cast_ray(&ray, &filter).unwrap_err();
        assert_eq!(world.cast_ray_any(&ray, &filter).unwrap_err(), error);
        let mut hits = vec![RayHit {
            body: world.bodies().next().unwrap().0,
            collider: 0,
            triangle: None,
            point: Vec3::ZERO,
            normal: Vec3::X,
            distance: 0.0,
        }];
        assert_eq!(
            world.cast_ray_all(&ray, &filter, &mut hits).unwrap_err(),
            error
        );
        assert!(hits.is_empty());
        (error.field, error.kind)
    };
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    assert_eq!(
        error(Ray { origin: nan, ..ray }),
        ("origin".into(), ErrorKind::NotFinite)
    );
    assert_eq!(
        error(Ray {
            direction: Vec3::ZERO,
            ..ray
        }),
        ("direction".into(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        error(Ray {
            direction: Vec3::splat(1e-30),
            ..ray
        }),
        ("direction".into(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        error(Ray {
            direction: Vec3::INFINITY,
            ..ray
        }),
        ("direction".into(), ErrorKind::NotFinite)
    );
    assert_eq!(
        error(ray.max_distance(-1.0)),
        ("max_distance".into(), ErrorKind::Negative(-1.0))
    );
    assert_eq!(
        error(ray.max_distance(f32::NAN)),
        ("max_distance".into(), ErrorKind::NotFinite)
    );
    assert!(world
        .cast_ray(&ray.max_distance(0.0), &filter)
        .unwrap()
        .is_none());
    assert!(world
        .cast_ray(
            &Ray {
                direction: Vec3::NEG_Y * 1e-20,
                ..ray
            },
            &filter
        )
        .unwrap()
        .is_some());

    let ball = Shape::sphere(0.5).unwrap();
    let cast_error = |pose: Pose, direction: Vec3, max: f32| {
        let error = world
            .cast_shape(&ball, &pose, direction, max, &filter)
            .unwrap_err();
        (error.field, error.kind)
    };
    let above = Pose::from_position(Vec3::new(0.0, 5.0, 0.0));
    assert_eq!(
        cast_error(
            Pose {
                position: nan,
                ..above
            },
            Vec3::Y,
            1.0
        )
        .0,
        "pose.position"
    );
    let zero_rotation = Pose {
        rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
        ..above
    };
    assert_eq!(
        cast_error(zero_rotation, Vec3::Y, 1.0),
        ("pose.rotation".into(), ErrorKind::ZeroQuaternion)
    );
    let nan_rotation = Pose {
        rotation: Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0),
        ..above
    };
    assert_eq!(
        cast_error(nan_rotation, Vec3::Y, 1.0),
        ("pose.rotation".into(), ErrorKind::NotFinite)
    );
    assert_eq!(
        cast_error(above, Vec3::ZERO, 1.0),
        ("direction".into(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        cast_error(above, Vec3::Y, -2.0),
        ("max_distance".into(), ErrorKind::Negative(-2.0))
    );
    // An unnormalised rotation is normalised, an unnormalised direction too.
    let scaled = Pose {
        rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 3.0),
        ..above
    };
    let hit = world
        .cast_shape(&ball, &scaled, Vec3::NEG_Y * 7.0, f32::INFINITY, &filter)
        .unwrap()
        .unwrap();
    assert!((hit.distance - 3.5).abs() < 1e-4);

    let mut found = vec![world.bodies().next().unwrap().0];
    let point_error = world
        .bodies_containing_point(nan, &filter, &mut found)
        .unwrap_err();
    assert_eq!((point_error.field.as_str(), found.len()), ("point", 0));
    let inverted = Aabb::new(Vec3::new(0.0, 2.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let aabb_error = world
        .bodies_overlapping_aabb(&inverted, &filter, &mut found)
        .unwrap_err();
    assert_eq!(aabb_error.field, "aabb.min[1]");
    assert!(
        matches!(aabb_error.kind, ErrorKind::OutOfRange { value, max, .. } if value == 2.0 && max == 1.0)
    );
    let open = Aabb::new(Vec3::ZERO, Vec3::new(f32::INFINITY, 1.0, 1.0));
    assert_eq!(
        world
            .bodies_overlapping_aabb(&open, &filter, &mut found)
            .unwrap_err()
            .field,
        "aabb.max[0]"
    );
    let shape_error = world
        .bodies_overlapping_shape(&ball, &zero_rotation, &filter, &mut found)
        .unwrap_err();
    assert_eq!(shape_error.field, "pose.rotation");
}
