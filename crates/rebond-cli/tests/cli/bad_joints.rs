//! Bad joints in scene files are refused before anything runs, at their place in the file
//! (`joints[2].motor.torque`), with exit status 2 and one `error:` line (`bad_input.rs` for the
//! rest of a scene).

use crate::bad_input::{assert_refused, BALL, GROUND};

/// A scene of the ground, a `door` and a `ball`, with `joint` as `joints[2]` after two valid
/// joints.
fn scene_with_joint(joint: &str) -> String {
    format!(
        r#"{{"bodies": [{GROUND},
        {{"name": "door", "shape": {{"type": "box", "half_extents": [0.5, 1, 0.05]}},
          "position": [0, 1, 0]}},
        {{"name": "ball", {BALL}, "position": [3, 1, 0]}}],
      "joints": [{{"name": "hinge", "type": "revolute", "body_a": "ground", "body_b": "door",
                   "anchor": [0.5, 1, 0], "axis": [0, 1, 0]}},
                 {{"type": "ball", "body_b": "ball"}},
                 {joint}]}}"#
    )
}

#[test]
fn joints_naming_unknown_bodies_or_joining_a_body_to_itself_are_refused() {
    assert_refused(
        "joint_unknown_body_b",
        &scene_with_joint(r#"{"type": "ball", "body_a": "door", "body_b": "dor"}"#),
        "joints[2].body_b",
        "no body is named \"dor\"",
    );
    assert_refused(
        "joint_unknown_body_a",
        &scene_with_joint(r#"{"type": "ball", "body_a": "frame", "body_b": "door"}"#),
        "joints[2].body_a",
        "no body is named \"frame\"",
    );
    assert_refused(
        "joint_missing_body_b",
        &scene_with_joint(r#"{"type": "ball", "body_a": "door"}"#),
        "joints[2].body_b",
        "required field is missing",
    );
    assert_refused(
        "joint_to_itself",
        &scene_with_joint(r#"{"type": "fixed", "body_a": "ball", "body_b": "ball"}"#),
        "joints[2].body_b",
        "cannot join a body to itself",
    );
}

#[test]
fn joint_axes_must_be_given_where_needed_and_not_zero() {
    assert_refused(
        "joint_zero_axis",
        &scene_with_joint(
            r#"{"type": "revolute", "body_a": "door", "body_b": "ball", "axis": [0, 0, 0]}"#,
        ),
        "joints[2].axis",
        "zero length",
    );
    assert_refused(
        "joint_missing_axis",
        &scene_with_joint(r#"{"type": "prismatic", "body_a": "door", "body_b": "ball"}"#),
        "joints[2].axis",
        "required field is missing (a prismatic joint needs it)",
    );
}

#[test]
fn inverted_joint_limits_are_refused() {
    assert_refused(
        "joint_inverted_limits",
        &scene_with_joint(
            r#"{"type": "revolute", "body_a": "door", "body_b": "ball", "axis": [0, 1, 0],
                "limits": [1, -1]}"#,
        ),
        "joints[2].limits",
        "min must not exceed max, got [1, -1]",
    );
    assert_refused(
        "joint_inverted_twist_limits",
        &scene_with_joint(
            r#"{"type": "ball", "body_a": "door", "body_b": "ball", "axis": [0, 1, 0],
                "twist_limits": [0.5, 0.2]}"#,
        ),
        "joints[2].twist_limits",
        "min must not exceed max",
    );
}

#[test]
fn negative_joint_stiffness_damping_max_force_friction_and_break_values_are_refused() {
    let motor = |motor: &str| {
        scene_with_joint(&format!(
            r#"{{"type": "revolute", "body_a": "door", "body_b": "ball", "axis": [0, 1, 0],
                "motor": {motor}}}"#
        ))
    };
    let spring = |spring: &str| {
        scene_with_joint(&format!(
            r#"{{"type": "distance", "body_a": "door", "body_b": "ball", "spring": {spring}}}"#
        ))
    };
    let ball = |field: &str| {
        scene_with_joint(&format!(
            r#"{{"type": "ball", "body_a": "door", "body_b": "ball", {field}}}"#
        ))
    };
    let cases = [
        (
            "joint_negative_spring_stiffness",
            spring(r#"{"stiffness": -5, "damping": 1}"#),
            "joints[2].spring.stiffness",
        ),
        (
            "joint_negative_spring_damping",
            spring(r#"{"stiffness": 5, "damping": -1}"#),
            "joints[2].spring.damping",
        ),
        (
            "joint_negative_motor_stiffness",
            motor(r#"{"target_position": 1, "stiffness": -5, "damping": 1}"#),
            "joints[2].motor.stiffness",
        ),
        (
            "joint_negative_motor_damping",
            motor(r#"{"target_position": 1, "stiffness": 5, "damping": -1}"#),
            "joints[2].motor.damping",
        ),
        (
            "joint_negative_max_force",
            motor(r#"{"target_velocity": 1, "max_force": -1}"#),
            "joints[2].motor.max_force",
        ),
        (
            "joint_negative_break_force",
            ball(r#""break_force": -1"#),
            "joints[2].break_force",
        ),
        (
            "joint_negative_break_torque",
            ball(r#""break_torque": -1"#),
            "joints[2].break_torque",
        ),
        (
            "joint_negative_friction",
            ball(r#""friction": -1"#),
            "joints[2].friction",
        ),
    ];
    for (test_name, scene, place) in cases {
        assert_refused(test_name, &scene, place, "must not be negative");
    }
}

#[test]
fn joint_fields_of_another_joint_type_are_refused() {
    assert_refused(
        "joint_spring_on_ball",
        &scene_with_joint(
            r#"{"type": "ball", "body_a": "door", "body_b": "ball",
                "spring": {"stiffness": 10, "damping": 1}}"#,
        ),
        "joints[2].spring",
        "does not apply to a ball joint",
    );
    assert_refused(
        "joint_motor_on_ball",
        &scene_with_joint(
            r#"{"type": "ball", "body_a": "door", "body_b": "ball",
                "motor": {"target_velocity": 1, "max_force": 5}}"#,
        ),
        "joints[2].motor",
        "does not apply to a ball joint",
    );
    assert_refused(
        "joint_anchor_b_on_fixed",
        &scene_with_joint(
            r#"{"type": "fixed", "body_a": "door", "body_b": "ball", "anchor_b": [0, 0, 0]}"#,
        ),
        "joints[2].anchor_b",
        "does not apply to a fixed joint",
    );
    assert_refused(
        "joint_swing_limit_on_prismatic",
        &scene_with_joint(
            r#"{"type": "prismatic", "body_a": "door", "body_b": "ball", "axis": [1, 0, 0],
                "swing_limit": 0.5}"#,
        ),
        "joints[2].swing_limit",
        "does not apply to a prismatic joint",
    );
    assert_refused(
        "joint_friction_on_distance",
        &scene_with_joint(
            r#"{"type": "distance", "body_a": "door", "body_b": "ball", "friction": 1}"#,
        ),
        "joints[2].friction",
        "does not apply to a distance joint",
    );
    assert_refused(
        "joint_position_field_on_velocity_motor",
        &scene_with_joint(
            r#"{"type": "revolute", "body_a": "door", "body_b": "ball", "axis": [0, 1, 0],
                "motor": {"target_velocity": 1, "stiffness": 5}}"#,
        ),
        "joints[2].motor.stiffness",
        "unknown field `stiffness` for a velocity motor",
    );
    assert_refused(
        "joint_motor_without_target",
        &scene_with_joint(
            r#"{"type": "revolute", "body_a": "door", "body_b": "ball", "axis": [0, 1, 0],
                "motor": {"max_force": 5}}"#,
        ),
        "joints[2].motor",
        "required field is missing",
    );
}

#[test]
fn duplicate_unknown_and_non_finite_joint_values_are_refused() {
    assert_refused(
        "joint_duplicate_name",
        &scene_with_joint(r#"{"name": "hinge", "type": "ball", "body_b": "door"}"#),
        "joints[2].name",
        "duplicate name \"hinge\": joints[0] and joints[2]",
    );
    assert_refused(
        "joint_duplicate_default_name",
        &scene_with_joint(r#"{"name": "joint1", "type": "ball", "body_b": "door"}"#),
        "joints[2].name",
        "duplicate name \"joint1\": joints[1] and joints[2]",
    );
    assert_refused(
        "joint_unknown_field",
        &scene_with_joint(r#"{"type": "ball", "body_b": "door", "stiffness": 3}"#),
        "joints[2].stiffness",
        "unknown field `stiffness`",
    );
    assert_refused(
        "joint_unknown_type",
        &scene_with_joint(r#"{"type": "hinge", "body_b": "door"}"#),
        "joints[2].type",
        "unknown variant `hinge`",
    );
    assert_refused(
        "joint_unknown_motor_field",
        &scene_with_joint(
            r#"{"type": "revolute", "body_b": "door", "axis": [0, 1, 0],
                "motor": {"target_velocity": 1, "torque": 5}}"#,
        ),
        "joints[2].motor.torque",
        "unknown field `torque`",
    );
    assert_refused(
        "joint_anchor_beyond_f32",
        &scene_with_joint(r#"{"type": "ball", "body_b": "door", "anchor": [0, 1e39, 0]}"#),
        "joints[2].anchor[1]",
        "must be finite",
    );
    assert_refused(
        "joint_break_force_beyond_f64",
        &scene_with_joint(r#"{"type": "ball", "body_b": "door", "break_force": 1e999}"#),
        "joints[2].break_force",
        "beyond the floating-point range",
    );
    assert_refused(
        "joint_limit_beyond_f32",
        &scene_with_joint(
            r#"{"type": "distance", "body_a": "door", "body_b": "ball", "limits": [0, 1e39]}"#,
        ),
        "joints[2].limits[1]",
        "must be finite",
    );
}

#[test]
fn bad_torque_motors_and_revolute_limits_are_refused() {
    let motor = |joint_type: &str, motor: &str| {
        scene_with_joint(&format!(
            r#"{{"type": "{joint_type}", "body_a": "door", "body_b": "ball",
                "axis": [0, 1, 0], "motor": {motor}}}"#
        ))
    };
    let cases = [
        (
            "torque_string",
            motor("revolute", r#"{"torque": "strong"}"#),
            "joints[2].motor.torque",
            "invalid type: string \"strong\"",
        ),
        (
            "torque_beyond_f32",
            motor("prismatic", r#"{"torque": -1e39}"#),
            "joints[2].motor.torque",
            "must be finite",
        ),
        (
            "torque_beyond_the_force_limit",
            motor("revolute", r#"{"torque": 2e12}"#),
            "joints[2].motor.torque",
            "must lie between -1000000000000 and 1000000000000, got 2000000000000",
        ),
        (
            "torque_with_max_force",
            motor("revolute", r#"{"torque": 1, "max_force": 5}"#),
            "joints[2].motor.max_force",
            "unknown field `max_force` for a torque motor, expected `torque`",
        ),
        (
            "torque_on_ball",
            motor("ball", r#"{"torque": 1}"#),
            "joints[2].motor",
            "does not apply to a ball joint",
        ),
        (
            "revolute_limits_beyond_the_coordinate_limit",
            scene_with_joint(
                r#"{"type": "revolute", "body_a": "door", "body_b": "ball", "axis": [0, 1, 0],
                    "limits": [-6.3, 20000]}"#,
            ),
            "joints[2].limits[1]",
            "must lie between",
        ),
    ];
    for (test_name, scene, place, message) in cases {
        assert_refused(test_name, &scene, place, message);
    }
    let distance = scene_with_joint(
        r#"{"type": "distance", "body_a": "door", "body_b": "ball", "motor": {"torque": 1}}"#,
    );
    assert_refused(
        "torque_on_distance",
        &distance,
        "joints[2].motor",
        "does not apply to a distance joint",
    );
}
