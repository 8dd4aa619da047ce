//! Kinematic bodies with a `path`: they pass each keyframe's pose at its time and carry what
//! rests on them, and a run saved mid-path resumes byte for byte.

use std::ffi::OsStr;
use std::fs;
use std::path::Path;

use serde_json::Value;

use crate::common::{rebond, TestDir};

/// At 64 Hz (a power of two, so the path clock lands exactly on each keyframe time): a platform
/// at rest for 0.5 s, then 2 m along x in 2 s, then stopped, with a box on it; and a turntable
/// whose points give only a rotation (their position is the body's), an eighth of a turn a second,
/// looping every 2 s (there and back).
const SCENE: &str = r#"{
  "timestep": 0.015625,
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "platform", "type": "kinematic", "shape": {"type": "box", "half_extents": [2, 0.1, 2]},
     "path": {"points": [{"time": 0, "position": [0, 0, 0]}, {"time": 0.5, "position": [0, 0, 0]},
                         {"time": 2.5, "position": [2, 0, 0]}]}},
    {"name": "box", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
     "position": [0, 0.6, 0], "can_sleep": false},
    {"name": "turntable", "type": "kinematic", "shape": {"type": "cylinder", "radius": 1, "half_height": 0.1},
     "position": [0, 0, 10],
     "path": {"loop": true, "points": [{"time": 0}, {"time": 1, "rotation": [0, 0.38268343, 0, 0.9238795]},
                                       {"time": 2}]}}
  ]
}"#;

fn os(text: &str) -> &OsStr {
    OsStr::new(text)
}

/// Runs `arguments` and returns the record's lines as JSON.
fn run_and_record(arguments: &[&OsStr], record: &Path) -> Vec<String> {
    let mut all = arguments.to_vec();
    all.extend([os("--record"), record.as_os_str()]);
    let outcome = rebond(&all);
    assert_eq!(outcome.status, 0, "stderr: {}", outcome.stderr);
    let text = fs::read_to_string(record).expect("a record");
    text.lines().map(str::to_owned).collect()
}

fn vector(body: &Value, field: &str) -> Vec<f64> {
    body[field]
        .as_array()
        .expect("a vector")
        .iter()
        .map(|value| value.as_f64().expect("a number"))
        .collect()
}

#[test]
fn a_platform_passes_its_keyframes_and_carries_a_box() {
    let dir = TestDir::new("kinematic_path");
    let scene = dir.write("scene.json", SCENE);
    let record = dir.path("record.jsonl");
    let lines = run_and_record(
        &[
            os("run"),
            scene.as_os_str(),
            os("--steps"),
            os("256"),
            os("--every"),
            os("32"),
        ],
        &record,
    );
    let at = |step: usize, body: usize| -> Value {
        let line: Value = serde_json::from_str(&lines[step / 32]).expect("a JSON line");
        assert_eq!(line["step"], step);
        line["bodies"][body].clone()
    };
    // The platform at each keyframe time exactly, and halfway between.
    for (step, x) in [(0, 0.0), (32, 0.0), (96, 1.0), (160, 2.0), (256, 2.0)] {
        assert_eq!(
            vector(&at(step, 0), "position"),
            [x, 0.0, 0.0],
            "step {step}"
        );
    }
    assert_eq!(vector(&at(96, 0), "linear_velocity"), [1.0, 0.0, 0.0]);
    assert_eq!(vector(&at(256, 0), "linear_velocity"), [0.0, 0.0, 0.0]);
    // The box rides at the platform's speed, and ends where it stood on it: it slips back
    // v²/(2μg) − vh/2 = 0.101 m at the start and forward by the same at the stop
    // (crates/rebond/tests/kinematic.rs); 1e-3 m covers the cancelling slips with room.
    let box_velocity = vector(&at(96, 1), "linear_velocity");
    assert!((box_velocity[0] - 1.0).abs() < 1e-3, "{box_velocity:?}");
    let box_x = vector(&at(256, 1), "position")[0];
    assert!((box_x - 2.0).abs() < 1e-3, "the box ends at {box_x}");
    // The turntable's points take its position; an eighth of a turn at 1 s, back at 2 s, again
    // at 3 s.
    let eighth = [0.0, 0.38268343f32 as f64, 0.0, 0.9238795f32 as f64];
    for (step, rotation) in [(64, eighth), (128, [0.0, 0.0, 0.0, 1.0]), (192, eighth)] {
        let turntable = at(step, 2);
        assert_eq!(vector(&turntable, "position"), [0.0, 0.0, 10.0]);
        let got = vector(&turntable, "rotation");
        // The record's f32 rotation, normalised on load: a few 1e-8 per component from the
        // written one; 1e-6 summed over the four.
        let error: f64 = got.iter().zip(rotation).map(|(a, b)| (a - b).abs()).sum();
        assert!(error < 1e-6, "step {step}: {got:?}");
    }
}

#[test]
fn a_run_saved_mid_path_resumes_byte_for_byte() {
    let dir = TestDir::new("kinematic_resume");
    let scene = dir.write("scene.json", SCENE);
    let (whole, first, second) = (
        dir.path("whole.jsonl"),
        dir.path("first.jsonl"),
        dir.path("second.jsonl"),
    );
    let state = dir.path("at-70.state");
    let whole = run_and_record(
        &[os("run"), scene.as_os_str(), os("--steps"), os("200")],
        &whole,
    );
    let save = [os("--save-state"), state.as_os_str()];
    let steps = [os("--steps"), os("70")];
    run_and_record(
        &[&[os("run"), scene.as_os_str()][..], &steps, &save].concat(),
        &first,
    );
    let resumed = run_and_record(
        &[os("resume"), state.as_os_str(), os("--steps"), os("130")],
        &second,
    );
    // The resumed record starts with step 70, as the whole run wrote it.
    assert_eq!(resumed.len(), 131);
    assert_eq!(resumed[..], whole[70..]);
}
