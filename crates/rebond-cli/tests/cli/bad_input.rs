//! Every kind of bad input the contract lists is refused before anything runs: exit status 2,
//! one `error:` line naming the file and the place, no panic, no record file. Files that cannot
//! be read or written give exit status 1.

use crate::common::{assert_one_error_line, rebond, TestDir};

/// A valid first body, so that the bad one is `bodies[1]`.
pub const GROUND: &str = r#"{"name": "ground", "type": "static",
    "shape": {"type": "box", "half_extents": [10, 0.5, 10]}, "position": [0, -0.5, 0]}"#;

/// A valid shape for bodies whose bad value lies elsewhere.
pub const BALL: &str = r#""shape": {"type": "sphere", "radius": 0.5}"#;

/// A scene of the ground and `body` (as `bodies[1]`).
fn scene_with(body: &str) -> String {
    format!("{{\"bodies\": [{GROUND},\n{body}]}}")
}

/// Runs `scene` with a record file and checks it is refused at `place` with a message
/// containing `message`.
pub fn assert_refused(test_name: &str, scene: &str, place: &str, message: &str) {
    let dir = TestDir::new(&format!("bad_input_{test_name}"));
    let scene_path = dir.write("scene.json", scene);
    let record_path = dir.path("record.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        scene_path.as_os_str(),
        "--steps".as_ref(),
        "2".as_ref(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    let line = assert_one_error_line(&outcome, 2, &scene_path);
    let expected = format!("error: {}: {place}: ", scene_path.display());
    assert!(
        line.starts_with(&expected),
        "{test_name}: expected the place `{place}`, got: {line}"
    );
    assert!(
        line.contains(message),
        "{test_name}: expected `{message}` in: {line}"
    );
    assert!(
        !record_path.exists(),
        "{test_name}: a refused scene must not create the record file"
    );
}

#[test]
fn invalid_json_is_refused_with_line_and_column() {
    assert_refused(
        "syntax",
        "{\"bodies\": [\n  {\"shape\": {\"type\": \"sphere\", \"radius\": 1},}\n]}",
        "line 2, column 45",
        "invalid JSON",
    );
    assert_refused("empty", "", "line 1, column 0", "invalid JSON");
    assert_refused(
        "trailing",
        "{\"bodies\": []} []",
        "line 1, column 16",
        "invalid JSON: trailing characters",
    );
    assert_refused(
        "number_out_of_range",
        "{\"gravity\": [0, 1e400, 0], \"bodies\": []}",
        "gravity[1]",
        "got 1e400, a number beyond the floating-point range",
    );
    assert_refused(
        "number_out_of_range_in_a_shape",
        "{\"bodies\": [\n  {\"shape\": {\"type\": \"sphere\", \"radius\": -1E+999}}\n]}",
        "bodies[0].shape.radius",
        "got -1E+999, a number beyond the floating-point range",
    );
}

#[test]
fn unknown_fields_are_refused_everywhere() {
    assert_refused(
        "unknown_top_level",
        r#"{"bodies": [], "gravitee": [0, 0, 0]}"#,
        "gravitee",
        "unknown field `gravitee`",
    );
    assert_refused(
        "unknown_in_body",
        &scene_with(&format!(r#"{{{BALL}, "colour": "red"}}"#)),
        "bodies[1].colour",
        "unknown field `colour`",
    );
    assert_refused(
        "unknown_in_shape",
        &scene_with(r#"{"shape": {"type": "sphere", "radius": 1, "colour": "red"}}"#),
        "bodies[1].shape.colour",
        "unknown field `colour`",
    );
    assert_refused(
        "field_of_another_shape_type",
        &scene_with(r#"{"shape": {"type": "sphere", "radius": 1, "half_extents": [1, 1, 1]}}"#),
        "bodies[1].shape.half_extents",
        "unknown field `half_extents` for a sphere shape",
    );
    assert_refused(
        "unknown_in_compound_child",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "sphere", "radius": 1}, "scale": 2}]}}"#,
        ),
        "bodies[1].shape.children[0].scale",
        "unknown field `scale`",
    );
}

#[test]
fn unknown_shape_and_body_types_are_refused() {
    assert_refused(
        "unknown_shape_type",
        &scene_with(r#"{"shape": {"type": "cone", "radius": 1}}"#),
        "bodies[1].shape.type",
        "unknown variant `cone`",
    );
    assert_refused(
        "unknown_body_type",
        &scene_with(&format!(r#"{{{BALL}, "type": "floating"}}"#)),
        "bodies[1].type",
        "unknown variant `floating`",
    );
}

#[test]
fn missing_required_fields_are_refused() {
    assert_refused(
        "missing_bodies",
        r#"{"gravity": [0, -9.81, 0]}"#,
        "bodies",
        "required field is missing",
    );
    assert_refused(
        "missing_shape",
        &scene_with(r#"{"name": "shapeless"}"#),
        "bodies[1].shape",
        "required field is missing",
    );
    assert_refused(
        "missing_radius",
        &scene_with(r#"{"shape": {"type": "sphere"}}"#),
        "bodies[1].shape.radius",
        "required field is missing",
    );
    assert_refused(
        "missing_half_height",
        &scene_with(r#"{"shape": {"type": "capsule", "radius": 0.5}}"#),
        "bodies[1].shape.half_height",
        "required field is missing",
    );
    assert_refused(
        "missing_shape_type",
        &scene_with(r#"{"shape": {"radius": 1}}"#),
        "bodies[1].shape.type",
        "required field is missing",
    );
}

#[test]
fn wrong_json_types_are_refused() {
    assert_refused(
        "string_for_number",
        &scene_with(r#"{"shape": {"type": "sphere", "radius": "big"}}"#),
        "bodies[1].shape.radius",
        "invalid type: string \"big\"",
    );
    assert_refused(
        "short_vector",
        &scene_with(&format!(r#"{{{BALL}, "position": [1, 2]}}"#)),
        "bodies[1].position",
        "invalid length 2",
    );
    assert_refused(
        "array_for_scene",
        "[null, null, null, []]",
        "top level",
        "expected a JSON object",
    );
    assert_refused(
        "array_for_shape",
        &scene_with(r#"{"shape": ["sphere", 1]}"#),
        "bodies[1].shape",
        "expected a JSON object",
    );
    assert_refused(
        "duplicate_field",
        &scene_with(&format!(r#"{{{BALL}, "mass": 1, "mass": 2}}"#)),
        "bodies[1]",
        "duplicate field `mass`",
    );
}

#[test]
fn values_beyond_f32_are_refused_as_not_finite() {
    assert_refused(
        "huge_radius",
        &scene_with(r#"{"shape": {"type": "sphere", "radius": 1e39}}"#),
        "bodies[1].shape.radius",
        "must be finite, got 1e39",
    );
    assert_refused(
        "huge_position",
        &scene_with(&format!(r#"{{{BALL}, "position": [0, -1e39, 0]}}"#)),
        "bodies[1].position[1]",
        "must be finite",
    );
    assert_refused(
        "huge_gravity",
        r#"{"gravity": [0, 0, 1e39], "bodies": []}"#,
        "gravity[2]",
        "must be finite",
    );
    assert_refused(
        "huge_hull_point",
        &scene_with(
            r#"{"shape": {"type": "convex_hull",
                "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1e39]]}}"#,
        ),
        "bodies[1].shape.points[3][2]",
        "must be finite",
    );
    assert_refused(
        "huge_rotation",
        &scene_with(&format!(r#"{{{BALL}, "rotation": [0, 0, 0, 1e39]}}"#)),
        "bodies[1].rotation[3]",
        "must be finite",
    );
}

#[test]
fn negative_and_zero_sizes_are_refused() {
    assert_refused(
        "negative_radius",
        &scene_with(r#"{"shape": {"type": "sphere", "radius": -1}}"#),
        "bodies[1].shape.radius",
        "must be positive, got -1",
    );
    assert_refused(
        "zero_half_extent",
        &scene_with(r#"{"shape": {"type": "box", "half_extents": [1, 0, 1]}}"#),
        "bodies[1].shape.half_extents[1]",
        "must be positive, got 0",
    );
    assert_refused(
        "zero_half_height",
        &scene_with(r#"{"shape": {"type": "cylinder", "radius": 1, "half_height": 0}}"#),
        "bodies[1].shape.half_height",
        "must be positive, got 0",
    );
}

#[test]
fn values_out_of_range_are_refused() {
    assert_refused(
        "negative_friction",
        &scene_with(&format!(r#"{{{BALL}, "friction": -0.1}}"#)),
        "bodies[1].friction",
        "must not be negative, got -0.1",
    );
    assert_refused(
        "negative_rolling_resistance",
        &scene_with(&format!(r#"{{{BALL}, "rolling_resistance": -0.1}}"#)),
        "bodies[1].rolling_resistance",
        "must not be negative, got -0.1",
    );
    assert_refused(
        "negative_linear_damping",
        &scene_with(&format!(r#"{{{BALL}, "linear_damping": -1}}"#)),
        "bodies[1].linear_damping",
        "must not be negative",
    );
    assert_refused(
        "negative_angular_damping",
        &scene_with(&format!(r#"{{{BALL}, "angular_damping": -0.5}}"#)),
        "bodies[1].angular_damping",
        "must not be negative",
    );
    assert_refused(
        "restitution_above_one",
        &scene_with(&format!(r#"{{{BALL}, "restitution": 1.5}}"#)),
        "bodies[1].restitution",
        "must lie between 0 and 1, got 1.5",
    );
    assert_refused(
        "restitution_below_zero",
        &scene_with(&format!(r#"{{{BALL}, "restitution": -0.1}}"#)),
        "bodies[1].restitution",
        "must lie between 0 and 1",
    );
}

#[test]
fn zero_quaternions_are_refused() {
    assert_refused(
        "zero_rotation",
        &scene_with(&format!(r#"{{{BALL}, "rotation": [0, 0, 0, 0]}}"#)),
        "bodies[1].rotation",
        "quaternion has zero length",
    );
    assert_refused(
        "zero_child_rotation",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "sphere", "radius": 1}, "rotation": [0, 0, 0, 0]}]}}"#,
        ),
        "bodies[1].shape.children[0].rotation",
        "quaternion has zero length",
    );
    assert_refused(
        "negative_child_friction",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "sphere", "radius": 1}, "friction": -0.5}]}}"#,
        ),
        "bodies[1].shape.children[0].friction",
        "must not be negative, got -0.5",
    );
    assert_refused(
        "child_restitution_above_one",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "sphere", "radius": 1}, "restitution": 1.5}]}}"#,
        ),
        "bodies[1].shape.children[0].restitution",
        "must lie between 0 and 1, got 1.5",
    );
    assert_refused(
        "negative_restitution_threshold",
        r#"{"restitution_threshold": -1, "bodies": []}"#,
        "restitution_threshold",
        "must not be negative, got -1",
    );
}

#[test]
fn dynamic_bodies_without_a_positive_finite_mass_are_refused() {
    assert_refused(
        "zero_mass",
        &scene_with(&format!(r#"{{{BALL}, "mass": 0}}"#)),
        "bodies[1].mass",
        "must be positive, got 0",
    );
    assert_refused(
        "negative_density",
        &scene_with(&format!(r#"{{{BALL}, "density": -1000}}"#)),
        "bodies[1].density",
        "must be positive",
    );
    assert_refused(
        "infinite_mass_from_density",
        &scene_with(
            r#"{"shape": {"type": "box", "half_extents": [1000, 1000, 1000]}, "density": 1e38}"#,
        ),
        "bodies[1].density",
        "mass of a dynamic body must be positive and finite",
    );
    assert_refused(
        "sphere_below_the_smallest_size",
        &scene_with(r#"{"shape": {"type": "sphere", "radius": 1e-9}}"#),
        "bodies[1].shape.radius",
        "must lie between 0.001 and 100000",
    );
    assert_refused(
        "needle_cylinder",
        &scene_with(r#"{"shape": {"type": "cylinder", "radius": 1e-20, "half_height": 1}}"#),
        "bodies[1].shape.radius",
        "must lie between 0.001 and 100000",
    );
}

#[test]
fn duplicate_names_are_refused_naming_both_bodies() {
    assert_refused(
        "duplicate_name",
        &format!(
            r#"{{"bodies": [{GROUND}, {{"name": "crate", {BALL}}}, {{"name": "crate", {BALL}}}]}}"#
        ),
        "bodies[2].name",
        "duplicate name \"crate\": bodies[1] and bodies[2]",
    );
    assert_refused(
        "duplicate_default_name",
        &format!(r#"{{"bodies": [{{{BALL}}}, {{"name": "body0", {BALL}}}]}}"#),
        "bodies[1].name",
        "duplicate name \"body0\"",
    );
}

#[test]
fn halfspaces_are_refused_on_dynamic_bodies_and_with_a_zero_normal() {
    assert_refused(
        "dynamic_halfspace",
        &scene_with(r#"{"shape": {"type": "halfspace", "normal": [0, 1, 0]}}"#),
        "bodies[1].shape",
        "only allowed on static or kinematic bodies",
    );
    assert_refused(
        "zero_normal",
        &scene_with(r#"{"type": "static", "shape": {"type": "halfspace", "normal": [0, 0, 0]}}"#),
        "bodies[1].shape.normal",
        "zero length",
    );
}

#[test]
fn degenerate_hulls_are_refused() {
    assert_refused(
        "three_point_hull",
        &scene_with(
            r#"{"shape": {"type": "convex_hull", "points": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}}"#,
        ),
        "bodies[1].shape.points",
        "degenerate convex hull",
    );
    assert_refused(
        "coplanar_hull",
        &scene_with(
            r#"{"shape": {"type": "convex_hull",
                "points": [[0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 1], [0.5, 0, 0.5]]}}"#,
        ),
        "bodies[1].shape.points",
        "degenerate convex hull",
    );
    assert_refused(
        "coincident_hull",
        &scene_with(
            r#"{"shape": {"type": "convex_hull",
                "points": [[1, 2, 3], [1, 2, 3], [1, 2, 3], [1, 2, 3]]}}"#,
        ),
        "bodies[1].shape.points",
        "degenerate convex hull",
    );
    assert_refused(
        "hull_in_compound",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "convex_hull",
                 "points": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]}}]}}"#,
        ),
        "bodies[1].shape.children[0].shape.points",
        "degenerate convex hull",
    );
}

#[test]
fn bad_compound_children_are_refused() {
    assert_refused(
        "bad_child_size",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "sphere", "radius": 1}},
                {"shape": {"type": "sphere", "radius": 0}, "position": [1, 0, 0]}]}}"#,
        ),
        "bodies[1].shape.children[1].shape.radius",
        "must be positive, got 0",
    );
    assert_refused(
        "nested_compound",
        &scene_with(
            r#"{"shape": {"type": "compound", "children": [
                {"shape": {"type": "compound", "children": [
                    {"shape": {"type": "sphere", "radius": 1}}]}}]}}"#,
        ),
        "bodies[1].shape.children[0].shape",
        "a child may not be a compound",
    );
    assert_refused(
        "halfspace_child",
        &scene_with(
            r#"{"type": "static", "shape": {"type": "compound", "children": [
                {"shape": {"type": "halfspace", "normal": [0, 1, 0]}}]}}"#,
        ),
        "bodies[1].shape.children[0].shape",
        "a child may not be a halfspace",
    );
    assert_refused(
        "no_children",
        &scene_with(r#"{"shape": {"type": "compound", "children": []}}"#),
        "bodies[1].shape.children",
        "at least one child",
    );
    assert_refused(
        "child_without_shape",
        &scene_with(r#"{"shape": {"type": "compound", "children": [{"position": [0, 1, 0]}]}}"#),
        "bodies[1].shape.children[0].shape",
        "required field is missing",
    );
}

#[test]
fn bad_world_settings_are_refused() {
    assert_refused(
        "zero_timestep",
        r#"{"timestep": 0, "bodies": []}"#,
        "timestep",
        "must be positive, got 0",
    );
    assert_refused(
        "negative_timestep",
        r#"{"timestep": -0.01, "bodies": []}"#,
        "timestep",
        "must be positive",
    );
    assert_refused(
        "timestep_below_f32",
        r#"{"timestep": 1e-50, "bodies": []}"#,
        "timestep",
        "rounds to 0",
    );
    assert_refused(
        "huge_timestep",
        r#"{"timestep": 1e39, "bodies": []}"#,
        "timestep",
        "must be finite",
    );
    assert_refused(
        "zero_substeps",
        r#"{"substeps": 0, "bodies": []}"#,
        "substeps",
        "must lie between 1 and",
    );
    assert_refused(
        "too_many_substeps",
        r#"{"substeps": 100000, "bodies": []}"#,
        "substeps",
        "must lie between 1 and",
    );
    assert_refused(
        "negative_substeps",
        r#"{"substeps": -1, "bodies": []}"#,
        "substeps",
        "invalid value",
    );
}

#[test]
fn every_other_world_setting_is_refused_at_its_field() {
    // Every world setting the top level takes, out of its range, beyond f32 and of the wrong
    // JSON type.
    let out_of_range = [
        ("max_linear_speed", "0", "must be positive, got 0"),
        (
            "max_linear_speed",
            "20000",
            "must lie between 0 and 10000, got 20000",
        ),
        ("contact_hertz", "-60", "must be positive, got -60"),
        (
            "contact_damping_ratio",
            "-0.5",
            "must not be negative, got -0.5",
        ),
        ("contact_push_speed", "0", "must be positive, got 0"),
        (
            "restitution_threshold",
            "-0.5",
            "must not be negative, got -0.5",
        ),
        (
            "speculative_distance",
            "-0.01",
            "must not be negative, got -0.01",
        ),
        ("sleep_speed", "-0.05", "must not be negative, got -0.05"),
        ("sleep_time", "-1", "must not be negative, got -1"),
        ("joint_hertz", "0", "must be positive, got 0"),
        ("joint_damping_ratio", "-2", "must not be negative, got -2"),
    ];
    for (field, value, message) in out_of_range {
        let scene = |value: &str| format!(r#"{{"{field}": {value}, "bodies": []}}"#);
        assert_refused(&format!("{field}_{value}"), &scene(value), field, message);
        assert_refused(
            &format!("{field}_huge"),
            &scene("1e39"),
            field,
            "must be finite",
        );
        let string = scene(r#""fast""#);
        let wrong_type = "invalid type: string \"fast\"";
        assert_refused(&format!("{field}_string"), &string, field, wrong_type);
    }
    for field in ["friction_combine", "restitution_combine"] {
        let scene = |value: &str| format!(r#"{{"{field}": {value}, "bodies": []}}"#);
        let unknown = "unknown variant `median`, expected one of `geometric_mean`";
        assert_refused(
            &format!("{field}_unknown"),
            &scene(r#""median""#),
            field,
            unknown,
        );
        let number = "invalid type: integer `1`, expected a string";
        assert_refused(&format!("{field}_number"), &scene("1"), field, number);
    }
}

#[test]
fn the_first_bad_body_is_reported() {
    assert_refused(
        "first_bad_body",
        &format!(
            r#"{{"bodies": [{GROUND}, {{{BALL}}}, {{{BALL}}},
                {{"shape": {{"type": "sphere", "radius": -1}}}},
                {{"shape": {{"type": "sphere", "radius": -2}}}}]}}"#
        ),
        "bodies[3].shape.radius",
        "must be positive, got -1",
    );
}

#[test]
fn a_missing_scene_file_is_an_error_with_status_1() {
    let dir = TestDir::new("missing_scene");
    let scene_path = dir.path("no-such-scene.json");
    let record_path = dir.path("record.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        scene_path.as_os_str(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    let line = assert_one_error_line(&outcome, 1, &scene_path);
    assert!(line.contains("cannot read scene"), "{line}");
    assert!(!record_path.exists());
}

#[test]
fn an_unreadable_scene_is_an_error_with_status_1() {
    let dir = TestDir::new("unreadable_scene");
    let outcome = rebond(["bench".as_ref(), dir.root().as_os_str()]);
    let line = assert_one_error_line(&outcome, 1, dir.root());
    assert!(line.contains("cannot read scene"), "{line}");
}

#[test]
fn an_unwritable_record_is_an_error_with_status_1() {
    let dir = TestDir::new("unwritable_record");
    let scene_path = dir.write("scene.json", &scene_with(&format!("{{{BALL}}}")));
    for record_path in [dir.path("missing-directory/record.jsonl"), dir.path("")] {
        let outcome = rebond([
            "run".as_ref(),
            scene_path.as_os_str(),
            "--steps".as_ref(),
            "3".as_ref(),
            "--record".as_ref(),
            record_path.as_os_str(),
        ]);
        let line = assert_one_error_line(&outcome, 1, &record_path);
        assert!(line.contains("cannot create record file"), "{line}");
    }
}

#[test]
fn an_invalid_scene_is_reported_before_an_unwritable_record() {
    let dir = TestDir::new("invalid_before_unwritable");
    let scene_path = dir.write("scene.json", r#"{"bodies": 3}"#);
    let record_path = dir.path("missing-directory/record.jsonl");
    let outcome = rebond([
        "run".as_ref(),
        scene_path.as_os_str(),
        "--record".as_ref(),
        record_path.as_os_str(),
    ]);
    let line = assert_one_error_line(&outcome, 2, &scene_path);
    assert!(line.contains("bodies: invalid type"), "{line}");
}

#[test]
fn bad_locked_axes_are_refused_at_their_path() {
    assert_refused(
        "locked_axes_number",
        &scene_with(&format!(
            r#"{{{BALL}, "locked_axes": {{"rotation": [true, 1, false]}}}}"#
        )),
        "bodies[1].locked_axes.rotation[1]",
        "invalid type: integer `1`, expected a boolean",
    );
    assert_refused(
        "locked_axes_short",
        &scene_with(&format!(
            r#"{{{BALL}, "locked_axes": {{"translation": [true, true]}}}}"#
        )),
        "bodies[1].locked_axes.translation",
        "invalid length 2",
    );
    assert_refused(
        "locked_axes_unknown",
        &scene_with(&format!(
            r#"{{{BALL}, "locked_axes": {{"spin": [true, true, true]}}}}"#
        )),
        "bodies[1].locked_axes.spin",
        "unknown field `spin`",
    );
    assert_refused(
        "locked_axes_not_object",
        &scene_with(&format!(r#"{{{BALL}, "locked_axes": true}}"#)),
        "bodies[1].locked_axes",
        "expected a JSON object",
    );
}

#[test]
fn bad_paths_are_refused_at_their_place() {
    let platform = |path: &str| {
        scene_with(&format!(
            r#"{{"type": "kinematic", {BALL}, "path": {path}}}"#
        ))
    };
    let cases = [
        (
            "path_on_dynamic",
            scene_with(&format!(
                r#"{{{BALL}, "path": {{"points": [{{"time": 0}}]}}}}"#
            )),
            "bodies[1].path",
            "only a kinematic body",
        ),
        (
            "path_on_static",
            scene_with(&format!(
                r#"{{"type": "static", {BALL}, "path": {{"points": [{{"time": 0}}]}}}}"#
            )),
            "bodies[1].path",
            "only a kinematic body",
        ),
        (
            "path_without_points",
            platform(r#"{"points": []}"#),
            "bodies[1].path.points",
            "required",
        ),
        (
            "path_points_missing",
            platform(r#"{"loop": true}"#),
            "bodies[1].path.points",
            "required field is missing",
        ),
        (
            "path_first_time_not_zero",
            platform(r#"{"points": [{"time": 0.5}]}"#),
            "bodies[1].path.points[0].time",
            "must lie between 0 and 0, got 0.5",
        ),
        (
            "path_time_missing",
            platform(r#"{"points": [{"time": 0}, {"position": [1, 0, 0]}]}"#),
            "bodies[1].path.points[1].time",
            "required field is missing",
        ),
        (
            "path_times_not_increasing",
            platform(r#"{"points": [{"time": 0}, {"time": 2}, {"time": 1}]}"#),
            "bodies[1].path.points[2].time",
            "must be greater than the one before, 2, got 1",
        ),
        (
            "path_times_equal",
            platform(r#"{"points": [{"time": 0}, {"time": 0}]}"#),
            "bodies[1].path.points[1].time",
            "must be greater than the one before",
        ),
        (
            "path_time_beyond_f32",
            platform(r#"{"points": [{"time": 0}, {"time": 1e300}]}"#),
            "bodies[1].path.points[1].time",
            "must be finite",
        ),
        (
            "path_position_too_far",
            platform(r#"{"points": [{"time": 0}, {"time": 1, "position": [0, 1e9, 0]}]}"#),
            "bodies[1].path.points[1].position",
            "must not exceed",
        ),
        (
            "path_position_beyond_f32",
            platform(r#"{"points": [{"time": 0, "position": [0, 0, 1e300]}]}"#),
            "bodies[1].path.points[0].position[2]",
            "must be finite",
        ),
        (
            "path_zero_rotation",
            platform(r#"{"points": [{"time": 0}, {"time": 1, "rotation": [0, 0, 0, 0]}]}"#),
            "bodies[1].path.points[1].rotation",
            "zero length",
        ),
        (
            "path_unknown_field",
            platform(r#"{"points": [{"time": 0}], "speed": 2}"#),
            "bodies[1].path.speed",
            "unknown field `speed`, expected `points` or `loop`",
        ),
        (
            "path_point_unknown_field",
            platform(r#"{"points": [{"time": 0, "velocity": [1, 0, 0]}]}"#),
            "bodies[1].path.points[0].velocity",
            "unknown field `velocity`",
        ),
        (
            "path_loop_not_a_bool",
            platform(r#"{"points": [{"time": 0}], "loop": 1}"#),
            "bodies[1].path.loop",
            "invalid type",
        ),
        (
            "path_points_not_a_list",
            platform(r#"{"points": {"time": 0}}"#),
            "bodies[1].path.points",
            "invalid type",
        ),
    ];
    for (name, scene, place, message) in cases {
        assert_refused(name, &scene, place, message);
    }
}

#[test]
fn bad_collider_fields_of_compound_children_are_refused() {
    let children = |second: &str| {
        scene_with(&format!(
            r#"{{"shape": {{"type": "compound", "children": [
                {{{BALL}, "name": "torso"}}, {{{BALL}, {second}}}]}}}}"#
        ))
    };
    assert_refused(
        "duplicate_child_name",
        &children(r#""name": "torso""#),
        "bodies[1].shape.children[1].name",
        "share a name",
    );
    assert_refused(
        "empty_child_name",
        &children(r#""name": """#),
        "bodies[1].shape.children[1].name",
        "may not be empty",
    );
    assert_refused(
        "child_sensor_not_a_boolean",
        &children(r#""sensor": 1"#),
        "bodies[1].shape.children[1].sensor",
        "invalid type: integer `1`",
    );
    assert_refused(
        "negative_child_groups",
        &children(r#""collision_groups": {"memberships": -1}"#),
        "bodies[1].shape.children[1].collision_groups.memberships",
        "invalid value: integer `-1`",
    );
}
