//! NumPy arrays in and out: inputs converted to contiguous `float32` and checked for shape and
//! finiteness, outputs built from flat vectors.

use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// `value` as a flat `float32` vector of exactly `shape`, every number finite. `name` is the
/// argument's name and `meaning` says what the axes are (`(bodies, 3)`), for errors.
pub fn input(
    value: &Bound<'_, PyAny>,
    shape: &[usize],
    name: &str,
    meaning: &str,
) -> PyResult<Vec<f32>> {
    input_where(value, shape, name, meaning, |_| true)
}

/// [`input`], with only the numbers at the flat indices where `must_be_finite` holds checked
/// finite (joint coordinates are NaN where a joint has none).
pub fn input_where(
    value: &Bound<'_, PyAny>,
    shape: &[usize],
    name: &str,
    meaning: &str,
    must_be_finite: impl Fn(usize) -> bool,
) -> PyResult<Vec<f32>> {
    let py = value.py();
    let numpy = py.import("numpy")?;
    let kwargs = pyo3::types::PyDict::new(py);
    kwargs.set_item("dtype", numpy.getattr("float32")?)?;
    let converted = numpy
        .call_method("ascontiguousarray", (value,), Some(&kwargs))
        .map_err(|error| {
            PyValueError::new_err(format!(
                "{name}: cannot be read as an array of float32 numbers: {error}"
            ))
        })?;
    let array = converted.downcast::<PyArrayDyn<f32>>()?;
    if array.shape() != shape {
        return Err(PyValueError::new_err(format!(
            "{name}: got an array of shape {}, expected {} {meaning}",
            shape_text(array.shape()),
            shape_text(shape)
        )));
    }
    let values = array.readonly().as_slice()?.to_vec();
    let not_finite = |(index, value): &(usize, &f32)| !value.is_finite() && must_be_finite(*index);
    if let Some((index, _)) = values.iter().enumerate().find(not_finite) {
        return Err(PyValueError::new_err(format!(
            "{name}: element {} must be finite, got {}",
            index_text(index, shape),
            values[index]
        )));
    }
    Ok(values)
}

/// A `float32` array of `shape` holding `values`.
pub fn output<'py>(
    py: Python<'py>,
    values: Vec<f32>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
    PyArray1::from_vec(py, values).reshape(shape)
}

/// `(2, 3)`, as Python prints a shape.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [single] => format!("({single},)"),
        _ => {
            let parts: Vec<String> = shape.iter().map(usize::to_string).collect();
            format!("({})", parts.join(", "))
        }
    }
}

/// `[1, 2]`: the place of the flat `index` in an array of `shape`.
pub fn index_text(mut index: usize, shape: &[usize]) -> String {
    let mut parts = vec![0; shape.len()];
    for (part, &size) in parts.iter_mut().zip(shape).rev() {
        if size > 0 {
            *part = index % size;
            index /= size;
        }
    }
    let parts: Vec<String> = parts.iter().map(usize::to_string).collect();
    format!("[{}]", parts.join(", "))
}
