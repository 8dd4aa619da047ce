//! The command line itself: summaries, bench reports, defaults and usage errors.

use std::ffi::OsStr;

use crate::common::{rebond, TestDir};

/// A small scene file: a ground and two unnamed balls.
const SCENE: &str = r#"{"bodies": [
    {"name": "ground", "type": "static",
     "shape": {"type": "box", "half_extents": [10, 0.5, 10]}, "position": [0, -0.5, 0]},
    {"shape": {"type": "sphere", "radius": 0.5}, "position": [0, 5, 0]},
    {"shape": {"type": "sphere", "radius": 0.5}, "position": [2, 5, 0]}
]}"#;

#[test]
fn run_prints_a_summary() {
    let dir = TestDir::new("run_summary");
    let scene = dir.write("scene.json", SCENE);
    let outcome = rebond([
        "run".as_ref(),
        scene.as_os_str(),
        "--steps".as_ref(),
        "30".as_ref(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    assert_eq!(outcome.stderr, "");
    for label in [
        "scene ",
        "steps ",
        "simulated time ",
        "bodies ",
        "contacts ",
        "islands ",
        "sleeping bodies ",
        "ms per step ",
        "energy at start ",
        "energy at end ",
    ] {
        assert!(
            outcome.stdout.lines().any(|line| line.starts_with(label)),
            "no `{label}` line in:\n{}",
            outcome.stdout
        );
    }
    assert!(outcome.stdout.contains("steps            30\n"));
    assert!(outcome.stdout.contains("simulated time   0.5 s\n"));
    assert!(outcome.stdout.contains("bodies           3\n"));
}

#[test]
fn bench_prints_timings_and_counts() {
    let dir = TestDir::new("bench_report");
    let scene = dir.write("scene.json", SCENE);
    let outcome = rebond([
        "bench".as_ref(),
        scene.as_os_str(),
        "--steps".as_ref(),
        "20".as_ref(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    for label in [
        "warm-up steps    30",
        "measured steps   20",
        "median ",
        "min ",
        "max ",
        "interquartile ",
        "bodies           3",
        "contacts ",
        "islands ",
        "sleep            allowed",
        "awake bodies ",
        "sleeping bodies ",
    ] {
        assert!(
            outcome.stdout.lines().any(|line| line.starts_with(label)),
            "no `{label}` line in:\n{}",
            outcome.stdout
        );
    }
}

/// Two boxes resting on a static ground: still from the start, so asleep after half a second.
const RESTING_SCENE: &str = r#"{"bodies": [
    {"name": "ground", "type": "static",
     "shape": {"type": "box", "half_extents": [10, 0.5, 10]}, "position": [0, -0.5, 0]},
    {"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 0.5, 0]},
    {"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [3, 0.5, 0]}
]}"#;

/// The note `rebond bench` prints when every dynamic body sleeps at the end.
const ASLEEP_NOTE: &str = "note             every dynamic body is asleep at the end";

/// Runs `rebond bench` on `scene`, written in a test folder `name`, with `arguments` after it;
/// checks that it succeeds and returns what it printed.
fn bench_stdout(name: &str, scene: &str, arguments: &[&str]) -> String {
    let dir = TestDir::new(name);
    let scene = dir.write("scene.json", scene);
    let mut all = vec!["bench".as_ref(), scene.as_os_str()];
    all.extend(arguments.iter().map(OsStr::new));
    let outcome = rebond(all);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    outcome.stdout
}

#[test]
fn bench_says_when_it_timed_a_sleeping_scene() {
    let stdout = bench_stdout("bench_asleep", RESTING_SCENE, &["--steps", "60"]);
    assert!(stdout.contains("sleep            allowed\n"), "{stdout}");
    // The static ground neither sleeps nor counts as awake.
    assert!(stdout.contains("awake bodies     0\n"), "{stdout}");
    assert!(stdout.contains("sleeping bodies  2\n"), "{stdout}");
    assert!(stdout.contains(ASLEEP_NOTE), "{stdout}");
    assert!(
        stdout.contains("--no-sleep"),
        "the note names the way out: {stdout}"
    );
}

#[test]
fn bench_no_sleep_keeps_every_body_awake() {
    let stdout = bench_stdout(
        "bench_no_sleep",
        RESTING_SCENE,
        &["--steps", "60", "--no-sleep"],
    );
    assert!(stdout.contains("measured steps   60\n"), "{stdout}");
    assert!(
        stdout.contains("sleep            off (--no-sleep)\n"),
        "{stdout}"
    );
    assert!(stdout.contains("awake bodies     2\n"), "{stdout}");
    assert!(stdout.contains("sleeping bodies  0\n"), "{stdout}");
    assert!(!stdout.contains("note "), "{stdout}");
}

#[test]
fn bench_of_moving_bodies_has_no_sleeping_note() {
    let stdout = bench_stdout("bench_awake", SCENE, &["--steps", "5"]);
    // The balls are still falling after 35 steps.
    assert!(stdout.contains("awake bodies     2\n"), "{stdout}");
    assert!(stdout.contains("sleeping bodies  0\n"), "{stdout}");
    assert!(!stdout.contains("note "), "{stdout}");
}

#[test]
fn bench_refuses_a_bad_scene_like_run() {
    let dir = TestDir::new("bench_bad_scene");
    let scene = dir.write(
        "scene.json",
        r#"{"bodies": [{"shape": {"type": "sphere", "radius": 0}}]}"#,
    );
    let outcome = rebond(["bench".as_ref(), scene.as_os_str()]);
    let line = crate::common::assert_one_error_line(&outcome, 2, &scene);
    assert!(
        line.contains("bodies[0].shape.radius: must be positive"),
        "{line}"
    );
}

#[test]
fn an_unknown_scene_name_is_an_error_with_status_1() {
    let outcome = rebond(["run", "no-such-scene-or-file"]);
    assert_eq!(outcome.status, 1);
    assert_eq!(outcome.stdout, "");
    assert_eq!(outcome.stderr.lines().count(), 1);
    assert!(outcome
        .stderr
        .starts_with("error: no-such-scene-or-file: cannot read scene"));
}

#[test]
fn bad_arguments_are_usage_errors() {
    for arguments in [
        &["run", "column", "--steps", "5", "--seconds", "1"][..],
        &["run", "column", "--steps", "0"],
        &["run", "column", "--steps", "-3"],
        &["run", "column", "--seconds", "0"],
        &["run", "column", "--seconds", "inf"],
        &["run", "column", "--record", "x.jsonl", "--every", "0"],
        &["run", "column", "--every", "2"],
        &["run"],
        &["bench", "column", "--steps", "0"],
        &["bench", "column", "--no-sleep=yes"],
        &["fly", "column"],
    ] {
        let outcome = rebond(arguments);
        assert_eq!(outcome.status, 2, "{arguments:?}: {}", outcome.stderr);
        assert_eq!(outcome.stdout, "", "{arguments:?}");
        assert!(outcome.stderr.starts_with("error:"), "{arguments:?}");
        assert!(!outcome.stderr.contains("panicked"), "{arguments:?}");
    }
}

#[test]
fn no_subcommand_prints_usage_with_status_2() {
    let outcome = rebond::<[&str; 0], &str>([]);
    assert_eq!(outcome.status, 2);
    assert_eq!(outcome.stdout, "");
    assert!(outcome.stderr.contains("Usage: rebond"));
}

#[test]
fn help_documents_the_defaults_and_the_scene_rule() {
    // clap wraps help to the terminal's width: compare the words, not the line breaks.
    let words = |text: &str| text.split_whitespace().collect::<Vec<_>>().join(" ");
    let outcome = rebond(["run", "--help"]);
    assert_eq!(outcome.status, 0);
    let help = words(&outcome.stdout);
    assert!(help.contains("A path that exists wins"), "{help}");
    assert!(help.contains("10 s of simulated time"), "{help}");
    let outcome = rebond(["bench", "--help"]);
    let help = words(&outcome.stdout);
    assert!(help.contains("30 warm-up steps"), "{help}");
    assert!(help.contains("[default: 300]"), "{help}");
    assert!(help.contains("--no-sleep"), "{help}");
    assert!(help.contains("awake and asleep"), "{help}");
}

#[cfg(feature = "viewer")]
#[test]
fn help_says_the_viewer_is_a_cargo_feature() {
    let outcome = rebond(["view", "--help"]);
    assert_eq!(outcome.status, 0);
    let help = outcome
        .stdout
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        help.contains("the cargo feature `viewer`, on by default"),
        "{help}"
    );
}

#[cfg(not(feature = "viewer"))]
#[test]
fn without_the_viewer_view_is_one_error_line_with_status_2() {
    for arguments in [
        &["view", "showcase"][..],
        &[
            "view",
            "no-such-scene",
            "--screenshot",
            "frame.png",
            "--steps",
            "5",
        ],
    ] {
        let outcome = rebond(arguments);
        assert_eq!(outcome.status, 2, "{arguments:?}: {}", outcome.stderr);
        assert_eq!(outcome.stdout, "", "{arguments:?}");
        let lines: Vec<&str> = outcome.stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{arguments:?}: {}", outcome.stderr);
        assert!(
            lines[0].starts_with(
                "error: this rebond was built without the viewer (cargo feature `viewer`); "
            ),
            "{}",
            lines[0]
        );
    }
    // Arguments are still checked first, as in a build with the viewer.
    let outcome = rebond(["view", "showcase", "--steps", "5"]);
    assert_eq!(outcome.status, 2);
    assert!(
        outcome.stderr.contains("--screenshot"),
        "{}",
        outcome.stderr
    );
    let help = rebond(["view", "--help"]).stdout;
    let help = help.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(help.starts_with("Not in this build"), "{help}");
    assert!(
        help.contains("without the cargo feature `viewer`"),
        "{help}"
    );
}

#[test]
fn soak_reports_a_line_every_k_steps_and_the_last() {
    let outcome = rebond(["soak", "--steps", "250", "--every", "100"]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    let lines: Vec<&str> = outcome.stdout.lines().collect();
    assert_eq!(
        lines[0],
        "step,seconds,energy_j,resident_kib,ms_per_step,awake_bodies,contacts"
    );
    let steps: Vec<&str> = lines[1..]
        .iter()
        .map(|line| line.split(',').next().unwrap_or_default())
        .collect();
    assert_eq!(steps, ["0", "100", "200", "250"]);
    for line in &lines[1..] {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), 7, "{line}");
        let energy: f64 = fields[2].parse().expect("an energy");
        assert!(energy.is_finite(), "{line}");
    }
}
