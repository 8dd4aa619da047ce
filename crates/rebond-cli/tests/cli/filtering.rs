//! The scene format's optional extensions for sensors and collision groups (documented in the
//! README): a ball falls through a sensor and through a platform whose groups exclude it, but
//! lands on one whose groups include it; bad masks are refused like any other bad value.

use std::fs;

use serde_json::Value;

use crate::common::{assert_one_error_line, rebond, TestDir};

/// Three balls dropped from y = 5 (bottom at 4.5) onto three platforms whose tops are at y = 2,
/// above a ground whose top is y = 0: the first platform is a sensor, the second is in group 2
/// and interacts with group 2 only (the ball is in group 1), the third has the default groups.
const SCENE: &str = r#"{
  "timestep": 0.02,
  "bodies": [
    {"name": "ground", "type": "static",
     "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
    {"name": "sensor_platform", "type": "static", "sensor": true,
     "shape": {"type": "box", "half_extents": [1, 0.25, 1]}, "position": [-4, 1.75, 0]},
    {"name": "excluding_platform", "type": "static",
     "collision_groups": {"memberships": 2, "filter": 2},
     "shape": {"type": "box", "half_extents": [1, 0.25, 1]}, "position": [0, 1.75, 0]},
    {"name": "platform", "type": "static",
     "shape": {"type": "box", "half_extents": [1, 0.25, 1]}, "position": [4, 1.75, 0]},
    {"name": "ball_a", "shape": {"type": "sphere", "radius": 0.5}, "position": [-4, 5, 0],
     "collision_groups": {"memberships": 1}},
    {"name": "ball_b", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 5, 0],
     "collision_groups": {"memberships": 1}},
    {"name": "ball_c", "shape": {"type": "sphere", "radius": 0.5}, "position": [4, 5, 0],
     "collision_groups": {"memberships": 1}}
  ]
}"#;

#[test]
fn balls_fall_through_sensors_and_excluding_groups_and_land_on_the_rest() {
    let dir = TestDir::new("filtering_platforms");
    let scene = dir.write("scene.json", SCENE);
    let record = dir.path("record.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        scene.as_os_str(),
        "--seconds".as_ref(),
        "3".as_ref(),
        "--record".as_ref(),
        record.as_os_str(),
        "--every".as_ref(),
        "1000".as_ref(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    let text = fs::read_to_string(&record).unwrap();
    let last: Value = serde_json::from_str(text.lines().last().unwrap()).unwrap();
    let height = |name: &str| {
        last["bodies"]
            .as_array()
            .unwrap()
            .iter()
            .find(|body| body["name"] == name)
            .unwrap()["position"][1]
            .as_f64()
            .unwrap()
    };
    // After 3 s every ball has landed and come to rest: its centre one radius (0.5 m) above
    // what it rests on, to the soft contact's few-millimetre sink.
    for (name, expected) in [("ball_a", 0.5), ("ball_b", 0.5), ("ball_c", 2.5)] {
        let y = height(name);
        assert!(
            (y - expected).abs() < 0.02,
            "{name} at y = {y}, expected {expected}"
        );
    }
}

#[test]
fn bad_sensor_flags_and_group_masks_are_refused() {
    let cases = [
        (r#""sensor": 1"#, "bodies[0].sensor"),
        (
            r#""collision_groups": {"memberships": -1}"#,
            "bodies[0].collision_groups.memberships",
        ),
        (
            r#""collision_groups": {"filter": 4294967296}"#,
            "bodies[0].collision_groups.filter",
        ),
        (
            r#""collision_groups": {"groups": 1}"#,
            "bodies[0].collision_groups",
        ),
        (
            r#""collision_groups": [1, 2]"#,
            "bodies[0].collision_groups",
        ),
    ];
    for (index, (field, place)) in cases.into_iter().enumerate() {
        let dir = TestDir::new(&format!("filtering_bad_{index}"));
        let scene = dir.write(
            "scene.json",
            &format!(
                r#"{{"bodies": [{{"shape": {{"type": "sphere", "radius": 0.5}}, {field}}}]}}"#
            ),
        );
        let outcome = rebond([
            "run".as_ref(),
            scene.as_os_str(),
            "--steps".as_ref(),
            "1".as_ref(),
        ]);
        let line = assert_one_error_line(&outcome, 2, &scene);
        let expected = format!("error: {}: {place}", scene.display());
        assert!(
            line.starts_with(&expected),
            "{field}: expected `{place}` in: {line}"
        );
    }
}
