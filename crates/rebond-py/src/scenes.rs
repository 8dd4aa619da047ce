//! Scenes named by a path or by the name of a scene built into the library, so that
//! `World.from_scene("pendulum")` works from any directory, as `rebond run pendulum` does.

use std::path::Path;

use pyo3::exceptions::PyFileNotFoundError;
use pyo3::prelude::*;
use rebond::scene::{builtin, Scene, BUILTIN_SCENES};

use crate::errors::load_failed;
use crate::sim::Sim;

/// The scene at `path`, or the built-in scene of that name when no such file exists: a path
/// that exists wins. Neither raises `FileNotFoundError` naming both and listing the built-in
/// scenes.
pub fn load_path(path: &Path) -> PyResult<Sim> {
    let label = path.display().to_string();
    if path.exists() {
        let loaded = Scene::from_file(path).map_err(|error| load_failed(&label, &error))?;
        return Ok(Sim::new(loaded, Some(label)));
    }
    let Some(scene) = path.to_str().and_then(builtin) else {
        let names: Vec<&str> = BUILTIN_SCENES.iter().map(|scene| scene.name).collect();
        return Err(PyFileNotFoundError::new_err(format!(
            "{label}: cannot read scene: no such file, and no built-in scene of that name \
             (built-in scenes: {})",
            names.join(", ")
        )));
    };
    let label = format!("{} (built-in)", scene.name);
    let loaded = scene.load().map_err(|error| load_failed(&label, &error))?;
    Ok(Sim::new(loaded, Some(label)))
}

/// The scenes built into rebond: name to a one-line description, in the command line's order
/// (`rebond scenes`). Each loads by its name: `World.from_scene("pendulum")`.
#[pyfunction]
pub fn builtin_scenes() -> Vec<(&'static str, &'static str)> {
    BUILTIN_SCENES
        .iter()
        .map(|scene| (scene.name, scene.description))
        .collect()
}
