//! `rebond.Batch`: copies of one world stepped in parallel on every core, without the GIL.

use numpy::PyArrayDyn;
use pyo3::exceptions::{PyIndexError, PyMemoryError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;

use crate::arrays::{input, output};
use crate::errors::StepError;
use crate::robust::{copies, step_in_rounds, whole_number, StepCount};
use crate::sim::{Input, Quantity, Sim};
use crate::world::{load_scene, World};

/// `count` copies of one world, stepped in parallel; arrays have a leading batch axis.
///
/// Each copy steps exactly as a world of its own would: a batch of N gives bit for bit the
/// states of N separate worlds stepped one by one.
#[pyclass(module = "rebond")]
pub struct Batch {
    /// The world every copy starts from, and `reset` returns to.
    pub(crate) initial: Sim,
    /// The copies.
    pub(crate) sims: Vec<Sim>,
}

#[pymethods]
impl Batch {
    /// `count` copies of `scene`: a path to a scene file or a built-in scene's name, a dict in
    /// the scene format, or a `World` (copied in its current state). A `count` whose copies
    /// cannot fit in memory raises `MemoryError` before any is made.
    #[new]
    fn new(scene: &Bound<'_, PyAny>, count: &Bound<'_, PyAny>) -> PyResult<Self> {
        let count = whole_number(count, "count", 1)?;
        let initial = load_scene(scene)?;
        let count = usize::try_from(count).map_err(|_| {
            PyMemoryError::new_err(format!("count: {count} worlds cannot be addressed"))
        })?;
        let sims = copies(&initial, count)?;
        Ok(Self { initial, sims })
    }

    /// Number of worlds.
    #[getter]
    fn count(&self) -> usize {
        self.sims.len()
    }

    fn __len__(&self) -> usize {
        self.sims.len()
    }

    /// Seconds per step.
    #[getter]
    fn timestep(&self) -> f64 {
        self.initial.timestep()
    }

    /// Number of bodies in each world.
    #[getter]
    fn body_count(&self) -> usize {
        self.initial.body_count()
    }

    /// Body names in scene order.
    fn body_names(&self) -> Vec<String> {
        self.initial.body_names()
    }

    /// Joint names in scene order.
    fn joint_names(&self) -> Vec<String> {
        self.initial.joint_names()
    }

    /// Names of the joints with a motor, in the order of `set_motor_targets`.
    fn motor_names(&self) -> Vec<String> {
        self.initial.motor_names()
    }

    /// Advances every world by `n` steps, in parallel on all cores, without the GIL. A failed
    /// step raises `StepError` for the first failing world (`world 3: step 12 failed: ...`);
    /// the other worlds have still stepped. Ctrl-C stops it within about a tenth of a second
    /// with `KeyboardInterrupt`, every world having taken the same whole number of steps.
    #[pyo3(signature = (n = StepCount(1)))]
    fn step(&mut self, py: Python<'_>, n: StepCount) -> PyResult<()> {
        let sims = &mut self.sims;
        sims.iter_mut().for_each(Sim::begin_call);
        let mut failures: Vec<Option<String>> = vec![None; sims.len()];
        let rounds = step_in_rounds(py, n.0, |steps| {
            sims.par_iter_mut()
                .zip(failures.par_iter_mut())
                .filter(|(_, failure)| failure.is_none())
                .for_each(|(sim, failure)| *failure = sim.step_round(steps).err());
            Ok::<(), std::convert::Infallible>(())
        });
        self.sims.iter_mut().for_each(Sim::end_call);
        let Ok(()) = rounds?;
        if let Some((index, message)) = failures
            .into_iter()
            .enumerate()
            .find_map(|(index, failure)| Some((index, failure?)))
        {
            return Err(StepError::new_err(format!("world {index}: {message}")));
        }
        Ok(())
    }

    /// A copy of world `index` as a `World`.
    fn world(&self, index: i64) -> PyResult<World> {
        usize::try_from(index)
            .ok()
            .and_then(|index| self.sims.get(index))
            .map(|sim| World { sim: sim.clone() })
            .ok_or_else(|| {
                PyIndexError::new_err(format!(
                    "index: {index} is not a world of this batch (0 to {})",
                    self.sims.len() - 1
                ))
            })
    }

    /// Body origins, m: float32 array (count, bodies, 3).
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::Position)
    }

    /// Rotations (x, y, z, w): float32 array (count, bodies, 4).
    fn rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::Rotation)
    }

    /// Velocities of the centres of mass, m/s: float32 array (count, bodies, 3).
    fn linear_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::LinearVelocity)
    }

    /// Angular velocities, rad/s: float32 array (count, bodies, 3).
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::AngularVelocity)
    }

    /// Centres of mass, m: float32 array (count, bodies, 3).
    fn centers_of_mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::CenterOfMass)
    }

    /// Inertia tensors about the centres of mass in world axes, kg·m², `R I Rᵀ` as xx, yy, zz,
    /// xy, xz, yz: float32 array (count, bodies, 6); zeros for static and kinematic bodies.
    fn inertias<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::Inertia)
    }

    /// Sets every body's linear velocity in every world: array (count, bodies, 3).
    fn set_linear_velocities(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write(py, a, Input::LinearVelocity, "set_linear_velocities")
    }

    /// Sets every body's angular velocity in every world: array (count, bodies, 3).
    fn set_angular_velocities(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write(py, a, Input::AngularVelocity, "set_angular_velocities")
    }

    /// Sets every motor's target in every world: array (count, motors).
    fn set_motor_targets(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        let motors = self.initial.motor_count();
        let shape = [self.sims.len(), motors];
        let values = input(a, &shape, "set_motor_targets", "(count, motors)")?;
        let sims = &mut self.sims;
        let result = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(values.par_chunks(motors.max(1)))
                .try_for_each(|(sim, targets)| sim.set_motor_targets(targets))
        });
        result.map_err(|error| PyValueError::new_err(format!("set_motor_targets: {error}")))
    }

    fn __repr__(&self) -> String {
        format!(
            "Batch(count={}, bodies={}, timestep={})",
            self.sims.len(),
            self.initial.body_count(),
            self.initial.timestep()
        )
    }
}

impl Batch {
    /// One per-body quantity of every world, (count, bodies, width).
    fn read<'py>(
        &self,
        py: Python<'py>,
        quantity: Quantity,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let bodies = self.initial.body_count();
        let per_world = bodies * quantity.width();
        let mut values = vec![0.0; self.sims.len() * per_world];
        let sims = &self.sims;
        py.allow_threads(|| {
            values
                .par_chunks_mut(per_world.max(1))
                .zip(sims.par_iter())
                .for_each(|(out, sim)| sim.read(quantity, out));
        });
        output(py, values, &[self.sims.len(), bodies, quantity.width()])
    }

    /// One per-body input to every world, from (count, bodies, 3).
    fn write(
        &mut self,
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        what: Input,
        name: &str,
    ) -> PyResult<()> {
        let bodies = self.initial.body_count();
        let shape = [self.sims.len(), bodies, 3];
        let values = input(a, &shape, name, "(count, bodies, 3)")?;
        let sims = &mut self.sims;
        let result = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(values.par_chunks((bodies * 3).max(1)))
                .try_for_each(|(sim, chunk)| sim.write(what, chunk))
        });
        result.map_err(|error| PyValueError::new_err(format!("{name}: {error}")))
    }
}
