//! `--save-state` and `rebond resume` against the contract's "Saving and resuming a world": a
//! resumed run writes the record lines of an uninterrupted one, byte for byte; state files that
//! are not whole states are refused; outputs never overwrite the files a command reads.

use std::ffi::OsStr;
use std::fs;
use std::path::Path;

use super::common::{assert_one_error_line, rebond, Outcome, TestDir};

/// Runs `rebond` with string-like arguments and checks it succeeded.
fn succeed(arguments: &[&OsStr]) -> Outcome {
    let outcome = rebond(arguments);
    assert_eq!(outcome.status, 0, "stderr: {}", outcome.stderr);
    outcome
}

fn os(text: &str) -> &OsStr {
    OsStr::new(text)
}

/// `--steps STEPS --record RECORD`.
fn run<'a>(steps: &'a str, record: &'a Path) -> [&'a OsStr; 4] {
    [os("--steps"), os(steps), os("--record"), record.as_os_str()]
}

/// The lines of a record, by step.
fn lines_by_step(path: &Path) -> Vec<(u64, String)> {
    fs::read_to_string(path)
        .expect("a record")
        .lines()
        .map(|line| {
            let value: serde_json::Value = serde_json::from_str(line).expect("a JSON line");
            (value["step"].as_u64().expect("a step"), line.to_owned())
        })
        .collect()
}

#[test]
fn resuming_a_saved_state_writes_the_record_of_an_uninterrupted_run() {
    // Built-in scenes with joints, contacts, sleeping, every convex shape and a triangle mesh:
    // 120 steps in one go, or 50 steps saved, resumed for 40 and saved again, then resumed for
    // 30. Every line the pieces write is the uninterrupted run's line for that step, byte for
    // byte.
    for scene in ["ragdolls", "car", "showcase", "level"] {
        let dir = TestDir::new(&format!("state_resume_{scene}"));
        let (whole, first, second, third) = (
            dir.path("whole.jsonl"),
            dir.path("first.jsonl"),
            dir.path("second.jsonl"),
            dir.path("third.jsonl"),
        );
        let (at_50, at_90) = (dir.path("at-50.state"), dir.path("at-90.state"));
        let every = ["--every".as_ref(), os("7")];

        succeed(&[&[os("run"), os(scene)], &run("120", &whole)[..], &every].concat());
        succeed(
            &[
                &[os("run"), os(scene)],
                &run("50", &first)[..],
                &every,
                &[os("--save-state"), at_50.as_os_str()],
            ]
            .concat(),
        );
        let resumed = succeed(
            &[
                &[os("resume"), at_50.as_os_str()],
                &run("40", &second)[..],
                &every,
                &[os("--save-state"), at_90.as_os_str()],
            ]
            .concat(),
        );
        assert!(
            resumed.stdout.contains("steps            40\n"),
            "{}",
            resumed.stdout
        );
        succeed(
            &[
                &[os("resume"), at_90.as_os_str()],
                &run("30", &third)[..],
                &every,
            ]
            .concat(),
        );
        let whole = lines_by_step(&whole);
        let mut pieces = Vec::new();
        for piece in [&first, &second, &third] {
            pieces.extend(lines_by_step(piece));
        }
        // Each piece starts with the step it resumed from, then its multiples of 7 and its last.
        let steps: Vec<u64> = pieces.iter().map(|(step, _)| *step).collect();
        assert_eq!(&steps[..3], &[0, 7, 14]);
        for step in [50, 90, 120] {
            assert!(steps.contains(&step), "{scene}: step {step} recorded");
        }
        for (step, line) in &pieces {
            if let Some((_, expected)) = whole.iter().find(|(whole_step, _)| whole_step == step) {
                assert_eq!(line, expected, "{scene}: step {step}");
            }
        }
        let shared = pieces
            .iter()
            .filter(|(step, _)| whole.iter().any(|(other, _)| other == step))
            .count();
        assert!(shared >= 18, "{scene}: only {shared} shared lines");
    }
}

#[test]
fn a_state_another_build_wrote_resumes_from_its_snapshot() {
    // The state as a build of other sources writes it: its fingerprint differs. The resumed run
    // starts from the saved bodies, so its first line (the step saved) is the exact resume's;
    // contacts start cold, so later lines may differ.
    let dir = TestDir::new("state_other_build");
    let state = dir.path("at-40.state");
    let (exact, portable) = (dir.path("exact.jsonl"), dir.path("portable.jsonl"));
    succeed(&[
        os("run"),
        os("showcase"),
        os("--steps"),
        os("40"),
        os("--save-state"),
        state.as_os_str(),
    ]);
    succeed(&[&[os("resume"), state.as_os_str()], &run("30", &exact)[..]].concat());
    let mut bytes = fs::read(&state).expect("the state");
    bytes[12] ^= 0x01;
    let other = dir.path("other-build.state");
    fs::write(&other, bytes).expect("write the state");
    succeed(
        &[
            &[os("resume"), other.as_os_str()],
            &run("30", &portable)[..],
        ]
        .concat(),
    );
    let (exact, portable) = (lines_by_step(&exact), lines_by_step(&portable));
    assert_eq!(portable.first(), exact.first());
    assert_eq!(portable.first().map(|(step, _)| *step), Some(40));
    assert_eq!(portable.last().map(|(step, _)| *step), Some(70));
}

#[test]
fn a_state_file_that_is_not_a_whole_state_is_refused_with_status_2() {
    let dir = TestDir::new("state_bad_files");
    let state = dir.path("good.state");
    succeed(&[
        os("run"),
        os("pyramid"),
        os("--steps"),
        os("20"),
        os("--save-state"),
        state.as_os_str(),
    ]);
    let bytes = fs::read(&state).expect("the state");
    let mut flipped = bytes.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x01;
    let mut newer = bytes.clone();
    newer[8] = newer[8].wrapping_add(1);
    let newer_message = format!("format version {}", rebond::state::STATE_FORMAT_VERSION + 1);
    let cases: [(&str, Vec<u8>, &str); 5] = [
        (
            "scene.json",
            br#"{"bodies": []}"#.to_vec(),
            "not a rebond state file",
        ),
        ("empty.state", Vec::new(), "not a rebond state file"),
        (
            "cut.state",
            bytes[..bytes.len() - 10].to_vec(),
            "truncated state",
        ),
        ("flipped.state", flipped, "damaged state"),
        ("newer.state", newer, &newer_message),
    ];
    for (name, contents, message) in cases {
        let path = dir.path(name);
        fs::write(&path, contents).expect("write the file");
        let outcome = rebond([os("resume"), path.as_os_str(), os("--steps"), os("1")]);
        let line = assert_one_error_line(&outcome, 2, &path);
        assert!(line.contains(message), "{name}: {line}");
    }
    let missing = dir.path("missing.state");
    let outcome = rebond([os("resume"), missing.as_os_str()]);
    let line = assert_one_error_line(&outcome, 1, &missing);
    assert!(line.contains("cannot read state"), "{line}");
}

#[test]
fn outputs_never_overwrite_the_scene_or_the_state_read() {
    let dir = TestDir::new("state_no_overwrite");
    let scene = dir.write(
        "scene.json",
        r#"{"bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.5}}]}"#,
    );
    let original = fs::read(&scene).expect("the scene");
    let outcome = rebond([
        os("run"),
        scene.as_os_str(),
        os("--save-state"),
        scene.as_os_str(),
    ]);
    let line = assert_one_error_line(&outcome, 2, &scene);
    assert!(
        line.contains("--save-state names the scene file itself"),
        "{line}"
    );
    assert_eq!(fs::read(&scene).expect("the scene"), original);
    let state = dir.path("ball.state");
    succeed(&[
        os("run"),
        scene.as_os_str(),
        os("--steps"),
        os("3"),
        os("--save-state"),
        state.as_os_str(),
    ]);
    let saved = fs::read(&state).expect("the state");
    for option in ["--save-state", "--record"] {
        let outcome = rebond([
            os("resume"),
            state.as_os_str(),
            os(option),
            state.as_os_str(),
        ]);
        let line = assert_one_error_line(&outcome, 2, &state);
        assert!(
            line.contains(&format!("{option} names the state file itself")),
            "{line}"
        );
        assert_eq!(fs::read(&state).expect("the state"), saved);
    }
    // A state that cannot be written is an error, and leaves no file behind.
    let unwritable = dir.path("no-such-directory").join("ball.state");
    let outcome = rebond([
        os("run"),
        scene.as_os_str(),
        os("--steps"),
        os("3"),
        os("--save-state"),
        unwritable.as_os_str(),
    ]);
    let line = assert_one_error_line(&outcome, 1, &unwritable);
    assert!(line.contains("cannot write state"), "{line}");
    let left: Vec<_> = fs::read_dir(dir.root())
        .expect("the test directory")
        .collect();
    assert_eq!(left.len(), 2, "only the scene and the state");
}
