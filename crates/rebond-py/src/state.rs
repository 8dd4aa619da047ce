//! Setting any state from Python: body poses (teleports), joint coordinates read and set in
//! `joint_names()` order, and `Batch.reset` with new states.

use numpy::PyArrayDyn;
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use rayon::prelude::*;
use rebond::internals::math::normalize_rotation;
use rebond::limits::MAX_COORDINATE;
use rebond::{JointHandle, JointType, Quat, Vec3};

use crate::arrays::{input, input_where, output};
use crate::batch::Batch;
use crate::sim::{Input, Sim};
use crate::world::World;

/// A body pose part that the teleports set.
#[derive(Debug, Clone, Copy)]
pub enum Placement {
    /// Body origin, m: three numbers a body.
    Position,
    /// Rotation quaternion x, y, z, w (normalised): four numbers a body.
    Rotation,
}

impl Placement {
    /// Numbers per body.
    fn width(self) -> usize {
        match self {
            Self::Position => 3,
            Self::Rotation => 4,
        }
    }

    /// What the axes of a world's array are, for errors.
    fn meaning(self) -> &'static str {
        match self {
            Self::Position => "(bodies, 3)",
            Self::Rotation => "(bodies, 4)",
        }
    }
}

/// A joint coordinate: its position (`joint_position`) or its rate (`joint_velocity`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coordinate {
    /// Angle (rad, counted across turns) or slide or length (m).
    Position,
    /// Its rate, rad/s or m/s.
    Velocity,
}

/// The states `Batch.reset` may set, each an array with a leading axis of `len(indices)`.
#[derive(Default)]
struct States {
    positions: Option<Vec<f32>>,
    rotations: Option<Vec<f32>>,
    linear_velocities: Option<Vec<f32>>,
    angular_velocities: Option<Vec<f32>>,
    joint_positions: Option<Vec<f32>>,
    joint_velocities: Option<Vec<f32>>,
}

impl Sim {
    /// Joint handles in scene order.
    fn joint_list(&self) -> Vec<JointHandle> {
        self.scene()
            .joint_handles()
            .map(|(_, handle)| handle)
            .collect()
    }

    /// Number of joints, removed ones included.
    pub fn joint_count(&self) -> usize {
        self.scene().joint_handles().count()
    }

    /// Whether each joint (scene order) has a coordinate: revolute, prismatic and distance
    /// joints do; fixed, ball and removed joints do not (they read NaN).
    fn coordinate_joints(&self) -> Vec<bool> {
        let world = self.scene().world();
        self.scene()
            .joint_handles()
            .map(|(_, handle)| {
                world.joint(handle).is_ok_and(|joint| {
                    matches!(
                        joint.joint_type(),
                        JointType::Revolute | JointType::Prismatic | JointType::Distance
                    )
                })
            })
            .collect()
    }

    /// Writes every joint's coordinate into `out` (scene order); NaN for a joint without one.
    pub fn read_joints(&self, coordinate: Coordinate, out: &mut [f32]) {
        let world = self.scene().world();
        for ((_, handle), slot) in self.scene().joint_handles().zip(out) {
            let value = match coordinate {
                Coordinate::Position => world.joint_position(handle),
                Coordinate::Velocity => world.joint_velocity(handle),
            };
            *slot = value.unwrap_or(f32::NAN);
        }
    }

    /// Sets every joint's coordinate from `values` (scene order, checked: NaN exactly at the
    /// joints without a coordinate). An error names the element of `values`.
    fn write_joints(&mut self, coordinate: Coordinate, values: &[f32]) -> Result<(), String> {
        let handles = self.joint_list();
        let mut entries = Vec::with_capacity(handles.len());
        let mut places = Vec::with_capacity(handles.len());
        for (index, (&handle, &value)) in handles.iter().zip(values).enumerate() {
            if !value.is_nan() {
                entries.push((handle, value));
                places.push(index);
            }
        }
        let world = self.scene_mut().world_mut();
        let result = match coordinate {
            Coordinate::Position => world.set_joint_positions(&entries),
            Coordinate::Velocity => world.set_joint_velocities(&entries),
        };
        result.map_err(|error| {
            let entry = error
                .field
                .split_once('[')
                .and_then(|(_, rest)| rest.trim_end_matches(']').parse::<usize>().ok())
                .and_then(|entry| places.get(entry));
            match entry {
                Some(index) => format!("element [{index}] {}", error.kind),
                None => error.kind.to_string(),
            }
        })
    }

    /// Teleports every body to `values` (`placement.width()` numbers a body, checked by
    /// [`check_placements`]); the bodies wake.
    fn write_placements(
        &mut self,
        placement: Placement,
        values: &[f32],
    ) -> Result<(), rebond::Error> {
        let handles: Vec<_> = self.scene().body_handles().map(|(_, h)| h).collect();
        let world = self.scene_mut().world_mut();
        for (&handle, value) in handles.iter().zip(values.chunks_exact(placement.width())) {
            let body = world.body_mut(handle)?;
            match placement {
                Placement::Position => {
                    body.set_position(Vec3::new(value[0], value[1], value[2]))?
                }
                Placement::Rotation => {
                    body.set_rotation(Quat::from_xyzw(value[0], value[1], value[2], value[3]))?;
                }
            }
        }
        Ok(())
    }
}

/// Checks teleport values (already finite, `shape` the whole array's): positions within
/// ±[`MAX_COORDINATE`] m, rotations of non-zero length; the error names the element.
fn check_placements(
    placement: Placement,
    values: &[f32],
    shape: &[usize],
    name: &str,
) -> PyResult<()> {
    let width = placement.width();
    for (index, value) in values.chunks_exact(width).enumerate() {
        let place = element(index * width, shape, true);
        match placement {
            Placement::Position => {
                if let Some(&far) = value.iter().find(|v| v.abs() > MAX_COORDINATE) {
                    return Err(PyValueError::new_err(format!(
                        "{name}: element {place} must lie between {} and {MAX_COORDINATE} m, \
                         got {far}",
                        -MAX_COORDINATE
                    )));
                }
            }
            Placement::Rotation => {
                let rotation = Quat::from_xyzw(value[0], value[1], value[2], value[3]);
                if normalize_rotation("", rotation).is_err() {
                    return Err(PyValueError::new_err(format!(
                        "{name}: element {place} is a zero quaternion {value:?}: a rotation \
                         needs a length"
                    )));
                }
            }
        }
    }
    Ok(())
}

/// `[w, b]` (or `[b]`): the element of an array of `shape` at the flat `index`, without its
/// last axis when `per_row`.
fn element(index: usize, shape: &[usize], per_row: bool) -> String {
    let axes = if per_row {
        &shape[..shape.len() - 1]
    } else {
        shape
    };
    let row = if per_row {
        index / shape[shape.len() - 1].max(1)
    } else {
        index
    };
    let mut parts = vec![0; axes.len()];
    let mut rest = row;
    for (part, &size) in parts.iter_mut().zip(axes).rev() {
        if size > 0 {
            *part = rest % size;
            rest /= size;
        }
    }
    let parts: Vec<String> = parts.iter().map(usize::to_string).collect();
    format!("[{}]", parts.join(", "))
}

/// Joint coordinates from `a` of `shape` (last axis the joints): finite at the joints with a
/// coordinate, NaN at the others (what `joint_positions()` reads there); the error names the
/// element and the joint.
fn joint_input(
    sim: &Sim,
    a: &Bound<'_, PyAny>,
    shape: &[usize],
    name: &str,
    meaning: &str,
) -> PyResult<Vec<f32>> {
    let has = sim.coordinate_joints();
    let joints = has.len().max(1);
    let values = input_where(a, shape, name, meaning, |index| has[index % joints])?;
    if let Some(index) =
        (0..values.len()).find(|&index| !has[index % joints] && !values[index].is_nan())
    {
        let joint = index % joints;
        let names = sim.joint_names();
        return Err(PyValueError::new_err(format!(
            "{name}: element {} is joint '{}', which has no coordinate (a fixed, ball or \
             removed joint): give NaN, as joint_positions() reads, got {}",
            element(index, shape, false),
            names[joint],
            values[index]
        )));
    }
    Ok(values)
}

#[pymethods]
impl World {
    /// Teleports every body's origin to an array (bodies, 3), m, keeping rotations and
    /// velocities; the bodies wake.
    fn set_positions(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_placements(a, Placement::Position, "set_positions")
    }

    /// Turns every body about its origin to the quaternions (x, y, z, w) of an array
    /// (bodies, 4), normalised; a zero quaternion is refused. The bodies wake.
    fn set_rotations(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_placements(a, Placement::Rotation, "set_rotations")
    }

    /// Every joint's position in `joint_names()` order: float32 array (joints,); rad (revolute,
    /// counted across turns), m (prismatic slide, distance length); NaN for fixed, ball and
    /// removed joints.
    fn joint_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_joints(py, Coordinate::Position)
    }

    /// Every joint's rate in `joint_names()` order: float32 array (joints,), rad/s or m/s;
    /// NaN for fixed, ball and removed joints.
    fn joint_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_joints(py, Coordinate::Velocity)
    }

    /// Places the bodies along each joint tree so that the joints read `a` (joints,): NaN
    /// exactly at the joints without a coordinate. The roots keep their poses; velocities are
    /// kept. See docs/python.md.
    fn set_joint_positions(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_joints(a, Coordinate::Position, "set_joint_positions")
    }

    /// Sets the bodies' velocities along each joint tree so that the joints' rates read `a`
    /// (joints,): NaN exactly at the joints without a coordinate. Poses are kept.
    fn set_joint_velocities(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_joints(a, Coordinate::Velocity, "set_joint_velocities")
    }
}

impl World {
    fn set_placements(
        &mut self,
        a: &Bound<'_, PyAny>,
        placement: Placement,
        name: &str,
    ) -> PyResult<()> {
        let shape = [self.sim.body_count(), placement.width()];
        let values = input(a, &shape, name, placement.meaning())?;
        check_placements(placement, &values, &shape, name)?;
        self.sim
            .write_placements(placement, &values)
            .map_err(|error| PyValueError::new_err(format!("{name}: {error}")))
    }

    fn read_joints<'py>(
        &self,
        py: Python<'py>,
        coordinate: Coordinate,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let mut values = vec![0.0; self.sim.joint_count()];
        self.sim.read_joints(coordinate, &mut values);
        output(py, values, &[self.sim.joint_count()])
    }

    fn write_joints(
        &mut self,
        a: &Bound<'_, PyAny>,
        coordinate: Coordinate,
        name: &str,
    ) -> PyResult<()> {
        let shape = [self.sim.joint_count()];
        let values = joint_input(&self.sim, a, &shape, name, "(joints,)")?;
        self.sim
            .write_joints(coordinate, &values)
            .map_err(|error| PyValueError::new_err(format!("{name}: {error}")))
    }
}

#[pymethods]
impl Batch {
    /// Teleports every body's origin in every world: array (count, bodies, 3), m.
    fn set_positions(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_placements(py, a, Placement::Position, "set_positions")
    }

    /// Turns every body in every world to the quaternions (x, y, z, w) of an array
    /// (count, bodies, 4), normalised.
    fn set_rotations(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.set_placements(py, a, Placement::Rotation, "set_rotations")
    }

    /// Every world's joint positions: float32 array (count, joints), NaN where a joint has no
    /// coordinate.
    fn joint_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_joints(py, Coordinate::Position)
    }

    /// Every world's joint rates: float32 array (count, joints).
    fn joint_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read_joints(py, Coordinate::Velocity)
    }

    /// Sets every world's joint positions from an array (count, joints).
    fn set_joint_positions(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_joints(py, a, Coordinate::Position, "set_joint_positions")
    }

    /// Sets every world's joint rates from an array (count, joints).
    fn set_joint_velocities(&mut self, py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write_joints(py, a, Coordinate::Velocity, "set_joint_velocities")
    }

    /// Puts the worlds at `indices` (all when `None`) back in their starting state, then sets
    /// the states given, each an array with a leading axis of `len(indices)` (`count` when
    /// `None`): positions, rotations, joint positions, then linear and angular velocities and
    /// joint velocities, in that order. Every array is checked before any world changes.
    #[pyo3(signature = (
        indices = None,
        *,
        positions = None,
        rotations = None,
        linear_velocities = None,
        angular_velocities = None,
        joint_positions = None,
        joint_velocities = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn reset(
        &mut self,
        py: Python<'_>,
        indices: Option<&Bound<'_, PyAny>>,
        positions: Option<&Bound<'_, PyAny>>,
        rotations: Option<&Bound<'_, PyAny>>,
        linear_velocities: Option<&Bound<'_, PyAny>>,
        angular_velocities: Option<&Bound<'_, PyAny>>,
        joint_positions: Option<&Bound<'_, PyAny>>,
        joint_velocities: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let chosen = match indices {
            None => (0..self.sims.len()).collect(),
            Some(indices) => self.indices(indices)?,
        };
        let n = chosen.len();
        let bodies = self.initial.body_count();
        let joints = self.initial.joint_count();
        let body_input =
            |a: Option<&Bound<'_, PyAny>>, name: &str, placement: Option<Placement>| {
                let width = placement.map_or(3, Placement::width);
                let shape = [n, bodies, width];
                let meaning = if width == 3 {
                    "(len(indices), bodies, 3)"
                } else {
                    "(len(indices), bodies, 4)"
                };
                a.map(|a| {
                    let values = input(a, &shape, name, meaning)?;
                    if let Some(placement) = placement {
                        check_placements(placement, &values, &shape, name)?;
                    }
                    Ok::<_, PyErr>(values)
                })
                .transpose()
            };
        let joint_shape = [n, joints];
        let meaning = "(len(indices), joints)";
        let states = States {
            positions: body_input(positions, "positions", Some(Placement::Position))?,
            rotations: body_input(rotations, "rotations", Some(Placement::Rotation))?,
            linear_velocities: body_input(linear_velocities, "linear_velocities", None)?,
            angular_velocities: body_input(angular_velocities, "angular_velocities", None)?,
            joint_positions: joint_positions
                .map(|a| joint_input(&self.initial, a, &joint_shape, "joint_positions", meaning))
                .transpose()?,
            joint_velocities: joint_velocities
                .map(|a| joint_input(&self.initial, a, &joint_shape, "joint_velocities", meaning))
                .transpose()?,
        };
        if states.is_empty() {
            // Back to the start only: reusing each world's storage.
            for index in chosen {
                self.sims[index].clone_from(&self.initial);
            }
            return Ok(());
        }
        let initial = &self.initial;
        let fresh: Vec<Result<Sim, String>> = py.allow_threads(|| {
            (0..n)
                .into_par_iter()
                .map(|row| {
                    let mut sim = initial.clone();
                    states.apply(&mut sim, row, bodies, joints)?;
                    Ok(sim)
                })
                .collect()
        });
        let mut built = Vec::with_capacity(n);
        for (row, sim) in fresh.into_iter().enumerate() {
            built.push(sim.map_err(|message| {
                PyValueError::new_err(format!("reset: indices[{row}]: {message}"))
            })?);
        }
        for (index, sim) in chosen.into_iter().zip(built) {
            self.sims[index] = sim;
        }
        Ok(())
    }
}

impl States {
    /// Whether no state is given.
    fn is_empty(&self) -> bool {
        [
            &self.positions,
            &self.rotations,
            &self.linear_velocities,
            &self.angular_velocities,
            &self.joint_positions,
            &self.joint_velocities,
        ]
        .iter()
        .all(|state| state.is_none())
    }

    /// Sets row `row` of every state given on `sim`, in the order `reset` documents.
    fn apply(&self, sim: &mut Sim, row: usize, bodies: usize, joints: usize) -> Result<(), String> {
        fn rows(values: &Option<Vec<f32>>, row: usize, width: usize) -> Option<&[f32]> {
            values
                .as_ref()
                .map(|values| &values[row * width..(row + 1) * width])
        }
        let engine = |name: &'static str| move |error: rebond::Error| format!("{name}: {error}");
        if let Some(values) = rows(&self.positions, row, bodies * 3) {
            sim.write_placements(Placement::Position, values)
                .map_err(engine("positions"))?;
        }
        if let Some(values) = rows(&self.rotations, row, bodies * 4) {
            sim.write_placements(Placement::Rotation, values)
                .map_err(engine("rotations"))?;
        }
        if let Some(values) = rows(&self.joint_positions, row, joints) {
            sim.write_joints(Coordinate::Position, values)
                .map_err(|error| format!("joint_positions: {error}"))?;
        }
        if let Some(values) = rows(&self.linear_velocities, row, bodies * 3) {
            sim.write(Input::LinearVelocity, values)
                .map_err(engine("linear_velocities"))?;
        }
        if let Some(values) = rows(&self.angular_velocities, row, bodies * 3) {
            sim.write(Input::AngularVelocity, values)
                .map_err(engine("angular_velocities"))?;
        }
        if let Some(values) = rows(&self.joint_velocities, row, joints) {
            sim.write_joints(Coordinate::Velocity, values)
                .map_err(|error| format!("joint_velocities: {error}"))?;
        }
        Ok(())
    }
}

impl Batch {
    /// `indices` (one whole number or an iterable of them) checked against the batch.
    fn indices(&self, indices: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
        let indices: Vec<i64> = match indices.extract::<i64>() {
            Ok(single) => vec![single],
            Err(_) => indices
                .try_iter()?
                .map(|item| item.and_then(|item| item.extract::<i64>()))
                .collect::<PyResult<_>>()
                .map_err(|error| {
                    PyValueError::new_err(format!("indices: expected whole numbers: {error}"))
                })?,
        };
        let count = self.sims.len();
        indices
            .iter()
            .enumerate()
            .map(|(place, &index)| {
                usize::try_from(index)
                    .ok()
                    .filter(|&index| index < count)
                    .ok_or_else(|| {
                        PyIndexError::new_err(format!(
                            "indices[{place}]: {index} is not a world of this batch (0 to {})",
                            count - 1
                        ))
                    })
            })
            .collect()
    }

    fn set_placements(
        &mut self,
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        placement: Placement,
        name: &str,
    ) -> PyResult<()> {
        let width = placement.width();
        let bodies = self.initial.body_count();
        let shape = [self.sims.len(), bodies, width];
        let meaning = if width == 3 {
            "(count, bodies, 3)"
        } else {
            "(count, bodies, 4)"
        };
        let values = input(a, &shape, name, meaning)?;
        check_placements(placement, &values, &shape, name)?;
        let sims = &mut self.sims;
        let result = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(values.par_chunks((bodies * width).max(1)))
                .try_for_each(|(sim, chunk)| sim.write_placements(placement, chunk))
        });
        result.map_err(|error| PyValueError::new_err(format!("{name}: {error}")))
    }

    fn read_joints<'py>(
        &self,
        py: Python<'py>,
        coordinate: Coordinate,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let joints = self.initial.joint_count();
        let mut values = vec![0.0; self.sims.len() * joints];
        let sims = &self.sims;
        py.allow_threads(|| {
            values
                .par_chunks_mut(joints.max(1))
                .zip(sims.par_iter())
                .for_each(|(out, sim)| sim.read_joints(coordinate, out));
        });
        output(py, values, &[self.sims.len(), joints])
    }

    /// Sets every world's joint coordinates; a world the engine refuses (a body that would be
    /// placed out of range) is left unchanged and named, the others are set.
    fn write_joints(
        &mut self,
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        coordinate: Coordinate,
        name: &str,
    ) -> PyResult<()> {
        let joints = self.initial.joint_count();
        let shape = [self.sims.len(), joints];
        let values = joint_input(&self.initial, a, &shape, name, "(count, joints)")?;
        let sims = &mut self.sims;
        let results: Vec<Result<(), String>> = py.allow_threads(|| {
            sims.par_iter_mut()
                .zip(values.par_chunks(joints.max(1)))
                .map(|(sim, chunk)| sim.write_joints(coordinate, chunk))
                .collect()
        });
        for (index, result) in results.into_iter().enumerate() {
            if let Err(message) = result {
                return Err(PyValueError::new_err(format!(
                    "{name}: world {index}: {message}"
                )));
            }
        }
        Ok(())
    }
}
