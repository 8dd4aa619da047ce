//! Python values (dicts, lists, tuples, NumPy arrays and scalars) turned into JSON, so that
//! scenes, bodies and joints given from Python go through the scene loader's own checks and
//! error messages.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use serde_json::{Map, Number, Value};

use crate::errors::SceneError;

/// `value` as JSON; `place` is its path in the scene (`bodies[2].position`), for errors.
pub fn to_json(value: &Bound<'_, PyAny>, place: &str) -> PyResult<Value> {
    if value.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(flag) = value.downcast::<PyBool>() {
        return Ok(Value::Bool(flag.is_true()));
    }
    if let Ok(text) = value.downcast::<PyString>() {
        return Ok(Value::String(text.to_cow()?.into_owned()));
    }
    if let Ok(dict) = value.downcast::<PyDict>() {
        let mut object = Map::new();
        for (key, item) in dict.iter() {
            let Ok(key) = key.downcast::<PyString>() else {
                return Err(scene_error(place, "keys must be strings"));
            };
            let key = key.to_cow()?.into_owned();
            let item = to_json(&item, &join(place, &key))?;
            object.insert(key, item);
        }
        return Ok(Value::Object(object));
    }
    if let Ok(integer) = value.downcast::<PyInt>() {
        if let Ok(integer) = integer.extract::<i64>() {
            return Ok(Value::Number(integer.into()));
        }
        if let Ok(integer) = integer.extract::<u64>() {
            return Ok(Value::Number(integer.into()));
        }
        return number(integer.extract::<f64>()?, place);
    }
    if value.downcast::<PyFloat>().is_ok() {
        return number(value.extract::<f64>()?, place);
    }
    if let Ok(items) = value.try_iter() {
        let mut array = Vec::new();
        for (index, item) in items.enumerate() {
            array.push(to_json(&item?, &format!("{place}[{index}]"))?);
        }
        return Ok(Value::Array(array));
    }
    // NumPy scalars: whole numbers (which have `__index__`) stay whole, as `substeps` needs;
    // anything else that converts to a float is a number.
    if value.hasattr("__index__")? {
        if let Ok(integer) = value.extract::<i64>() {
            return Ok(Value::Number(integer.into()));
        }
    }
    if let Ok(float) = value.extract::<f64>() {
        return number(float, place);
    }
    let type_name = value.get_type().name()?;
    Err(scene_error(
        place,
        &format!("cannot be given as a Python {type_name}"),
    ))
}

/// A JSON number, refusing NaN and infinities as the scene loader refuses what is not finite.
fn number(value: f64, place: &str) -> PyResult<Value> {
    Number::from_f64(value)
        .map(Value::Number)
        .ok_or_else(|| scene_error(place, &format!("must be finite, got {value}")))
}

/// `parent.field`, or `field` at the top level.
pub fn join(parent: &str, field: &str) -> String {
    if parent.is_empty() {
        field.to_owned()
    } else {
        format!("{parent}.{field}")
    }
}

/// A `SceneError` at `place` (the top level when empty).
fn scene_error(place: &str, message: &str) -> PyErr {
    if place.is_empty() {
        SceneError::new_err(message.to_owned())
    } else {
        SceneError::new_err(format!("{place}: {message}"))
    }
}

/// The JSON text of `value`; serialising a `Value` cannot fail, but the error is kept.
pub fn to_bytes(value: &Value) -> PyResult<Vec<u8>> {
    serde_json::to_vec(value).map_err(|error| PyValueError::new_err(error.to_string()))
}
