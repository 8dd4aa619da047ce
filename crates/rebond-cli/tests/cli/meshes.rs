//! Triangle meshes and heightfields in scene files: inline, from an OBJ file beside the scene,
//! and every bad input refused at its place.

use crate::bad_input::assert_refused;
use crate::common::{assert_one_error_line, rebond, rebond_in, TestDir};

/// A 4 m square floor of two triangles, as an OBJ file.
const FLOOR_OBJ: &str = "# a floor\nv -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 4 3 2\n";

/// A scene of a static `floor_shape` at the origin and a ball dropped on it, recorded.
fn ball_on(floor_shape: &str) -> String {
    format!(
        r#"{{"bodies": [
            {{"name": "floor", "type": "static", "shape": {floor_shape}}},
            {{"name": "ball", "shape": {{"type": "sphere", "radius": 0.5}}, "position": [0.3, 2, 0.2]}}
        ]}}"#
    )
}

/// The ball's height in the last record line.
fn final_ball_height(record: &str) -> f64 {
    let last = record.lines().last().expect("a record line");
    let line: serde_json::Value = serde_json::from_str(last).expect("JSON");
    line["bodies"][1]["position"][1].as_f64().expect("a height")
}

/// Runs `scene_path` for 2 s from `directory`, recording, and returns the record.
fn run_scene(
    directory: &std::path::Path,
    scene_path: &std::path::Path,
    record: &std::path::Path,
) -> String {
    let outcome = rebond_in(
        Some(directory),
        [
            "run".as_ref(),
            scene_path.as_os_str(),
            "--seconds".as_ref(),
            "2".as_ref(),
            "--record".as_ref(),
            record.as_os_str(),
        ],
    );
    assert_eq!(outcome.status, 0, "stderr: {}", outcome.stderr);
    std::fs::read_to_string(record).expect("the record")
}

#[test]
fn a_ball_rests_on_an_inline_trimesh_an_obj_floor_and_a_heightfield() {
    let dir = TestDir::new("meshes_floors");
    let inline = r#"{"type": "trimesh",
        "vertices": [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]],
        "indices": [[0, 3, 2], [0, 2, 1]]}"#;
    // The OBJ is found beside the scene, whatever the working directory; scaled ×2 in X and Z.
    std::fs::create_dir_all(dir.path("models")).expect("a models folder");
    dir.write("models/floor.obj", FLOOR_OBJ);
    let obj = r#"{"type": "trimesh", "file": "models/floor.obj", "scale": [2, 1, 2]}"#;
    let heightfield = r#"{"type": "heightfield", "heights": [[0, 0, 0], [0, 0, 0], [0, 0, 0]], "scale": [4, 1, 4]}"#;
    for (name, floor) in [
        ("inline", inline),
        ("obj", obj),
        ("heightfield", heightfield),
    ] {
        let scene = dir.write(&format!("{name}.json"), &ball_on(floor));
        let record = dir.path(&format!("{name}.jsonl"));
        let height = final_ball_height(&run_scene(&std::env::temp_dir(), &scene, &record));
        // Resting on the floor at its radius, within the few millimetres a contact settles.
        assert!(
            (height - 0.5).abs() < 5e-3,
            "{name}: the ball ends at {height} m"
        );
    }
}

#[test]
fn a_missing_or_broken_obj_file_is_an_io_error() {
    let dir = TestDir::new("meshes_missing_obj");
    for (name, contents) in [("missing", None), ("broken", Some("v 1 2\nf 1 2 x\n"))] {
        if let Some(contents) = contents {
            dir.write(&format!("{name}.obj"), contents);
        }
        let floor = format!(r#"{{"type": "trimesh", "file": "{name}.obj"}}"#);
        let scene = dir.write(&format!("{name}.json"), &ball_on(&floor));
        let outcome = rebond(["run".as_ref(), scene.as_os_str()]);
        let line = assert_one_error_line(&outcome, 1, &scene);
        assert!(
            line.contains("bodies[0].shape.file") && line.contains(&format!("{name}.obj")),
            "{name}: {line}"
        );
    }
}

#[test]
fn bad_meshes_and_heightfields_are_refused_at_their_place() {
    let floor = |shape: &str| format!(r#"{{"bodies": [{{"type": "static", "shape": {shape}}}]}}"#);
    let square = r#""vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]]"#;
    let cases = [
        (
            "index_out_of_range",
            floor(&format!(r#"{{"type": "trimesh", {square}, "indices": [[0, 2, 1], [0, 1, 3]]}}"#)),
            "bodies[0].shape.indices[1]",
            "out of range",
        ),
        (
            "missing_indices",
            floor(&format!(r#"{{"type": "trimesh", {square}}}"#)),
            "bodies[0].shape.indices",
            "required",
        ),
        (
            "file_and_vertices",
            floor(&format!(
                r#"{{"type": "trimesh", "file": "a.obj", {square}, "indices": [[0, 2, 1]]}}"#
            )),
            "bodies[0].shape.file",
            "not both",
        ),
        (
            "zero_area_only",
            floor(&format!(r#"{{"type": "trimesh", {square}, "indices": [[0, 1, 1]]}}"#)),
            "bodies[0].shape.indices",
            "no triangle of positive area",
        ),
        (
            "zero_scale",
            floor(&format!(
                r#"{{"type": "trimesh", {square}, "indices": [[0, 2, 1]], "scale": [1, 0, 1]}}"#
            )),
            "bodies[0].shape.scale[1]",
            "must be positive",
        ),
        (
            "ragged_rows",
            floor(r#"{"type": "heightfield", "heights": [[0, 1], [0]], "scale": [1, 1, 1]}"#),
            "bodies[0].shape.heights[1]",
            "same length",
        ),
        (
            "one_row",
            floor(r#"{"type": "heightfield", "heights": [[0, 1]], "scale": [1, 1, 1]}"#),
            "bodies[0].shape.heights",
            "at least 2",
        ),
        (
            "heightfield_scale_missing",
            floor(r#"{"type": "heightfield", "heights": [[0, 1], [0, 1]]}"#),
            "bodies[0].shape.scale",
            "required",
        ),
        (
            "dynamic_trimesh",
            format!(
                r#"{{"bodies": [{{"shape": {{"type": "trimesh", {square}, "indices": [[0, 2, 1]]}}}}]}}"#
            ),
            "bodies[0].shape",
            "only allowed on static or kinematic bodies",
        ),
        (
            "dynamic_heightfield",
            r#"{"bodies": [{"shape": {"type": "heightfield", "heights": [[0, 1], [0, 1]], "scale": [1, 1, 1]}}]}"#
                .to_owned(),
            "bodies[0].shape",
            "only allowed on static or kinematic bodies",
        ),
    ];
    for (name, scene, place, message) in cases {
        assert_refused(&format!("mesh_{name}"), &scene, place, message);
    }
}
