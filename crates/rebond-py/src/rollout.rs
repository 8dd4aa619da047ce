//! Rollouts: `T` steps of motor targets then one step, recorded, with no Python between steps.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use crate::arrays::{input, output};
use crate::batch::Batch;
use crate::errors::StepError;
use crate::sim::{Quantity, Sim};
use crate::state::Coordinate;
use crate::world::World;

/// The per-body quantities a rollout records, with their names in the returned dict.
const BODY_RECORDS: [(&str, Quantity); 4] = [
    ("positions", Quantity::Position),
    ("rotations", Quantity::Rotation),
    ("linear_velocities", Quantity::LinearVelocity),
    ("angular_velocities", Quantity::AngularVelocity),
];

/// The joint coordinates a rollout records, with their names in the returned dict.
const JOINT_RECORDS: [(&str, Coordinate); 2] = [
    ("joint_positions", Coordinate::Position),
    ("joint_velocities", Coordinate::Velocity),
];

/// One world's record of a rollout: for each of [`BODY_RECORDS`] then [`JOINT_RECORDS`], the
/// values after each step, step after step.
struct Record {
    series: Vec<Vec<f32>>,
}

/// Why a rollout stopped: a motor target the engine refused, or a step that failed.
enum Stop {
    Target { step: usize, message: String },
    Step(String),
}

impl Record {
    /// Room for `steps` steps of `sim`.
    fn new(sim: &Sim, steps: usize) -> Self {
        let bodies = sim.body_count();
        let joints = sim.joint_count();
        let mut series: Vec<Vec<f32>> = BODY_RECORDS
            .iter()
            .map(|(_, quantity)| vec![0.0; steps * bodies * quantity.width()])
            .collect();
        series.extend(JOINT_RECORDS.iter().map(|_| vec![0.0; steps * joints]));
        Self { series }
    }
}

impl Sim {
    /// For each of `steps` steps: sets the motor targets of `controls` (steps, motors), steps
    /// once, and records the state into `record` (what `set_motor_targets` then `step(1)` do,
    /// call for call).
    fn rollout(&mut self, controls: &[f32], steps: usize, record: &mut Record) -> Result<(), Stop> {
        let motors = self.motor_count();
        for step in 0..steps {
            let targets = &controls[step * motors..(step + 1) * motors];
            self.set_motor_targets(targets)
                .map_err(|error| Stop::Target {
                    step,
                    message: error.to_string(),
                })?;
            self.step(1).map_err(Stop::Step)?;
            for ((_, quantity), series) in BODY_RECORDS.iter().zip(&mut record.series) {
                let width = self.body_count() * quantity.width();
                self.read(*quantity, &mut series[step * width..(step + 1) * width]);
            }
            for ((_, coordinate), series) in JOINT_RECORDS.iter().zip(&mut record.series[4..]) {
                let width = self.joint_count();
                self.read_joints(*coordinate, &mut series[step * width..(step + 1) * width]);
            }
        }
        Ok(())
    }
}

/// The error for a stopped rollout; `world` prefixes a batch's messages.
fn stop_error(stop: Stop, world: Option<usize>) -> PyErr {
    match (stop, world) {
        (Stop::Target { step, message }, Some(world)) => {
            PyValueError::new_err(format!("controls[{step}, {world}]: {message}"))
        }
        (Stop::Target { step, message }, None) => {
            PyValueError::new_err(format!("controls[{step}]: {message}"))
        }
        (Stop::Step(message), Some(world)) => {
            StepError::new_err(format!("world {world}: {message}"))
        }
        (Stop::Step(message), None) => StepError::new_err(message),
    }
}

/// The dict of a rollout's arrays: each series of the records, `(T, count, ...)` (without
/// `count` for a world, `batch` false).
fn arrays<'py>(
    py: Python<'py>,
    sim: &Sim,
    records: &[Record],
    steps: usize,
    batch: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let bodies = sim.body_count();
    let joints = sim.joint_count();
    let layouts = BODY_RECORDS
        .iter()
        .map(|(name, quantity)| (*name, vec![bodies, quantity.width()]))
        .chain(JOINT_RECORDS.iter().map(|(name, _)| (*name, vec![joints])));
    for (series, (name, inner)) in layouts.enumerate() {
        let per_step: usize = inner.iter().product();
        let mut values = Vec::with_capacity(steps * records.len() * per_step);
        for step in 0..steps {
            for record in records {
                values.extend_from_slice(
                    &record.series[series][step * per_step..(step + 1) * per_step],
                );
            }
        }
        let mut shape = vec![steps];
        if batch {
            shape.push(records.len());
        }
        shape.extend(inner);
        dict.set_item(name, output(py, values, &shape)?)?;
    }
    Ok(dict)
}

/// The number of steps of `controls` (its first axis), before it is read whole.
fn steps_of(controls: &Bound<'_, PyAny>) -> PyResult<usize> {
    let shape: Vec<usize> = controls
        .py()
        .import("numpy")?
        .call_method1("shape", (controls,))?
        .extract()?;
    shape.first().copied().ok_or_else(|| {
        PyValueError::new_err("controls: got a single number, expected an array (T, ...)")
    })
}

#[pymethods]
impl Batch {
    /// For each `t` of `controls` (float array (T, count, motors)): `set_motor_targets(controls[t])`
    /// then `step(1)`, in parallel, without the GIL, with no Python between steps; returns the
    /// state after every step as a dict of float32 arrays: `positions`, `linear_velocities`,
    /// `angular_velocities` (T, count, bodies, 3), `rotations` (T, count, bodies, 4),
    /// `joint_positions`, `joint_velocities` (T, count, joints). The same bits as the calls one
    /// by one. A refused target or a failed step raises for the first world it stopped, whose
    /// steps up to there stand, as the other worlds' whole rollouts do.
    fn rollout<'py>(
        &mut self,
        py: Python<'py>,
        controls: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let motors = self.initial.motor_count();
        let count = self.sims.len();
        let steps = steps_of(controls)?;
        let values = input(
            controls,
            &[steps, count, motors],
            "controls",
            "(T, count, motors)",
        )?;
        let mut records: Vec<Record> = self
            .sims
            .iter()
            .map(|sim| Record::new(sim, steps))
            .collect();
        let sims = &mut self.sims;
        let results: Vec<Result<(), Stop>> = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(records.par_iter_mut())
                .enumerate()
                .map(|(world, (sim, record))| {
                    let controls: Vec<f32> = (0..steps)
                        .flat_map(|step| {
                            let start = (step * count + world) * motors;
                            values[start..start + motors].iter().copied()
                        })
                        .collect();
                    sim.rollout(&controls, steps, record)
                })
                .collect()
        });
        for (world, result) in results.into_iter().enumerate() {
            result.map_err(|stop| stop_error(stop, Some(world)))?;
        }
        arrays(py, &self.initial, &records, steps, true)
    }
}

#[pymethods]
impl World {
    /// `Batch.rollout` for one world: controls (T, motors); arrays (T, bodies, 3),
    /// (T, bodies, 4) and (T, joints).
    fn rollout<'py>(
        &mut self,
        py: Python<'py>,
        controls: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let motors = self.sim.motor_count();
        let steps = steps_of(controls)?;
        let values = input(controls, &[steps, motors], "controls", "(T, motors)")?;
        let mut record = Record::new(&self.sim, steps);
        let sim = &mut self.sim;
        py.allow_threads(|| sim.rollout(&values, steps, &mut record))
            .map_err(|stop| stop_error(stop, None))?;
        arrays(py, &self.sim, &[record], steps, false)
    }
}
