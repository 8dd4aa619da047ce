//! Python bindings of rebond: `rebond.World` (one world, state as NumPy arrays) and
//! `rebond.Batch` (copies of a world stepped in parallel on every core, without the GIL).
//!
//! Scenes, bodies and joints given from Python go through the scene loader, so they are checked
//! as scene files are and their errors are the command line's. The Python package around this
//! module (`python/rebond`) re-exports it and carries the typed stubs.

mod actuators;
mod arrays;
mod batch;
mod dicts;
mod drive;
mod errors;
mod json;
mod readouts;
mod render;
mod robust;
mod rollout;
mod scenes;
mod sim;
mod state;
mod world;

use pyo3::prelude::*;

/// The native module, imported by the `rebond` package.
#[pymodule]
fn _rebond(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    module.add_class::<world::World>()?;
    module.add_class::<world::RayHit>()?;
    module.add_class::<batch::Batch>()?;
    module.add("SceneError", py.get_type::<errors::SceneError>())?;
    module.add("StepError", py.get_type::<errors::StepError>())?;
    module.add("StateError", py.get_type::<errors::StateError>())?;
    module.add_function(wrap_pyfunction!(scenes::builtin_scenes, module)?)?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
