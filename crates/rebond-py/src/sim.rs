//! One simulated world as Python sees it: a loaded scene with its bodies and motors in scene
//! order, and the number of steps taken. `World` owns one, `Batch` many.

use rebond::scene::Scene;
use rebond::{BodyHandle, JointHandle, Motor, Vec3};

use crate::drive::Loads;
use crate::readouts::StepEvents;

/// A per-body quantity that the getters read.
#[derive(Debug, Clone, Copy)]
pub enum Quantity {
    /// Body origin, m.
    Position,
    /// Rotation quaternion, x, y, z, w.
    Rotation,
    /// Velocity of the centre of mass, m/s.
    LinearVelocity,
    /// Angular velocity, rad/s.
    AngularVelocity,
    /// Centre of mass, m.
    CenterOfMass,
    /// Inertia about the centre of mass in world axes, kg·m²: `R I Rᵀ` as its six distinct
    /// entries xx, yy, zz, xy, xz, yz (zero unless dynamic).
    Inertia,
}

impl Quantity {
    /// Numbers per body.
    pub fn width(self) -> usize {
        match self {
            Self::Rotation => 4,
            Self::Inertia => 6,
            _ => 3,
        }
    }
}

/// A per-body vector that the setters write.
#[derive(Debug, Clone, Copy)]
pub enum Input {
    /// Replaces the velocity of the centre of mass, m/s.
    LinearVelocity,
    /// Replaces the angular velocity, rad/s.
    AngularVelocity,
}

/// A world with its scene's names, stepped with the scene's timestep.
#[derive(Debug, Clone)]
pub struct Sim {
    scene: Scene,
    /// The scene file's path, which error messages start with; `None` for dicts and `World()`.
    source: Option<String>,
    /// Body handles in scene order.
    bodies: Vec<BodyHandle>,
    /// Each body's place in `bodies`, by its handle's slot (`u32::MAX` for no body), so that a
    /// handle from an event or a ray hit finds its index without a search.
    places: Vec<u32>,
    /// Joints with a motor, in scene order.
    motors: Vec<JointHandle>,
    /// Steps taken so far.
    steps: u64,
    /// Forces and torques for every step of the next `step(n)`.
    loads: Loads,
    /// Contact and sensor events of the last `step(n)`.
    events: StepEvents,
}

impl Sim {
    /// A world for `scene`, with `source` for error messages.
    pub fn new(scene: Scene, source: Option<String>) -> Self {
        let mut sim = Self {
            scene,
            source,
            bodies: Vec::new(),
            places: Vec::new(),
            motors: Vec::new(),
            steps: 0,
            loads: Loads::default(),
            events: StepEvents::default(),
        };
        sim.refresh();
        sim
    }

    /// A world for `scene` restored from a saved state after `steps` steps.
    pub fn restored(scene: Scene, steps: u64) -> Self {
        let mut sim = Self::new(scene, None);
        sim.steps = steps;
        sim
    }

    /// The scene's state after the steps taken so far, as bytes ([`Scene::save_state`]).
    pub fn save(&self) -> Vec<u8> {
        self.scene.save_state(self.steps)
    }

    /// Reads the body and motor lists again after a body or joint was added.
    pub fn refresh(&mut self) {
        self.bodies = self
            .scene
            .body_handles()
            .map(|(_, handle)| handle)
            .collect();
        let slots = self.bodies.iter().map(|body| body.slot() + 1).max();
        self.places = vec![u32::MAX; slots.unwrap_or(0)];
        for (place, body) in self.bodies.iter().enumerate() {
            self.places[body.slot()] = place as u32;
        }
        let world = self.scene.world();
        self.motors = self
            .scene
            .joint_handles()
            .filter(|&(_, handle)| {
                world
                    .joint(handle)
                    .is_ok_and(|joint| joint.desc().motor.is_some())
            })
            .map(|(_, handle)| handle)
            .collect();
    }

    /// The scene, to add bodies and joints.
    pub fn scene_mut(&mut self) -> &mut Scene {
        &mut self.scene
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Where error messages say the world comes from.
    pub fn source(&self) -> Option<&str> {
        self.source.as_deref()
    }

    /// Body handles in scene order.
    pub fn bodies(&self) -> &[BodyHandle] {
        &self.bodies
    }

    /// Joints with a motor, in scene order.
    pub fn motors(&self) -> &[JointHandle] {
        &self.motors
    }

    /// The forces and torques held for the next `step(n)`.
    pub fn loads(&self) -> &Loads {
        &self.loads
    }

    /// The forces and torques held for the next `step(n)`, to change.
    pub fn loads_mut(&mut self) -> &mut Loads {
        &mut self.loads
    }

    /// Contact and sensor events of the last `step(n)`.
    pub fn events(&self) -> &StepEvents {
        &self.events
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Number of joints with a motor.
    pub fn motor_count(&self) -> usize {
        self.motors.len()
    }

    /// Body names in scene order.
    pub fn body_names(&self) -> Vec<String> {
        self.scene
            .body_handles()
            .map(|(name, _)| name.to_owned())
            .collect()
    }

    /// Joint names in scene order.
    pub fn joint_names(&self) -> Vec<String> {
        self.scene
            .joint_handles()
            .map(|(name, _)| name.to_owned())
            .collect()
    }

    /// Names of the joints with a motor, in scene order: the order of `set_motor_targets`.
    pub fn motor_names(&self) -> Vec<String> {
        self.scene
            .joint_handles()
            .filter(|(_, handle)| self.motors.contains(handle))
            .map(|(name, _)| name.to_owned())
            .collect()
    }

    /// The index in scene order of the body `handle`.
    pub fn body_index(&self, handle: BodyHandle) -> Option<usize> {
        place_of(&self.bodies, &self.places, handle)
    }

    /// Seconds per step.
    pub fn timestep(&self) -> f64 {
        self.scene.timestep().seconds
    }

    /// Steps `count` times as one `step(count)` call in one round (a rollout's `step(1)`).
    pub fn step(&mut self, count: u64) -> Result<(), String> {
        self.begin_call();
        let result = self.step_round(count);
        self.end_call();
        result
    }

    /// Starts a `step(n)` call, which may run in several rounds ([`Self::step_round`]): the
    /// events of the call before are dropped.
    pub fn begin_call(&mut self) {
        self.events.clear();
    }

    /// Ends a `step(n)` call, even one cut short: the held loads are dropped.
    pub fn end_call(&mut self) {
        self.loads.clear();
    }

    /// Steps `count` times within a `step(n)` call, giving the held loads before each step and
    /// keeping its events; the error is the command line's `step N failed: ...`, N counted from
    /// the world's first step.
    pub fn step_round(&mut self, count: u64) -> Result<(), String> {
        for _ in 0..count {
            self.steps += 1;
            let stepped = self
                .loads
                .apply(self.scene.world_mut(), &self.bodies)
                .and_then(|()| self.scene.step());
            if let Err(error) = stepped {
                let message = format!("step {} failed: {error}", self.steps);
                return Err(crate::errors::with_source(self.source(), message));
            }
            let (bodies, places) = (&self.bodies, &self.places);
            self.events.record(self.scene.world(), |handle| {
                place_of(bodies, places, handle)
            });
        }
        Ok(())
    }

    /// Writes `quantity` of every body into `out`, `width` numbers a body.
    pub fn read(&self, quantity: Quantity, out: &mut [f32]) {
        let world = self.scene.world();
        let width = quantity.width();
        for (&handle, slot) in self.bodies.iter().zip(out.chunks_exact_mut(width)) {
            let Ok(body) = world.body(handle) else {
                slot.fill(f32::NAN);
                continue;
            };
            match quantity {
                Quantity::Position => slot.copy_from_slice(&body.position().to_array()),
                Quantity::Rotation => slot.copy_from_slice(&body.rotation().to_array()),
                Quantity::LinearVelocity => {
                    slot.copy_from_slice(&body.linear_velocity().to_array());
                }
                Quantity::AngularVelocity => {
                    slot.copy_from_slice(&body.angular_velocity().to_array());
                }
                Quantity::CenterOfMass => slot.copy_from_slice(&body.center_of_mass().to_array()),
                Quantity::Inertia => {
                    let inertia = body.world_inertia();
                    let (x, y, z) = (inertia.x_axis, inertia.y_axis, inertia.z_axis);
                    slot.copy_from_slice(&[x.x, y.y, z.z, y.x, z.x, z.y]);
                }
            }
        }
    }

    /// Applies `input` to every body, three numbers a body, already checked finite.
    pub fn write(&mut self, input: Input, values: &[f32]) -> Result<(), rebond::Error> {
        let world = self.scene.world_mut();
        for (&handle, value) in self.bodies.iter().zip(values.chunks_exact(3)) {
            let value = Vec3::new(value[0], value[1], value[2]);
            let body = world.body_mut(handle)?;
            match input {
                Input::LinearVelocity => body.set_linear_velocity(value)?,
                Input::AngularVelocity => body.set_angular_velocity(value)?,
            }
        }
        Ok(())
    }

    /// Sets each motor's target (velocity, position or torque, as the motor is), already checked
    /// finite.
    pub fn set_motor_targets(&mut self, targets: &[f32]) -> Result<(), rebond::Error> {
        let world = self.scene.world_mut();
        for (&handle, &target) in self.motors.iter().zip(targets) {
            let Some(motor) = world.joint(handle)?.desc().motor else {
                continue;
            };
            let motor = match motor {
                Motor::Velocity { max_force, .. } => Motor::velocity(target, max_force),
                Motor::Position {
                    stiffness,
                    damping,
                    max_force,
                    ..
                } => Motor::position(target, stiffness, damping, max_force),
                Motor::Torque { .. } => Motor::torque(target),
            };
            world.set_joint_motor(handle, Some(motor))?;
        }
        Ok(())
    }
}

/// The index in `bodies` of `handle`, from `places` (each body's index by slot): `None` for a
/// handle of no body here, or a stale one that names a slot's earlier body.
fn place_of(bodies: &[BodyHandle], places: &[u32], handle: BodyHandle) -> Option<usize> {
    let place = *places.get(handle.slot())? as usize;
    (bodies.get(place) == Some(&handle)).then_some(place)
}
