//! Driving bodies and per-environment parameters: forces and torques held through the next
//! `step(n)`, and the masses, frictions, restitutions, gravity and position-motor gains that
//! each world of a batch may have of its own (domain randomisation).

use numpy::PyArrayDyn;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;
use rebond::limits::{MAX_COORDINATE, MAX_FORCE, MAX_GRAVITY, MAX_MASS, MIN_MASS};
use rebond::{BodyHandle, BodyType, Motor, Vec3, World as Engine};

use crate::arrays::{index_text, input, output};
use crate::batch::Batch;
use crate::sim::Sim;
use crate::world::World;

/// Forces and torques given by `apply_forces` and `apply_torques`, in body order: each acts,
/// unchanged in world axes at the body's centre of mass, on every step of the next `step(n)`,
/// which then drops them.
#[derive(Debug, Clone, Default)]
pub struct Loads {
    /// Force (N) and torque about the centre of mass (N·m) per body, world axes.
    per_body: Vec<(Vec3, Vec3)>,
    /// Whether any is held, so that steps without loads walk no bodies.
    held: bool,
}

impl Loads {
    /// Gives every dynamic body its held force and torque for the coming step.
    pub fn apply(&self, world: &mut Engine, bodies: &[BodyHandle]) -> Result<(), rebond::Error> {
        if !self.held {
            return Ok(());
        }
        for (&handle, &(force, torque)) in bodies.iter().zip(&self.per_body) {
            if force != Vec3::ZERO || torque != Vec3::ZERO {
                let body = world.body_mut(handle)?;
                body.apply_force(force)?;
                body.apply_torque(torque)?;
            }
        }
        Ok(())
    }

    /// Drops every held force and torque, at the end of a `step(n)`.
    pub fn clear(&mut self) {
        if self.held {
            self.per_body.fill((Vec3::ZERO, Vec3::ZERO));
            self.held = false;
        }
    }
}

/// A per-body parameter that `set_masses`, `set_frictions` and `set_restitutions` write.
#[derive(Debug, Clone, Copy)]
pub enum Parameter {
    /// kg, from 1e-6 to 1e9 on dynamic bodies; static and kinematic bodies ignore it.
    Mass,
    /// Coulomb friction coefficient, ≥ 0.
    Friction,
    /// Coefficient of restitution, 0 to 1.
    Restitution,
}

impl Parameter {
    /// Why `value` does not fit a body of `body_type`, or `None` when it does.
    fn refusal(self, value: f32, body_type: BodyType) -> Option<String> {
        match self {
            Self::Mass if body_type == BodyType::Dynamic => (!(MIN_MASS..=MAX_MASS)
                .contains(&value))
            .then(|| format!("must be from {MIN_MASS:e} to {MAX_MASS:e} kg, got {value}")),
            Self::Mass => None,
            Self::Friction => (value < 0.0).then(|| format!("must be at least 0, got {value}")),
            Self::Restitution => {
                (!(0.0..=1.0).contains(&value)).then(|| format!("must be from 0 to 1, got {value}"))
            }
        }
    }
}

/// Why a per-body input is refused: the body's index and what is wrong.
type Refusal = (usize, String);

/// Checked loads for one world, from [`Sim::with_forces`] or [`Sim::with_torques`], for
/// [`Sim::hold`].
pub struct Held(Vec<(Vec3, Vec3)>);

impl Sim {
    /// The held loads with `forces` (N, three numbers a body) added, at the centres of mass or
    /// at the world `points` (m), whose arm `r = point − c` gives the torque `r × F` held with
    /// it; or why not.
    pub fn with_forces(&self, forces: &[f32], points: Option<&[f32]>) -> Result<Held, Refusal> {
        let world = self.scene().world();
        let mut loads = self.held_loads();
        for (index, (&handle, force)) in
            self.bodies().iter().zip(forces.chunks_exact(3)).enumerate()
        {
            let force = Vec3::from_slice(force);
            let torque = match points {
                Some(points) => {
                    let point = Vec3::from_slice(&points[3 * index..3 * index + 3]);
                    if point.abs().max_element() > MAX_COORDINATE {
                        return Err((
                            index,
                            format!("point {point} is farther than {MAX_COORDINATE:e} m out"),
                        ));
                    }
                    let body = world
                        .body(handle)
                        .map_err(|error| (index, error.to_string()))?;
                    (point - body.center_of_mass()).cross(force)
                }
                None => Vec3::ZERO,
            };
            let (held_force, held_torque) = &mut loads[index];
            *held_force += force;
            *held_torque += torque;
            check_load(index, *held_force, "force", "N")?;
            check_load(index, *held_torque, "torque", "N·m")?;
        }
        Ok(Held(loads))
    }

    /// The held loads with `torques` (N·m, three numbers a body, world axes) added, or why not.
    pub fn with_torques(&self, torques: &[f32]) -> Result<Held, Refusal> {
        let mut loads = self.held_loads();
        for (index, torque) in torques.chunks_exact(3).enumerate() {
            let held_torque = &mut loads[index].1;
            *held_torque += Vec3::from_slice(torque);
            check_load(index, *held_torque, "torque", "N·m")?;
        }
        Ok(Held(loads))
    }

    /// The held loads, one per body.
    fn held_loads(&self) -> Vec<(Vec3, Vec3)> {
        let mut loads = self.loads().per_body.clone();
        loads.resize(self.body_count(), (Vec3::ZERO, Vec3::ZERO));
        loads
    }

    /// Holds `loads` for the next `step(n)`.
    pub fn hold(&mut self, Held(per_body): Held) {
        *self.loads_mut() = Loads {
            per_body,
            held: true,
        };
    }

    /// Checks one value a body of `parameter`, without changing anything.
    pub fn check_parameter(&self, parameter: Parameter, values: &[f32]) -> Result<(), Refusal> {
        let world = self.scene().world();
        for (index, (&handle, &value)) in self.bodies().iter().zip(values).enumerate() {
            let body = world
                .body(handle)
                .map_err(|error| (index, error.to_string()))?;
            if let Some(refusal) = parameter.refusal(value, body.body_type()) {
                return Err((index, refusal));
            }
        }
        Ok(())
    }

    /// Sets `parameter` of every body from `values`, already checked by `check_parameter`.
    pub fn set_parameter(
        &mut self,
        parameter: Parameter,
        values: &[f32],
    ) -> Result<(), rebond::Error> {
        let bodies = self.bodies().to_vec();
        let world = self.scene_mut().world_mut();
        for (&handle, &value) in bodies.iter().zip(values) {
            let body = world.body_mut(handle)?;
            match parameter {
                Parameter::Mass => body.set_mass(value)?,
                Parameter::Friction => body.set_friction(value)?,
                Parameter::Restitution => body.set_restitution(value)?,
            }
        }
        Ok(())
    }

    /// Writes `parameter` of every body into `out`: masses read 0 for static and kinematic
    /// bodies.
    pub fn read_parameter(&self, parameter: Parameter, out: &mut [f32]) {
        let world = self.scene().world();
        for (&handle, slot) in self.bodies().iter().zip(out) {
            *slot = world.body(handle).map_or(f32::NAN, |body| match parameter {
                Parameter::Mass => body.mass(),
                Parameter::Friction => body.friction(),
                Parameter::Restitution => body.restitution(),
            });
        }
    }

    /// The world's gravity, m/s².
    pub fn gravity(&self) -> Vec3 {
        self.scene().world().settings().gravity
    }

    /// Sets the world's gravity, m/s² (each component at most [`MAX_GRAVITY`] in magnitude);
    /// a change wakes every body.
    pub fn set_gravity(&mut self, gravity: Vec3) -> Result<(), rebond::Error> {
        let world = self.scene_mut().world_mut();
        let mut settings = *world.settings();
        settings.gravity = gravity;
        world.set_settings(settings)
    }

    /// Gives every position motor the `stiffness` and `damping` of its place (already checked
    /// from 0 to [`MAX_FORCE`]), keeping its target and force limit; other motors are left.
    pub fn set_motor_gains(
        &mut self,
        stiffness: &[f32],
        damping: &[f32],
    ) -> Result<(), rebond::Error> {
        let motors = self.motors().to_vec();
        let world = self.scene_mut().world_mut();
        for ((&handle, &stiffness), &damping) in motors.iter().zip(stiffness).zip(damping) {
            if let Some(Motor::Position {
                target_position,
                max_force,
                ..
            }) = world.joint(handle)?.desc().motor
            {
                let motor = Motor::position(target_position, stiffness, damping, max_force);
                world.set_joint_motor(handle, Some(motor))?;
            }
        }
        Ok(())
    }

    /// Writes every motor's stiffness and damping into `out`, two numbers a motor: zeros for
    /// velocity and torque motors.
    pub fn read_motor_gains(&self, out: &mut [f32]) {
        let world = self.scene().world();
        for (&handle, slot) in self.motors().iter().zip(out.chunks_exact_mut(2)) {
            let motor = world
                .joint(handle)
                .ok()
                .and_then(|joint| joint.desc().motor);
            let gains = match motor {
                Some(Motor::Position {
                    stiffness, damping, ..
                }) => [stiffness, damping],
                _ => [0.0, 0.0],
            };
            slot.copy_from_slice(&gains);
        }
    }
}

/// Refuses a held load past the engine's limit.
fn check_load(index: usize, load: Vec3, what: &str, unit: &str) -> Result<(), Refusal> {
    let length = load.length();
    if length <= MAX_FORCE {
        return Ok(());
    }
    Err((
        index,
        format!(
            "the {what} held on the body would be {length:e} {unit}, past the limit {MAX_FORCE:e}"
        ),
    ))
}

/// Refuses the first gain outside 0 to [`MAX_FORCE`], naming `name` and its element in an
/// array of `shape`.
fn check_gains(values: &[f32], shape: &[usize], name: &str) -> PyResult<()> {
    match values
        .iter()
        .position(|value| !(0.0..=MAX_FORCE).contains(value))
    {
        Some(index) => Err(PyValueError::new_err(format!(
            "{name}: element {} must be from 0 to {MAX_FORCE:e}, got {}",
            index_text(index, shape),
            values[index]
        ))),
        None => Ok(()),
    }
}

/// Refuses a gravity component past [`MAX_GRAVITY`], naming its element in an array of `shape`.
fn check_gravity(values: &[f32], shape: &[usize]) -> PyResult<()> {
    match values.iter().position(|value| value.abs() > MAX_GRAVITY) {
        Some(index) => Err(PyValueError::new_err(format!(
            "set_gravity: element {} must be from -{MAX_GRAVITY} to {MAX_GRAVITY} m/s², got {}",
            index_text(index, shape),
            values[index]
        ))),
        None => Ok(()),
    }
}

/// `name: element [w, b]: why` for a refusal in world `world` of a batch (`None` for a World).
fn refused(name: &str, world: Option<usize>, (body, why): Refusal) -> PyErr {
    let place = match world {
        Some(world) => format!("[{world}, {body}]"),
        None => format!("[{body}]"),
    };
    PyValueError::new_err(format!("{name}: element {place} {why}"))
}

/// An engine error on a value already checked, which should not happen, as a `ValueError`.
fn engine_error(name: &str) -> impl Fn(rebond::Error) -> PyErr + '_ {
    move |error| PyValueError::new_err(format!("{name}: {error}"))
}

#[pymethods]
impl World {
    /// Adds forces, N, world axes, array (bodies, 3), at each body's centre of mass or, with
    /// `points` (bodies, 3), at those world points (with the torque `r × F` about the centre of
    /// mass). They act on every step of the next `step(n)` call, then stop.
    #[pyo3(signature = (a, points = None))]
    fn apply_forces(
        &mut self,
        a: &Bound<'_, PyAny>,
        points: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let shape = [self.sim.body_count(), 3];
        let forces = input(a, &shape, "apply_forces", "(bodies, 3)")?;
        let points = points
            .map(|points| input(points, &shape, "points", "(bodies, 3)"))
            .transpose()?;
        let held = self
            .sim
            .with_forces(&forces, points.as_deref())
            .map_err(|refusal| refused("apply_forces", None, refusal))?;
        self.sim.hold(held);
        Ok(())
    }

    /// Adds torques, N·m, world axes, array (bodies, 3), acting on every step of the next
    /// `step(n)` call.
    fn apply_torques(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        let shape = [self.sim.body_count(), 3];
        let torques = input(a, &shape, "apply_torques", "(bodies, 3)")?;
        let held = self
            .sim
            .with_torques(&torques)
            .map_err(|refusal| refused("apply_torques", None, refusal))?;
        self.sim.hold(held);
        Ok(())
    }

    /// Body masses, kg: float32 array (bodies,); 0 for static and kinematic bodies.
    fn masses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_parameter(py, Parameter::Mass)
    }

    /// Body friction coefficients: float32 array (bodies,).
    fn frictions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_parameter(py, Parameter::Friction)
    }

    /// Body restitution coefficients: float32 array (bodies,).
    fn restitutions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_parameter(py, Parameter::Restitution)
    }

    /// Sets every dynamic body's mass, kg, array (bodies,): inertia scales with it,
    /// `I_new = (m_new / m_old) I_old`. Static and kinematic bodies ignore their entries.
    fn set_masses(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_parameter(a, Parameter::Mass, "set_masses")
    }

    /// Sets every body's friction coefficient (≥ 0), array (bodies,).
    fn set_frictions(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_parameter(a, Parameter::Friction, "set_frictions")
    }

    /// Sets every body's restitution (0 to 1), array (bodies,).
    fn set_restitutions(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_parameter(a, Parameter::Restitution, "set_restitutions")
    }

    /// The world's gravity, m/s²: float32 array (3,).
    fn gravity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        output(py, self.sim.gravity().to_array().to_vec(), &[3])
    }

    /// Sets the world's gravity, m/s², array (3,); wakes every body.
    fn set_gravity(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        let values = input(a, &[3], "set_gravity", "(3,)")?;
        check_gravity(&values, &[3])?;
        self.sim
            .set_gravity(Vec3::from_slice(&values))
            .map_err(engine_error("set_gravity"))
    }

    /// Stiffness and damping of every motor, `motor_names()` order: float32 array (motors, 2);
    /// zeros for velocity and torque motors.
    fn motor_gains<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let mut values = vec![0.0; self.sim.motor_count() * 2];
        self.sim.read_motor_gains(&mut values);
        output(py, values, &[self.sim.motor_count(), 2])
    }

    /// Sets the gains of every position motor, `motor_names()` order: `stiffness` (N·m/rad or
    /// N/m) and `damping` (N·m·s/rad or N·s/m), arrays (motors,), each from 0 to 1e12. Entries
    /// of velocity and torque motors are ignored.
    fn set_motor_gains(
        &mut self,
        stiffness: &Bound<'_, PyAny>,
        damping: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let shape = [self.sim.motor_count()];
        let stiffness = input(stiffness, &shape, "stiffness", "(motors,)")?;
        let damping = input(damping, &shape, "damping", "(motors,)")?;
        check_gains(&stiffness, &shape, "stiffness")?;
        check_gains(&damping, &shape, "damping")?;
        self.sim
            .set_motor_gains(&stiffness, &damping)
            .map_err(engine_error("set_motor_gains"))
    }
}

impl World {
    /// One per-body parameter as an array (bodies,).
    fn read_parameter<'py>(
        &self,
        py: Python<'py>,
        parameter: Parameter,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let mut values = vec![0.0; self.sim.body_count()];
        self.sim.read_parameter(parameter, &mut values);
        output(py, values, &[self.sim.body_count()])
    }

    /// One per-body parameter from an array (bodies,), all checked before any is set.
    fn write_parameter(
        &mut self,
        a: &Bound<'_, PyAny>,
        parameter: Parameter,
        name: &str,
    ) -> PyResult<()> {
        let values = input(a, &[self.sim.body_count()], name, "(bodies,)")?;
        self.sim
            .check_parameter(parameter, &values)
            .map_err(|refusal| refused(name, None, refusal))?;
        self.sim
            .set_parameter(parameter, &values)
            .map_err(engine_error(name))
    }
}

#[pymethods]
impl Batch {
    /// Adds forces, N, array (count, bodies, 3), at the centres of mass or at the world
    /// `points` (count, bodies, 3); they act on every step of the next `step(n)` call.
    #[pyo3(signature = (a, points = None))]
    fn apply_forces(
        &mut self,
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        points: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let bodies = self.initial.body_count();
        let shape = [self.sims.len(), bodies, 3];
        let forces = input(a, &shape, "apply_forces", "(count, bodies, 3)")?;
        let points = points
            .map(|points| input(points, &shape, "points", "(count, bodies, 3)"))
            .transpose()?;
        self.hold_in_every_world(py, "apply_forces", |index, sim| {
            let chunk = index * bodies * 3..(index + 1) * bodies * 3;
            let points = points.as_ref().map(|points| &points[chunk.clone()]);
            sim.with_forces(&forces[chunk], points)
        })
    }

    /// Adds torques, N·m, array (count, bodies, 3), acting on every step of the next `step(n)`.
    fn apply_torques(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        let bodies = self.initial.body_count();
        let shape = [self.sims.len(), bodies, 3];
        let torques = input(a, &shape, "apply_torques", "(count, bodies, 3)")?;
        self.hold_in_every_world(py, "apply_torques", |index, sim| {
            sim.with_torques(&torques[index * bodies * 3..(index + 1) * bodies * 3])
        })
    }

    /// Body masses in every world, kg: float32 array (count, bodies).
    fn masses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_parameter(py, Parameter::Mass)
    }

    /// Body friction coefficients in every world: float32 array (count, bodies).
    fn frictions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_parameter(py, Parameter::Friction)
    }

    /// Body restitutions in every world: float32 array (count, bodies).
    fn restitutions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_parameter(py, Parameter::Restitution)
    }

    /// Sets the masses of every world's dynamic bodies, kg, array (count, bodies).
    fn set_masses(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_parameter(py, a, Parameter::Mass, "set_masses")
    }

    /// Sets every world's body frictions, array (count, bodies).
    fn set_frictions(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_parameter(py, a, Parameter::Friction, "set_frictions")
    }

    /// Sets every world's body restitutions, array (count, bodies).
    fn set_restitutions(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_parameter(py, a, Parameter::Restitution, "set_restitutions")
    }

    /// Every world's gravity, m/s²: float32 array (count, 3).
    fn gravity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let values = self
            .sims
            .iter()
            .flat_map(|sim| sim.gravity().to_array())
            .collect();
        output(py, values, &[self.sims.len(), 3])
    }

    /// Sets every world's gravity, m/s², array (count, 3).
    fn set_gravity(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        let shape = [self.sims.len(), 3];
        let values = input(a, &shape, "set_gravity", "(count, 3)")?;
        check_gravity(&values, &shape)?;
        for (sim, gravity) in self.sims.iter_mut().zip(values.chunks_exact(3)) {
            sim.set_gravity(Vec3::from_slice(gravity))
                .map_err(engine_error("set_gravity"))?;
        }
        Ok(())
    }

    /// Stiffness and damping of every motor of every world: float32 array (count, motors, 2).
    fn motor_gains<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let motors = self.initial.motor_count();
        let mut values = vec![0.0; self.sims.len() * motors * 2];
        for (sim, out) in self.sims.iter().zip(values.chunks_mut((motors * 2).max(1))) {
            sim.read_motor_gains(out);
        }
        output(py, values, &[self.sims.len(), motors, 2])
    }

    /// Sets the gains of every world's position motors: `stiffness` and `damping`, arrays
    /// (count, motors).
    fn set_motor_gains(
        &mut self,
        stiffness: &Bound<'_, PyAny>,
        damping: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let motors = self.initial.motor_count();
        let shape = [self.sims.len(), motors];
        let stiffness = input(stiffness, &shape, "stiffness", "(count, motors)")?;
        let damping = input(damping, &shape, "damping", "(count, motors)")?;
        check_gains(&stiffness, &shape, "stiffness")?;
        check_gains(&damping, &shape, "damping")?;
        for (index, sim) in self.sims.iter_mut().enumerate() {
            let place = index * motors..(index + 1) * motors;
            sim.set_motor_gains(&stiffness[place.clone()], &damping[place])
                .map_err(engine_error("set_motor_gains"))?;
        }
        Ok(())
    }
}

impl Batch {
    /// Holds in every world the loads `loads(index, sim)` gives, all or none: on a refusal no
    /// world changes.
    fn hold_in_every_world(
        &mut self,
        py: Python<'_>,
        name: &str,
        loads: impl Fn(usize, &Sim) -> Result<Held, Refusal> + Sync,
    ) -> PyResult<()> {
        let sims = &self.sims;
        let held: Result<Vec<Held>, (usize, Refusal)> = py.allow_threads(|| {
            sims.par_iter()
                .enumerate()
                .map(|(index, sim)| loads(index, sim).map_err(|refusal| (index, refusal)))
                .collect()
        });
        let held = held.map_err(|(world, refusal)| refused(name, Some(world), refusal))?;
        for (sim, held) in self.sims.iter_mut().zip(held) {
            sim.hold(held);
        }
        Ok(())
    }

    /// One per-body parameter of every world, (count, bodies).
    fn read_parameter<'py>(
        &self,
        py: Python<'py>,
        parameter: Parameter,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let bodies = self.initial.body_count();
        let mut values = vec![0.0; self.sims.len() * bodies];
        for (sim, out) in self.sims.iter().zip(values.chunks_mut(bodies.max(1))) {
            sim.read_parameter(parameter, out);
        }
        output(py, values, &[self.sims.len(), bodies])
    }

    /// One per-body parameter of every world from (count, bodies), all checked before any is
    /// set.
    fn write_parameter(
        &mut self,
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        parameter: Parameter,
        name: &str,
    ) -> PyResult<()> {
        let bodies = self.initial.body_count();
        let values = input(a, &[self.sims.len(), bodies], name, "(count, bodies)")?;
        let width = bodies.max(1);
        for (index, (sim, chunk)) in self.sims.iter().zip(values.chunks(width)).enumerate() {
            sim.check_parameter(parameter, chunk)
                .map_err(|refusal| refused(name, Some(index), refusal))?;
        }
        let sims = &mut self.sims;
        let result = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(values.par_chunks(width))
                .try_for_each(|(sim, chunk)| sim.set_parameter(parameter, chunk))
        });
        result.map_err(engine_error(name))
    }
}
