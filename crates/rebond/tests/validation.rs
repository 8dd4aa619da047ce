//! Every kind of bad construction returns an error naming the field, and leaves the world as it
//! was. No call panics on user input.

use rebond::shape::{Capsule, Compound, CompoundChild, Cuboid, Cylinder, Halfspace, Sphere};
use rebond::{
    limits, Aabb, BodyDesc, BodyType, ErrorKind, InteractionGroups, JointDesc, Motor, Pose, Quat,
    QueryFilter, Ray, Result, Shape, Vec3, World, WorldSettings,
};

fn field_of<T: std::fmt::Debug>(result: Result<T>) -> (String, ErrorKind) {
    let error = result.expect_err("expected an error");
    (error.field, error.kind)
}

fn unit_box() -> Shape {
    Shape::cuboid(Vec3::splat(0.5)).unwrap()
}

#[test]
fn shape_sizes_must_be_finite_and_positive() {
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(field_of(Sphere::new(bad)).0, "radius");
        assert_eq!(field_of(Capsule::new(bad, 1.0)).0, "radius");
        assert_eq!(field_of(Capsule::new(1.0, bad)).0, "half_height");
        assert_eq!(field_of(Cylinder::new(bad, 1.0)).0, "radius");
        assert_eq!(field_of(Cylinder::new(1.0, bad)).0, "half_height");
        assert_eq!(
            field_of(Cuboid::new(Vec3::new(1.0, 1.0, bad))).0,
            "half_extents[2]"
        );
    }
    assert_eq!(field_of(Sphere::new(-2.0)).1, ErrorKind::NotPositive(-2.0));
    assert_eq!(field_of(Sphere::new(f32::NAN)).1, ErrorKind::NotFinite);
}

#[test]
fn halfspace_normal_must_be_finite_and_non_zero() {
    assert_eq!(
        field_of(Halfspace::new(Vec3::ZERO)),
        ("normal".to_owned(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        field_of(Halfspace::new(Vec3::new(0.0, f32::NAN, 0.0))),
        ("normal".to_owned(), ErrorKind::NotFinite)
    );
    let normal = Halfspace::new(Vec3::new(0.0, 2.0, 0.0)).unwrap().normal();
    assert_eq!(normal, Vec3::Y);
}

#[test]
fn degenerate_hulls_are_refused() {
    let flat = [
        Vec3::ZERO,
        Vec3::X,
        Vec3::Y,
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.5, 0.5, 0.0),
    ];
    for points in [&flat[..], &flat[..3], &[Vec3::ONE; 6][..], &[][..]] {
        assert!(matches!(
            field_of(Shape::convex_hull(points)),
            (field, ErrorKind::DegenerateHull(_)) if field == "points"
        ));
    }
    let mut with_nan = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
    with_nan[2].y = f32::NAN;
    assert_eq!(
        field_of(Shape::convex_hull(&with_nan)),
        ("points[2]".to_owned(), ErrorKind::NotFinite)
    );
}

#[test]
fn compounds_need_valid_children() {
    assert_eq!(field_of(Compound::new(Vec::new())).0, "children");
    let child = |pose: Pose, shape: Shape| CompoundChild::new(shape, pose);
    let nested = Shape::compound(vec![child(Pose::IDENTITY, unit_box())]).unwrap();
    let cases = [
        (child(Pose::IDENTITY, nested), "children[1].shape"),
        (
            child(Pose::IDENTITY, Shape::halfspace(Vec3::Y).unwrap()),
            "children[1].shape",
        ),
        (
            child(Pose::from_position(Vec3::splat(f32::INFINITY)), unit_box()),
            "children[1].position",
        ),
        (
            child(
                Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
                unit_box(),
            ),
            "children[1].rotation",
        ),
    ];
    for (bad_child, field) in cases {
        let children = vec![child(Pose::IDENTITY, unit_box()), bad_child];
        assert_eq!(field_of(Compound::new(children)).0, field);
    }
}

#[test]
fn every_bad_body_value_is_refused_and_the_world_is_unchanged() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    world.add_body(BodyDesc::dynamic(unit_box())).unwrap();
    let base = || BodyDesc::dynamic(unit_box());
    let cases: Vec<(BodyDesc, &str)> = vec![
        (base().position(Vec3::new(f32::NAN, 0.0, 0.0)), "position"),
        (
            base().rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
            "rotation",
        ),
        (
            base().rotation(Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0)),
            "rotation",
        ),
        (
            base().linear_velocity(Vec3::splat(f32::INFINITY)),
            "linear_velocity",
        ),
        (
            base().angular_velocity(Vec3::splat(f32::NAN)),
            "angular_velocity",
        ),
        (base().density(0.0), "density"),
        (base().density(-5.0), "density"),
        (base().density(1.0e38), "density"),
        (base().mass(0.0), "mass"),
        (base().mass(-1.0), "mass"),
        (base().mass(f32::INFINITY), "mass"),
        (base().mass(1.0e-45), "mass"),
        (base().friction(-0.1), "friction"),
        (base().restitution(1.5), "restitution"),
        (base().restitution(-0.5), "restitution"),
        (base().rolling_resistance(-0.1), "rolling_resistance"),
        (base().rolling_resistance(f32::NAN), "rolling_resistance"),
        (base().constant_force(Vec3::splat(f32::NAN)), "force"),
        (base().constant_torque(Vec3::splat(f32::INFINITY)), "torque"),
        (base().damping(-1.0, 0.0), "linear_damping"),
        (base().damping(0.0, f32::NAN), "angular_damping"),
        (
            BodyDesc::dynamic(Shape::halfspace(Vec3::Y).unwrap()),
            "shape",
        ),
    ];
    for (desc, field) in cases {
        let error = world.add_body(desc).expect_err(field);
        assert_eq!(error.field, field, "{error}");
        assert_eq!(world.body_count(), 1);
    }
    // A halfspace is fine on static and kinematic bodies.
    let halfspace = Shape::halfspace(Vec3::Y).unwrap();
    world
        .add_body(BodyDesc::new(BodyType::Static, halfspace.clone()))
        .unwrap();
    world.add_body(BodyDesc::kinematic(halfspace)).unwrap();
}

#[test]
fn setters_refuse_bad_values_and_keep_the_old_state() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let handle = world
        .add_body(BodyDesc::dynamic(unit_box()).position(Vec3::Y))
        .unwrap();
    let body = world.body_mut(handle).unwrap();
    let nan = Vec3::splat(f32::NAN);
    assert_eq!(field_of(body.set_position(nan)).0, "position");
    assert_eq!(
        field_of(body.set_rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0))).1,
        ErrorKind::ZeroQuaternion
    );
    assert_eq!(field_of(body.set_linear_velocity(nan)).0, "linear_velocity");
    assert_eq!(
        field_of(body.set_angular_velocity(nan)).0,
        "angular_velocity"
    );
    assert_eq!(field_of(body.apply_force(nan)).0, "force");
    assert_eq!(field_of(body.apply_force_at_point(Vec3::X, nan)).0, "point");
    assert_eq!(field_of(body.apply_torque(nan)).0, "torque");
    assert_eq!(field_of(body.apply_impulse(nan)).0, "impulse");
    assert_eq!(
        field_of(body.apply_impulse_at_point(nan, Vec3::ZERO)).0,
        "impulse"
    );
    assert_eq!(field_of(body.set_constant_force(nan)).0, "force");
    assert_eq!(field_of(body.set_constant_torque(nan)).0, "torque");
    assert_eq!(field_of(body.set_damping(-1.0, 0.0)).0, "linear_damping");
    assert_eq!(field_of(body.set_friction(f32::NAN)).0, "friction");
    assert_eq!(field_of(body.set_restitution(2.0)).0, "restitution");
    assert_eq!(
        field_of(body.set_rolling_resistance(-1.0)).0,
        "rolling_resistance"
    );
    assert_eq!(body.position(), Vec3::Y);
    assert_eq!(body.linear_velocity(), Vec3::ZERO);
    world.step(1.0 / 60.0).unwrap();
    let body = world.body(handle).unwrap();
    assert!(body.position().is_finite() && body.linear_velocity().is_finite());
}

#[test]
fn world_settings_and_time_step_are_checked() {
    let bad_settings = [
        (
            WorldSettings {
                gravity: Vec3::new(0.0, f32::NAN, 0.0),
                ..WorldSettings::default()
            },
            "gravity",
        ),
        (
            WorldSettings {
                substeps: 0,
                ..WorldSettings::default()
            },
            "substeps",
        ),
        (
            WorldSettings {
                substeps: 1000,
                ..WorldSettings::default()
            },
            "substeps",
        ),
    ];
    let mut world = World::new(WorldSettings::default()).unwrap();
    for (settings, field) in bad_settings {
        assert_eq!(field_of(World::new(settings)).0, field);
        assert_eq!(field_of(world.set_settings(settings)).0, field);
        assert_eq!(world.settings(), &WorldSettings::default());
    }
    for dt in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(field_of(world.step(dt)).0, "dt");
    }
}

/// Every `f32` world setting, by name, with a way to set it.
type Setter = fn(&mut WorldSettings, f32);

/// Each `f32` world setting with values out of its range (NaN and infinity refused for all).
fn f32_settings_and_bad_values() -> [(&'static str, Setter, &'static [f32]); 11] {
    [
        (
            "max_linear_speed",
            |s, v| s.max_linear_speed = v,
            &[0.0, -1.0, 2.0 * limits::MAX_SPEED],
        ),
        ("contact_hertz", |s, v| s.contact_hertz = v, &[0.0, -60.0]),
        (
            "contact_damping_ratio",
            |s, v| s.contact_damping_ratio = v,
            &[-0.5],
        ),
        (
            "contact_push_speed",
            |s, v| s.contact_push_speed = v,
            &[0.0, -3.0],
        ),
        (
            "restitution_threshold",
            |s, v| s.restitution_threshold = v,
            &[-1.0],
        ),
        (
            "speculative_distance",
            |s, v| s.speculative_distance = v,
            &[-0.01],
        ),
        ("sleep_speed", |s, v| s.sleep_speed = v, &[-0.05]),
        ("sleep_time", |s, v| s.sleep_time = v, &[-0.5]),
        ("joint_hertz", |s, v| s.joint_hertz = v, &[0.0, -60.0]),
        (
            "joint_damping_ratio",
            |s, v| s.joint_damping_ratio = v,
            &[-2.0],
        ),
        (
            "gravity",
            |s, v| s.gravity.y = v,
            &[-2.0 * limits::MAX_GRAVITY],
        ),
    ]
}

#[test]
fn every_world_setting_out_of_range_is_refused_naming_it() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    for (field, set, bad_values) in f32_settings_and_bad_values() {
        for &value in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY]
            .iter()
            .chain(bad_values)
        {
            let mut settings = WorldSettings::default();
            set(&mut settings, value);
            assert_eq!(field_of(World::new(settings)).0, field, "{field} = {value}");
            assert_eq!(
                field_of(world.set_settings(settings)).0,
                field,
                "{field} = {value}"
            );
            assert_eq!(world.settings(), &WorldSettings::default());
        }
    }
}

#[test]
fn stale_handles_are_errors() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let handle = world.add_body(BodyDesc::dynamic(unit_box())).unwrap();
    world.remove_body(handle).unwrap();
    assert_eq!(field_of(world.body(handle)).1, ErrorKind::StaleHandle);
    assert_eq!(
        field_of(world.remove_body(handle)).1,
        ErrorKind::StaleHandle
    );
}

#[test]
fn a_handle_of_another_world_is_an_error_and_changes_neither_world() {
    // Two worlds built alike, so that every handle of one names a slot and generation the other
    // has: before worlds had identities, such a handle reached the other world's body.
    let build = || {
        let mut world = World::new(WorldSettings::default()).unwrap();
        let a = world.add_body(BodyDesc::dynamic(unit_box())).unwrap();
        let b = (world.add_body(BodyDesc::dynamic(unit_box()).position(Vec3::X * 2.0))).unwrap();
        let hinge = JointDesc::revolute(a, b, Vec3::X, Vec3::Z);
        let joint = world.add_joint(hinge).unwrap();
        world.step(1.0 / 60.0).unwrap();
        (world, [a, b], joint)
    };
    let (mut ours, [a, b], joint) = build();
    let (theirs, [their_a, their_b], their_joint) = build();
    assert_eq!(
        (a.slot(), joint.slot()),
        (their_a.slot(), their_joint.slot())
    );
    assert_ne!(a, their_a);
    let (ours_before, theirs_before) = (ours.save_state(), theirs.save_state());

    let stale = ErrorKind::StaleHandle;
    assert_eq!(field_of(ours.body(their_a)).1, stale);
    assert_eq!(field_of(ours.body_mut(their_a)).1, stale);
    assert_eq!(field_of(ours.remove_body(their_a)).1, stale);
    let groups = InteractionGroups::NONE;
    assert_eq!(
        field_of(ours.set_collision_groups(their_b, groups)).1,
        stale
    );
    assert_eq!(field_of(ours.set_pair_ignored(a, their_b, true)).1, stale);
    assert_eq!(field_of(ours.set_pair_ignored(their_a, b, true)).1, stale);
    assert!(!ours.is_pair_ignored(their_a, their_b));
    let ball = |body_a, body_b| JointDesc::ball(body_a, body_b, Vec3::X);
    let body_a = field_of(ours.add_joint(ball(Some(their_a), b)));
    assert_eq!(body_a, ("body_a".to_owned(), stale.clone()));
    let body_b = field_of(ours.add_joint(ball(None, their_b)));
    assert_eq!(body_b, ("body_b".to_owned(), stale.clone()));
    let stale_joint = ErrorKind::StaleJointHandle;
    assert_eq!(field_of(ours.joint(their_joint)).1, stale_joint);
    assert_eq!(field_of(ours.joint_placement(their_joint)).1, stale_joint);
    let motor = Some(Motor::velocity(1.0, 10.0));
    assert_eq!(
        field_of(ours.set_joint_motor(their_joint, motor)).1,
        stale_joint
    );
    assert_eq!(field_of(ours.remove_joint(their_joint)).1, stale_joint);
    let excluded = [a, their_b];
    let filter = QueryFilter::new().exclude_bodies(&excluded);
    let ray = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y);
    let place = ("excluded_bodies[1]".to_owned(), stale.clone());
    assert_eq!(field_of(ours.cast_ray(&ray, &filter)), place);
    let mut found = vec![a];
    let everywhere = Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0));
    let overlaps = ours.bodies_overlapping_aabb(&everywhere, &filter, &mut found);
    assert_eq!((field_of(overlaps), found), (place, Vec::new()));

    assert!(
        ours.save_state() == ours_before,
        "a foreign handle changed this world"
    );
    assert!(
        theirs.save_state() == theirs_before,
        "a foreign handle changed its world"
    );
    // Their own handles still work on each.
    assert!(ours.body(a).is_ok() && theirs.body(their_a).is_ok());
    assert!(ours.remove_joint(joint).is_ok() && ours.remove_body(a).is_ok());
}

#[test]
fn huge_finite_values_never_turn_into_infinity() {
    // Every value at (or, for vectors of three equal components, just within) its limit, the
    // force on the lightest body: 1e18 m/s² that the speed limit must hold.
    let mut world = World::new(WorldSettings::default()).unwrap();
    let handle = world
        .add_body(
            BodyDesc::dynamic(unit_box())
                .mass(limits::MIN_MASS)
                .position(Vec3::splat(limits::MAX_COORDINATE))
                .linear_velocity(Vec3::splat(0.5 * limits::MAX_SPEED))
                .angular_velocity(Vec3::splat(-0.5 * limits::MAX_ANGULAR_SPEED))
                .constant_force(Vec3::splat(0.5 * limits::MAX_FORCE)),
        )
        .unwrap();
    for _ in 0..100 {
        world.step(1.0 / 60.0).unwrap();
    }
    let body = world.body(handle).unwrap();
    let limit = world.settings().max_linear_speed;
    assert!(body.linear_velocity().length() <= limit * 1.0001);
    assert!(body.position().is_finite());
    assert!(body.rotation().is_finite() && body.angular_velocity().is_finite());
}

#[test]
fn a_rotation_too_long_to_square_in_f32_is_normalised_not_lost() {
    // Found by fuzzing the scene loader (fuzz/regressions/scene_loader): a quaternion with a
    // component of 3.3e27 has a squared length past f32's range, and normalising it gave a
    // non-finite body. Scaled first, it is the rotation its direction says: half a turn about X.
    let mut world = World::new(WorldSettings::default()).unwrap();
    let handle = world
        .add_body(BodyDesc::dynamic(unit_box()).rotation(Quat::from_xyzw(3.3e27, 0.0, 0.17, 0.98)))
        .unwrap();
    let rotation = world.body(handle).unwrap().rotation();
    assert!((rotation.length() - 1.0).abs() < 1e-6, "{rotation:?}");
    assert!((rotation.x - 1.0).abs() < 1e-6, "{rotation:?}");
    for _ in 0..3 {
        world.step(1.0 / 60.0).unwrap();
    }
    let body = world.body(handle).unwrap();
    assert!(body.rotation().is_finite() && body.position().is_finite());
}

#[test]
fn a_car_torn_apart_by_an_unlimited_motor_stays_finite() {
    // Found by fuzzing the scene loader: the `car` scene with wheels metres from their axle
    // anchors, one of 1,070 kg, and a −100 rad/s motor of unlimited force, which asks for about
    // 1e9 N. The solver's velocities, held to the speed limits only as forces were integrated,
    // grew from substep to substep until they overflowed within three steps.
    step_fuzzed_scene(
        "nonfinite-car-with-overlaps-and-unlimited-motor.json",
        |world| {
            let limit = world.settings().max_linear_speed;
            for (_, body) in world.bodies() {
                assert!(body.position().is_finite() && body.rotation().is_finite());
                assert!(body.linear_velocity().length() <= limit * (1.0 + 1e-6));
                assert!(body.angular_velocity().is_finite());
            }
        },
    );
}

#[test]
fn a_car_with_an_axle_anchored_kilometres_away_stays_finite() {
    // Found by fuzzing the scene loader: the `car` with one axle anchored 9 km from the chassis.
    // Corrected at the joint's stiffness through a 9 km lever, the error asked for velocities
    // of 1e17 within one pass, which overflowed in three steps. Joints now correct their
    // position error at 100 m/s at most.
    step_fuzzed_scene("car-axle-anchor-9-km-away.json", |world| {
        for (_, body) in world.bodies() {
            assert!(body.position().is_finite() && body.rotation().is_finite());
            assert!(body.linear_velocity().is_finite() && body.angular_velocity().is_finite());
        }
    });
}

/// Loads `fuzz/regressions/scene_loader/FILE` and runs `check` on its world after each of 600
/// steps.
fn step_fuzzed_scene(file: &str, mut check: impl FnMut(&World)) {
    let folder = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fuzz/regressions/scene_loader/"
    );
    let mut scene = rebond::scene::Scene::from_file(format!("{folder}{file}")).unwrap();
    for _ in 0..600 {
        scene.world_mut().step(1.0 / 60.0).unwrap();
        check(scene.world());
    }
}

#[test]
fn a_capsule_past_every_limit_is_refused() {
    // Found by fuzzing library calls: a capsule of radius 2e37 with a mass of 2e37 spinning at
    // 2e37 rad/s stepped to a non-finite body. Each value is now refused where it enters.
    assert_eq!(field_of(Shape::capsule(2e37, 1.0)).0, "radius");
    let capsule = Shape::capsule(0.5, 1.0).unwrap();
    let mut world = World::new(WorldSettings::default()).unwrap();
    let spinning = BodyDesc::dynamic(capsule.clone()).angular_velocity(Vec3::Y * 2e37);
    assert_eq!(field_of(world.add_body(spinning)).0, "angular_velocity");
    assert_eq!(
        field_of(world.add_body(BodyDesc::dynamic(capsule).mass(2e37))).0,
        "mass"
    );
}

#[test]
fn joint_values_past_the_limits_are_refused() {
    // Found by fuzzing library calls: a prismatic joint from a dynamic body to a kinematic one
    // with a motor of target 5e33 m/s and force 5e33 N overflowed an impulse, and zero times
    // infinity gave the kinematic body NaN.
    let mut world = World::new(WorldSettings::default()).unwrap();
    let a = world.add_body(BodyDesc::dynamic(unit_box())).unwrap();
    let b = world
        .add_body(BodyDesc::kinematic(unit_box()).position(Vec3::X * 2.0))
        .unwrap();
    let slide = || rebond::JointDesc::prismatic(a, b, Vec3::X, Vec3::X);
    let huge = 5e33;
    let cases = [
        (
            slide().motor(rebond::Motor::velocity(huge, 1.0)),
            "motor.target_velocity",
        ),
        (
            slide().motor(rebond::Motor::velocity(1.0, huge)),
            "motor.max_force",
        ),
        (slide().limits(-huge, huge), "limits[0]"),
        (slide().friction(huge), "friction"),
    ];
    for (desc, field) in cases {
        assert_eq!(field_of(world.add_joint(desc)).0, field);
    }
    let unlimited = slide().motor(rebond::Motor::velocity(1.0, f32::INFINITY));
    assert!(world.add_joint(unlimited).is_ok());
}

#[test]
fn bad_torque_motors_and_joint_coordinates_are_refused() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let a = world.add_body(BodyDesc::dynamic(unit_box())).unwrap();
    let b = world
        .add_body(BodyDesc::dynamic(unit_box()).position(Vec3::X * 2.0))
        .unwrap();
    let hinge = || rebond::JointDesc::revolute(a, b, Vec3::X, Vec3::Y);
    let torque = |value| Some(rebond::Motor::torque(value));
    let cases = [
        (f32::NAN, ErrorKind::NotFinite),
        (f32::INFINITY, ErrorKind::NotFinite),
        (
            -2e12,
            ErrorKind::OutOfRange {
                value: -2e12,
                min: -limits::MAX_FORCE,
                max: limits::MAX_FORCE,
            },
        ),
    ];
    for (value, kind) in cases {
        let mut desc = hinge();
        desc.motor = torque(value);
        let expected = ("motor.torque".to_owned(), kind);
        assert_eq!(field_of(world.add_joint(desc)), expected);
    }
    let mut ball = rebond::JointDesc::ball(a, b, Vec3::X);
    ball.motor = torque(1.0);
    assert_eq!(
        field_of(world.add_joint(ball)),
        ("motor".to_owned(), ErrorKind::NotForJointType("ball"))
    );
    // Revolute limits are on the angle counted across turns: two turns either way are
    // accepted, past the coordinate limit is not.
    let two_turns = 4.0 * std::f32::consts::PI;
    assert!(world
        .add_joint(hinge().limits(-two_turns, two_turns))
        .is_ok());
    assert_eq!(
        field_of(world.add_joint(hinge().limits(-2e4, 0.0))).0,
        "limits[0]"
    );

    // At run time a bad motor is refused naming its field, and the joint keeps its motor.
    let joint = world
        .add_joint(hinge().motor(rebond::Motor::torque(2.0)))
        .unwrap();
    assert_eq!(
        field_of(world.set_joint_motor(joint, torque(f32::NAN))).0,
        "motor.torque"
    );
    assert_eq!(
        world.joint(joint).unwrap().desc().motor,
        Some(rebond::Motor::torque(2.0))
    );
    let socket = world
        .add_joint(rebond::JointDesc::ball(a, b, Vec3::X))
        .unwrap();
    assert_eq!(
        field_of(world.set_joint_motor(socket, torque(1.0))),
        ("motor".to_owned(), ErrorKind::NotForJointType("ball"))
    );
    assert_eq!(world.joint(socket).unwrap().desc().motor, None);

    // Fixed and ball joints have no coordinate to read.
    assert_eq!(
        field_of(world.joint_position(socket)),
        ("position".to_owned(), ErrorKind::NotForJointType("ball"))
    );
    assert_eq!(
        field_of(world.joint_velocity(socket)),
        ("velocity".to_owned(), ErrorKind::NotForJointType("ball"))
    );
    world.remove_joint(socket).unwrap();
    assert_eq!(
        field_of(world.joint_position(socket)).1,
        ErrorKind::StaleJointHandle
    );
    for _ in 0..10 {
        world.step(1.0 / 60.0).unwrap();
    }
    for (_, body) in world.bodies() {
        assert!(body.position().is_finite() && body.rotation().is_finite());
    }
}

#[test]
fn bad_pose_targets_and_paths_are_refused_naming_the_field() {
    use rebond::{KinematicPath, PathPoint};
    let mut world = World::new(WorldSettings::default()).unwrap();
    let at = |time: f32| PathPoint::new(time, Vec3::ZERO, Quat::IDENTITY);
    let path = |points: Vec<PathPoint>| KinematicPath::new(points);
    let zero = Quat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    let far = Vec3::new(0.0, 2.0 * limits::MAX_COORDINATE, 0.0);
    let cases: Vec<(KinematicPath, &str, ErrorKind)> = vec![
        (path(vec![]), "path.points", ErrorKind::Missing),
        (
            path(vec![at(0.5)]),
            "path.points[0].time",
            ErrorKind::OutOfRange {
                value: 0.5,
                min: 0.0,
                max: 0.0,
            },
        ),
        (
            path(vec![at(0.0), at(f32::NAN)]),
            "path.points[1].time",
            ErrorKind::NotFinite,
        ),
        (
            path(vec![at(0.0), at(1.0), at(1.0)]),
            "path.points[2].time",
            ErrorKind::NotIncreasing {
                value: 1.0,
                previous: 1.0,
            },
        ),
        (
            path(vec![at(0.0), at(1.0), at(0.5)]),
            "path.points[2].time",
            ErrorKind::NotIncreasing {
                value: 0.5,
                previous: 1.0,
            },
        ),
        (
            path(vec![at(0.0), PathPoint::new(1.0, far, Quat::IDENTITY)]),
            "path.points[1].position",
            ErrorKind::TooLarge {
                value: far.y,
                max: limits::MAX_COORDINATE,
            },
        ),
        (
            path(vec![PathPoint::new(0.0, Vec3::NAN, Quat::IDENTITY)]),
            "path.points[0].position",
            ErrorKind::NotFinite,
        ),
        (
            path(vec![at(0.0), PathPoint::new(1.0, Vec3::ZERO, zero)]),
            "path.points[1].rotation",
            ErrorKind::ZeroQuaternion,
        ),
    ];
    for (bad, field, kind) in cases {
        let desc = BodyDesc::kinematic(unit_box()).path(bad.clone());
        let error = world.add_body(desc).expect_err(field);
        assert_eq!((error.field.as_str(), &error.kind), (field, &kind));
        assert_eq!(world.body_count(), 0);
        let handle = world.add_body(BodyDesc::kinematic(unit_box())).unwrap();
        let body = world.body_mut(handle).unwrap();
        assert_eq!(field_of(body.set_path(Some(bad))), (field.to_owned(), kind));
        assert!(body.path().is_none());
        world.remove_body(handle).unwrap();
    }

    // Only kinematic bodies follow a path or a pose target.
    let good = path(vec![at(0.0), at(1.0)]);
    for body_type in [BodyType::Dynamic, BodyType::Static] {
        let desc = BodyDesc::new(body_type, unit_box()).path(good.clone());
        let error = world.add_body(desc).unwrap_err();
        assert_eq!(
            (error.field.as_str(), error.kind),
            ("path", ErrorKind::NotKinematic)
        );
        let handle = world
            .add_body(BodyDesc::new(body_type, unit_box()))
            .unwrap();
        let body = world.body_mut(handle).unwrap();
        assert_eq!(
            field_of(body.set_path(Some(good.clone()))),
            ("path".to_owned(), ErrorKind::NotKinematic)
        );
        assert_eq!(
            field_of(body.set_kinematic_target(Pose::IDENTITY)),
            ("target".to_owned(), ErrorKind::NotKinematic)
        );
        assert_eq!(body.kinematic_target(), None);
    }

    let handle = world.add_body(BodyDesc::kinematic(unit_box())).unwrap();
    let body = world.body_mut(handle).unwrap();
    let bad_targets = [
        (Pose::new(Vec3::NAN, Quat::IDENTITY), "target.position"),
        (Pose::new(far, Quat::IDENTITY), "target.position"),
        (Pose::new(Vec3::ZERO, zero), "target.rotation"),
        (
            Pose::new(Vec3::ZERO, Quat::from_xyzw(f32::INFINITY, 0.0, 0.0, 1.0)),
            "target.rotation",
        ),
    ];
    for (pose, field) in bad_targets {
        assert_eq!(field_of(body.set_kinematic_target(pose)).0, field);
        assert_eq!(body.kinematic_target(), None);
    }
    // A target far beyond the speed limits is still reached; the velocity stays at the limit.
    let distant = Pose::from_position(Vec3::splat(limits::MAX_COORDINATE));
    body.set_kinematic_target(distant).unwrap();
    world.step(limits::MIN_TIMESTEP).unwrap();
    let body = world.body(handle).unwrap();
    assert_eq!(body.position(), distant.position);
    assert!(body.linear_velocity().length() <= limits::MAX_SPEED * (1.0 + 1.0e-6));
}
