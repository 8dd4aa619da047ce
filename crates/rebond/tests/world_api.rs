//! The world's conveniences: user data, waking, and scene files loaded by the library.

mod common;

use common::{add_ground, run, scene_path, unit_box, world, G};
use rebond::scene::{LoadError, Scene};
use rebond::{
    BodyDesc, CombineRule, JointType, Motor, QueryFilter, Ray, Shape, Vec3, World, WorldSettings,
};

#[test]
fn user_data_rides_along_with_the_body() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let body = world
        .add_body(BodyDesc::dynamic(Shape::sphere(0.5).unwrap()).user_data(42))
        .unwrap();
    assert_eq!(world.body(body).unwrap().user_data(), 42);
    world.body_mut(body).unwrap().set_user_data(u128::MAX);
    run(&mut world, 3);
    assert_eq!(world.body(body).unwrap().user_data(), u128::MAX);
}

/// A unit box resting on the ground until it sleeps, with the step count it took.
fn box_asleep_on_the_ground() -> (World, rebond::BodyHandle) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let body = world.add_body(unit_box(Vec3::new(0.0, 0.5, 0.0))).unwrap();
    run(&mut world, 120);
    assert!(world.body(body).unwrap().is_sleeping(), "the box rests");
    (world, body)
}

#[test]
fn wake_all_wakes_every_sleeping_body() {
    let (mut world, body) = box_asleep_on_the_ground();
    world.wake_all();
    assert!(!world.body(body).unwrap().is_sleeping());
    assert_eq!(world.sleeping_body_count(), 0);
}

#[test]
fn a_change_of_gravity_wakes_the_bodies_and_they_follow_it() {
    let (mut world, body) = box_asleep_on_the_ground();
    let settings = *world.settings();
    world
        .set_settings(WorldSettings {
            gravity: Vec3::new(0.0, G, 0.0),
            ..settings
        })
        .unwrap();
    assert!(!world.body(body).unwrap().is_sleeping());
    run(&mut world, 60);
    // Pulled up at g for one second from rest: 4.9 m, less the few millimetres of the step's
    // start on the ground.
    let height = world.body(body).unwrap().position().y - 0.5;
    assert!((height - 0.5 * G).abs() < 0.05, "rose {height} m");
}

#[test]
fn the_same_gravity_again_leaves_sleeping_bodies_asleep() {
    let (mut world, body) = box_asleep_on_the_ground();
    let settings = *world.settings();
    world.set_settings(settings).unwrap();
    assert!(world.body(body).unwrap().is_sleeping());
}

/// The workspace's built-in scenes, for the loader.
#[test]
fn a_scene_file_loads_into_a_world_with_its_names_and_timestep() {
    let scene = Scene::from_file(scene_path("column")).unwrap();
    assert_eq!(scene.bodies().count(), 11);
    let ground = scene
        .body_handle("ground")
        .expect("the column stands on `ground`");
    assert!(scene.world().body(ground).is_ok());
    assert!((scene.timestep().seconds - 1.0 / 60.0).abs() < 1e-9);
    let world = World::from_scene_file(scene_path("column")).unwrap();
    assert_eq!(world.body_count(), 11);
}

#[test]
fn a_missing_scene_file_is_a_read_error_and_a_bad_one_names_the_place() {
    match Scene::from_file(scene_path("no such scene")) {
        Err(LoadError::Read { path, .. }) => assert!(path.ends_with("no such scene.json")),
        other => panic!("expected a read error, got {other:?}"),
    }
    let error = Scene::from_json(br#"{"bodies": [{"shape": {"type": "sphere", "radius": -1}}]}"#)
        .unwrap_err();
    assert_eq!(error.place, "bodies[0].shape.radius");
    assert_eq!(error.message, "must be positive, got -1");
}

#[test]
fn every_world_setting_is_read_from_a_scene_file_under_its_name() {
    let json = br#"{
        "gravity": [1, -2, 3], "substeps": 5, "max_linear_speed": 50, "contact_hertz": 30,
        "contact_damping_ratio": 0.7, "contact_push_speed": 1.5, "restitution_threshold": 0.25,
        "speculative_distance": 0.01, "sleep_speed": 0.1, "sleep_time": 2, "joint_hertz": 20,
        "joint_damping_ratio": 1.5, "friction_combine": "min", "restitution_combine": "multiply",
        "bodies": []
    }"#;
    let expected = WorldSettings {
        gravity: Vec3::new(1.0, -2.0, 3.0),
        substeps: 5,
        max_linear_speed: 50.0,
        contact_hertz: 30.0,
        contact_damping_ratio: 0.7,
        contact_push_speed: 1.5,
        restitution_threshold: 0.25,
        speculative_distance: 0.01,
        sleep_speed: 0.1,
        sleep_time: 2.0,
        joint_hertz: 20.0,
        joint_damping_ratio: 1.5,
        friction_combine: CombineRule::Min,
        restitution_combine: CombineRule::Multiply,
    };
    assert_eq!(
        Scene::from_json(json).unwrap().world().settings(),
        &expected
    );
    let empty = Scene::from_json(br#"{"bodies": []}"#).unwrap();
    assert_eq!(empty.world().settings(), &WorldSettings::default());
    let rules = [
        ("geometric_mean", CombineRule::GeometricMean),
        ("average", CombineRule::Average),
        ("min", CombineRule::Min),
        ("max", CombineRule::Max),
        ("multiply", CombineRule::Multiply),
    ];
    for (name, rule) in rules {
        let json = format!(
            r#"{{"friction_combine": "{name}", "restitution_combine": "{name}", "bodies": []}}"#
        );
        let scene = Scene::from_json(json.as_bytes()).unwrap();
        let settings = scene.world().settings();
        assert_eq!(
            (settings.friction_combine, settings.restitution_combine),
            (rule, rule)
        );
    }
}

#[test]
fn bad_world_settings_in_a_scene_file_are_refused_at_their_field() {
    let refused = |field: &str, value: &str| {
        let json = format!(r#"{{"{field}": {value}, "bodies": []}}"#);
        let error = Scene::from_json(json.as_bytes()).expect_err(&json);
        assert_eq!(error.place, field, "{json}: {error}");
        error.message
    };
    let out_of_range = [
        ("max_linear_speed", "0", "must be positive"),
        ("max_linear_speed", "1e5", "must lie between 0 and 10000"),
        ("contact_hertz", "0", "must be positive"),
        ("contact_damping_ratio", "-0.5", "must not be negative"),
        ("contact_push_speed", "-3", "must be positive"),
        ("restitution_threshold", "-1", "must not be negative"),
        ("speculative_distance", "-0.01", "must not be negative"),
        ("sleep_speed", "-0.05", "must not be negative"),
        ("sleep_time", "-1", "must not be negative"),
        ("joint_hertz", "0", "must be positive"),
        ("joint_damping_ratio", "-2", "must not be negative"),
    ];
    for (field, value, message) in out_of_range {
        let said = refused(field, value);
        assert!(said.starts_with(message), "{field} = {value}: {said}");
        // Beyond f32, and of the wrong JSON type.
        assert!(
            refused(field, "1e39").starts_with("must be finite"),
            "{field}"
        );
        assert!(
            refused(field, r#""fast""#).contains("invalid type"),
            "{field}"
        );
    }
    for field in ["friction_combine", "restitution_combine"] {
        assert!(
            refused(field, r#""median""#).contains("unknown variant"),
            "{field}"
        );
        assert!(refused(field, r#""GeometricMean""#).contains("unknown variant"));
        assert!(refused(field, "1").contains("invalid type"), "{field}");
    }
}

/// A post, a door and a ball, with `joints` (the inside of the JSON list).
fn scene_with_joints(joints: &str) -> Result<Scene, rebond::scene::SceneError> {
    let json = format!(
        r#"{{"bodies": [
            {{"name": "post", "type": "static", "shape": {{"type": "box", "half_extents": [0.1, 1, 0.1]}}}},
            {{"name": "door", "shape": {{"type": "box", "half_extents": [0.5, 1, 0.05]}},
              "position": [0.6, 0, 0]}},
            {{"name": "ball", "shape": {{"type": "sphere", "radius": 0.2}}, "position": [3, 1, 2]}}
        ], "joints": [{joints}]}}"#
    );
    Scene::from_json(json.as_bytes())
}

#[test]
fn scene_joints_load_in_order_with_their_names_and_defaults() {
    let scene = scene_with_joints(
        r#"{"name": "hinge", "type": "revolute", "body_a": "post", "body_b": "door",
            "anchor": [0.1, 0, 0], "axis": [0, 3, 0],
            "motor": {"target_velocity": 1.5}},
           {"type": "ball", "body_a": null, "body_b": "ball"},
           {"type": "distance", "body_a": "door", "body_b": "ball", "anchor": [1, 0, 0],
            "spring": {"stiffness": 40}},
           {"name": "servo", "type": "prismatic", "body_a": "post", "body_b": "door",
            "axis": [1, 0, 0], "collide_connected": true, "break_force": 100,
            "motor": {"target_position": 0.2, "stiffness": 50}}"#,
    )
    .unwrap();
    let names: Vec<&str> = scene.joints().map(|(name, _)| name).collect();
    assert_eq!(names, ["hinge", "joint1", "joint2", "servo"]);
    let joint = |name: &str| {
        let handle = scene.joint_handle(name).expect("a joint of that name");
        scene.world().joint(handle).unwrap()
    };
    let (post, door, ball) = (
        scene.body_handle("post").unwrap(),
        scene.body_handle("door").unwrap(),
        scene.body_handle("ball").unwrap(),
    );

    let hinge = joint("hinge");
    assert_eq!(hinge.joint_type(), JointType::Revolute);
    assert_eq!(hinge.bodies(), (Some(post), door));
    assert_eq!(
        hinge.desc().motor,
        Some(Motor::velocity(1.5, f32::INFINITY)),
        "a motor without `max_force` is unlimited"
    );
    let placement = scene
        .world()
        .joint_placement(scene.joint_handle("hinge").unwrap())
        .unwrap();
    assert!(
        (placement.axis_a - Vec3::Y).length() < 1e-6,
        "the axis is normalised"
    );

    let hung = joint("joint1");
    assert_eq!(hung.bodies(), (None, ball));
    assert_eq!(
        hung.desc().anchor,
        Vec3::new(3.0, 1.0, 2.0),
        "the anchor defaults to body_b's position"
    );
    assert!(!hung.desc().collide_connected);

    let spring = joint("joint2").desc();
    assert_eq!(spring.anchor_b, None, "anchor_b defaults to the anchor");
    assert_eq!(spring.spring.map(|spring| spring.damping), Some(0.0));

    let servo = joint("servo").desc();
    assert!(servo.collide_connected);
    assert_eq!(servo.break_force, 100.0);
    assert_eq!(servo.break_torque, f32::INFINITY);
    assert_eq!(
        servo.motor,
        Some(Motor::position(0.2, 50.0, 0.0, f32::INFINITY))
    );
}

#[test]
fn bad_scene_joints_are_refused_at_their_place() {
    let cases = [
        (
            r#"{"type": "ball", "body_b": "dor"}"#,
            "joints[0].body_b",
            "no body is named \"dor\"",
        ),
        (
            r#"{"type": "ball", "body_a": "door", "body_b": "door"}"#,
            "joints[0].body_b",
            "a joint cannot join a body to itself",
        ),
        (
            r#"{"type": "revolute", "body_b": "door"}"#,
            "joints[0].axis",
            "required field is missing (a revolute joint needs it)",
        ),
        (
            r#"{"type": "revolute", "body_b": "door", "axis": [0, 0, 0]}"#,
            "joints[0].axis",
            "vector has zero length",
        ),
        (
            r#"{"type": "distance", "body_b": "door", "limits": [2, 1]}"#,
            "joints[0].limits",
            "min must not exceed max, got [2, 1]",
        ),
        (
            r#"{"type": "ball", "body_b": "door", "spring": {"stiffness": 1}}"#,
            "joints[0].spring",
            "does not apply to a ball joint",
        ),
        (
            r#"{"type": "distance", "body_b": "door", "spring": {"stiffness": -1}}"#,
            "joints[0].spring.stiffness",
            "must not be negative, got -1",
        ),
        (
            r#"{"type": "prismatic", "body_b": "door", "axis": [1, 0, 0],
                "motor": {"target_position": 1, "damping": 2}}"#,
            "joints[0].motor.stiffness",
            "required field is missing (a position motor needs it)",
        ),
        (
            r#"{"type": "ball", "body_b": "door"}, {"name": "joint0", "type": "ball", "body_b": "ball"}"#,
            "joints[1].name",
            "duplicate name \"joint0\": joints[0] and joints[1] both have it",
        ),
    ];
    for (joints, place, message) in cases {
        let error = scene_with_joints(joints).unwrap_err();
        assert_eq!(
            (error.place.as_str(), error.message.as_str()),
            (place, message)
        );
    }
}

#[test]
fn the_builtin_joint_scenes_load_with_their_joints() {
    for (name, joints) in [
        ("pendulum", 7),
        ("chain", 34),
        ("bridge", 15),
        ("ragdolls", 270),
        ("car", 4),
        ("cradle_hanging", 10),
    ] {
        let scene = Scene::from_file(scene_path(name)).unwrap();
        assert_eq!(scene.joints().count(), joints, "{name}");
        assert_eq!(scene.world().joint_count(), joints, "{name}");
    }
}

#[test]
fn force_point_in_a_scene_turns_the_body_as_r_cross_f() {
    let json = br#"{"gravity": [0, 0, 0], "bodies": [{"name": "rod",
        "shape": {"type": "box", "half_extents": [1, 0.1, 0.1]}, "mass": 3,
        "force": [0, 6, 0], "force_point": [1, 0, 0]}]}"#;
    let mut scene = Scene::from_json(json).unwrap();
    scene.step().unwrap();
    let rod = scene.body_handle("rod").unwrap();
    let body = scene.world().body(rod).unwrap();
    // Izz = m (a² + b²) / 3 with half extents a = 1, b = 0.1; τ = r × F = (0, 0, 6).
    let izz = 3.0 * (1.0 + 0.01) / 3.0;
    let expected = 6.0 / izz * scene.timestep().engine_seconds;
    assert!((body.angular_velocity().z - expected).abs() <= 1e-5 * expected);
    assert!((body.linear_velocity().y - 2.0 * scene.timestep().engine_seconds).abs() < 1e-6);
}

#[test]
fn a_static_body_moved_by_the_user_is_found_and_collided_where_it_now_is() {
    // Static bodies are left out of the step's per-body passes; one lent out by `body_mut` has
    // its bounding box refreshed at the next step.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let shelf = world
        .add_body(BodyDesc::static_body(
            Shape::cuboid(Vec3::new(1.0, 0.1, 1.0)).unwrap(),
        ))
        .unwrap();
    world
        .body_mut(shelf)
        .unwrap()
        .set_position(Vec3::new(10.0, 0.0, 0.0))
        .unwrap();
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.25).unwrap()).position(Vec3::new(10.0, 1.0, 0.0)),
        )
        .unwrap();
    run(&mut world, 120);
    let down = Ray::new(Vec3::new(10.0, 5.0, 0.0), Vec3::NEG_Y);
    let hit = world
        .cast_ray(&down, &QueryFilter::new().exclude_bodies(&[ball]))
        .unwrap();
    assert_eq!(hit.map(|hit| hit.body), Some(shelf));
    // The ball rests on the shelf's new place: its top face at y = 0.1.
    let height = world.body(ball).unwrap().position().y;
    assert!((height - 0.35).abs() < 0.01, "the ball is at y = {height}");
}

#[test]
fn bodies_and_joints_added_as_json_are_checked_like_scene_entries() {
    let mut scene = Scene::from_json(
        br#"{"gravity": [0, 0, 0], "bodies": [{"name": "base",
        "type": "static", "shape": {"type": "box", "half_extents": [1, 1, 1]}}]}"#,
    )
    .unwrap();
    let arm = br#"{"name": "arm", "shape": {"type": "box", "half_extents": [0.5, 0.1, 0.1]},
        "position": [1.5, 0, 0]}"#;
    assert_eq!(scene.add_body_json(arm).unwrap(), 1);
    let hinge = br#"{"type": "revolute", "body_a": "base", "body_b": "arm", "anchor": [1, 0, 0],
        "axis": [0, 0, 1], "motor": {"target_velocity": 1, "max_force": 100}}"#;
    assert_eq!(scene.add_joint_json(hinge).unwrap(), 0);
    let names: Vec<&str> = scene.body_handles().map(|(name, _)| name).collect();
    assert_eq!(names, ["base", "arm"]);
    let joints: Vec<&str> = scene.joint_handles().map(|(name, _)| name).collect();
    assert_eq!(joints, ["joint0"]);

    // Errors name the place the entry would have in a scene file.
    let error = scene
        .add_body_json(br#"{"shape": {"type": "sphere", "radius": -1}}"#)
        .unwrap_err();
    assert_eq!(error.place, "bodies[2].shape.radius");
    assert_eq!(error.message, "must be positive, got -1");
    let error = scene.add_body_json(arm).unwrap_err();
    assert_eq!(error.place, "bodies[2].name");
    let error = scene
        .add_body_json(br#"{"position": [0, 0, 0]}"#)
        .unwrap_err();
    assert_eq!(error.place, "bodies[2].shape");
    assert!(error.message.starts_with("required field is missing"));
    let error = scene.add_body_json(b"[1, 2]").unwrap_err();
    assert_eq!(error.place, "bodies[2]");
    let error = scene
        .add_joint_json(br#"{"type": "ball", "body_b": "hand"}"#)
        .unwrap_err();
    assert_eq!(error.place, "joints[1].body_b");
    assert_eq!(error.message, "no body is named \"hand\"");
    // A refused entry adds nothing.
    assert_eq!(scene.bodies().count(), 2);
    assert_eq!(scene.joints().count(), 1);

    for _ in 0..60 {
        scene.step().unwrap();
    }
    let arm = scene.body_handle("arm").unwrap();
    let spin = scene.world().body(arm).unwrap().angular_velocity();
    assert!(
        (spin.z - 1.0).abs() < 1e-3,
        "the motor turns the arm: {spin}"
    );
}
