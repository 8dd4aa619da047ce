//! Values past the engine's numeric limits (`docs/limits.md`) are refused like any bad input.

use crate::bad_input::assert_refused;

/// The ground of the bad-input scenes.
const GROUND: &str = r#"{"name": "ground", "type": "static",
    "shape": {"type": "box", "half_extents": [10, 0.5, 10]}, "position": [0, -0.5, 0]}"#;

#[test]
fn values_past_the_engines_limits_are_refused() {
    // The inputs issue 17 found accepted (exit 0) and simulated wrongly; the limits are in
    // docs/limits.md.
    assert_refused(
        "huge_box",
        r#"{"bodies": [{"name": "floor", "type": "static",
              "shape": {"type": "box", "half_extents": [1e20, 0.5, 1e20]}}]}"#,
        "bodies[0].shape.half_extents[0]",
        "must lie between 0.001 and 100000",
    );
    assert_refused(
        "huge_velocity",
        &format!(
            r#"{{"bodies": [{GROUND}, {{"shape": {{"type": "sphere", "radius": 0.5}},
              "linear_velocity": [1e30, 0, 0]}}]}}"#
        ),
        "bodies[1].linear_velocity",
        "must not exceed 1e4 (the engine's limit)",
    );
    let ground_only = format!(r#""bodies": [{GROUND}]"#);
    assert_refused(
        "huge_gravity",
        &format!(r#"{{"gravity": [0, -1e30, 0], {ground_only}}}"#),
        "gravity",
        "must not exceed 1e3 (the engine's limit)",
    );
    assert_refused(
        "huge_timestep",
        &format!(r#"{{"timestep": 1e30, {ground_only}}}"#),
        "timestep",
        "must lie between 0.0001 and 0.1 (the engine's limits)",
    );
}
