//! The exceptions the module raises, with the command line's messages.

use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;
use rebond::scene::{LoadError, SceneError as InvalidScene};

create_exception!(
    rebond,
    SceneError,
    PyValueError,
    "A scene, body or joint that is not valid: the message names the place of the bad value \
     (`bodies[3].shape.radius: must be positive, got -1`), as the command line does."
);

create_exception!(
    rebond,
    StateError,
    PyValueError,
    "Bytes that are not a world saved by `World.save` of this build of rebond: not a state, \
     cut short, damaged, or of another format version or build; the message says which."
);

create_exception!(
    rebond,
    StepError,
    PyRuntimeError,
    "The engine refused to step a world: `step N failed: ...`, as the command line says."
);

/// `source: error`, or the error alone without a source.
pub fn with_source(source: Option<&str>, message: impl std::fmt::Display) -> String {
    match source {
        Some(source) => format!("{source}: {message}"),
        None => message.to_string(),
    }
}

/// The exception for an invalid scene from `source`.
pub fn invalid_scene(source: Option<&str>, error: &InvalidScene) -> PyErr {
    SceneError::new_err(with_source(source, error))
}

/// The exception for a scene file that could not be loaded: `OSError` when it could not be
/// read (`path: cannot read scene: ...`), `SceneError` when it is not valid (`path: place: ...`).
pub fn load_failed(path: &str, error: &LoadError) -> PyErr {
    match error {
        LoadError::Read { .. } | LoadError::Mesh { .. } => PyOSError::new_err(error.to_string()),
        LoadError::Invalid(invalid) => invalid_scene(Some(path), invalid),
    }
}
