//! Records: JSON Lines with every body in every line in scene order, step 0 first, every K-th
//! step, the last step always, consistent times, and byte-identical output across runs.

use std::ffi::OsString;
use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};
use std::thread;
use std::time::Duration;

use serde_json::Value;

use crate::common::{assert_one_error_line, rebond, Outcome, TestDir};

/// A static ground, a named falling ball, an unnamed spinning box and a kinematic paddle.
const SCENE: &str = r#"{
  "timestep": 0.02,
  "bodies": [
    {"name": "ground", "type": "static",
     "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 50, 0],
     "restitution": 0.5},
    {"shape": {"type": "box", "half_extents": [0.5, 0.25, 1]}, "position": [5, 60, 0],
     "angular_velocity": [0, 2, 0.1]},
    {"name": "paddle", "type": "kinematic", "shape": {"type": "capsule", "radius": 0.2,
     "half_height": 1}, "position": [-5, 1, 0], "linear_velocity": [1, 0, 0]}
  ]
}"#;

/// The names of [`SCENE`]'s bodies, in scene order (the third takes its default name).
const NAMES: [&str; 4] = ["ground", "ball", "body2", "paddle"];

/// Runs `scene` with `options` and a record, and returns the outcome and the record lines.
fn record(dir: &TestDir, scene: &Path, options: &[&str]) -> (Outcome, Vec<Value>) {
    let record_path = dir.path("record.jsonl");
    let mut arguments = vec![
        OsString::from("run"),
        scene.as_os_str().to_owned(),
        OsString::from("--record"),
        record_path.as_os_str().to_owned(),
    ];
    arguments.extend(options.iter().map(OsString::from));
    let outcome = rebond(arguments);
    assert_eq!(outcome.status, 0, "stderr: {}", outcome.stderr);
    let text = fs::read_to_string(&record_path).expect("the record file exists");
    assert!(text.ends_with('\n'), "every line ends with a newline");
    let lines = text
        .lines()
        .map(|line| serde_json::from_str(line).expect("each record line is JSON"))
        .collect();
    (outcome, lines)
}

/// The `step` of every line.
fn steps(lines: &[Value]) -> Vec<u64> {
    lines
        .iter()
        .map(|line| line["step"].as_u64().expect("step is an unsigned integer"))
        .collect()
}

/// Checks one record line against the contract: its keys, and every body in scene order with
/// the right fields.
fn check_line(line: &Value, names: &[&str], timestep: f64) {
    let object = line.as_object().expect("a record line is an object");
    let mut keys: Vec<&str> = object.keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(keys, ["bodies", "step", "time"]);
    let step = line["step"].as_u64().expect("step") as f64;
    let time = line["time"].as_f64().expect("time is a number");
    assert!(
        (time - step * timestep).abs() <= 1e-9 * step.max(1.0),
        "time {time} at step {step}"
    );
    let bodies = line["bodies"].as_array().expect("bodies is an array");
    let line_names: Vec<&str> = bodies
        .iter()
        .map(|body| body["name"].as_str().expect("name is a string"))
        .collect();
    assert_eq!(line_names, names, "every body, in scene order");
    for body in bodies {
        let mut fields: Vec<&str> = body
            .as_object()
            .expect("a body is an object")
            .keys()
            .map(String::as_str)
            .collect();
        fields.sort_unstable();
        assert_eq!(
            fields,
            [
                "angular_velocity",
                "linear_velocity",
                "name",
                "position",
                "rotation",
                "sleeping"
            ]
        );
        for (field, length) in [
            ("position", 3),
            ("rotation", 4),
            ("linear_velocity", 3),
            ("angular_velocity", 3),
        ] {
            let values = body[field].as_array().expect("a vector is an array");
            assert_eq!(values.len(), length, "{field}");
            assert!(values.iter().all(Value::is_f64), "{field} holds numbers");
        }
        assert!(body["sleeping"].is_boolean());
    }
}

#[test]
fn a_record_holds_step_zero_every_kth_step_and_the_last_step() {
    let dir = TestDir::new("record_every");
    let scene = dir.write("scene.json", SCENE);
    let (_, lines) = record(&dir, &scene, &["--steps", "10", "--every", "4"]);
    assert_eq!(steps(&lines), [0, 4, 8, 10]);
    for line in &lines {
        check_line(line, &NAMES, 0.02);
    }
}

#[test]
fn the_last_step_is_recorded_once() {
    let dir = TestDir::new("record_last_once");
    let scene = dir.write("scene.json", SCENE);
    let (_, lines) = record(&dir, &scene, &["--steps", "8", "--every", "4"]);
    assert_eq!(steps(&lines), [0, 4, 8]);
    let (_, lines) = record(&dir, &scene, &["--steps", "3", "--every", "100"]);
    assert_eq!(steps(&lines), [0, 3]);
}

#[test]
fn every_step_is_recorded_by_default() {
    let dir = TestDir::new("record_default_every");
    let scene = dir.write("scene.json", SCENE);
    let (_, lines) = record(&dir, &scene, &["--steps", "5"]);
    assert_eq!(steps(&lines), [0, 1, 2, 3, 4, 5]);
    for line in &lines {
        check_line(line, &NAMES, 0.02);
    }
}

#[test]
fn seconds_become_steps_rounded_up() {
    let dir = TestDir::new("record_seconds");
    let scene = dir.write("scene.json", SCENE);
    let (_, lines) = record(&dir, &scene, &["--seconds", "0.1", "--every", "1000"]);
    assert_eq!(steps(&lines), [0, 5]);
    let (_, lines) = record(&dir, &scene, &["--seconds", "0.11", "--every", "1000"]);
    assert_eq!(steps(&lines), [0, 6]);
}

#[test]
fn the_default_run_is_ten_seconds() {
    let dir = TestDir::new("record_default_length");
    let scene = dir.write("scene.json", SCENE);
    let (outcome, lines) = record(&dir, &scene, &["--every", "100"]);
    assert_eq!(steps(&lines).last(), Some(&500));
    assert!(
        outcome.stdout.contains("simulated time   10 s"),
        "{}",
        outcome.stdout
    );
}

#[test]
fn time_is_step_times_timestep_in_double_precision() {
    let dir = TestDir::new("record_time");
    let scene = dir.write(
        "scene.json",
        r#"{"bodies": [{"shape": {"type": "sphere", "radius": 1}}]}"#,
    );
    let record_path = dir.path("record.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        scene.as_os_str(),
        "--steps".as_ref(),
        "120".as_ref(),
        "--every".as_ref(),
        "60".as_ref(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    let text = fs::read_to_string(&record_path).expect("the record file exists");
    let last = text.lines().last().expect("a last line");
    assert!(
        last.starts_with(r#"{"step":120,"time":2.0,"bodies":[{"name":"body0","#),
        "{last}"
    );
}

#[test]
fn bodies_move_as_their_types_say() {
    let dir = TestDir::new("record_motion");
    let scene = dir.write("scene.json", SCENE);
    let (_, lines) = record(&dir, &scene, &["--steps", "20", "--every", "20"]);
    let first = &lines[0]["bodies"];
    let last = &lines[1]["bodies"];
    assert_eq!(first[0], last[0], "the static ground does not move");
    assert_eq!(
        first[0]["linear_velocity"],
        serde_json::json!([0.0, 0.0, 0.0])
    );
    // The ball falls freely for 20 steps of 0.02 s: the engine's semi-implicit Euler, each
    // substep in f32 (`tests/motion.rs` checks the same in the library). The record holds the
    // shortest text that reads back as the same f32, so the fall is exact, to the bit.
    let settings = rebond::WorldSettings::default();
    let h = 0.02f32 / settings.substeps as f32;
    let (mut height, mut speed) = (50.0f32, 0.0f32);
    for _ in 0..20 * settings.substeps {
        speed += h * settings.gravity.y;
        height += h * speed;
    }
    let ball = |bodies: &Value, field: &str| bodies[1][field][1].as_f64().expect("a number") as f32;
    assert_eq!(ball(first, "position"), 50.0);
    assert_eq!(ball(last, "position"), height, "the ball falls");
    assert_eq!(ball(last, "linear_velocity"), speed, "the ball falls");
    let paddle_x = |bodies: &Value| bodies[3]["position"][0].as_f64().expect("a number");
    assert!(
        (paddle_x(last) - paddle_x(first) - 0.4).abs() < 1e-4,
        "the kinematic paddle moves at its velocity for 0.4 s"
    );
    assert_eq!(
        first[2]["angular_velocity"],
        serde_json::json!([0.0, 2.0, 0.1])
    );
    assert_eq!(
        first[1]["rotation"],
        serde_json::json!([0.0, 0.0, 0.0, 1.0])
    );
}

#[test]
fn rotations_are_normalised_on_load() {
    let dir = TestDir::new("record_rotation");
    let scene = dir.write(
        "scene.json",
        r#"{"bodies": [{"type": "static", "shape": {"type": "sphere", "radius": 1},
            "rotation": [0, 0, 0, 2]}]}"#,
    );
    let (_, lines) = record(&dir, &scene, &["--steps", "1"]);
    assert_eq!(
        lines[0]["bodies"][0]["rotation"],
        serde_json::json!([0.0, 0.0, 0.0, 1.0])
    );
}

#[test]
fn two_runs_give_byte_identical_records() {
    let dir = TestDir::new("record_deterministic");
    let scene = dir.write("scene.json", SCENE);
    let run = |name: &str, scene: &Path| {
        let path = dir.path(name);
        let outcome = rebond([
            "run".as_ref(),
            scene.as_os_str(),
            "--steps".as_ref(),
            "60".as_ref(),
            "--every".as_ref(),
            "7".as_ref(),
            "--record".as_ref(),
            path.as_os_str(),
        ]);
        assert_eq!(outcome.status, 0, "{}", outcome.stderr);
        fs::read(path).expect("the record file exists")
    };
    assert_eq!(run("first.jsonl", &scene), run("second.jsonl", &scene));
    let spinner = Path::new("spinner");
    assert_eq!(run("third.jsonl", spinner), run("fourth.jsonl", spinner));
}

#[test]
fn an_existing_record_file_is_replaced() {
    let dir = TestDir::new("record_replaced");
    let scene = dir.write("scene.json", SCENE);
    dir.write(
        "record.jsonl",
        "old contents that are not JSON\n".repeat(100).as_str(),
    );
    let (_, lines) = record(&dir, &scene, &["--steps", "2"]);
    assert_eq!(steps(&lines), [0, 1, 2]);
}

#[test]
fn a_record_naming_the_scene_file_is_refused_and_the_scene_kept() {
    let dir = TestDir::new("record_is_scene");
    let scene = dir.write("scene.json", SCENE);
    let roundabout = dir
        .root()
        .join("..")
        .join(dir.root().file_name().expect("the test folder has a name"));
    for record_path in [scene.clone(), roundabout.join("scene.json")] {
        let outcome = rebond([
            "run".as_ref(),
            scene.as_os_str(),
            "--steps".as_ref(),
            "2".as_ref(),
            "--record".as_ref(),
            record_path.as_os_str(),
        ]);
        let line = assert_one_error_line(&outcome, 2, &record_path);
        assert!(
            line.contains("--record names the scene file itself"),
            "{line}"
        );
        assert_eq!(fs::read_to_string(&scene).unwrap(), SCENE);
    }
}

#[test]
fn a_killed_run_leaves_no_record_under_its_name() {
    let dir = TestDir::new("record_killed");
    let record_path = dir.path("record.jsonl");
    let mut child = Command::new(env!("CARGO_BIN_EXE_rebond"))
        .args(["run", "rain", "--steps", "1000000", "--record"])
        .arg(&record_path)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("rebond starts");
    // Long enough to load the scene and record some steps of the 4,096 falling boxes.
    thread::sleep(Duration::from_millis(1500));
    child.kill().expect("the run is still going");
    child.wait().expect("the run ends");
    assert!(
        !record_path.exists(),
        "a partial record took the record's name"
    );
}
