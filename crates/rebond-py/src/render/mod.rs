//! Pictures: `World.render` and `Batch.render` draw worlds on the CPU into `(height, width, 3)`
//! `uint8` arrays, with no GPU, window or system library, and `World.render_camera` tells the
//! camera a picture is taken with.

mod camera;
mod raster;

use numpy::{PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString};
use rayon::prelude::*;
use rebond::Vec3;

use crate::arrays::input;
use crate::batch::Batch;
use crate::sim::Sim;
use crate::world::World;
use camera::{Camera, CameraRequest};

/// Largest width or height of a picture, pixels.
const MAX_SIZE: i64 = 8192;
/// The fields of a camera dict.
const CAMERA_FIELDS: &str = "position, target, fov, up";

/// `width` and `height` checked: whole numbers from 1 to [`MAX_SIZE`].
fn picture_size(width: i64, height: i64) -> PyResult<(usize, usize)> {
    let check = |name: &str, value: i64| {
        if (1..=MAX_SIZE).contains(&value) {
            Ok(value as usize)
        } else {
            Err(PyValueError::new_err(format!(
                "{name}: must be from 1 to {MAX_SIZE} pixels, got {value}"
            )))
        }
    };
    Ok((check("width", width)?, check("height", height)?))
}

/// A camera dict read into a request: `None` asks for the default camera; fields left out are
/// the default's. Errors name the field (`camera.position: ...`).
fn camera_request(camera: Option<&Bound<'_, PyAny>>) -> PyResult<CameraRequest> {
    let mut request = CameraRequest::default();
    let Some(camera) = camera.filter(|camera| !camera.is_none()) else {
        return Ok(request);
    };
    let Ok(fields) = camera.downcast::<PyDict>() else {
        let type_name = camera.get_type().name()?;
        return Err(PyValueError::new_err(format!(
            "camera: expected a dict with some of {CAMERA_FIELDS}, got a {type_name}"
        )));
    };
    for (key, value) in fields.iter() {
        let Ok(key) = key.downcast::<PyString>() else {
            return Err(PyValueError::new_err(format!(
                "camera: keys must be strings ({CAMERA_FIELDS}), got {}",
                key.repr()?
            )));
        };
        let key = key.to_cow()?;
        let name = format!("camera.{key}");
        let vector = |value: &Bound<'_, PyAny>| -> PyResult<Vec3> {
            let values = input(value, &[3], &name, "(x, y, z)")?;
            Ok(Vec3::new(values[0], values[1], values[2]))
        };
        match key.as_ref() {
            "position" => request.position = Some(vector(&value)?),
            "target" => request.target = Some(vector(&value)?),
            "up" => request.up = Some(vector(&value)?),
            "fov" => {
                let degrees = value
                    .downcast::<PyBool>()
                    .is_err()
                    .then(|| value.extract::<f64>().ok())
                    .flatten()
                    .ok_or_else(|| {
                        PyValueError::new_err(format!(
                            "{name}: expected a number of degrees, got {}",
                            value
                                .repr()
                                .map(|text| text.to_string())
                                .unwrap_or_default()
                        ))
                    })?;
                request.fov_degrees = Some(degrees as f32);
            }
            _ => {
                return Err(PyValueError::new_err(format!(
                    "{name}: unknown field (a camera has {CAMERA_FIELDS})"
                )))
            }
        }
    }
    Ok(request)
}

/// The camera `request` resolves to for `sim` on a `width` × `height` picture.
fn resolve(sim: &Sim, request: &CameraRequest, width: usize, height: usize) -> PyResult<Camera> {
    request
        .resolve(sim.scene().world(), width, height)
        .map_err(PyValueError::new_err)
}

/// The checked size and the resolved camera of a picture of `sim`.
fn picture_camera(
    sim: &Sim,
    width: i64,
    height: i64,
    camera: Option<&Bound<'_, PyAny>>,
) -> PyResult<(usize, usize, Camera)> {
    let (width, height) = picture_size(width, height)?;
    let camera = resolve(sim, &camera_request(camera)?, width, height)?;
    Ok((width, height, camera))
}

/// A picture's bytes as a `uint8` array `(height, width, 3)`.
fn picture<'py>(
    py: Python<'py>,
    pixels: Vec<u8>,
    width: usize,
    height: usize,
) -> PyResult<Bound<'py, PyArrayDyn<u8>>> {
    PyArray1::from_vec(py, pixels).reshape(vec![height, width, 3])
}

#[pymethods]
impl World {
    /// The world drawn from `camera` (a dict of `position`, `target`, `fov` in degrees, `up`;
    /// fields left out, or all with `None`, are the default camera's, which frames the moving
    /// bodies): a `uint8` array `(height, width, 3)` of red, green, blue, top row first.
    #[pyo3(signature = (width, height, camera = None))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        width: i64,
        height: i64,
        camera: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArrayDyn<u8>>> {
        let (width, height, camera) = picture_camera(&self.sim, width, height, camera)?;
        let sim = &self.sim;
        let pixels = py.allow_threads(|| raster::render(sim.scene(), &camera, width, height));
        picture(py, pixels, width, height)
    }

    /// The camera `render(width, height, camera)` draws with, every field filled in: a dict of
    /// `position` and `target` (m), `fov` (degrees) and `up`. Passing it to `render` gives the
    /// same picture; keeping it keeps the view still while the bodies move.
    #[pyo3(signature = (width, height, camera = None))]
    fn render_camera<'py>(
        &self,
        py: Python<'py>,
        width: i64,
        height: i64,
        camera: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (_, _, camera) = picture_camera(&self.sim, width, height, camera)?;
        let dict = PyDict::new(py);
        let list = |vector: Vec3| PyList::new(py, vector.to_array().map(f64::from));
        dict.set_item("position", list(camera.position)?)?;
        dict.set_item("target", list(camera.target)?)?;
        dict.set_item("fov", f64::from(camera.fov_degrees))?;
        dict.set_item("up", list(camera.up)?)?;
        Ok(dict)
    }
}

#[pymethods]
impl Batch {
    /// World `index` drawn as `World.render` draws it: `(height, width, 3)` `uint8`. With a list
    /// of indices, those worlds drawn in parallel: `(len(index), height, width, 3)`; with the
    /// default camera each world is framed on its own bodies.
    #[pyo3(signature = (index, width, height, camera = None))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        index: &Bound<'py, PyAny>,
        width: i64,
        height: i64,
        camera: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArrayDyn<u8>>> {
        let (width, height) = picture_size(width, height)?;
        let request = camera_request(camera)?;
        // An int or a NumPy integer is one world; anything else iterable is a list of them.
        let single = index.extract::<i64>().ok();
        let indices: Vec<i64> = match single {
            Some(single) => vec![single],
            None => index
                .try_iter()
                .and_then(|items| items.map(|item| item?.extract::<i64>()).collect())
                .map_err(|error| {
                    PyValueError::new_err(format!(
                        "index: expected a world index or a list of them: {error}"
                    ))
                })?,
        };
        let sims = &self.sims;
        let mut chosen = Vec::with_capacity(indices.len());
        for (place, &world) in indices.iter().enumerate() {
            let sim = usize::try_from(world)
                .ok()
                .and_then(|world| sims.get(world))
                .ok_or_else(|| {
                    let name = match single {
                        Some(_) => "index".to_owned(),
                        None => format!("index[{place}]"),
                    };
                    PyIndexError::new_err(format!(
                        "{name}: {world} is not a world of this batch (0 to {})",
                        sims.len() - 1
                    ))
                })?;
            chosen.push((sim, resolve(sim, &request, width, height)?));
        }
        let pictures: Vec<Vec<u8>> = py.allow_threads(|| {
            chosen
                .par_iter()
                .map(|(sim, camera)| raster::render(sim.scene(), camera, width, height))
                .collect()
        });
        let pixels = pictures.concat();
        match single {
            Some(_) => picture(py, pixels, width, height),
            None => PyArray1::from_vec(py, pixels).reshape(vec![chosen.len(), height, width, 3]),
        }
    }
}
