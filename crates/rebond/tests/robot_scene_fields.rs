//! The scene fields robot models need: a body's explicit `mass_properties` and the top-level
//! `actuators` with `Scene::set_controls`.

use rebond::scene::{ActuatorKind, Scene};
use rebond::{Mat3, Vec3};

/// A scene of one body with the given `mass_properties` JSON object, no gravity.
fn body_with(mass_properties: &str) -> Result<Scene, rebond::scene::SceneError> {
    let json = format!(
        r#"{{ "gravity": [0, 0, 0], "bodies": [ {{ "name": "b",
              "shape": {{ "type": "sphere", "radius": 0.1 }},
              "mass_properties": {mass_properties} }} ] }}"#
    );
    Scene::from_json(json.as_bytes())
}

#[test]
fn explicit_mass_properties_replace_the_shapes() {
    let scene = body_with(
        r#"{ "mass": 2.5, "center_of_mass": [0.5, 0, 0],
             "inertia": [0.1, 0.2, 0.3, 0.01, 0.0, -0.02] }"#,
    )
    .unwrap();
    let body = scene.world().body(scene.body_handle("b").unwrap()).unwrap();
    // Given outright, so exact: no density or shape enters.
    assert_eq!(body.mass(), 2.5);
    assert_eq!(body.local_center_of_mass(), Vec3::new(0.5, 0.0, 0.0));
    let expected = Mat3::from_cols(
        Vec3::new(0.1, 0.01, 0.0),
        Vec3::new(0.01, 0.2, -0.02),
        Vec3::new(0.0, -0.02, 0.3),
    );
    assert_eq!(body.local_inertia(), expected);
    // The centre of mass sits 0.5 m along X from the origin the file places at 0.
    assert_eq!(body.center_of_mass(), Vec3::new(0.5, 0.0, 0.0));
}

#[test]
fn bad_mass_properties_are_refused_at_their_field() {
    let cases = [
        (
            r#"{ "mass": -1, "inertia": [1, 1, 1, 0, 0, 0] }"#,
            "bodies[0].mass_properties.mass",
        ),
        (
            // Eigenvalues 3, 1, -1: not positive definite.
            r#"{ "mass": 1, "inertia": [1, 1, 1, 2, 0, 0] }"#,
            "bodies[0].mass_properties.inertia",
        ),
        (
            r#"{ "mass": 1, "inertia": [1, 1, 1, 0, 0, 0], "center_of_mass": [1e39, 0, 0] }"#,
            "bodies[0].mass_properties.center_of_mass[0]",
        ),
        (
            r#"{ "mass": 1, "inertia": [1, 1, 0] }"#,
            "bodies[0].mass_properties.inertia",
        ),
    ];
    for (properties, place) in cases {
        let error = body_with(properties).unwrap_err();
        assert_eq!(error.place, place, "{properties}: {error}");
    }
    let both = r#"{ "bodies": [ { "shape": { "type": "sphere", "radius": 0.1 }, "mass": 1,
        "mass_properties": { "mass": 1, "inertia": [1, 1, 1, 0, 0, 0] } } ] }"#;
    let error = Scene::from_json(both.as_bytes()).unwrap_err();
    assert_eq!(error.place, "bodies[0].mass");
}

/// A wheel of inertia 0.5 kg·m² about Z on a revolute joint to the world, driven by one
/// actuator given as JSON.
fn wheel(actuator: &str) -> Result<Scene, rebond::scene::SceneError> {
    let json = format!(
        r#"{{ "gravity": [0, 0, 0], "timestep": 0.01,
            "bodies": [ {{ "name": "wheel", "shape": {{ "type": "sphere", "radius": 0.1 }},
                "mass_properties": {{ "mass": 1, "inertia": [0.5, 0.5, 0.5, 0, 0, 0] }},
                "can_sleep": false }} ],
            "joints": [ {{ "name": "axle", "type": "revolute", "body_b": "wheel",
                "axis": [0, 0, 1] }} ],
            "actuators": [ {actuator} ] }}"#
    );
    Scene::from_json(json.as_bytes())
}

#[test]
fn a_torque_motor_gives_gear_times_the_clamped_control() {
    let mut scene = wheel(
        r#"{ "name": "m", "joint": "axle", "type": "motor", "gear": 2, "ctrl_range": [-1, 1] }"#,
    )
    .unwrap();
    let actuator = &scene.actuators()[0];
    assert_eq!(actuator.name, "m");
    assert_eq!(actuator.kind, ActuatorKind::Motor);
    assert_eq!(actuator.ctrl_range, Some([-1.0, 1.0]));
    assert_eq!(actuator.joint, scene.joint_handle("axle").unwrap());
    // u = 5 is clamped to 1: the torque is 2 N·m, the acceleration 2 / 0.5 = 4 rad/s².
    scene.set_controls(&[5.0]).unwrap();
    for _ in 0..100 {
        scene.step().unwrap();
    }
    let axle = scene.joint_handle("axle").unwrap();
    let speed = scene.world().joint_velocity(axle).unwrap();
    // After 1 s: 4 rad/s; the joint's correction and f32 sums stay well under 0.1 %.
    assert!((speed - 4.0).abs() < 4e-3, "speed {speed}");
    let angle = scene.world().joint_position(axle).unwrap();
    // ½ a t² = 2 rad, less the half step the symplectic Euler start lags: within 1 %.
    assert!((angle - 2.0).abs() < 0.03, "angle {angle}");
}

#[test]
fn a_position_actuator_holds_its_target() {
    let mut scene =
        wheel(r#"{ "joint": "axle", "type": "position", "kp": 50, "kv": 10 }"#).unwrap();
    assert_eq!(scene.actuators()[0].name, "actuator0");
    scene.set_controls(&[0.5]).unwrap();
    for _ in 0..500 {
        scene.step().unwrap();
    }
    let axle = scene.joint_handle("axle").unwrap();
    let angle = scene.world().joint_position(axle).unwrap();
    // ω₀ = √(50 / 0.5) = 10 rad/s, ζ = 10 / (2·√(50·0.5)) = 1: settled after 5 s to far below 0.1 %.
    assert!((angle - 0.5).abs() < 5e-4, "angle {angle}");
}

#[test]
fn controls_are_checked_before_anything_changes() {
    let mut scene = wheel(r#"{ "joint": "axle", "type": "motor" }"#).unwrap();
    let error = scene.set_controls(&[1.0, 2.0]).unwrap_err();
    assert_eq!(error.field, "controls");
    let error = scene.set_controls(&[f32::NAN]).unwrap_err();
    assert_eq!(error.field, "controls[0]");
    let error = scene.set_controls(&[1e30]).unwrap_err();
    assert_eq!(error.field, "controls[0].motor.torque");
    let cases = [
        (
            r#"{ "joint": "nothing", "type": "motor" }"#,
            "actuators[0].joint",
        ),
        (
            r#"{ "joint": "axle", "type": "motor", "kp": 1 }"#,
            "actuators[0].kp",
        ),
        (
            r#"{ "joint": "axle", "type": "velocity", "kp": 1 }"#,
            "actuators[0].kp",
        ),
        (
            r#"{ "joint": "axle", "type": "motor", "gear": 0 }"#,
            "actuators[0].gear",
        ),
        (
            r#"{ "joint": "axle", "type": "position", "kp": -1 }"#,
            "actuators[0].kp",
        ),
        (
            r#"{ "joint": "axle", "type": "motor", "ctrl_range": [1, -1] }"#,
            "actuators[0].ctrl_range",
        ),
    ];
    for (actuator, place) in cases {
        let error = wheel(actuator).unwrap_err();
        assert_eq!(error.place, place, "{actuator}: {error}");
    }
}
