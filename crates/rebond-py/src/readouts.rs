//! Readouts: contact forces on bodies, joint reaction forces and torques, the contact and sensor
//! events of the last `step(n)`, and batched ray casts for range sensors.

use numpy::{PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;
use rebond::{
    BodyHandle, ContactEventKind, QueryFilter, Ray, SensorEventKind, Vec3, World as Engine,
};

use crate::arrays::{input, output};
use crate::batch::Batch;
use crate::sim::Sim;
use crate::world::World;

/// One event as Python sees it: its kind and two body indices.
pub type Event = (&'static str, usize, usize);

/// The contact and sensor events of every step of the last `step(n)`, in step order, with body
/// indices in scene order.
#[derive(Debug, Clone, Default)]
pub struct StepEvents {
    /// `("started" | "stopped", body a, body b)`.
    contacts: Vec<Event>,
    /// `("entered" | "exited", sensor body, body)`.
    sensors: Vec<Event>,
}

impl StepEvents {
    /// Forgets the events, at the start of a `step(n)`.
    pub fn clear(&mut self) {
        self.contacts.clear();
        self.sensors.clear();
    }

    /// Keeps the events of the step `world` just took; `index` gives a body's index in scene
    /// order, `None` for a body Python does not number.
    pub fn record(&mut self, world: &Engine, index: impl Fn(BodyHandle) -> Option<usize>) {
        for event in world.contact_events() {
            let kind = match event.kind {
                ContactEventKind::Started => "started",
                ContactEventKind::Stopped => "stopped",
            };
            if let (Some(a), Some(b)) = (index(event.body_a), index(event.body_b)) {
                self.contacts.push((kind, a, b));
            }
        }
        for event in world.sensor_events() {
            let kind = match event.kind {
                SensorEventKind::Entered => "entered",
                SensorEventKind::Exited => "exited",
            };
            if let (Some(sensor), Some(body)) = (index(event.sensor), index(event.body)) {
                self.sensors.push((kind, sensor, body));
            }
        }
    }
}

/// Where each of a world's rays stopped: distance (m, infinity for a miss), body index (-1 for
/// a miss) and unit normal (zeros for a miss).
struct RayOut<'a> {
    distances: &'a mut [f32],
    bodies: &'a mut [i64],
    normals: &'a mut [f32],
}

impl Sim {
    /// Writes the contact force on every body over the last step into `out`, N, world axes,
    /// three numbers a body: `Σ (Σᵢ λᵢ n + λ_t) / h` over the body's contacts, with `λᵢ` the
    /// normal impulses and `λ_t` the friction impulse of the step's last substep, `n` the
    /// contact normal (from A to B: the sum counts for B, its opposite for A) and
    /// `h = dt / substeps`. Contacts of sleeping bodies keep the impulses they slept with.
    pub fn contact_forces(&self, out: &mut [f32]) {
        let world = self.scene().world();
        let substep = self.scene().timestep().engine_seconds / world.settings().substeps as f32;
        let slots = self.bodies().iter().map(BodyHandle::slot);
        let mut index_of_slot = vec![usize::MAX; slots.max().map_or(0, |slot| slot + 1)];
        for (index, handle) in self.bodies().iter().enumerate() {
            index_of_slot[handle.slot()] = index;
        }
        let mut forces = vec![Vec3::ZERO; self.body_count()];
        for contact in world.contacts().iter().chain(world.sleeping_contacts()) {
            let normal_impulse: f32 = contact.normal_impulses().iter().sum();
            let force = (contact.normal() * normal_impulse + contact.friction_impulse()) / substep;
            let (a, b) = contact.bodies();
            if let Some(&index) = index_of_slot.get(a.slot()) {
                if let Some(on_a) = forces.get_mut(index) {
                    *on_a -= force;
                }
            }
            if let Some(&index) = index_of_slot.get(b.slot()) {
                if let Some(on_b) = forces.get_mut(index) {
                    *on_b += force;
                }
            }
        }
        for (slot, force) in out.chunks_exact_mut(3).zip(forces) {
            slot.copy_from_slice(&force.to_array());
        }
    }

    /// Writes every joint's mean force (N) and torque (N·m) on its `body_b` over the last step,
    /// world axes, three numbers a joint each, joints in scene order; zeros once broken.
    pub fn joint_loads(&self, forces: &mut [f32], torques: &mut [f32]) {
        let world = self.scene().world();
        let joints = self.scene().joint_handles();
        for ((_, handle), (force, torque)) in
            joints.zip(forces.chunks_exact_mut(3).zip(torques.chunks_exact_mut(3)))
        {
            let (joint_force, joint_torque) =
                world.joint(handle).map_or((Vec3::NAN, Vec3::NAN), |joint| {
                    (joint.force(), joint.torque())
                });
            force.copy_from_slice(&joint_force.to_array());
            torque.copy_from_slice(&joint_torque.to_array());
        }
    }

    /// Casts one ray a row of `origins` and `directions` (m, three numbers a ray; a direction
    /// need not be unit) up to `max_distance` metres; the error names the ray.
    fn ray_casts(
        &self,
        origins: &[f32],
        directions: &[f32],
        max_distance: f32,
        out: RayOut<'_>,
    ) -> Result<(), (usize, String)> {
        let world = self.scene().world();
        let filter = QueryFilter::new();
        let rows = origins.chunks_exact(3).zip(directions.chunks_exact(3));
        let outs = out
            .distances
            .iter_mut()
            .zip(out.bodies.iter_mut())
            .zip(out.normals.chunks_exact_mut(3));
        for (index, ((origin, direction), ((distance, body), normal))) in rows.zip(outs).enumerate()
        {
            let ray = Ray::new(Vec3::from_slice(origin), Vec3::from_slice(direction))
                .max_distance(max_distance);
            let hit = world
                .cast_ray(&ray, &filter)
                .map_err(|error| (index, error.to_string()))?;
            let found = hit.and_then(|hit| Some((hit, self.body_index(hit.body)?)));
            match found {
                Some((hit, index)) => {
                    *distance = hit.distance;
                    *body = index as i64;
                    normal.copy_from_slice(&hit.normal.to_array());
                }
                None => {
                    *distance = f32::INFINITY;
                    *body = -1;
                    normal.fill(0.0);
                }
            }
        }
        Ok(())
    }
}

/// `(rays, 3)` rows of `value`, named `name`, with `leading` axes before them (a batch's count).
fn rays_input(value: &Bound<'_, PyAny>, leading: &[usize], name: &str) -> PyResult<Vec<f32>> {
    let numpy = value.py().import("numpy")?;
    let shape: Vec<usize> = numpy.call_method1("shape", (value,))?.extract()?;
    let rays = shape.get(leading.len()).copied().unwrap_or(0);
    let mut expected = leading.to_vec();
    expected.extend([rays, 3]);
    let meaning = if leading.is_empty() {
        "(rays, 3)"
    } else {
        "(count, rays, 3)"
    };
    input(value, &expected, name, meaning)
}

/// `max_distance`, which must be positive (infinity allowed).
fn checked_max_distance(max_distance: f32) -> PyResult<f32> {
    if max_distance > 0.0 {
        Ok(max_distance)
    } else {
        Err(PyValueError::new_err(format!(
            "max_distance: must be positive, got {max_distance}"
        )))
    }
}

/// Distances, body indices and normals of `count` worlds' casts of `rays` rays each.
struct RayArrays {
    distances: Vec<f32>,
    bodies: Vec<i64>,
    normals: Vec<f32>,
}

impl RayArrays {
    /// Casts every world's rays, `origins` and `directions` of shape `leading` + (rays, 3)
    /// (no leading axis for a World, the count for a Batch), in parallel without the GIL: the
    /// arrays of distances, body indices and normals. An error names the ray (`ray [5]`, or
    /// `ray [2, 5]` in a batch).
    fn cast<'py>(
        py: Python<'py>,
        sims: &[Sim],
        origins: &Bound<'_, PyAny>,
        directions: &Bound<'_, PyAny>,
        max_distance: f32,
        leading: &[usize],
    ) -> PyResult<RayHitArrays<'py>> {
        let max_distance = checked_max_distance(max_distance)?;
        let origins = rays_input(origins, leading, "origins")?;
        let directions = rays_input(directions, leading, "directions")?;
        let worlds = sims.len().max(1);
        let per_world = origins.len() / 3 / worlds;
        if origins.len() != directions.len() {
            return Err(PyValueError::new_err(format!(
                "directions: got {} rays, origins has {per_world}",
                directions.len() / 3 / worlds
            )));
        }
        let rays = sims.len() * per_world;
        let mut arrays = Self {
            distances: vec![0.0; rays],
            bodies: vec![0; rays],
            normals: vec![0.0; rays * 3],
        };
        let width = per_world.max(1);
        let result = py.allow_threads(|| {
            arrays
                .distances
                .par_chunks_mut(width)
                .zip(arrays.bodies.par_chunks_mut(width))
                .zip(arrays.normals.par_chunks_mut(width * 3))
                .zip(sims.par_iter())
                .enumerate()
                .try_for_each(|(index, (((distances, bodies), normals), sim))| {
                    let rows = index * per_world * 3..(index + 1) * per_world * 3;
                    let out = RayOut {
                        distances,
                        bodies,
                        normals,
                    };
                    sim.ray_casts(&origins[rows.clone()], &directions[rows], max_distance, out)
                        .map_err(|(ray, why)| (index, ray, why))
                })
        });
        result.map_err(|(world, ray, why)| {
            let place = if leading.is_empty() {
                format!("[{ray}]")
            } else {
                format!("[{world}, {ray}]")
            };
            PyValueError::new_err(format!("ray_casts: ray {place}: {why}"))
        })?;
        let mut shape = leading.to_vec();
        shape.push(per_world);
        let distances = output(py, arrays.distances, &shape)?;
        let bodies = PyArray1::from_vec(py, arrays.bodies).reshape(shape.clone())?;
        shape.push(3);
        let normals = output(py, arrays.normals, &shape)?;
        Ok((distances, bodies, normals))
    }
}

/// Distances (float32), body indices (int64) and normals (float32) of ray casts.
type RayHitArrays<'py> = (
    Bound<'py, PyArrayDyn<f32>>,
    Bound<'py, PyArrayDyn<i64>>,
    Bound<'py, PyArrayDyn<f32>>,
);

/// Joint forces (N) and torques (N·m), float32.
type JointLoadArrays<'py> = (Bound<'py, PyArrayDyn<f32>>, Bound<'py, PyArrayDyn<f32>>);

#[pymethods]
impl World {
    /// The contact force on each body over the last step, N, world axes: float32 array
    /// (bodies, 3), the contacts' normal and friction impulses on the body in the step's last
    /// substep over the substep's length. A box at rest on the ground reads `m g` up.
    fn contact_forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let mut values = vec![0.0; self.sim.body_count() * 3];
        self.sim.contact_forces(&mut values);
        output(py, values, &[self.sim.body_count(), 3])
    }

    /// The mean force each joint applied to its `body_b` over the last step, N, world axes:
    /// float32 array (joints, 3), `joint_names()` order; zeros once broken.
    fn joint_forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.joint_loads(py).map(|(forces, _)| forces)
    }

    /// The mean torque each joint applied to its `body_b` over the last step about its anchor
    /// there, N·m, world axes: float32 array (joints, 3), `joint_names()` order.
    fn joint_torques<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.joint_loads(py).map(|(_, torques)| torques)
    }

    /// The pairs of bodies that started or stopped touching during the last `step(n)` call, in
    /// step order: a list of `(kind, body_a, body_b)` with `kind` `"started"` or `"stopped"`
    /// and body indices (one per touching pair of colliders).
    fn contact_events(&self) -> Vec<Event> {
        self.sim.events().contacts.clone()
    }

    /// The bodies that entered or left a sensor during the last `step(n)` call, in step order:
    /// a list of `(kind, sensor, body)` with `kind` `"entered"` or `"exited"` and body indices.
    fn sensor_events(&self) -> Vec<Event> {
        self.sim.events().sensors.clone()
    }

    /// Casts rays from `origins` along `directions` (float arrays (rays, 3), m; directions
    /// need not be unit) up to `max_distance` m: the distance to the nearest body each meets,
    /// float32 array (rays,), infinity for a miss.
    #[pyo3(signature = (origins, directions, max_distance = f32::INFINITY))]
    fn ray_casts<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'_, PyAny>,
        directions: &Bound<'_, PyAny>,
        max_distance: f32,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.ray_hits(py, origins, directions, max_distance)
            .map(|(distances, ..)| distances)
    }

    /// As `ray_casts`, with what each ray hit: `(distances, bodies, normals)`, float32 (rays,),
    /// int64 (rays,) body indices (-1 for a miss) and float32 (rays, 3) unit normals facing the
    /// ray (zeros for a miss).
    #[pyo3(signature = (origins, directions, max_distance = f32::INFINITY))]
    fn ray_hits<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'_, PyAny>,
        directions: &Bound<'_, PyAny>,
        max_distance: f32,
    ) -> PyResult<RayHitArrays<'py>> {
        let sims = std::slice::from_ref(&self.sim);
        RayArrays::cast(py, sims, origins, directions, max_distance, &[])
    }
}

impl World {
    /// Joint forces and torques, (joints, 3) each.
    fn joint_loads<'py>(&self, py: Python<'py>) -> PyResult<JointLoadArrays<'py>> {
        let joints = self.sim.joint_names().len();
        let mut forces = vec![0.0; joints * 3];
        let mut torques = vec![0.0; joints * 3];
        self.sim.joint_loads(&mut forces, &mut torques);
        Ok((
            output(py, forces, &[joints, 3])?,
            output(py, torques, &[joints, 3])?,
        ))
    }
}

#[pymethods]
impl Batch {
    /// The contact force on each body of every world over the last step, N: float32 array
    /// (count, bodies, 3).
    fn contact_forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        let bodies = self.initial.body_count();
        let mut values = vec![0.0; self.sims.len() * bodies * 3];
        let sims = &self.sims;
        py.allow_threads(|| {
            values
                .par_chunks_mut((bodies * 3).max(1))
                .zip(sims.par_iter())
                .for_each(|(out, sim)| sim.contact_forces(out));
        });
        output(py, values, &[self.sims.len(), bodies, 3])
    }

    /// Every world's joint forces on `body_b`, N: float32 array (count, joints, 3).
    fn joint_forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.joint_loads(py).map(|(forces, _)| forces)
    }

    /// Every world's joint torques on `body_b`, N·m: float32 array (count, joints, 3).
    fn joint_torques<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.joint_loads(py).map(|(_, torques)| torques)
    }

    /// Every world's contact events of the last `step(n)`: a list (count) of lists of
    /// `(kind, body_a, body_b)`.
    fn contact_events(&self) -> Vec<Vec<Event>> {
        self.sims
            .iter()
            .map(|sim| sim.events().contacts.clone())
            .collect()
    }

    /// Every world's sensor events of the last `step(n)`: a list (count) of lists of
    /// `(kind, sensor, body)`.
    fn sensor_events(&self) -> Vec<Vec<Event>> {
        self.sims
            .iter()
            .map(|sim| sim.events().sensors.clone())
            .collect()
    }

    /// Casts each world's rays, `origins` and `directions` (count, rays, 3), up to
    /// `max_distance` m: distances, float32 (count, rays), infinity for a miss.
    #[pyo3(signature = (origins, directions, max_distance = f32::INFINITY))]
    fn ray_casts<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'_, PyAny>,
        directions: &Bound<'_, PyAny>,
        max_distance: f32,
    ) -> PyResult<Bound<'py, PyArrayDyn<f32>>> {
        self.ray_hits(py, origins, directions, max_distance)
            .map(|(distances, ..)| distances)
    }

    /// As `ray_casts`, with what each ray hit: `(distances, bodies, normals)`, shapes
    /// (count, rays), (count, rays) int64 (-1 for a miss) and (count, rays, 3).
    #[pyo3(signature = (origins, directions, max_distance = f32::INFINITY))]
    fn ray_hits<'py>(
        &self,
        py: Python<'py>,
        origins: &Bound<'_, PyAny>,
        directions: &Bound<'_, PyAny>,
        max_distance: f32,
    ) -> PyResult<RayHitArrays<'py>> {
        let count = [self.sims.len()];
        RayArrays::cast(py, &self.sims, origins, directions, max_distance, &count)
    }
}

impl Batch {
    /// Joint forces and torques of every world, (count, joints, 3) each.
    fn joint_loads<'py>(&self, py: Python<'py>) -> PyResult<JointLoadArrays<'py>> {
        let joints = self.initial.joint_names().len();
        let mut forces = vec![0.0; self.sims.len() * joints * 3];
        let mut torques = vec![0.0; self.sims.len() * joints * 3];
        let width = (joints * 3).max(1);
        for ((sim, forces), torques) in self
            .sims
            .iter()
            .zip(forces.chunks_mut(width))
            .zip(torques.chunks_mut(width))
        {
            sim.joint_loads(forces, torques);
        }
        let shape = [self.sims.len(), joints, 3];
        Ok((output(py, forces, &shape)?, output(py, torques, &shape)?))
    }
}
