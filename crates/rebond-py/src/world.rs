//! `rebond.World`: one world, its state as NumPy arrays.

use numpy::PyArrayDyn;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyInt, PyString};
use rebond::scene::Scene;
use rebond::{QueryFilter, Ray, Vec3};

use crate::arrays::{input, output};
use crate::dicts::dict_error;
use crate::errors::StepError;
use crate::json::{join, to_bytes, to_json};
use crate::robust::{step_in_rounds, StepCount};
use crate::sim::{Input, Quantity, Sim};

/// Loads a scene given as a path (`str` or `os.PathLike`) or a built-in scene's name, a dict
/// in the scene format, or a `World` (copied).
pub fn load_scene(scene: &Bound<'_, PyAny>) -> PyResult<Sim> {
    if let Ok(world) = scene.downcast::<World>() {
        return Ok(world.borrow().sim.clone());
    }
    if scene.downcast::<PyDict>().is_ok() {
        let bytes = to_bytes(&to_json(scene, "")?)?;
        let loaded = Scene::from_json(&bytes).map_err(|error| dict_error(&error))?;
        return Ok(Sim::new(loaded, None));
    }
    let Ok(path) = scene.extract::<std::path::PathBuf>() else {
        let type_name = scene.get_type().name()?;
        return Err(PyValueError::new_err(format!(
            "scene: expected a path, a dict in the scene format or a World, got a {type_name}"
        )));
    };
    crate::scenes::load_path(&path)
}

/// A body's place in the scene given as its index: the body's name, as the scene format wants.
fn body_reference(sim: &Sim, value: &Bound<'_, PyAny>, field: &str) -> PyResult<Option<String>> {
    // Python and NumPy whole numbers have `__index__`; `True` is not an index.
    let is_index = value.downcast::<PyInt>().is_ok() || value.hasattr("__index__")?;
    if !is_index || value.downcast::<PyString>().is_ok() || value.downcast::<PyBool>().is_ok() {
        return Ok(None);
    }
    let names = sim.body_names();
    let index: i64 = value.extract()?;
    usize::try_from(index)
        .ok()
        .and_then(|index| names.get(index).cloned())
        .map(Some)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "{field}: no body has index {index} ({} bodies)",
                names.len()
            ))
        })
}

/// A simulated world: bodies, joints, and the scene's timestep.
///
/// Built from a scene (`World.from_scene`) or empty (`World(gravity=..., timestep=...,
/// substeps=...)`) and filled with `add_body` and `add_joint`. Bodies and motors are numbered in
/// scene order, the order of every array.
#[pyclass(module = "rebond")]
#[derive(Clone)]
pub struct World {
    /// The world and its names.
    pub sim: Sim,
}

#[pymethods]
impl World {
    /// An empty world. `gravity` (m/s², default (0, -9.81, 0)), `timestep` (seconds per step,
    /// default 1/60) and `substeps` (default 8) are checked as a scene file's.
    #[new]
    #[pyo3(signature = (gravity = None, timestep = None, substeps = None))]
    fn new(
        gravity: Option<&Bound<'_, PyAny>>,
        timestep: Option<&Bound<'_, PyAny>>,
        substeps: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let mut object = serde_json::Map::new();
        object.insert("bodies".to_owned(), serde_json::Value::Array(Vec::new()));
        for (name, value) in [
            ("gravity", gravity),
            ("timestep", timestep),
            ("substeps", substeps),
        ] {
            if let Some(value) = value {
                object.insert(name.to_owned(), to_json(value, name)?);
            }
        }
        let bytes = to_bytes(&serde_json::Value::Object(object))?;
        let scene = Scene::from_json(&bytes).map_err(|error| dict_error(&error))?;
        Ok(Self {
            sim: Sim::new(scene, None),
        })
    }

    /// The world of a scene: a path to a scene file, the name of a built-in scene
    /// (`builtin_scenes()`; a path that exists wins), or a dict in the scene format.
    #[staticmethod]
    fn from_scene(scene: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(Self {
            sim: load_scene(scene)?,
        })
    }

    /// Adds a body: `shape` and the keyword fields of a scene body (`type`, `name`, `position`,
    /// `mass`, ...). Returns its index.
    #[pyo3(signature = (shape, **fields))]
    fn add_body(
        &mut self,
        shape: &Bound<'_, PyAny>,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<usize> {
        let place = format!("bodies[{}]", self.sim.body_count());
        let mut object = match fields {
            Some(fields) => match to_json(fields.as_any(), &place)? {
                serde_json::Value::Object(object) => object,
                _ => serde_json::Map::new(),
            },
            None => serde_json::Map::new(),
        };
        object.insert("shape".to_owned(), to_json(shape, &join(&place, "shape"))?);
        let bytes = to_bytes(&serde_json::Value::Object(object))?;
        let index = self
            .sim
            .scene_mut()
            .add_body_json(&bytes)
            .map_err(|error| dict_error(&error))?;
        self.sim.refresh();
        Ok(index)
    }

    /// Adds a joint: its `type` and the keyword fields of a scene joint (`body_b`, `body_a`,
    /// `anchor`, `axis`, `motor`, ...); bodies by name or index. Returns its index.
    #[pyo3(signature = (r#type, **fields))]
    fn add_joint(
        &mut self,
        r#type: &Bound<'_, PyAny>,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<usize> {
        let place = format!("joints[{}]", self.sim.joint_names().len());
        let mut object = match fields {
            Some(fields) => match to_json(fields.as_any(), &place)? {
                serde_json::Value::Object(object) => object,
                _ => serde_json::Map::new(),
            },
            None => serde_json::Map::new(),
        };
        if let Some(fields) = fields {
            for side in ["body_a", "body_b"] {
                if let Some(value) = fields.get_item(side)? {
                    let field = join(&place, side);
                    if let Some(name) = body_reference(&self.sim, &value, &field)? {
                        object.insert(side.to_owned(), serde_json::Value::String(name));
                    }
                }
            }
        }
        object.insert("type".to_owned(), to_json(r#type, &join(&place, "type"))?);
        let bytes = to_bytes(&serde_json::Value::Object(object))?;
        let index = self
            .sim
            .scene_mut()
            .add_joint_json(&bytes)
            .map_err(|error| dict_error(&error))?;
        self.sim.refresh();
        Ok(index)
    }

    /// Advances the world by `n` steps of its timestep, without the GIL. Ctrl-C stops it within
    /// about a tenth of a second with `KeyboardInterrupt`, after a whole number of steps.
    #[pyo3(signature = (n = StepCount(1)))]
    fn step(&mut self, py: Python<'_>, n: StepCount) -> PyResult<()> {
        let sim = &mut self.sim;
        sim.begin_call();
        let rounds = step_in_rounds(py, n.0, |steps| sim.step_round(steps));
        self.sim.end_call();
        rounds?.map_err(StepError::new_err)
    }

    /// A copy of this world, which steps on exactly as this one would.
    fn copy(&self) -> Self {
        self.clone()
    }

    /// The whole world as bytes (every body, joint, contact, warm-start impulse and sleep
    /// timer, its names and timestep, and the steps taken): `World.load` restores a world that
    /// steps on exactly as this one would. The format is the command line's `--save-state`.
    fn save<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.sim.save())
    }

    /// A world saved by `save` (or by the command line's `--save-state`), exactly by this build,
    /// from its portable snapshot (contacts cold) by another; bytes that are not such a state
    /// raise `StateError` saying why.
    #[staticmethod]
    fn load(data: &[u8]) -> PyResult<Self> {
        let (scene, steps) = Scene::load_state(data)
            .map_err(|error| crate::errors::StateError::new_err(error.to_string()))?;
        Ok(Self {
            sim: Sim::restored(scene, steps),
        })
    }

    /// Seconds per step.
    #[getter]
    fn timestep(&self) -> f64 {
        self.sim.timestep()
    }

    /// Number of bodies.
    #[getter]
    fn body_count(&self) -> usize {
        self.sim.body_count()
    }

    fn __len__(&self) -> usize {
        self.sim.body_count()
    }

    /// Body names in scene order.
    fn body_names(&self) -> Vec<String> {
        self.sim.body_names()
    }

    /// Joint names in scene order.
    fn joint_names(&self) -> Vec<String> {
        self.sim.joint_names()
    }

    /// Names of the joints with a motor, in the order of `set_motor_targets`.
    fn motor_names(&self) -> Vec<String> {
        self.sim.motor_names()
    }

    /// Body origins, m: float32 array (bodies, 3).
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::Position)
    }

    /// Rotations as quaternions (x, y, z, w): float32 array (bodies, 4).
    fn rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::Rotation)
    }

    /// Velocities of the centres of mass, m/s: float32 array (bodies, 3).
    fn linear_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::LinearVelocity)
    }

    /// Angular velocities, rad/s: float32 array (bodies, 3).
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::AngularVelocity)
    }

    /// Centres of mass, m: float32 array (bodies, 3).
    fn centers_of_mass<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::CenterOfMass)
    }

    /// Inertia tensors about the centres of mass in world axes, kg·m², `R I Rᵀ` as xx, yy, zz,
    /// xy, xz, yz: float32 array (bodies, 6); zeros for static and kinematic bodies.
    fn inertias<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.read(py, Quantity::Inertia)
    }

    /// Sets every body's linear velocity, m/s, from an array (bodies, 3).
    fn set_linear_velocities(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write(a, Input::LinearVelocity, "set_linear_velocities")
    }

    /// Sets every body's angular velocity, rad/s, from an array (bodies, 3).
    fn set_angular_velocities(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write(a, Input::AngularVelocity, "set_angular_velocities")
    }

    /// Sets the target of every joint with a motor (`motor_names()` order): a velocity (rad/s,
    /// m/s) for velocity motors, a position (rad, m) for position motors. Array (motors,).
    fn set_motor_targets(&mut self, a: &Bound<'_, PyAny>) -> PyResult<()> {
        let shape = [self.sim.motor_count()];
        let values = input(a, &shape, "set_motor_targets", "(motors,)")?;
        self.sim
            .set_motor_targets(&values)
            .map_err(|error| PyValueError::new_err(format!("set_motor_targets: {error}")))
    }

    /// The nearest body hit by the ray from `origin` along `direction` within `max_distance`
    /// metres, or `None`.
    #[pyo3(signature = (origin, direction, max_distance = f32::INFINITY))]
    fn ray_cast(
        &self,
        origin: [f32; 3],
        direction: [f32; 3],
        max_distance: f32,
    ) -> PyResult<Option<RayHit>> {
        let ray = Ray::new(Vec3::from_array(origin), Vec3::from_array(direction))
            .max_distance(max_distance);
        let hit = self
            .sim
            .scene()
            .world()
            .cast_ray(&ray, &QueryFilter::new())
            .map_err(|error| PyValueError::new_err(format!("ray_cast: {error}")))?;
        let Some(hit) = hit else {
            return Ok(None);
        };
        let Some(body) = self.sim.body_index(hit.body) else {
            return Ok(None);
        };
        let name = self.sim.body_names().swap_remove(body);
        Ok(Some(RayHit {
            body,
            name,
            point: hit.point.to_array(),
            normal: hit.normal.to_array(),
            distance: hit.distance,
        }))
    }

    fn __repr__(&self) -> String {
        format!(
            "World(bodies={}, joints={}, timestep={})",
            self.sim.body_count(),
            self.sim.joint_names().len(),
            self.sim.timestep()
        )
    }
}

impl World {
    /// One per-body quantity as an array (bodies, width).
    fn read<'py>(
        &self,
        py: Python<'py>,
        quantity: Quantity,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let width = quantity.width();
        let mut values = vec![0.0; self.sim.body_count() * width];
        self.sim.read(quantity, &mut values);
        output(py, values, &[self.sim.body_count(), width])
    }

    /// One per-body input from an array (bodies, 3).
    fn write(&mut self, a: &Bound<'_, PyAny>, what: Input, name: &str) -> PyResult<()> {
        let values = input(a, &[self.sim.body_count(), 3], name, "(bodies, 3)")?;
        self.sim
            .write(what, &values)
            .map_err(|error| PyValueError::new_err(format!("{name}: {error}")))
    }
}

/// Where a ray met a body.
#[pyclass(module = "rebond", frozen, get_all)]
#[derive(Debug, Clone)]
pub struct RayHit {
    /// The body's index in scene order.
    pub body: usize,
    /// The body's name.
    pub name: String,
    /// The point hit, world, m.
    pub point: [f32; 3],
    /// The unit normal there, facing the ray.
    pub normal: [f32; 3],
    /// Distance from the ray's origin, m.
    pub distance: f32,
}

#[pymethods]
impl RayHit {
    fn __repr__(&self) -> String {
        format!(
            "RayHit(body={}, name={:?}, point={:?}, normal={:?}, distance={})",
            self.body, self.name, self.point, self.normal, self.distance
        )
    }
}
