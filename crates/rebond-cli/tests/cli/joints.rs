//! Joints in records: every line of a scene with joints carries `"joints"` in scene order, with
//! the force and torque each joint applied to its `body_b` over the step, and zeros once broken,
//! and for revolute, prismatic and distance joints their position and velocity.

use std::fs;

use serde_json::Value;

use crate::common::{rebond, TestDir};

/// A hinge and a rope holding a box to a post, a ball hung from the world by an unnamed joint,
/// and a fixed joint to an unnamed body.
const SCENE: &str = r#"{
  "bodies": [
    {"name": "post", "type": "static", "shape": {"type": "box", "half_extents": [0.1, 2, 0.1]},
     "position": [0, 2, 0]},
    {"name": "door", "shape": {"type": "box", "half_extents": [0.5, 1, 0.05]},
     "position": [0.6, 2, 0]},
    {"name": "bob", "shape": {"type": "sphere", "radius": 0.2}, "position": [3, 2, 0]},
    {"shape": {"type": "sphere", "radius": 0.2}, "position": [3, 1.5, 0]}
  ],
  "joints": [
    {"name": "hinge", "type": "revolute", "body_a": "post", "body_b": "door",
     "anchor": [0.1, 2, 0], "axis": [0, 1, 0], "limits": [-1, 1],
     "motor": {"target_velocity": 0.5, "max_force": 20}},
    {"name": "rope", "type": "distance", "body_a": "post", "body_b": "door",
     "anchor": [0, 4, 0], "anchor_b": [1, 3, 0], "limits": [0, 2]},
    {"type": "ball", "body_a": null, "body_b": "bob", "anchor": [3, 3, 0]},
    {"name": "weld", "type": "fixed", "body_a": "bob", "body_b": "body3"}
  ]
}"#;

/// Runs `scene` (written to `dir`) for `steps` steps with a record, and returns the record's
/// lines.
fn record(dir: &TestDir, scene: &str, steps: &str) -> Vec<Value> {
    let scene_path = dir.write("scene.json", scene);
    let record_path = dir.path("record.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        scene_path.as_os_str(),
        "--steps".as_ref(),
        steps.as_ref(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    fs::read_to_string(&record_path)
        .expect("the record file exists")
        .lines()
        .map(|line| serde_json::from_str(line).expect("each line is JSON"))
        .collect()
}

/// The `index`-th component of a vector field of a joint in a record line.
fn component(joint: &Value, field: &str, index: usize) -> f64 {
    joint[field][index]
        .as_f64()
        .unwrap_or_else(|| panic!("`{field}` of {joint} is not a vector of numbers"))
}

#[test]
fn every_line_carries_the_joints_in_scene_order() {
    let dir = TestDir::new("joints_in_order");
    let lines = record(&dir, SCENE, "30");
    assert_eq!(lines.len(), 31);
    for line in &lines {
        let joints = line["joints"].as_array().expect("a joints array");
        let names: Vec<&str> = joints
            .iter()
            .map(|joint| joint["name"].as_str().expect("a name"))
            .collect();
        assert_eq!(names, ["hinge", "rope", "joint2", "weld"]);
        for joint in joints {
            let object = joint.as_object().expect("a joint is an object");
            let keys: Vec<&str> = object.keys().map(String::as_str).collect();
            // Revolute, prismatic and distance joints carry their coordinate and its rate.
            let coordinates = ["hinge", "rope"].contains(&joint["name"].as_str().unwrap());
            assert_eq!(keys.len(), if coordinates { 6 } else { 4 }, "{joint}");
            for key in ["name", "force", "torque", "broken"] {
                assert!(object.contains_key(key), "{joint} lacks `{key}`");
            }
            if coordinates {
                for key in ["position", "velocity"] {
                    assert!(joint[key].as_f64().is_some_and(f64::is_finite), "{joint}");
                }
            }
            for field in ["force", "torque"] {
                for index in 0..3 {
                    assert!(component(joint, field, index).is_finite(), "{joint}");
                }
            }
            assert_eq!(joint["broken"], false);
        }
    }
    let first = &lines[0]["joints"][0];
    assert_eq!(first["force"], serde_json::json!([0.0, 0.0, 0.0]));
    // The ball joint holds the bob and, through the weld, the second ball: both hang from it.
    let hanging = &lines[30]["joints"][2];
    assert!(component(hanging, "force", 1) > 0.0, "{hanging}");
}

#[test]
fn a_ball_hanging_still_from_a_ball_joint_pulls_it_with_its_weight() {
    let dir = TestDir::new("joints_hanging_weight");
    let scene = r#"{
      "bodies": [{"name": "bob", "shape": {"type": "sphere", "radius": 0.25}, "mass": 3.0,
                  "position": [1, 4, -2], "can_sleep": false}],
      "joints": [{"name": "hook", "type": "ball", "body_b": "bob", "anchor": [1, 5, -2]}]
    }"#;
    let lines = record(&dir, scene, "120");
    let hook = &lines.last().expect("a last line")["joints"][0];
    assert_eq!(hook["name"], "hook");
    assert_eq!(hook["broken"], false);
    let weight = 3.0 * 9.81;
    let up = component(hook, "force", 1);
    assert!(
        (up - weight).abs() <= 0.01 * weight,
        "the joint holds up {up} N of a {weight} N weight"
    );
    for index in [0, 2] {
        assert!(
            component(hook, "force", index).abs() <= 0.01 * weight,
            "{hook}"
        );
    }
    for index in 0..3 {
        assert!(
            component(hook, "torque", index).abs() <= 0.01 * weight,
            "{hook}"
        );
    }
}

#[test]
fn a_broken_joint_reports_zeros_and_stays_broken() {
    let dir = TestDir::new("joints_broken");
    let scene = r#"{
      "bodies": [{"name": "bob", "shape": {"type": "sphere", "radius": 0.25}, "mass": 3.0,
                  "position": [0, 4, 0]}],
      "joints": [{"name": "weak", "type": "ball", "body_b": "bob", "anchor": [0, 5, 0],
                  "break_force": 10}]
    }"#;
    let lines = record(&dir, scene, "20");
    let last = &lines.last().expect("a last line");
    let weak = &last["joints"][0];
    assert_eq!(weak["broken"], true);
    assert_eq!(weak["force"], serde_json::json!([0.0, 0.0, 0.0]));
    assert_eq!(weak["torque"], serde_json::json!([0.0, 0.0, 0.0]));
    let fall_speed = last["bodies"][0]["linear_velocity"][1]
        .as_f64()
        .expect("a number");
    assert!(fall_speed < -1.0, "the bob falls free once the joint broke");
}

#[test]
fn a_scene_without_joints_writes_no_joints_field() {
    let dir = TestDir::new("joints_none");
    let bodies = r#""bodies": [{"shape": {"type": "sphere", "radius": 0.5}}]"#;
    for scene in [
        format!("{{{bodies}}}"),
        format!("{{{bodies}, \"joints\": []}}"),
    ] {
        for line in record(&dir, &scene, "2") {
            assert!(line.get("joints").is_none(), "{line}");
            assert_eq!(
                line.as_object().expect("an object").keys().count(),
                3,
                "{line}"
            );
        }
    }
}

#[test]
fn a_builtin_joint_scene_records_its_joints() {
    let dir = TestDir::new("joints_builtin");
    let record_path = dir.path("chain.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        "chain".as_ref(),
        "--steps".as_ref(),
        "60".as_ref(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    let text = fs::read_to_string(&record_path).expect("the record file exists");
    let last: Value = serde_json::from_str(text.lines().last().expect("lines")).expect("JSON");
    let joints = last["joints"].as_array().expect("a joints array");
    assert_eq!(joints.len(), 34);
    assert_eq!(joints[0]["name"], "ball_joint_0");
    assert_eq!(joints[33]["name"], "hinge_joint_weight");
    for joint in joints {
        assert_eq!(joint["broken"], false, "{joint}");
        for index in 0..3 {
            assert!(component(joint, "force", index).is_finite(), "{joint}");
        }
    }
}

#[test]
fn joint_positions_count_turns_and_torque_motors_drive_them() {
    // A wheel (2 kg disc of radius 0.5 m: I = m r² / 2 = 0.25 kg·m²) on a hinge through its
    // centre driven by a torque of 0.75 N·m, a 3 kg box on a slide pushed by 4.5 N, both against
    // the world, and a ball on a rope that breaks at once under its weight. After 2 s at 8
    // substeps of h = 1/480 s (n = 960), semi-implicit Euler gives ω = τ t / I = 6 rad/s and
    // θ = τ h² n (n + 1) / (2 I) = 6.00625 rad (past π: not wrapped), v = F t / m = 3 m/s and
    // s = 3.003125 m; rounding is under 1e-5 of each, 1e-4 allows for it.
    let dir = TestDir::new("joints_coordinates");
    let scene = r#"{
      "bodies": [
        {"name": "wheel", "shape": {"type": "cylinder", "radius": 0.5, "half_height": 0.1},
         "mass": 2, "position": [0, 2, 0], "can_sleep": false},
        {"name": "box", "shape": {"type": "box", "half_extents": [0.3, 0.1, 0.2]}, "mass": 3,
         "position": [0, 5, 0], "can_sleep": false},
        {"name": "bob", "shape": {"type": "sphere", "radius": 0.2}, "position": [3, 2, 0]}
      ],
      "joints": [
        {"name": "axle", "type": "revolute", "body_b": "wheel", "anchor": [0, 2, 0],
         "axis": [0, 1, 0], "motor": {"torque": 0.75}},
        {"name": "slide", "type": "prismatic", "body_b": "box", "anchor": [0, 5, 0],
         "axis": [1, 0, 0], "motor": {"torque": 4.5}},
        {"name": "rope", "type": "distance", "body_b": "bob", "anchor": [3, 3, 0],
         "anchor_b": [3, 2, 0],
         "break_force": 1}
      ]
    }"#;
    let lines = record(&dir, scene, "120");
    let first = &lines[0]["joints"];
    for index in 0..3 {
        assert_eq!(first[index]["velocity"], 0.0, "{}", first[index]);
    }
    assert_eq!(first[2]["position"], 1.0, "the rope starts 1 m long");
    let joints = &lines[120]["joints"];
    let close = |joint: &Value, field: &str, expected: f64| {
        let value = joint[field].as_f64().expect("a number");
        assert!(
            (value / expected - 1.0).abs() < 1e-4,
            "{field} {value}, expected {expected}: {joint}"
        );
    };
    close(&joints[0], "position", 6.00625);
    close(&joints[0], "velocity", 6.0);
    close(&joints[1], "position", 3.003125);
    close(&joints[1], "velocity", 3.0);
    // The torque motor's torque is what the joint applies to the wheel, about its axis.
    let torque = component(&joints[0], "torque", 1);
    assert!((torque - 0.75).abs() < 1e-5, "{}", joints[0]);
    // The broken rope is still measured between its anchors: the bob has fallen for about 2 s
    // (some 20 m, at some 20 m/s), and the rope reads its length and rate.
    let rope = &joints[2];
    assert_eq!(rope["broken"], true);
    assert!(
        rope["position"].as_f64().expect("a number") > 10.0,
        "{rope}"
    );
    assert!(
        rope["velocity"].as_f64().expect("a number") > 10.0,
        "{rope}"
    );
}
