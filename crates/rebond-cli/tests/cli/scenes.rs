//! The built-in scenes: listed by `rebond scenes`, each loads and runs a few steps by name.

use crate::common::{rebond, rebond_in, TestDir};

/// Every built-in scene the brief asks for, with its body count (ground included).
const BUILTIN_SCENES: [(&str, usize); 17] = [
    ("showcase", 31),
    ("pyramid", 211),
    ("column", 11),
    ("rain", 4097),
    ("ramp", 28),
    ("cradle", 5),
    ("spinner", 5),
    ("pendulum", 8),
    ("chain", 35),
    ("bridge", 23),
    ("ragdolls", 301),
    ("car", 12),
    ("cradle_hanging", 6),
    ("terrain", 501),
    ("level", 151),
    ("soak", 47),
    ("platformer", 19),
];

/// The value of a `label  value` line of a summary.
fn summary_value<'a>(summary: &'a str, label: &str) -> &'a str {
    summary
        .lines()
        .find_map(|line| line.strip_prefix(label))
        .map(str::trim)
        .unwrap_or_else(|| panic!("no `{label}` line in:\n{summary}"))
}

#[test]
fn scenes_lists_every_builtin_scene_with_a_description() {
    let outcome = rebond(["scenes"]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    assert_eq!(outcome.stderr, "");
    let listed: Vec<(&str, &str)> = outcome
        .stdout
        .lines()
        .map(|line| {
            let (name, description) = line.split_once(' ').expect("a name and a description");
            (name, description.trim())
        })
        .collect();
    let names: Vec<&str> = listed.iter().map(|(name, _)| *name).collect();
    let expected: Vec<&str> = BUILTIN_SCENES.iter().map(|(name, _)| *name).collect();
    assert_eq!(names, expected);
    assert!(listed
        .iter()
        .all(|(_, description)| !description.is_empty()));
}

#[test]
fn every_builtin_scene_loads_and_runs_a_few_steps() {
    for (name, body_count) in BUILTIN_SCENES {
        let steps = if name == "rain" { "2" } else { "5" };
        let outcome = rebond(["run", name, "--steps", steps]);
        assert_eq!(outcome.status, 0, "{name}: {}", outcome.stderr);
        assert_eq!(outcome.stderr, "", "{name}: no progress bar off a terminal");
        assert_eq!(
            summary_value(&outcome.stdout, "scene"),
            format!("{name} (built-in)")
        );
        assert_eq!(summary_value(&outcome.stdout, "steps"), steps);
        assert_eq!(
            summary_value(&outcome.stdout, "bodies"),
            body_count.to_string(),
            "{name}"
        );
    }
}

#[test]
fn builtin_scenes_record_every_body() {
    let dir = TestDir::new("builtin_record");
    let record_path = dir.path("rain.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        "rain".as_ref(),
        "--steps".as_ref(),
        "1".as_ref(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    let text = std::fs::read_to_string(&record_path).expect("the record file exists");
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|line| serde_json::from_str(line).expect("JSON"))
        .collect();
    assert_eq!(lines.len(), 2);
    let bodies = lines[1]["bodies"].as_array().expect("bodies");
    assert_eq!(bodies.len(), 4097);
    assert_eq!(bodies[0]["name"], "ground");
    assert_eq!(bodies[1]["name"], "body1");
    assert_eq!(bodies[4096]["name"], "body4096");
}

#[test]
fn a_path_that_exists_wins_over_a_builtin_name() {
    let dir = TestDir::new("path_wins");
    dir.write(
        "column",
        r#"{"bodies": [{"shape": {"type": "sphere", "radius": 1}}]}"#,
    );
    let outcome = rebond_in(Some(dir.root()), ["run", "column", "--steps", "1"]);
    assert_eq!(outcome.status, 0, "{}", outcome.stderr);
    assert_eq!(summary_value(&outcome.stdout, "scene"), "column");
    assert_eq!(summary_value(&outcome.stdout, "bodies"), "1");
}
