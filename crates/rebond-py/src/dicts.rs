//! Errors on scenes, bodies and joints given as Python dicts, told in the user's terms: the
//! loader reads the JSON text the module wrote from the dict, so the line and column it quotes
//! in that text mean nothing to the user and are dropped; the place (`bodies[0].shape.radius`)
//! and the value stay.

use pyo3::PyErr;
use rebond::scene::SceneError as InvalidScene;

use crate::errors::SceneError;

/// The exception for `error`, found loading a dict.
pub fn dict_error(error: &InvalidScene) -> PyErr {
    let error = InvalidScene {
        place: error.place.clone(),
        message: without_position(&error.message).to_owned(),
    };
    SceneError::new_err(error.to_string())
}

/// `message` without the loader's ` (line 1, column 57)` at its end.
fn without_position(message: &str) -> &str {
    let Some(start) = message.rfind(" (line ") else {
        return message;
    };
    let is_position = message[start + " (line ".len()..]
        .strip_suffix(')')
        .and_then(|tail| tail.split_once(", column "))
        .is_some_and(|(line, column)| {
            [line, column]
                .iter()
                .all(|part| !part.is_empty() && part.bytes().all(|byte| byte.is_ascii_digit()))
        });
    if is_position {
        &message[..start]
    } else {
        message
    }
}
