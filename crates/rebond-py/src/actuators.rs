//! A scene's actuators from Python (MuJoCo's `motor`, `position` and `velocity` actuators of
//! imported MJCF files, or a scene's `actuators`): their names, control ranges, and the
//! controls, one value per actuator in scene order.

use numpy::PyArrayDyn;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;

use crate::arrays::{input, output};
use crate::batch::Batch;
use crate::sim::Sim;
use crate::world::World;

impl Sim {
    /// Number of actuators.
    fn actuator_count(&self) -> usize {
        self.scene().actuators().len()
    }

    /// Actuator names in scene order.
    fn actuator_names(&self) -> Vec<String> {
        let actuators = self.scene().actuators();
        actuators
            .iter()
            .map(|actuator| actuator.name.clone())
            .collect()
    }

    /// Each actuator's control range `[lo, hi]`, `[-inf, inf]` for an unclamped one, as a
    /// (actuators, 2) array.
    fn ctrl_ranges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let actuators = self.scene().actuators();
        let values = actuators
            .iter()
            .flat_map(|actuator| {
                actuator
                    .ctrl_range
                    .unwrap_or([f32::NEG_INFINITY, f32::INFINITY])
            })
            .collect();
        output(py, values, &[actuators.len(), 2])
    }
}

#[pymethods]
impl World {
    /// Actuator names in scene order: the order of `set_controls`.
    fn actuator_names(&self) -> Vec<String> {
        self.sim.actuator_names()
    }

    /// Each actuator's control range `[lo, hi]` that `set_controls` clamps to: float32 array
    /// (actuators, 2); `[-inf, inf]` for an actuator without one.
    fn ctrl_ranges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.sim.ctrl_ranges(py)
    }

    /// Sets every actuator's control `u` (actuators,), held until set again: a `motor` gives its
    /// joint the torque or force `gear · clamp(u)`, a `position` actuator a position motor
    /// towards `clamp(u) / gear`, a `velocity` actuator a velocity motor towards
    /// `clamp(u) / gear`. Every value is checked before any joint changes.
    fn set_controls(&mut self, u: &Bound<'_, PyAny>) -> PyResult<()> {
        let shape = [self.sim.actuator_count()];
        let values = input(u, &shape, "set_controls", "(actuators,)")?;
        self.sim
            .scene_mut()
            .set_controls(&values)
            .map_err(|error| PyValueError::new_err(format!("set_controls: {error}")))
    }
}

#[pymethods]
impl Batch {
    /// Actuator names in scene order: the order of `set_controls`.
    fn actuator_names(&self) -> Vec<String> {
        self.initial.actuator_names()
    }

    /// Each actuator's control range `[lo, hi]`: float32 array (actuators, 2), the same in every
    /// world; `[-inf, inf]` for an actuator without one.
    fn ctrl_ranges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.initial.ctrl_ranges(py)
    }

    /// Sets every world's actuator controls, (count, actuators), as `World.set_controls` does,
    /// in parallel without the GIL. A world the engine refuses (a torque beyond its range) is
    /// left unchanged and named; the others are set.
    fn set_controls(&mut self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<()> {
        let actuators = self.initial.actuator_count();
        let shape = [self.sims.len(), actuators];
        let values = input(u, &shape, "set_controls", "(count, actuators)")?;
        let sims = &mut self.sims;
        let results: Vec<Result<(), rebond::Error>> = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(values.par_chunks(actuators.max(1)))
                .map(|(sim, controls)| sim.scene_mut().set_controls(controls))
                .collect()
        });
        for (index, result) in results.into_iter().enumerate() {
            if let Err(error) = result {
                return Err(PyValueError::new_err(format!(
                    "set_controls: world {index}: {error}"
                )));
            }
        }
        Ok(())
    }
}
